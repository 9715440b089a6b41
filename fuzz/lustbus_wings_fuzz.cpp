// The drive wings' LUSTBUS devices (docs/lustbus.md, "The drive wings as LUSTBUS devices"): the
// VF1000 and MC6000 Responders behind a Receiver, fed arbitrary bytes at arbitrary times, with
// valid telegrams mixed in so that the fuzzer reaches deep states. A checking proxy sits between
// the receiver and the drive. Asserts (LUSTBUS manual 3, 6, 9.2):
// - a parameter's value changes only inside a select() the drive acknowledged (the receiver calls
//   select() only for a complete SELECT with the right BCC: a broken telegram changes nothing);
//   the one exception, the MC6000's end of a download (11.4), only while one is open;
// - a select() answered NAK leaves a bit in 85 (its cause, or the one that refused it);
// - while a bit is set, every select() is refused and changes nothing;
// - an enquiry() never adds a bit; the ENQUIRY of 85 returns the bits and leaves none;
// - the PosMOD1 channel (49999, 11.6) changes no parameter and is not held by the latch (its
//   refusals are read with %RDF, LB-D22); the VF1000's reset (11-STAT = 000FH with an error,
//   8.1.1) may answer a cut ACK or nothing, and the inverter is deaf while it boots.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz_support.hpp"
#include "ibs/devices/mc6000/lustbus_device.hpp"
#include "ibs/devices/vf1000/lustbus_device.hpp"
#include "ibs/lustbus/code.hpp"
#include "ibs/lustbus/receiver.hpp"
#include "ibs/lustbus/telegram.hpp"

namespace {

using namespace ibs;
using namespace ibs::lustbus;
using ibs::fuzz::fail;
using In = ibs::fuzz::Input;
using namespace std::chrono_literals;

// The drive's observable state: every value its CODEs reach. The VF1000 keeps 85-SIOF in its one
// store (the drive core, devices/vf1000/core): its bits are checked on their own (bits_of).
std::vector<std::uint32_t> values_of(const devices::vf1000::LustbusDevice& d) {
  std::vector<std::uint32_t> v;
  for (std::uint16_t n = 0; n < 100; ++n) v.push_back(n == drive::kSiofNumber ? 0U : d.value(n));
  return v;
}
// The settings: the drive core's actual values (77-SPEED, 408-IBSTA, 85-SERR, ...) are its
// readings, which move with the plant and the latch.
std::vector<std::uint32_t> values_of(const devices::mc6000::LustbusDevice& d) {
  std::vector<std::uint32_t> v;
  for (const pcp::ParameterInfo& p : d.drive().parameters().table()) {
    if (p.category != pcp::Category::ram_actual) v.push_back(d.value(p.number));
  }
  return v;
}
std::uint8_t bits_of(const devices::vf1000::LustbusDevice& d) { return d.siof(); }
std::uint8_t bits_of(const devices::mc6000::LustbusDevice& d) { return d.serr(); }
bool may_change_alone(const devices::vf1000::LustbusDevice& d) { return d.booting(); }
// Only the servo has the PosMOD1 channel; to the inverter 49999 is no CODE (20H).
bool has_posmod(const devices::vf1000::LustbusDevice&) { return false; }
bool has_posmod(const devices::mc6000::LustbusDevice&) { return true; }
bool may_change_alone(const devices::mc6000::LustbusDevice& d) { return d.downloading(); }

template <typename Drive>
class Checker final : public Responder {
 public:
  explicit Checker(Drive& d) : d_(d) {}
  int acks = 0;  // select() calls the drive acknowledged
  int resets = 0;  // 11-STAT = 000FH taken: a new start, RAM values back to their defaults (8.1.1)

  EnquiryAnswer enquiry(const Code& code, const Context& ctx) override {
    d_.advance(ctx.now);  // what the drive does itself first: time-driven changes are not ours
    const auto before = values_of(d_);
    const std::uint8_t bits = bits_of(d_);
    const bool alone = may_change_alone(d_);
    const EnquiryAnswer a = d_.enquiry(code, ctx);
    const std::uint8_t after = bits_of(d_);
    if ((after & ~bits) != 0) fail("an ENQUIRY added a bit to 85");
    if (reads_siof(code) && a.reply == Reply::text) {
      if (after != 0) fail("reading 85 left a bit");
      if (a.value.view().find_first_not_of('0') == std::string::npos ? bits != 0 : bits == 0) {
        fail("85 answered " + std::string(a.value.view()) + " for bits " + std::to_string(bits));
      }
    }
    if (!alone && values_of(d_) != before) fail("an ENQUIRY changed a value");
    return a;
  }

  SelectAnswer select(const Code& code, const Value& value, const Context& ctx) override {
    d_.advance(ctx.now);
    const auto before = values_of(d_);
    const std::uint8_t bits = bits_of(d_);
    const SelectAnswer a = d_.select(code, value, ctx);
    if (code == kPosmodCode && has_posmod(d_)) {
      if (values_of(d_) != before) fail("a PosMOD1 telegram changed a parameter");
      if (bits_of(d_) != bits) fail("a PosMOD1 telegram changed 85");
      if (a.reply != Reply::ack && a.reply != Reply::nak) fail("PosMOD1 answered neither ACK nor NAK");
      return a;
    }
    const bool reset = (code.number() % 100) == 11 && value.view() == "000F";
    if (reset && (a.reply == Reply::cut || a.reply == Reply::none)) {
      if (bits != 0) fail("a reset taken while 85 held a bit");
      ++resets;
      return a;
    }
    if (a.reply == Reply::nak) {
      if (bits_of(d_) == 0) fail("a NAK without a bit in 85");
      if (values_of(d_) != before) fail("a refused SELECT changed a value");
    } else if (a.reply == Reply::ack) {
      ++acks;
    } else {
      fail("a SELECT answered neither ACK nor NAK");
    }
    if (bits != 0 && a.reply != Reply::nak) fail("a SELECT taken while 85 held a bit");
    return a;
  }

  void checksum_error(const Context& ctx) override {
    const auto before = values_of(d_);
    d_.checksum_error(ctx);
    if ((bits_of(d_) & 0x08) == 0) fail("a wrong BCC without 08H");
    if (values_of(d_) != before) fail("a wrong BCC changed a value");
  }

  [[nodiscard]] bool listening(Time now) const override { return d_.listening(now); }

  void telegram_received(const Context& ctx) override {
    d_.advance(ctx.now);
    const auto before = values_of(d_);
    d_.telegram_received(ctx);
    if (values_of(d_) != before) fail("a telegram's arrival changed a value");
  }

 private:
  Drive& d_;
};

template <typename Drive>
void run(In& in) {
  Drive drive;
  Checker<Drive> checker(drive);
  const auto own = static_cast<Address>(in.ConsumeIntegralInRange<int>(1, 30));
  Receiver rx(checker, own);
  Time now{0};
  while (in.remaining_bytes() > 0) {
    now += std::chrono::microseconds(in.ConsumeIntegralInRange<int>(0, 200000));
    const auto before = values_of(drive);
    const bool alone = may_change_alone(drive);
    const int acks_before = checker.acks;
    const int resets_before = checker.resets;
    switch (in.ConsumeIntegralInRange<int>(0, 4)) {
      case 0: {  // raw bytes
        const auto bytes = in.ConsumeBytes<std::uint8_t>(in.ConsumeIntegralInRange<std::size_t>(0, 24));
        for (const auto b : bytes) rx.receive(b, now);
        break;
      }
      case 1: {  // a valid SELECT, maybe cut short or with one byte changed
        const std::uint32_t code = in.ConsumeIntegralInRange<std::uint32_t>(0, 99999);
        const auto digits = in.ConsumeBytes<std::uint8_t>(in.ConsumeIntegralInRange<std::size_t>(1, 8));
        std::string v;
        for (const auto c : digits) v.push_back("0123456789ABCDEF"[c & 0x0F]);
        const auto t = encode_select(in.ConsumeBool() ? own : 0, make_code(code), make_value(v));
        auto bytes = std::vector<std::uint8_t>(t.span().begin(), t.span().end());
        const auto cut = in.ConsumeIntegralInRange<std::size_t>(0, bytes.size());
        if (in.ConsumeBool() && cut < bytes.size()) bytes[cut] ^= in.ConsumeIntegralInRange<std::uint8_t>(1, 255);
        for (const auto b : bytes) rx.receive(b, now);
        break;
      }
      case 2: {  // a valid ENQUIRY (85 often)
        const std::uint32_t code =
            in.ConsumeBool() ? 85 : in.ConsumeIntegralInRange<std::uint32_t>(0, 99999);
        const auto t = encode_enquiry(in.ConsumeBool() ? own : 0, make_code(code));
        for (const auto b : t.span()) rx.receive(b, now);
        break;
      }
      case 3: {  // a PosMOD1 telegram (11.6), from the commands docs/lustbus.md lists
        static constexpr const char* kUser[] = {"8GOA100",  "8GOR-5V10", "8ST",   "8HOME", "<%P1 (X)",
                                                "<N1 GO 0", "8END",      "1?",    "1%RDP1", "1%RDF",
                                                "1%RDP9",   "8GOA",      "\x7F?"};
        const auto pick = in.ConsumeIntegralInRange<std::size_t>(0, std::size(kUser));
        const auto t = pick == std::size(kUser)
                           ? encode_enquiry(own, kPosmodCode)
                           : encode_select(own, kPosmodCode, make_value(kUser[pick]));
        for (const auto b : t.span()) rx.receive(b, now);
        break;
      }
      default:
        drive.advance(now);
        break;
    }
    // Values change only through an acknowledged select(), or by the end of a download.
    if (!alone && checker.acks == acks_before && checker.resets == resets_before &&
        values_of(drive) != before) {
      fail("a value changed without an acknowledged SELECT");
    }
    if (const auto due = rx.answer_due()) {
      const auto a = rx.take_answer(*due);
      if (a.empty()) fail("an answer due but empty");
      now = *due;
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  In in(data, size);
  if (in.ConsumeBool()) {
    run<devices::vf1000::LustbusDevice>(in);
  } else {
    run<devices::mc6000::LustbusDevice>(in);
  }
  return 0;
}
