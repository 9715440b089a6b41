// One MC6000 drive core, two faces (docs/architecture.md, "One drive, many faces"): the INTERBUS
// face (PCP over the process-data ring) and the LUSTBUS face on one mc6000::Drive. A value written
// on one bus is what the other reads; and the same access through either face gives the same
// answer -- reads, writes, each refusal and its 85-SERR bit, the power-on bit, the fault reset,
// 4-PROG, the 80-SLOAD download and the EEPROM save, with the same timing (docs/errata.md MC-D1..D4).
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <optional>
#include <span>
#include <memory>
#include <string>
#include <vector>

#include "ibs/devices/mc6000/device.hpp"
#include "ibs/devices/mc6000/drive.hpp"
#include "ibs/devices/mc6000/lustbus_device.hpp"
#include "ibs/devices/mc6000/parameters.hpp"
#include "ibs/lustbus/chars.hpp"
#include "ibs/lustbus/receiver.hpp"
#include "ibs/lustbus/telegram.hpp"
#include "ibs/lustbus/value.hpp"
#include "ibs/pcp/client.hpp"

namespace {

using namespace std::chrono_literals;
using ibs::Duration;
using ibs::Time;
using ibs::Word;
using ibs::drivecom::State;
using ibs::DeviceStart;
namespace mc = ibs::devices::mc6000;
namespace pcp = ibs::pcp;
namespace lb = ibs::lustbus;

enum class Face { pcp, lustbus };
std::string name(Face f) { return f == Face::pcp ? "PCP" : "LUSTBUS"; }

// What an access through a face came to, in the drive's terms.
struct Answer {
  bool ok = false;
  std::uint32_t raw = 0;  // a read's value (the type's bit pattern)
  Duration took{};        // from the request to its answer
};

// An MC6000 with both faces on one core: the INTERBUS face sampled every 1 ms by a lock-step
// ring with a PCP client on its two channel words (405-SUPI 9, 406-IBCNF 1: control word and a
// 16-bit reference), the LUSTBUS face at address 3.
class Servo {
 public:
  explicit Servo(DeviceStart start = DeviceStart::operational)
      : core_(std::make_shared<mc::Drive>(mc::DriveConfig{}, start, Time{0})),
        interbus_(interbus_config(), core_, start, Time{0}),
        lustbus_(core_),
        rx_(lustbus_, 3),
        client_([] {
          pcp::ClientConfig c;
          c.channel_words = 2;
          return c;
        }()) {
    // After a power-on both link ends announce their restart first; the client then initiates again.
    for (int i = 0; i < 3; ++i) {
      client_.initiate(now_);
      const auto r = run_pcp();
      if (r && r->ok()) break;
    }
  }

  // After a power-on both link ends announce their restart first; the client then initiates again.
  bool connect() {
    for (int i = 0; i < 3; ++i) {
      client_.initiate(now_);
      const auto r = run_pcp();
      if (r && r->ok()) return true;
    }
    return false;
  }

  mc::Drive& core() { return *core_; }
  ibs::devices::Mc6000Device& interbus() { return interbus_; }
  mc::LustbusDevice& lustbus() { return lustbus_; }
  [[nodiscard]] Time now() const { return now_; }

  // One 1 ms ring cycle: the client's and the servo's channel words, the process data.
  void tick() {
    now_ += 1ms;
    client_.step(now_, s2m_, m2s_);
    interbus_.bus_cycle(now_);
    interbus_.sample(pd_m2s_, pd_s2m_, now_, m2s_, s2m_);
  }
  void idle(Duration d) {
    const Time end = now_ + d;
    while (now_ < end) tick();
  }
  void set_control_word(Word w) { pd_m2s_[0] = w; }
  void set_reference(Word rpm) { pd_m2s_[1] = rpm; }  // IBCNF 1: a 16-bit speed in rpm
  // Ring cycles that never reach the servo: its bus watchdog runs (INTERBUS manual 3.2.4).
  void silent(Duration d) {
    const Time end = now_ + d;
    while (now_ < end) {
      now_ += 1ms;
      interbus_.sample(pd_m2s_, pd_s2m_, now_, m2s_, s2m_);
    }
  }
  // A LUSTBUS SELECT and its answer as it went out: ADR ACK, ADR NAK, the ADR alone of a cut ACK
  // (LUSTBUS manual 8.1.2), or nothing.
  std::vector<std::uint8_t> select_answer(std::uint16_t number, std::uint32_t raw) {
    char hex[16];
    std::snprintf(hex, sizeof hex, "%X", raw);
    return telegram(lb::encode_select(3, lb::make_code(20000 + number), lb::make_value(hex)).span()).bytes;
  }

  Answer read(Face f, std::uint16_t number) {
    if (f == Face::pcp) {
      const Time t = now_;
      if (client_.read(now_, pcp::ParameterRef::number(number)) != pcp::SubmitStatus::accepted) return {};
      const auto r = run_pcp();
      if (!r || !r->ok()) return {false, 0, now_ - t};
      std::uint32_t v = 0;
      for (std::size_t i = 0; i < r->data.size; ++i) v = v << 8U | r->data.data[i];
      return {true, v, now_ - t};
    }
    const auto a = telegram(lb::encode_enquiry(3, lb::make_code(20000 + number)).span());
    if (a.bytes.size() < 2 || a.bytes[1] != lb::kStx) return {false, 0, a.took};
    // ADR STX CODE(5) '=' VALUE ETX BCC: the VALUE in hex.
    const std::string value(a.bytes.begin() + 8, a.bytes.end() - 2);
    return {true, static_cast<std::uint32_t>(std::stoul(value, nullptr, 16)), a.took};
  }

  Answer write(Face f, std::uint16_t number, std::uint32_t raw, Duration limit = 20s) {
    if (f == Face::pcp) {
      const pcp::ParameterInfo* p = core_->store().info(number);
      const pcp::Value v{p ? p->type : pcp::DataType::usign16, raw};
      const Time t = now_;
      if (client_.write(now_, pcp::ParameterRef::number(number), v, limit) != pcp::SubmitStatus::accepted) return {};
      const auto r = run_pcp(limit);
      return {r && r->ok(), 0, now_ - t};
    }
    char hex[16];
    std::snprintf(hex, sizeof hex, "%X", raw);
    const auto a = telegram(lb::encode_select(3, lb::make_code(20000 + number), lb::make_value(hex)).span());
    return {a.bytes.size() == 2 && a.bytes[1] == lb::kAck, 0, a.took};
  }

 private:
  static ibs::devices::Mc6000DeviceConfig interbus_config() {
    ibs::devices::Mc6000DeviceConfig c;
    c.supi = 9;  // 2 process-data words, 2 PCP words (INTERBUS manual 3.2.2)
    c.ibcnf = 1;
    c.pcp_latency = pcp::LatencyModel::immediate();
    return c;
  }

  std::optional<pcp::Result> run_pcp(Duration limit = 20s) {
    const Time end = now_ + limit + 1s;
    while (now_ < end) {
      tick();
      if (auto r = client_.take_result()) return r;
    }
    return std::nullopt;
  }

  struct Telegram {
    std::vector<std::uint8_t> bytes;
    Duration took{};
  };
  // A telegram at the next cycle; the ring runs on until its answer is due, then the host's EOT.
  Telegram telegram(std::span<const std::uint8_t> bytes) {
    tick();
    const Time t = now_;
    for (const auto b : bytes) rx_.receive(b, now_);
    Telegram out;
    if (const auto due = rx_.answer_due()) {
      while (now_ < *due) tick();
      const auto a = rx_.take_answer(*due);
      out.bytes.assign(a.begin(), a.end());
    }
    out.took = now_ - t;
    rx_.receive(lb::kEot, now_);
    return out;
  }

  std::shared_ptr<mc::Drive> core_;
  ibs::devices::Mc6000Device interbus_;
  mc::LustbusDevice lustbus_;
  lb::Receiver rx_;
  pcp::Client client_;
  Time now_{0};
  std::array<Word, 2> pd_m2s_{};
  std::array<Word, 2> pd_s2m_{};
  std::array<Word, 2> m2s_{};
  std::array<Word, 2> s2m_{};
};

constexpr Face kFaces[] = {Face::pcp, Face::lustbus};

TEST(Mc6000Faces, OneStoreBehindBothFaces) {
  Servo s;
  // Both faces serve the one core, and the PCP server serves its store.
  EXPECT_EQ(&s.interbus().drive(), &s.core());
  EXPECT_EQ(&s.lustbus().drive(), &s.core());
  EXPECT_EQ(&s.interbus().drive().store(), &s.lustbus().drive().store());
  EXPECT_EQ(s.interbus().pcp()->served().table().data(), s.core().store().table().data());

  ASSERT_TRUE(s.write(Face::pcp, 83, 1234).ok);
  EXPECT_EQ(s.read(Face::lustbus, 83).raw, 1234U) << "a PCP Write is what a LUSTBUS ENQUIRY reads";
  ASSERT_TRUE(s.write(Face::lustbus, 83, 0x0929).ok);
  EXPECT_EQ(s.read(Face::pcp, 83).raw, 0x0929U) << "a LUSTBUS SELECT is what a PCP Read reads";
  // An EEPROM value the same way, and its EEPROM copy is the core's.
  ASSERT_TRUE(s.write(Face::lustbus, 409, 250).ok);
  EXPECT_EQ(s.read(Face::pcp, 409).raw, 250U);
  s.idle(40ms);
  EXPECT_EQ(s.core().parameters().eeprom(409)->raw, 250U);
}

TEST(Mc6000Faces, ReadsAndWritesAlike) {
  for (const Face f : kFaces) {
    Servo s;
    EXPECT_EQ(s.read(f, mc::kType).raw, 6000U) << name(f);
    EXPECT_TRUE(s.write(f, 83, 7).ok) << name(f);
    EXPECT_EQ(s.read(f, 83).raw, 7U) << name(f);
    EXPECT_EQ(s.read(f, mc::kSerr).raw, 0U) << name(f);
    // LUSTBUS manual 6.1 note: a read of a missing parameter is refused and enters nothing.
    EXPECT_FALSE(s.read(f, 999).ok) << name(f);
    EXPECT_EQ(s.core().parameters().serr(), 0U) << name(f);
  }
}

// LUSTBUS manual 9.2: each refusal enters its cause; while a bit is set every write is refused and
// enters nothing (MC-D3); reading 85-SERR returns the bits and clears them.
TEST(Mc6000Faces, EachRefusalEntersItsSerrBitThroughEitherFace) {
  struct Case {
    std::uint16_t number;
    std::uint32_t raw;
    std::uint8_t bit;
  };
  const Case cases[] = {
      {999, 1, mc::kSerrNoParameter},     // no parameter
      {mc::kType, 1, mc::kSerrNoChange},  // 91-TYPE is an actual value
      {mc::kIbcnf, 9, mc::kSerrInvalidValue},  // above max
      {mc::kSload, 5, mc::kSerrInvalidValue},  // 11.4: the host writes -1 and -2 only
  };
  for (const Face f : kFaces) {
    for (const Case& c : cases) {
      Servo s;
      EXPECT_FALSE(s.write(f, c.number, c.raw).ok) << name(f) << " " << c.number;
      EXPECT_FALSE(s.write(f, 83, 1).ok) << name(f) << ": refused while 85-SERR holds a bit";
      EXPECT_EQ(s.core().parameters().raw(83), 0U) << name(f);
      EXPECT_EQ(s.read(f, mc::kSerr).raw, c.bit) << name(f) << " " << c.number;
      EXPECT_EQ(s.read(f, mc::kSerr).raw, 0U) << name(f) << ": reading clears it";
      EXPECT_TRUE(s.write(f, 83, 1).ok) << name(f);
    }
    // 11.4: 80-SLOAD = -2 without -1, and -1 while the power stage is on: 40H.
    Servo s;
    EXPECT_FALSE(s.write(f, mc::kSload, 0xFFFE).ok) << name(f);
    EXPECT_EQ(s.read(f, mc::kSerr).raw, mc::kSerrNoChange) << name(f);
  }
}

// LUSTBUS manual 6: "After every new start of the device, the bit for flagging power on ... is set".
TEST(Mc6000Faces, PowerOnBitRefusesTheFirstWriteOnEitherFace) {
  for (const Face f : kFaces) {
    Servo s(DeviceStart::initialised);
    EXPECT_EQ(s.core().parameters().serr(), mc::kSerrPowerOn) << name(f);
    EXPECT_FALSE(s.write(f, 83, 2).ok) << name(f);
    EXPECT_EQ(s.read(f, mc::kSerr).raw, mc::kSerrPowerOn) << name(f) << ": the refusal adds nothing";
    EXPECT_TRUE(s.write(f, 83, 2).ok) << name(f);
    s.core().power_on(s.now());
    EXPECT_EQ(s.read(f, mc::kSerr).raw, mc::kSerrPowerOn) << name(f);
  }
}

// LUSTBUS manual 3, 10.2.2: RAM at once, the EEPROM copy 15 ms per byte later; another EEPROM write
// meanwhile is refused with 04H.
TEST(Mc6000Faces, EepromSaveTakesFifteenMsPerByteOnEitherFace) {
  for (const Face f : kFaces) {
    Servo s;
    ASSERT_TRUE(s.write(f, mc::kSwdgt, 0).ok);  // settle: the first EEPROM write is the one timed
    s.idle(50ms);
    const Answer w = s.write(f, 409, 100);
    ASSERT_TRUE(w.ok) << name(f);
    const Time busy_until = s.core().parameters().eeprom_busy_until();
    // The save started when the write was executed: between the request and its answer.
    EXPECT_LE(busy_until, s.now() + 30ms) << name(f);
    EXPECT_GE(busy_until, s.now() - w.took + 30ms) << name(f);
    EXPECT_EQ(s.core().parameters().raw(409), 100U) << name(f) << ": RAM at once";
    EXPECT_FALSE(s.write(f, 84, 5).ok) << name(f) << ": EEPROM busy";
    EXPECT_EQ(s.read(f, mc::kSerr).raw, mc::kSerrEepromBusy) << name(f);
    while (s.now() < busy_until - 1ms) s.tick();
    EXPECT_EQ(s.core().parameters().eeprom(409)->raw, 0U) << name(f) << ": still saving";
    s.idle(2ms);
    EXPECT_EQ(s.core().parameters().eeprom(409)->raw, 100U) << name(f);
    EXPECT_EQ(s.core().parameters().timing().eeprom_per_byte * 2, 30ms);
  }
}

// LUSTBUS manual 10 exception 1 (MC-D1): the answer to 4-PROG = 1 comes once every parameter is back at
// its default, 9.9 s after the command on either bus -- within the seed's "up to 10 seconds".
TEST(Mc6000Faces, Prog1AnswersAfterTheSameTimeOnEitherFace) {
  for (const Face f : kFaces) {
    Servo s;
    ASSERT_TRUE(s.write(f, 83, 5).ok);
    ASSERT_TRUE(s.write(f, 417, 3).ok);
    s.idle(50ms);
    const Answer a = s.write(f, mc::kProg, 1, 12s);
    ASSERT_TRUE(a.ok) << name(f);
    EXPECT_GE(a.took, 9900ms) << name(f);
    EXPECT_LT(a.took, 10s) << name(f);
    EXPECT_EQ(s.read(f, 83).raw, 0U) << name(f);
    EXPECT_EQ(s.core().parameters().eeprom(417)->raw, 0U) << name(f);
    EXPECT_EQ(s.read(f, mc::kProg).raw, 0U) << name(f) << ": a command, not a setting";
  }
}

// LUSTBUS manual 11.4 (MC-D2): the download of the CardWriteable parameters, tested 200 ms after
// 80-SLOAD = -2 on either bus; a rejected dataset names its first invalid parameter and the old
// one comes back; an accepted one goes to EEPROM.
TEST(Mc6000Faces, DownloadResultAndTimingAlike) {
  for (const Face f : kFaces) {
    Servo s;
    ASSERT_TRUE(s.write(f, mc::kSload, 0xFFFF).ok) << name(f);
    ASSERT_TRUE(s.write(f, 418, 3).ok) << name(f);
    ASSERT_TRUE(s.write(f, 419, 9).ok) << name(f) << ": taken without the range check";
    ASSERT_TRUE(s.write(f, 83, 44).ok) << name(f) << ": not CardWriteable: acknowledged";
    EXPECT_EQ(s.core().parameters().raw(83), 0U) << name(f) << ": and dropped";
    ASSERT_TRUE(s.write(f, mc::kSload, 0xFFFE).ok) << name(f);
    const Time end = s.now();
    EXPECT_EQ(s.read(f, mc::kSload).raw, 0xFFFFU) << name(f) << ": -1 while testing";
    EXPECT_FALSE(s.write(f, 83, 1).ok) << name(f) << ": busy testing";
    EXPECT_EQ(s.read(f, mc::kSerr).raw, mc::kSerrNoChange) << name(f);
    // The test ended 200 ms after the -2 was executed, which was before its answer at `end`.
    while (s.now() < end + 150ms) s.tick();
    EXPECT_EQ(s.read(f, mc::kSload).raw, 0xFFFFU) << name(f);
    while (s.now() < end + 230ms) s.tick();
    EXPECT_EQ(s.read(f, mc::kSload).raw, 419U) << name(f) << ": rejected, first invalid";
    EXPECT_EQ(s.core().parameters().raw(418), 0U) << name(f) << ": the old dataset";
    EXPECT_EQ(s.core().parameters().raw(419), 6U) << name(f);

    ASSERT_TRUE(s.write(f, mc::kSload, 0xFFFF).ok) << name(f);
    ASSERT_TRUE(s.write(f, 418, 3).ok) << name(f);
    ASSERT_TRUE(s.write(f, mc::kSload, 0xFFFE).ok) << name(f);
    s.idle(250ms);
    EXPECT_EQ(s.read(f, mc::kSload).raw, 0U) << name(f) << ": accepted";
    EXPECT_EQ(s.core().parameters().eeprom(418)->raw, 3U) << name(f);
  }
}

// LUSTBUS manual 5.2 and 8.1.2 / INTERBUS manual 5.1.2: the serial watchdog's fault, and its reset through
// either face -- 416-SCTL1 bit 7 over LUSTBUS, control word bit 7 over INTERBUS, each from the
// control location (MC-D4) -- ends in the same core call: the cause cleared, DRIVECOM out of FAULT.
TEST(Mc6000Faces, FaultResetThroughEitherFace) {
  for (const Face f : kFaces) {
    Servo s;
    if (f == Face::lustbus) {
      ASSERT_TRUE(s.write(Face::lustbus, mc::kClsel, mc::kClselSio).ok);
    }
    s.idle(40ms);
    ASSERT_TRUE(s.write(Face::lustbus, mc::kSwdgt, 50).ok);
    s.idle(80ms);
    ASSERT_TRUE(s.core().serial_watchdog_fault()) << name(f);
    EXPECT_EQ(s.core().state(), State::fault) << name(f);
    EXPECT_EQ(s.core().parameters().serr() & mc::kSerrWatchdog, mc::kSerrWatchdog);
    s.read(Face::lustbus, mc::kSerr);
    // The other interface's reset does not act: it has not the control location.
    if (f == Face::pcp) {
      ASSERT_TRUE(s.write(Face::lustbus, mc::kSctl1, 0x80).ok);
    } else {
      s.set_control_word(0x0080);
      s.tick();
      s.set_control_word(0x0000);
    }
    s.tick();
    ASSERT_TRUE(s.core().serial_watchdog_fault()) << name(f);
    EXPECT_EQ(s.core().state(), State::fault) << name(f);
    if (f == Face::pcp) {
      s.set_control_word(0x0080);
      s.tick();
      s.set_control_word(0x0000);
    } else {
      ASSERT_TRUE(s.write(Face::lustbus, mc::kSctl1, 0x80).ok);
    }
    s.tick();
    EXPECT_FALSE(s.core().serial_watchdog_fault()) << name(f);
    // Out of FAULT (transition 15); on SIO the drive then walks on to READY TO SWITCH ON itself.
    EXPECT_EQ(s.core().state(), f == Face::pcp ? State::start_up_inhibit : State::ready) << name(f);
    if (f == Face::lustbus) {
      EXPECT_EQ(s.core().parameters().raw(mc::kSctl1) & mc::kSctl1Reset, 0U) << "a command, not kept";
    }
  }
}

// LUSTBUS manual 7.2 step 2, INTERBUS manual 3.2.1 (MC-D4): with both faces the INTERBUS face samples the
// drive; 402-CLSEL decides whose commands it follows -- the fieldbus's control word with the
// factory OPT1, 416-SCTL1 with SIO.
TEST(Mc6000Faces, ControlLocationDecidesWhichFaceCommands) {
  Servo s;
  EXPECT_FALSE(s.core().serial_control());
  ASSERT_TRUE(s.write(Face::lustbus, 300, mc::kCfconScon).ok);
  ASSERT_TRUE(s.write(Face::lustbus, mc::kSctl1, 1).ok);
  s.idle(10ms);
  EXPECT_EQ(s.core().state(), State::start_up_inhibit) << "SCTL1 does not command on OPT1";
  s.set_control_word(0x0006);  // SHUTDOWN
  s.idle(5ms);
  s.set_control_word(0x000F);  // ENABLE OPERATION
  s.idle(5ms);
  EXPECT_EQ(s.core().state(), State::enabled) << "the fieldbus commands on OPT1";
  s.set_control_word(0x0006);
  s.idle(500ms);
  ASSERT_TRUE(s.write(Face::pcp, mc::kClsel, mc::kClselSio).ok);  // the master hands over
  s.idle(10ms);
  EXPECT_TRUE(s.core().serial_control());
  EXPECT_EQ(s.core().state(), State::enabled) << "416-SCTL1 bit 0 commands on SIO";
  ASSERT_TRUE(s.write(Face::lustbus, mc::kSctl1, 0).ok);
  s.idle(5ms);
  EXPECT_EQ(s.core().state(), State::ready);
}

// INTERBUS manual 4.2: "When the servocontroller parameters have been changed, parameter 15-PLRDY should
// be set to 1 to trigger recalculation of the controller parameters and set the servocontroller
// to 'READY' mode"; LUSTBUS manual 11.2.1, InitControl (0040H): "If a parameter is overwritten with the
// attribute, then the [servo] will register a[n] ... initialization because it must calculate its
// initialization value anew" (MC-D11). The same through either face, in the core: a changed
// 300-CFCON (InitControl) takes the servo out of READY mode -- 15-PLRDY reads 0 on both faces and
// ENABLE stops in ON (the servo cannot be engaged, as during 11.4's download) -- until 15-PLRDY = 1
// recalculates (counted) and READY mode is back: PLRDY reads 1 and ENABLE goes on. An InitControl
// parameter written with the value it has registers nothing (7.2.1 writes 300 = SCON, the factory
// value, and starts at once); a start (power-on) calculates the controller: READY mode.
TEST(Mc6000Faces, Plrdy1RecalculatesAndSetsReadyModeThroughEitherFace) {
  for (const Face f : kFaces) {
    const Face other = f == Face::pcp ? Face::lustbus : Face::pcp;
    Servo s;
    EXPECT_EQ(s.read(f, mc::kPlrdy).raw, 1U) << name(f) << ": READY mode from the start";
    ASSERT_TRUE(s.write(f, mc::kCfcon, mc::kCfconScon).ok) << name(f);
    EXPECT_EQ(s.read(other, mc::kPlrdy).raw, 1U) << name(f) << ": its own value registers nothing";
    s.idle(40ms);  // the EEPROM save of the one before (LUSTBUS manual 3)
    ASSERT_TRUE(s.write(f, mc::kCfcon, 1).ok) << name(f);  // another control type
    EXPECT_EQ(s.read(f, mc::kPlrdy).raw, 0U) << name(f);
    EXPECT_EQ(s.read(other, mc::kPlrdy).raw, 0U) << name(f);
    EXPECT_FALSE(s.core().ready_mode()) << name(f);
    s.set_control_word(0x0006);  // SHUTDOWN
    s.idle(5ms);
    s.set_control_word(0x000F);  // ENABLE OPERATION
    s.idle(20ms);
    EXPECT_EQ(s.core().state(), State::on) << name(f) << ": not engaged before the recalculation";
    const std::uint32_t before = s.core().recalculations();
    ASSERT_TRUE(s.write(f, mc::kPlrdy, 1).ok) << name(f);
    EXPECT_EQ(s.core().recalculations(), before + 1) << name(f);
    EXPECT_EQ(s.read(other, mc::kPlrdy).raw, 1U) << name(f);
    s.idle(5ms);
    EXPECT_EQ(s.core().state(), State::enabled) << name(f) << ": READY mode, ENABLE goes on";
    // 15-PLRDY has the attribute itself: 0 registers an initialization, a new start ends it.
    s.set_control_word(0x0006);
    s.idle(5ms);
    ASSERT_TRUE(s.write(f, mc::kPlrdy, 0).ok) << name(f);
    EXPECT_FALSE(s.core().ready_mode()) << name(f);
    s.core().power_on(s.now());
    EXPECT_TRUE(s.core().ready_mode()) << name(f);
    EXPECT_EQ(s.core().parameters().raw(mc::kPlrdy), 1U) << name(f);
  }
}

// DeviceEmulator::clone: a copy of the INTERBUS face is an independent servo with its own core.
TEST(Mc6000Faces, CloneOfAFaceClonesItsCore) {
  Servo s;
  ASSERT_TRUE(s.write(Face::pcp, 83, 11).ok);
  const auto copy = s.interbus().clone();
  auto& twin = dynamic_cast<ibs::devices::Mc6000Device&>(*copy);
  EXPECT_NE(&twin.drive(), &s.core());
  EXPECT_EQ(twin.drive().parameters().raw(83), 11U);
  ASSERT_TRUE(s.write(Face::lustbus, 83, 12).ok);
  EXPECT_EQ(twin.drive().parameters().raw(83), 11U);
  EXPECT_EQ(twin.pcp()->served().table().data(), twin.drive().store().table().data());
}

}  // namespace

// --- Plant and fault events (issue 24; devices/plant_event.hpp), once in the core ---------------

ibs::devices::PlantEvent event(ibs::devices::PlantEvent::Kind k) {
  ibs::devices::PlantEvent e;
  e.kind = k;
  return e;
}
using Kind = ibs::devices::PlantEvent::Kind;

TEST(Mc6000Events, ADeviceFaultWithItsCauseShowsOnBothFaces) {
  // LUSTBUS manual 8: the servo shows an error in its status word on every bus; 408-IBSTA mirrors it
  // for LUSTBUS (INTERBUS manual 4.2.1). The cause is its error number, 16 = E-OP1 (INTERBUS manual 3.2.4).
  Servo s;
  auto e = event(Kind::fault);
  e.cause = 16;
  ASSERT_TRUE(s.interbus().apply_event(e, s.now()));
  s.idle(5ms);
  EXPECT_EQ(s.core().fault_cause(), 16);
  EXPECT_EQ(s.core().state(), State::fault);
  EXPECT_NE(s.interbus().status_word() & 0x0008U, 0U) << "DRIVECOM bit 3: fault";
  EXPECT_NE(s.read(Face::lustbus, mc::kIbsta).raw & 0x0008U, 0U);
  EXPECT_NE(s.read(Face::pcp, mc::kIbsta).raw & 0x0008U, 0U);
  ASSERT_TRUE(s.interbus().apply_event(event(Kind::fault_clear), s.now()));
  EXPECT_EQ(s.core().fault_cause(), std::nullopt);
}

TEST(Mc6000Events, InputsShowInStatusBits14And15WhileTheirSelectorIsRopt1) {
  // INTERBUS manual 5.3.2: "Bit 14 reflects the actual state of input IS00 when parameter 439-FIS00 =
  // ROPT1", bit 15 IS01 with 440-FIS01; the seeds give the inputs no other effect.
  Servo s;
  auto in = event(Kind::input);
  in.input = 0;
  in.level = true;
  ASSERT_TRUE(s.interbus().apply_event(in, s.now()));
  s.idle(2ms);
  EXPECT_EQ(s.interbus().status_word() & 0xC000U, 0x4000U);
  EXPECT_EQ(s.read(Face::lustbus, mc::kIbsta).raw & 0xC000U, 0x4000U);
  in.input = 1;
  ASSERT_TRUE(s.interbus().apply_event(in, s.now()));
  s.idle(2ms);
  EXPECT_EQ(s.interbus().status_word() & 0xC000U, 0xC000U);
  // Another function on 439: bit 14 no longer shows IS00.
  ASSERT_TRUE(s.write(Face::lustbus, mc::kFis00, mc::kFunctionOff).ok);
  s.idle(2ms);
  EXPECT_EQ(s.interbus().status_word() & 0xC000U, 0x8000U);
  in.level = false;
  ASSERT_TRUE(s.interbus().apply_event(in, s.now()));
  s.idle(2ms);
  EXPECT_EQ(s.interbus().status_word() & 0xC000U, 0x0000U);
}

TEST(Mc6000Events, ALoadTorqueIsHeldByTheSpeedLoop) {
  // The load goes into the plant (plant.hpp, Nm): enabled at 0 rpm, the speed loop answers a
  // braking load with the same torque; without one it holds no torque.
  Servo s;
  s.set_control_word(0x0006);
  s.idle(5ms);
  s.set_control_word(0x000F);
  s.idle(200ms);
  ASSERT_EQ(s.core().state(), State::enabled);
  EXPECT_NEAR(s.core().torque_nm(), 0.0, 0.05);
  auto load = event(Kind::load);
  load.value = 2.0;
  ASSERT_TRUE(s.interbus().apply_event(load, s.now()));
  EXPECT_EQ(s.core().load_torque(), 2.0);
  s.idle(500ms);
  EXPECT_NEAR(s.core().torque_nm(), 2.0, 0.2) << "the drive's torque balances the load";
  EXPECT_NEAR(s.core().actual_rpm(), 0.0, 5.0);
}

TEST(Mc6000Events, MainsLossSilencesBothFacesAndTheReturnIsAPowerOn) {
  // MC-D6: mains lost = the servo off (a module error, no LUSTBUS answer); back = a power-on
  // with the 85-SERR power-on bit (LUSTBUS manual 9.2).
  Servo s;
  s.read(Face::lustbus, mc::kSerr);  // clears the power-on bit of the start
  ASSERT_TRUE(s.interbus().apply_event(event(Kind::mains_off), s.now()));
  s.idle(5ms);
  EXPECT_TRUE(s.interbus().module_error(s.now()));
  EXPECT_FALSE(s.read(Face::lustbus, mc::kSerr).ok) << "no answer without mains";
  ASSERT_TRUE(s.interbus().apply_event(event(Kind::mains_on), s.now()));
  s.idle(5ms);
  EXPECT_FALSE(s.interbus().module_error(s.now()));
  const Answer serr = s.read(Face::lustbus, mc::kSerr);
  ASSERT_TRUE(serr.ok);
  EXPECT_EQ(serr.raw & mc::kSerrPowerOn, mc::kSerrPowerOn);
}

TEST(Mc6000Events, ASmartcardOperationDisablesBothBusesForItsTime) {
  // LUSTBUS manual 10 exception 2: "While a SMARTCARD is being read in, no communications with the
  // device via the LUSTBUS is possible. This condition can last up to 10 seconds, depending on
  // the device" -- "device" is either series (000, 1). INTERBUS manual says for the INTERBUS only, in
  // the VF1000's 6.1, "While the SMARTCARD is being read and written to bus operation is
  // disabled"; it has no MC6000 section that says otherwise. Decision MC-D9, as VF-E21: for the
  // operation's time the INTERBUS face shows a module error and takes no words (nor PCP frames),
  // the LUSTBUS face hears nothing; the servo runs on as last commanded and keeps its values;
  // the silence the servo made itself trips neither watchdog; afterwards both faces answer as
  // before, without a new start (no power-on bit).
  struct Row {
    Kind kind;
    Duration time;
  };
  for (const Row row : {Row{Kind::card_read, 2s}, Row{Kind::card_write, 3s}}) {
    SCOPED_TRACE(row.kind == Kind::card_read ? "read" : "written");
    Servo s;
    ASSERT_TRUE(s.read(Face::lustbus, mc::kSerr).ok);  // the power-on bit of the start read
    ASSERT_TRUE(s.write(Face::pcp, 83, 1234).ok);
    ASSERT_TRUE(s.write(Face::lustbus, 409, 100).ok);  // 409-BUTWD: 100 ms (INTERBUS manual 3.2.4)
    s.idle(40ms);                                       // its EEPROM save
    auto card = event(row.kind);
    card.value = std::chrono::duration<double>(row.time).count();
    const Time from = s.now();
    ASSERT_TRUE(s.interbus().apply_event(card, s.now()));
    s.idle(50ms);
    EXPECT_TRUE(s.interbus().module_error(s.now()));
    EXPECT_FALSE(s.read(Face::lustbus, 83).ok) << "no LUSTBUS answer during the operation";
    // The master's control word is not taken while the card is busy.
    s.set_control_word(0x0006);
    s.idle(100ms);
    EXPECT_EQ(s.core().state(), State::start_up_inhibit);
    while (s.now() < from + row.time) s.tick();
    s.idle(50ms);
    EXPECT_FALSE(s.interbus().module_error(s.now()));
    EXPECT_EQ(s.core().state(), State::ready) << "the words count again";
    EXPECT_FALSE(s.core().bus_watchdog_fault()) << "the servo's own silence is no E-OP1";
    const Answer lb = s.read(Face::lustbus, 83);
    ASSERT_TRUE(lb.ok);
    EXPECT_EQ(lb.raw, 1234U);
    const Answer ib = s.read(Face::pcp, 83);
    ASSERT_TRUE(ib.ok);
    EXPECT_EQ(ib.raw, 1234U);
    EXPECT_EQ(s.read(Face::lustbus, mc::kSerr).raw, 0U) << "no new start: no power-on bit";
  }
}

// INTERBUS manual 3.2.1 "Modified Factory Default": "The MC6000 servocontroller detects the INTERBUS
// card automatically on power-on. The first time it is detected the following parameters are
// changed in the MC6000 for INTERBUS operation" (the table), "After the INTERBUS card has been
// withdrawn from the MC6000 these parameters are reset to their factory defaults the next time
// the device is powered-up." The table's eleven rows, 443/444 included; the factory defaults
// without the card are not in the seeds: every selector at code 0, the one that names no option
// (RCON, OFF; CLSEL TERM) -- decision MC-D10.
struct OptionRow {
  std::uint16_t number;
  const char* name;
  std::uint32_t interbus;  // 3.2.1's value
  std::uint32_t factory;   // without the card (MC-D10)
  std::uint32_t user;      // a value the user sets meanwhile
};
constexpr OptionRow kOptionTable[] = {
    {402, "CLSEL", 4 /* OPT1 */, 0 /* TERM */, 2 /* SIO */},
    {417, "RSSL1", 0 /* RCON */, 0, 3 /* RSIO */},
    {418, "RSSL2", 0 /* RCON */, 0, 3},
    {419, "RSSL3", 6 /* OPT1 */, 0 /* RCON */, 3},
    {420, "RSSL4", 0 /* RCON */, 0, 3},
    {439, "FIS00", 6 /* ROPT1 */, 0 /* OFF */, 1},
    {440, "FIS01", 6 /* ROPT1 */, 0, 1},
    {445, "FOS00", 6 /* ROPT1 */, 0, 1},
    {446, "FOS01", 6 /* ROPT1 */, 0, 1},
    {443, "FIF0", 0 /* OFF */, 0, 1},
    {444, "FIF1", 0 /* OFF */, 0, 1},
};

void expect_option_values(Servo& s, std::uint32_t OptionRow::*column, const char* what) {
  for (const OptionRow& row : kOptionTable) {
    const Answer a = s.read(Face::lustbus, row.number);
    ASSERT_TRUE(a.ok) << row.name;
    EXPECT_EQ(a.raw, row.*column) << row.number << "-" << row.name << ": " << what;
    EXPECT_EQ(s.lustbus().eeprom_value(row.number), row.*column) << row.number << "-" << row.name << ": " << what
                                                                  << " (EEPROM)";
  }
}

TEST(Mc6000Events, WithdrawingTheInterbusCardRestoresFactoryDefaultsAtTheNextPowerOn) {
  Servo s;
  // The card is in and was detected: 3.2.1's values.
  expect_option_values(s, &OptionRow::interbus, "with the card");
  ASSERT_TRUE(s.read(Face::lustbus, mc::kSerr).ok);
  for (const OptionRow& row : kOptionTable) {
    ASSERT_TRUE(s.write(Face::lustbus, row.number, row.user).ok) << row.name;
    s.idle(20ms);  // the EEPROM save of one byte (LUSTBUS manual 3)
  }
  // Withdrawn: the card is gone at once (no INTERBUS answer: a module error, MC-D10); the serial
  // interface is the servo's own; the values change only at the next power-on.
  ASSERT_TRUE(s.interbus().apply_event(event(Kind::option_withdrawn), s.now()));
  s.idle(10ms);
  EXPECT_TRUE(s.interbus().module_error(s.now()));
  expect_option_values(s, &OptionRow::user, "withdrawn, not yet powered up");
  ASSERT_TRUE(s.interbus().apply_event(event(Kind::power_cycle), s.now()));
  s.idle(10ms);
  EXPECT_TRUE(s.interbus().module_error(s.now())) << "no card, no INTERBUS";
  expect_option_values(s, &OptionRow::factory, "the first power-on without the card");
  // Once: what the user sets afterwards stays at the next power-on without the card.
  ASSERT_TRUE(s.read(Face::lustbus, mc::kSerr).ok);
  ASSERT_TRUE(s.write(Face::lustbus, mc::kClsel, mc::kClselSio).ok);
  s.idle(20ms);
  ASSERT_TRUE(s.interbus().apply_event(event(Kind::power_cycle), s.now()));
  s.idle(10ms);
  EXPECT_EQ(s.read(Face::lustbus, mc::kClsel).raw, static_cast<std::uint32_t>(mc::kClselSio));
  // 4-PROG = 1 loads the factory defaults of the servo as it stands: without the card, these.
  ASSERT_TRUE(s.read(Face::lustbus, mc::kSerr).ok);
  ASSERT_TRUE(s.write(Face::lustbus, mc::kProg, 1).ok);
  expect_option_values(s, &OptionRow::factory, "4-PROG = 1 without the card");
  // It reset 405-SUPI / 406-IBCNF as well: the ring's layout written back (3.2.2, 3.2.3).
  ASSERT_TRUE(s.write(Face::lustbus, mc::kSupi, 9).ok);
  s.idle(20ms);
  ASSERT_TRUE(s.write(Face::lustbus, mc::kIbcnf, 1).ok);
  s.idle(20ms);
  // Inserted: detected at the next power-on only (3.2.1); then 3.2.1's values again and the
  // INTERBUS face serves, its PCP starting over.
  ASSERT_TRUE(s.interbus().apply_event(event(Kind::option_inserted), s.now()));
  s.idle(10ms);
  EXPECT_TRUE(s.interbus().module_error(s.now())) << "not detected before a power-on";
  ASSERT_TRUE(s.interbus().apply_event(event(Kind::power_cycle), s.now()));
  s.idle(10ms);
  EXPECT_FALSE(s.interbus().module_error(s.now()));
  expect_option_values(s, &OptionRow::interbus, "detected again");
  ASSERT_TRUE(s.connect());
  ASSERT_TRUE(s.read(Face::lustbus, mc::kSerr).ok);
  const Answer clsel = s.read(Face::pcp, mc::kClsel);
  ASSERT_TRUE(clsel.ok);
  EXPECT_EQ(clsel.raw, static_cast<std::uint32_t>(mc::kClselOpt1));
}

TEST(Mc6000Events, ACardWithdrawnAndPutBackBeforeAPowerOnChangesNothing) {
  // 3.2.1: detection is at power-on; a card that is in at the next power-on was not withdrawn.
  Servo s;
  ASSERT_TRUE(s.read(Face::lustbus, mc::kSerr).ok);
  for (const OptionRow& row : kOptionTable) {
    ASSERT_TRUE(s.write(Face::lustbus, row.number, row.user).ok) << row.name;
    s.idle(20ms);
  }
  ASSERT_TRUE(s.interbus().apply_event(event(Kind::option_withdrawn), s.now()));
  s.idle(10ms);
  ASSERT_TRUE(s.interbus().apply_event(event(Kind::option_inserted), s.now()));
  ASSERT_TRUE(s.interbus().apply_event(event(Kind::power_cycle), s.now()));
  s.idle(10ms);
  EXPECT_FALSE(s.interbus().module_error(s.now()));
  expect_option_values(s, &OptionRow::user, "the card was in at the power-on");
}

TEST(Mc6000Events, WithTheCardWithdrawnNoCycleReachesTheServo) {
  // MC-D10: the card is physically gone: the INTERBUS face shows a module error and takes no
  // words; the servo runs on as last commanded, and its bus watchdog 409-BUTWD (INTERBUS manual 3.2.4)
  // sees no cycle: error 16 E-OP1 once it runs out.
  Servo s;
  ASSERT_TRUE(s.read(Face::lustbus, mc::kSerr).ok);
  ASSERT_TRUE(s.write(Face::lustbus, 409, 50).ok);
  s.idle(40ms);
  s.set_control_word(0x0006);
  s.idle(10ms);
  ASSERT_EQ(s.core().state(), State::ready);
  ASSERT_TRUE(s.interbus().apply_event(event(Kind::option_withdrawn), s.now()));
  s.set_control_word(0x0000);
  s.idle(20ms);
  EXPECT_EQ(s.core().state(), State::ready) << "the last words hold";
  EXPECT_FALSE(s.core().bus_watchdog_fault());
  s.idle(60ms);
  EXPECT_TRUE(s.core().bus_watchdog_fault());
  EXPECT_EQ(s.interbus().error_number(), mc::kWatchdogError);
}

// --- Programmable error reactions (LUSTBUS manual 5.2, 8, 8.1.2; docs/errata.md MC-D7) -------------

namespace {

// The servo running at 1000 rpm under the control of face `f`'s interface: the fieldbus's control
// word for PCP, 416-SCTL1 / 428-RSIO with 402-CLSEL = SIO for LUSTBUS (LUSTBUS manual 7.2.1). 512-REDEV
// (the reaction to a device fault numbered other than 16) is programmed to `reaction` through the
// same face, at standstill (an EEPROM value).
void run_with_reaction(Servo& s, Face f, std::uint32_t reaction) {
  ASSERT_TRUE(s.write(f, mc::kRedev, reaction).ok) << name(f) << " " << reaction;
  s.idle(40ms);  // the EEPROM save (15 ms per byte)
  if (f == Face::pcp) {
    s.set_reference(1000);
    s.set_control_word(0x0006);
    s.idle(5ms);
    s.set_control_word(0x000F);
  } else {
    ASSERT_TRUE(s.write(f, mc::kClsel, mc::kClselSio).ok);
    s.idle(40ms);
    ASSERT_TRUE(s.write(f, mc::kRssl1, mc::kRsslRsio).ok);
    s.idle(40ms);
    ASSERT_TRUE(s.write(f, mc::kRsio, 1000U << 16U).ok);
    ASSERT_TRUE(s.write(f, mc::kSctl1, mc::kSctl1Start).ok);
  }
  s.idle(400ms);
  ASSERT_EQ(s.core().state(), State::enabled) << name(f);
  ASSERT_NEAR(s.core().actual_rpm(), 1000.0, 20.0) << name(f);
}

enum class AfterReset { runs_on, out_of_fault, still_fault, boots };

struct ReactionRow {
  std::uint32_t reaction;
  const char* name;
  State during;       // 2 ms after the fault came, at 1000 rpm
  bool alarm;         // status word bit 7 (INTERBUS manual 5.1.3) while the cause lasts
  bool brakes;        // the motor is braked (torque against the motion) rather than coasting
  AfterReset reset;   // the cause gone, the fault reset given through the face
};

// LUSTBUS manual 8: "The error reaction of the MasterControl servocontroller is programmable, in five
// steps, for every error"; 8.1.2 names step 5, RESET; steps 1-4 are MC-D7's decision.
constexpr ReactionRow kReactionTable[] = {
    {1, "WARN", State::enabled, true, false, AfterReset::runs_on},
    {2, "STOP", State::fault_response_active, false, true, AfterReset::out_of_fault},
    {3, "OFF", State::fault, false, false, AfterReset::out_of_fault},
    {4, "LOCK", State::fault, false, false, AfterReset::still_fault},
    {5, "RESET", State::fault, false, false, AfterReset::boots},
};

}  // namespace

TEST(Mc6000Reactions, FiveStepsAndTheirResetThroughEitherFace) {
  for (const Face f : kFaces) {
    for (const ReactionRow& row : kReactionTable) {
      SCOPED_TRACE(name(f) + " " + row.name);
      Servo s;
      run_with_reaction(s, f, row.reaction);
      ASSERT_EQ(s.read(f, mc::kSerr).raw, 0U);
      auto e = event(Kind::fault);
      e.cause = 7;
      ASSERT_TRUE(s.interbus().apply_event(e, s.now()));
      s.idle(2ms);
      EXPECT_EQ(s.core().state(), row.during);
      EXPECT_EQ((s.core().status_word() & 0x0080U) != 0, row.alarm) << "bit 7, alarm";
      EXPECT_EQ(s.core().torque_nm() < -1.0, row.brakes) << s.core().torque_nm() << " Nm";
      if (!row.brakes && row.reaction != 1) {
        EXPECT_NEAR(s.core().torque_nm(), 0.0, 0.5) << "the power stage is off: the motor coasts";
      }
      s.idle(300ms);
      if (row.reaction == 1) {
        EXPECT_NEAR(s.core().actual_rpm(), 1000.0, 20.0) << "a warning: the drive runs on";
      } else {
        EXPECT_EQ(s.core().state(), State::fault);
      }
      ASSERT_TRUE(s.interbus().apply_event(event(Kind::fault_clear), s.now()));
      s.idle(2ms);
      EXPECT_EQ(s.core().status_word() & 0x0080U, 0U) << "the alarm goes with its cause";

      // 8.1.2: 416-SCTL1 bit 7 over LUSTBUS (bit 0 kept: the drive may start again), control word
      // bit 7 over INTERBUS (with ENABLE) -- each from its control location (MC-D4).
      std::vector<std::uint8_t> answer;
      if (f == Face::pcp) {
        s.set_control_word(0x008F);
        s.tick();
      } else {
        answer = s.select_answer(mc::kSctl1, 0x81);
        const std::size_t full = row.reset == AfterReset::boots ? 1U : 2U;
        ASSERT_EQ(answer.size(), full) << "8.1.2: the ACK of a reset that boots is not sent in full";
        EXPECT_EQ(answer[0], 3U + 64U) << "ADR";
        if (full == 2) {
          EXPECT_EQ(answer[1], lb::kAck);
        }
      }
      s.idle(2ms);
      switch (row.reset) {
        case AfterReset::runs_on:
          EXPECT_EQ(s.core().state(), State::enabled);
          break;
        case AfterReset::out_of_fault:
          EXPECT_NE(s.core().state(), State::fault);
          EXPECT_NE(s.core().state(), State::not_ready);
          EXPECT_EQ(s.core().parameters().serr(), 0U) << "no new start";
          break;
        case AfterReset::still_fault:
          EXPECT_EQ(s.core().state(), State::fault) << "LOCK: the reset does not end it";
          s.idle(600ms);
          EXPECT_EQ(s.core().state(), State::fault);
          // Only a power-on does.
          ASSERT_TRUE(s.interbus().apply_event(event(Kind::power_cycle), s.now()));
          s.idle(600ms);
          EXPECT_NE(s.core().state(), State::fault);
          break;
        case AfterReset::boots: {
          EXPECT_EQ(s.core().state(), State::not_ready) << "the servo boots";
          EXPECT_EQ(s.core().parameters().serr(), mc::kSerrPowerOn) << "9.2: power-on bit after a reset";
          // "The connection ... is broken for the duration of the boot-up".
          EXPECT_FALSE(s.read(Face::lustbus, mc::kSerr).ok);
          s.idle(600ms);
          EXPECT_NE(s.core().state(), State::not_ready) << "booted";
          EXPECT_NE(s.core().state(), State::fault);
          // "The SERR parameter (powerdown-report) must be read ... before the next SELECT".
          EXPECT_FALSE(s.write(Face::lustbus, 83, 1).ok);
          const Answer serr = s.read(Face::lustbus, mc::kSerr);
          ASSERT_TRUE(serr.ok);
          EXPECT_EQ(serr.raw, mc::kSerrPowerOn);
          EXPECT_TRUE(s.write(Face::lustbus, 83, 1).ok);
          EXPECT_EQ(s.core().held_reaction(), std::nullopt);
          break;
        }
      }
    }
  }
}

TEST(Mc6000Reactions, FactoryReactionIsStopForEveryError) {
  // The factory value of every reaction parameter is STOP (2): a reset clears the fault with a
  // full ACK and 85-SERR stays 00H -- the behaviour before the reactions were programmable.
  for (const std::uint16_t n : {mc::kReop1, mc::kResio, mc::kRedev}) {
    const auto* p = ibs::pcp::find_parameter(mc::kParameters, n);
    ASSERT_NE(p, nullptr) << n;
    EXPECT_EQ(p->default_value, mc::kReactionStop) << n;
    EXPECT_EQ(p->category, ibs::pcp::Category::eeprom) << n;
  }
}

TEST(Mc6000Reactions, EachErrorTakesTheReactionOfItsOwnParameter) {
  // LUSTBUS manual 5.2: the watchdog's reaction "via parameter"; INTERBUS manual 3.2.4: the bus watchdog is
  // error 16 E-OP1. 510-REOP1: error 16, from the bus watchdog or as a device fault's number;
  // 511-RESIO: the serial watchdog; 512-REDEV: every other device fault (MC-D7).
  struct Row {
    const char* error;
    std::uint16_t parameter;
  };
  const Row rows[] = {{"device fault 16 (E-OP1)", mc::kReop1},
                      {"device fault 7", mc::kRedev},
                      {"device fault without a number", mc::kRedev},
                      {"bus watchdog 409-BUTWD", mc::kReop1},
                      {"serial watchdog 84-SWDGT", mc::kResio}};
  for (const Row& row : rows) {
    SCOPED_TRACE(row.error);
    Servo s;
    // Three different reactions, so that each error shows whose it took.
    ASSERT_TRUE(s.write(Face::pcp, mc::kReop1, 1).ok);
    s.idle(40ms);
    ASSERT_TRUE(s.write(Face::pcp, mc::kResio, 3).ok);
    s.idle(40ms);
    ASSERT_TRUE(s.write(Face::pcp, mc::kRedev, 4).ok);
    s.idle(40ms);
    const std::string what = row.error;
    if (what.rfind("device fault", 0) == 0) {
      auto e = event(Kind::fault);
      if (what == "device fault 16 (E-OP1)") e.cause = 16;
      if (what == "device fault 7") e.cause = 7;
      ASSERT_TRUE(s.interbus().apply_event(e, s.now()));
      s.idle(2ms);
    } else if (what == "bus watchdog 409-BUTWD") {
      s.interbus().set_bus_watchdog(20ms);
      s.idle(5ms);
      s.silent(30ms);
      ASSERT_TRUE(s.core().bus_watchdog_fault());
    } else {
      ASSERT_TRUE(s.write(Face::lustbus, mc::kSwdgt, 50).ok);
      s.idle(80ms);
      ASSERT_TRUE(s.core().serial_watchdog_fault());
    }
    const auto expected = static_cast<mc::ErrorReaction>(s.core().parameters().raw(row.parameter));
    EXPECT_EQ(s.core().present_reaction(), expected);
    EXPECT_EQ(s.core().held_reaction(), expected);
    if (expected == mc::ErrorReaction::warn) {
      EXPECT_NE(s.core().status_word() & 0x0080U, 0U) << "a warning: bit 7";
      EXPECT_NE(s.core().state(), State::fault);
    } else {
      EXPECT_EQ(s.core().state(), State::fault);
    }
  }
}

TEST(Mc6000Reactions, OnlyTheFiveStepsAreTaken) {
  // LUSTBUS manual 8: "five steps", 1..5 (5 is RESET, 8.1.2); anything else is an invalid value, 80H
  // (9.2), through either face.
  for (const Face f : kFaces) {
    for (const std::uint16_t n : {mc::kReop1, mc::kResio, mc::kRedev}) {
      Servo s;
      EXPECT_FALSE(s.write(f, n, 0).ok) << name(f) << " " << n;
      EXPECT_EQ(s.read(f, mc::kSerr).raw, mc::kSerrInvalidValue) << name(f);
      EXPECT_FALSE(s.write(f, n, 6).ok) << name(f) << " " << n;
      EXPECT_EQ(s.read(f, mc::kSerr).raw, mc::kSerrInvalidValue) << name(f);
      EXPECT_TRUE(s.write(f, n, 5).ok) << name(f) << " " << n;
      s.idle(40ms);
      EXPECT_EQ(s.read(f == Face::pcp ? Face::lustbus : Face::pcp, n).raw, 5U) << "one store";
    }
  }
}

// --- Control word bits 12-15 (INTERBUS manual 5.3.1), status word bits 12-15 (5.3.2) -----------------

TEST(Mc6000Events, ControlBits14And15SetOutputsOs00AndOs01WhileTheirSelectorIsRopt1) {
  // INTERBUS manual 5.3.1: "Bit 14 controls the reference state of output OS00 directly when parameter
  // 445-FOS00 = ROPT1", bit 15 OS01 with 446-FOS01; bits 11-13 "Unoccupied". 5.3.2: status bits
  // 12 and 13 "Reserved".
  struct Row {
    Word control;
    bool os00;
    bool os01;
  };
  const Row rows[] = {{0x0000, false, false}, {0x4000, true, false}, {0x8000, false, true},
                      {0xC000, true, true},   {0x3800, false, false}, {0x4006, true, false}};
  Servo s;
  for (const Row& r : rows) {
    s.set_control_word(r.control);
    s.idle(2ms);
    EXPECT_EQ(s.core().digital_output(0), r.os00) << std::hex << r.control;
    EXPECT_EQ(s.core().digital_output(1), r.os01) << std::hex << r.control;
    EXPECT_EQ(s.interbus().status_word() & 0x3000U, 0U) << "bits 12, 13 reserved";
  }
  // The outputs follow the option's (INTERBUS's) word whichever interface has the control
  // location: ROPT1 names the source.
  s.set_control_word(0xC000);
  ASSERT_TRUE(s.write(Face::lustbus, mc::kClsel, mc::kClselSio).ok);
  s.idle(40ms);
  EXPECT_TRUE(s.core().digital_output(0));
  EXPECT_TRUE(s.core().digital_output(1));
  // Another function on 445: bit 14 no longer sets OS00.
  ASSERT_TRUE(s.write(Face::lustbus, mc::kFos00, mc::kFunctionOff).ok);
  s.idle(2ms);
  EXPECT_FALSE(s.core().digital_output(0));
  EXPECT_TRUE(s.core().digital_output(1));
  // Without mains, or after a new start, the outputs are off until the word comes again.
  ASSERT_TRUE(s.interbus().apply_event(event(Kind::mains_off), s.now()));
  EXPECT_FALSE(s.core().digital_output(1));
}
