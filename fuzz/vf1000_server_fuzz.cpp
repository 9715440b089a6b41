// The VF1000 inverter's side of the communication-word parameter channel
// (vf1000_channel::Server, docs/vf1000_channel.md) fed arbitrary master words, step by step,
// with the power stage switched on and off, 85-SIOF bits raised by the device and power cycles.
//
// A model written from the documentation (not from the server's code) follows the telegram as
// the inverter must take it: a word is taken when its toggle differs from the last one taken,
// CODE 0 returns to wait mode (toggle 0), ACK or NAK ends the telegram. It asserts:
// - a parameter changes only in the step that ends a complete value transfer, and only to the
//   transferred value: a start word with CODE 2, no unintended control bits and the parameter's
//   number, taken in wait mode while 85-SIOF was 0 and the parameter writable; then DAT1 and DAT2
//   with CODE 2 and no unintended control bits; 85-SIOF still 0 when DAT2 is taken (4.1.4: any
//   bit refuses every transfer) and the value within min/max and writable then (4.1.3.2);
//   71-PROG = 1 then loads every default;
// - conversely, such a transfer is acknowledged and takes effect;
// - 85-SIOF changes only by a NAK's documented bit (one of 08H, 20H, 40H, 80H, value transfers
//   only), by its own value inquiry (clearing exactly the bits read), by the device or a power-on;
// - a value inquiry answers the value the parameter had when its number arrived;
// - the inverter's word is 0000 while initialising and otherwise has RESET distinction 1, no
//   unused bits, never ACK and NAK together, and echoes the toggle of the last word taken.
//
// Input: a header (start mode, initialisation time); then per step a control byte (time step,
// power stage, device action), a master word and, for a device action, one more byte.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "fuzz_support.hpp"
#include "ibs/vf1000_channel/comm_word.hpp"
#include "ibs/devices/vf1000/channel.hpp"
#include "ibs/devices/vf1000/parameters.hpp"
#include "ibs/vf1000_channel/server.hpp"

namespace {

using namespace ibs;
using namespace ibs::vf1000_channel;
using namespace ibs::drive;
using namespace ibs::devices::vf1000;
using ibs::fuzz::fail;
using ibs::fuzz::hex4;

// One word the inverter took in the current telegram, with what held when it was taken.
struct Taken {
  Word word = 0;
  std::uint8_t siof = 0;
  bool power_stage = false;
  std::optional<Word> value;  // the addressed parameter's value then
};

struct Model {
  bool toggle = false;        // toggle of the last word taken
  bool over = false;          // ACK or NAK sent: waiting for CODE 0
  std::vector<Taken> taken;   // this telegram's words
  void reset() {
    toggle = false;
    over = false;
    taken.clear();
  }
};

bool clean_transfer_word(Word w) {
  return master_code(w) == static_cast<std::uint8_t>(Code::value_transfer) && !master_unused_bits(w);
}

std::vector<Word> snapshot(const Server& s) {
  std::vector<Word> v;
  for (const ParameterInfo& p : s.table().params()) v.push_back(*s.value(p.number));
  return v;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  ibs::fuzz::Input in(data, size);
  const std::uint8_t header = in.ConsumeIntegral<std::uint8_t>();
  ServerConfig cfg = server_config();
  cfg.init_duration = std::chrono::milliseconds(in.ConsumeIntegral<std::uint8_t>());
  const ServerStart start = (header % 3) == 0 ? ServerStart::power_on
                            : (header % 3) == 1 ? ServerStart::initialised
                                                : ServerStart::operational;
  Time now{0};
  Server server(cfg, start, now, parameters());
  const auto params = server.table().params();
  const ParameterTable& table = server.table();
  Model model;
  bool power_stage = false;
  ibs::fuzz::Recent<> recent;

  // IBS_FUZZ_TRACE=1: say which transfers took effect.
  const bool trace = std::getenv("IBS_FUZZ_TRACE") != nullptr;
  while (in.remaining_bytes() > 0) {
    const std::uint8_t ctrl = in.ConsumeIntegral<std::uint8_t>();
    const Word m = in.ConsumeIntegral<std::uint16_t>();
    switch (ctrl & 3U) {
      case 0: break;
      case 1: now += 8200us; break;
      case 2: now += 33ms; break;
      default: now += std::chrono::milliseconds(in.ConsumeIntegral<std::uint8_t>()); break;
    }
    if (power_stage != ((ctrl & 4U) != 0)) recent.note((ctrl & 4U) != 0 ? "stage-on" : "stage-off");
    power_stage = (ctrl & 4U) != 0;
    switch ((ctrl >> 3U) & 7U) {
      case 1: {
        const auto bits = in.ConsumeIntegral<std::uint8_t>();
        server.raise_siof(bits);
        recent.note("siof-raised");
        break;
      }
      case 2:
        server.power_on(now);
        recent.note("power-on");
        break;
      default: break;
    }

    const std::vector<Word> before = snapshot(server);
    const std::uint8_t siof_before = server.siof();
    const bool was_initialising = server.state() == ServerState::initialising;
    const bool ignored = was_initialising && now < server.ready_at();
    if (was_initialising) model.reset();

    // What the inverter must do with this word, by the model.
    bool taken_now = false;
    if (!ignored) {
      if (master_code(m) == 0) {
        model.reset();
      } else if (master_toggle(m) != model.toggle) {
        model.toggle = master_toggle(m);
        taken_now = true;
        if (!model.over) {
          Taken t{m, siof_before, power_stage, std::nullopt};
          if (model.taken.empty()) t.value = server.value(master_number(m));
          model.taken.push_back(t);
        }
      }
    }
    const Word out = server.step(m, now, power_stage);
    const ServerEvent& e = server.last_event();
    const std::vector<Word> after = snapshot(server);
    recent.words(m, out);
    const auto where = [&] {
      return "master word " + hex4(m) + " answered " + hex4(out) + " (event " +
                              std::to_string(static_cast<int>(e.kind)) + " number " + std::to_string(e.number) +
             " value " + hex4(e.value) + "), 85-SIOF before " + hex4(siof_before) + "; steps (master>inverter):" +
             recent.str();
    };

    // The inverter's word.
    if (server.state() == ServerState::initialising) {
      if (out != 0) fail("initialising but the word is not 0000: " + where());
    } else {
      if (!inverter_ready(out)) fail("RESET distinction 0 after initialisation: " + where());
      if ((out & kInverterUnusedMask) != 0) fail("unused bits set: " + where());
      if (inverter_ack(out) && inverter_nak(out)) fail("ACK and NAK together: " + where());
      if (inverter_toggle(out) != model.toggle) fail("the toggle of the last word taken is not echoed: " + where());
      if (master_code(m) == 0 && out != kInverterWaitWord) fail("CODE 0 not answered with wait mode: " + where());
    }

    // A complete, checked value transfer, by the model: the telegram's third word, taken now.
    bool transfer_ok = false;
    std::uint16_t number = 0;
    Word value = 0;
    if (taken_now && !model.over && model.taken.size() == 3) {
      const Taken& s = model.taken[0];
      const Taken& d1 = model.taken[1];
      const Taken& d2 = model.taken[2];
      number = master_number(s.word);
      value = make_word(low_byte(d1.word), low_byte(d2.word));
      const ParameterInfo* p = table.find(number);
      transfer_ok = clean_transfer_word(s.word) && clean_transfer_word(d1.word) && clean_transfer_word(d2.word) &&
                    s.siof == 0 && check_access(p, s.power_stage) == WriteCheck::ok && d2.siof == 0 &&
                    check_write(p, value, d2.power_stage) == WriteCheck::ok;
    }
    const bool written = e.kind == ServerEvent::Kind::value_written;
    if (written && !transfer_ok) {
      fail("a value transfer took effect that was not complete and checked (parameter " + std::to_string(e.number) +
           " = " + hex4(e.value) + "; the telegram's words taken: " + std::to_string(model.taken.size()) + "): " + where());
    }
    if (transfer_ok && !written) {
      fail("a complete, checked value transfer of " + hex4(value) + " to parameter " + std::to_string(number) +
           " was not acknowledged: " + where());
    }
    if (written && (e.number != number || e.value != value)) {
      fail("the transfer wrote parameter " + std::to_string(e.number) + " = " + hex4(e.value) + ", the telegram carried " +
           std::to_string(number) + " = " + hex4(value) + ": " + where());
    }
    if (written && !inverter_ack(out)) fail("a value took effect without ACK: " + where());
    if (written && trace) std::fprintf(stderr, "parameter %u = %04X written\n", e.number, e.value);

    // Which parameters changed, and why they may have.
    const bool defaults = written && number == pnr::kProg && value == kLoadDefaults;
    for (std::size_t i = 0; i < params.size(); ++i) {
      const ParameterInfo& p = params[i];
      if (p.number == pnr::kSiof || before[i] == after[i]) continue;
      const bool by_transfer = written && p.number == number && after[i] == value;
      const bool by_defaults = defaults && after[i] == p.default_value;
      if (!by_transfer && !by_defaults) {
        fail("parameter " + std::to_string(p.number) + " changed from " + hex4(before[i]) + " to " + hex4(after[i]) +
             " without a value transfer: " + where());
      }
    }

    // 85-SIOF.
    std::uint8_t siof = siof_before;
    if (e.kind == ServerEvent::Kind::nak) {
      const std::uint8_t b = e.siof_set;
      if (b != 0 && b != 0x08 && b != 0x20 && b != 0x40 && b != 0x80) fail("NAK sets undocumented 85-SIOF bits: " + where());
      if (b != 0 && e.code != Code::value_transfer) fail("a NAK outside a value transfer sets 85-SIOF: " + where());
      if (!inverter_nak(out)) fail("NAK event without NAK in the word: " + where());
      siof = static_cast<std::uint8_t>(siof | b);
    }
    if (e.kind == ServerEvent::Kind::value_read) {
      if (!inverter_ack(out)) fail("value read without ACK: " + where());
      if (model.taken.empty() || !model.taken[0].value || *model.taken[0].value != e.value ||
          master_number(model.taken[0].word) != e.number) {
        fail("a value inquiry answered " + hex4(e.value) + " for parameter " + std::to_string(e.number) +
             ", not the value when its number arrived: " + where());
      }
      if (e.number == pnr::kSiof) siof = static_cast<std::uint8_t>(siof & ~e.value);
    }
    if (server.siof() != siof) {
      fail("85-SIOF went from " + hex4(siof_before) + " to " + hex4(server.siof()) + ", expected " + hex4(siof) + ": " + where());
    }
    if (inverter_ack(out) || inverter_nak(out)) model.over = true;
  }
  return 0;
}
