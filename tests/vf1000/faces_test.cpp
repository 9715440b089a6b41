// One VF1000 drive core behind its two faces (../shared/design.md, "One drive, many faces"): the
// INTERBUS face (communication word, INTERBUS manual) and the LUSTBUS face (LUSTBUS manual) on one core serve
// one store; the same parameter access through each face gives the same answer, with the drive's
// timing expressed in each face's units. Decisions VF-E11 .. VF-E16 (docs/errata.md).
#include <gtest/gtest.h>

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "../lustbus_devices/support.hpp"
#include "ibs/devices/plant_event.hpp"
#include "ibs/devices/vf1000/descriptor.hpp"
#include "ibs/devices/vf1000/device.hpp"
#include "ibs/devices/vf1000/drive.hpp"
#include "ibs/devices/vf1000/lustbus_device.hpp"
#include "ibs/devices/vf1000/lustbus_face.hpp"
#include "ibs/devices/vf1000/parameters.hpp"
#include "ibs/vf1000_channel/client.hpp"

namespace {

using namespace std::chrono_literals;
using ibs::Duration;
using ibs::Time;
using ibs::Word;
using ibs::DeviceStart;
using ibs::devices::Vf1000Device;
using ibs::devices::Vf1000DeviceConfig;
using ibs::drivecom::State;
namespace vf = ibs::devices::vf1000;
namespace pnr = ibs::devices::vf1000::pnr;
namespace lb = ibs::lustbus;
namespace vc = ibs::vf1000_channel;

constexpr Duration kSample = vf::kSamplePeriod;
constexpr lb::Address kAddress = 1;

// INTERBUS manual 5.2.1 / 5.1.2: a DRIVECOM control word with the ramp bits 4-6 set.
constexpr Word kRampBits = 0x0070;

// What a parameter access ended with, in words both faces share.
struct Result {
  std::string kind;   // "value", "written", "nak"
  Word value = 0;     // value: the value read
  std::uint8_t siof = 0;  // nak: 85-SIOF as the master read it right after the NAK
  Duration took{};    // from the request to its answer
  bool operator==(const Result&) const = default;
};
std::ostream& operator<<(std::ostream& os, const Result& r) {
  return os << r.kind << " value " << r.value << " siof " << int(r.siof) << " took "
            << r.took.count() << " ns";
}

// A drive with whichever faces a test gives it: the INTERBUS face sampled every 8.2 ms in
// lockstep with its master (the communication-word client), the LUSTBUS face on a simulated
// line at 9600 Bd with its host, both on one timeline.
struct Rig {
  explicit Rig(bool interbus = true, bool serial = true,
               DeviceStart start = DeviceStart::operational, const vf::DriveConfig& config = {})
      : drive(std::make_shared<vf::Drive>(config, start, Time{0})) {
    // INTERBUS manual 6.1 (VF-E16): on the INTERBUS with the factory 1-MODE = 4 the serial interface
    // cannot be used; a rig that reaches the drive through both faces runs it at another MODE
    // (the INTERBUS words still control: VF-E16).
    if (interbus && serial) drive->set_value(pnr::kMode, 1);
    if (interbus) ib = std::make_unique<Vf1000Device>(Vf1000DeviceConfig{}, drive, Time{0});
    if (serial) {
      lbd = std::make_unique<vf::LustbusDevice>(drive);
      bus.add(*lbd, kAddress);
    }
    wait(200ms);  // the master's channel synchronised (ClientConfig::resync_hold)
    // The client reads 85 before its first transfer (it cannot know what happened before it);
    // done here, so that every test's transfers take their own time.
    if (ib) {
      EXPECT_EQ(ib_write(pnr::kSiow, 0).kind, "written");
    }
  }

  // One 8.2 ms sample of the INTERBUS face (when there is one), the line brought to that time.
  void tick() {
    now += kSample;
    if (ib) {
      m2s[2] = master.step(s2m[2], now);
      ib->bus_cycle(now);
      ib->sample(m2s, s2m, now);
    }
    drive->advance(now);  // the drive's own time passes between telegrams
    bus.line.run_until(now);
  }
  void wait(Duration d) {
    const Time until = now + d;
    while (now < until) tick();
  }

  Result lustbus(const lb::Request& r) {
    const Time start = now;
    const auto s = bus.host.submit(r);
    EXPECT_TRUE(s);
    for (int i = 0; i < 2000; ++i) {
      tick();
      if (const lb::Outcome* o = bus.host.outcome(s.id)) {
        Result res;
        res.took = o->finished - start;
        switch (o->kind) {
          case lb::OutcomeKind::value: {
            res.kind = "value";
            const auto raw = lb::parse_raw(lb::Family::standard, o->value.view());
            EXPECT_TRUE(raw.ok());
            res.value = static_cast<Word>(raw.value);
            break;
          }
          case lb::OutcomeKind::acknowledged: res.kind = "written"; break;
          case lb::OutcomeKind::nak:
            res.kind = "nak";
            res.siof = o->siof.value_or(0xFF);
            break;
          default: res.kind = std::string(lb::to_string(o->kind)); break;
        }
        return res;
      }
    }
    ADD_FAILURE() << "no LUSTBUS outcome";
    return {};
  }
  Result lb_read(std::uint16_t number) {
    return lustbus(lb::enquiry(kAddress, lb::make_code(100U + number)));
  }
  // `wait_for`: how long the host waits for the answer (the seed's "up to 10 seconds" of 71-PROG).
  Result lb_write(std::uint16_t number, Word value, Duration wait_for = Duration{0}) {
    char v[5];
    std::snprintf(v, sizeof v, "%04X", static_cast<unsigned>(value));
    lb::Request req = lb::select(kAddress, lb::make_code(100U + number), lb::make_value(v));
    if (wait_for > Duration{0}) req.response_timeout = wait_for;
    return lustbus(req);
  }

  Result interbus(const vc::Request& r) {
    const Time start = now;
    const auto s = master.submit(r);
    EXPECT_TRUE(s);
    for (int i = 0; i < 2000; ++i) {
      tick();
      if (const vc::Outcome* o = master.outcome(s.id)) {
        Result res;
        res.took = now - start;
        switch (o->kind) {
          case vc::OutcomeKind::value: res.kind = "value"; res.value = o->value; break;
          case vc::OutcomeKind::written: res.kind = "written"; break;
          case vc::OutcomeKind::nak:
            res.kind = "nak";
            res.siof = o->nak_cause == vc::NakCause::siof ? o->siof : 0xFF;
            break;
          default: res.kind = std::string(vc::to_string(o->kind)); break;
        }
        return res;
      }
    }
    ADD_FAILURE() << "no INTERBUS outcome";
    return {};
  }
  Result ib_read(std::uint16_t number) { return interbus(vc::value_inquiry(number)); }
  Result ib_write(std::uint16_t number, Word value) {
    return interbus(vc::value_transfer(number, value));
  }

  // The master's control word (INTERBUS manual 5.1.2), held until changed.
  void control(Word w) { m2s[0] = w; }

  std::shared_ptr<vf::Drive> drive;
  std::unique_ptr<Vf1000Device> ib;
  std::unique_ptr<vf::LustbusDevice> lbd;
  lb::devtest::Bus bus;
  vc::Client master;
  std::array<Word, 3> m2s{0x0000, 0x0000, vc::Client::initial_word()};
  std::array<Word, 3> s2m{};
  Time now{0};
};

// The same access through a drive of its own behind each face (the results without `took`).
enum class Via { interbus, lustbus };
Result read(Rig& r, Via v, std::uint16_t n) { return v == Via::interbus ? r.ib_read(n) : r.lb_read(n); }
Result write(Rig& r, Via v, std::uint16_t n, Word value) {
  return v == Via::interbus ? r.ib_write(n, value) : r.lb_write(n, value);
}
Result untimed(Result r) {
  r.took = Duration{0};
  return r;
}
std::unique_ptr<Rig> rig_for(Via v, DeviceStart start = DeviceStart::operational) {
  return std::make_unique<Rig>(v == Via::interbus, v == Via::lustbus, start);
}

// --- One store -----------------------------------------------------------------------------------

TEST(Vf1000Faces, BothFacesServeTheOneStoreOfTheirDrive) {
  Rig r;
  ASSERT_TRUE(r.ib && r.lbd);
  // The one store: both faces reach the same object.
  EXPECT_EQ(&r.ib->drive(), r.drive.get());
  EXPECT_EQ(&r.lbd->drive(), r.drive.get());
  EXPECT_EQ(&r.ib->drive().store(), &r.lbd->drive().store());
  EXPECT_EQ(&r.ib->channel().parameters(), static_cast<const ibs::drive::ParameterAccess*>(r.drive.get()));

  // Written through the communication word, run to its ACK: LUSTBUS reads it.
  EXPECT_EQ(r.ib_write(pnr::kFmax1, 0x01F4).kind, "written");
  EXPECT_EQ(untimed(r.lb_read(pnr::kFmax1)), (Result{"value", 0x01F4, 0, {}}));
  EXPECT_EQ(r.drive->eeprom_value(pnr::kFmax1), 0x01F4);
  // And the other way: written by a SELECT, read by a value inquiry.
  EXPECT_EQ(r.lb_write(pnr::kVb2, 0x0064).kind, "written");
  EXPECT_EQ(untimed(r.ib_read(pnr::kVb2)), (Result{"value", 0x0064, 0, {}}));
  // A RAM value too (83-SIOW).
  EXPECT_EQ(r.ib_write(pnr::kSiow, 0x1234).kind, "written");
  EXPECT_EQ(r.lb_read(pnr::kSiow).value, 0x1234);
}

TEST(Vf1000Faces, ARefusalOnOneFaceLatches85ForTheOther) {
  // 85-SIOF is the drive's: a bit a refused SELECT set refuses the next value transfer on
  // INTERBUS until 85 is read (LUSTBUS manual 9.2; INTERBUS manual 4.1.4), and reading it there clears it.
  // A wrong BCC on the serial line sets 08H (9.2 bit 3); no host reads 85 after it.
  Rig r;
  r.lbd->checksum_error({kAddress, r.now});
  EXPECT_EQ(r.drive->siof(), 0x08);
  const Result w = r.ib_write(pnr::kFssel, 8);
  EXPECT_EQ(w.kind, "nak");
  EXPECT_EQ(w.siof, 0x08) << "the client read 85 after the NAK";
  EXPECT_EQ(r.drive->siof(), 0);
  EXPECT_EQ(r.lb_write(pnr::kFssel, 8).kind, "written");
}

// --- Conformance: the same access, the same answer --------------------------------------------

TEST(Vf1000Faces, ReadsAndWritesAnswerAlikeThroughEitherFace) {
  for (const Via v : {Via::interbus, Via::lustbus}) {
    SCOPED_TRACE(v == Via::interbus ? "INTERBUS" : "LUSTBUS");
    auto r = rig_for(v);
    EXPECT_EQ(untimed(read(*r, v, pnr::kFmax1)), (Result{"value", 1000, 0, {}}));
    EXPECT_EQ(untimed(write(*r, v, pnr::kFssel, 8)), (Result{"written", 0, 0, {}}));
    EXPECT_EQ(r->drive->value(pnr::kFssel), 8);
    EXPECT_EQ(r->drive->eeprom_value(pnr::kFssel), 8);
    // 11-STAT and 12 read the drive's state (LB-D19, VF-E14): ready, stopped.
    EXPECT_EQ(untimed(read(*r, v, pnr::kStat)), (Result{"value", vf::kStatReady, 0, {}}));
    EXPECT_EQ(untimed(read(*r, v, pnr::kFout)), (Result{"value", 0, 0, {}}));
  }
}

TEST(Vf1000Faces, EachRefusalSetsTheSameBitThroughEitherFace) {
  for (const Via v : {Via::interbus, Via::lustbus}) {
    SCOPED_TRACE(v == Via::interbus ? "INTERBUS" : "LUSTBUS");
    auto r = rig_for(v);
    // No parameter 99: 20H. Read-only 91-TYPE: 40H. 4-FSSEL 26 > 25: 80H. 11-STAT other than
    // 000FH: 80H (VF-E14). Each master reads 85 after the NAK, which clears it (9.2, 4.1.4).
    EXPECT_EQ(untimed(write(*r, v, 99, 0)), (Result{"nak", 0, 0x20, {}}));
    EXPECT_EQ(r->drive->siof(), 0);
    EXPECT_EQ(untimed(write(*r, v, pnr::kType, 1)), (Result{"nak", 0, 0x40, {}}));
    EXPECT_EQ(untimed(write(*r, v, pnr::kFssel, 26)), (Result{"nak", 0, 0x80, {}}));
    EXPECT_EQ(untimed(write(*r, v, pnr::kStat, 1)), (Result{"nak", 0, 0x80, {}}));
    // 81-SIOC in baud, the steps of the LUSTBUS manual 4 up to 9600 (LB-E18): 5000 is none, 19200 too high.
    EXPECT_EQ(untimed(write(*r, v, pnr::kSioc, 5000)), (Result{"nak", 0, 0x80, {}}));
    EXPECT_EQ(untimed(write(*r, v, pnr::kSioc, 19200)), (Result{"nak", 0, 0x80, {}}));
    EXPECT_EQ(r->drive->value(pnr::kSioc), 9600);
    EXPECT_EQ(r->drive->value(pnr::kFssel), 25);
    EXPECT_EQ(r->drive->siof(), 0);
    // A value inquiry of a missing parameter is refused without an entry in 85 (INTERBUS manual 4.1.4,
    // LUSTBUS manual 6.1 note).
    EXPECT_EQ(read(*r, v, 99).kind, "nak");
    EXPECT_EQ(r->drive->siof(), 0);
  }
}

TEST(Vf1000Faces, AnEepromParameterIsRefusedWhileThePowerStageRunsThroughEitherFace) {
  // INTERBUS manual 4.1.3.2 / LUSTBUS manual 3: EEPROM parameters are not writable with the power stage
  // enabled; 5-FSSIO (EEPROM/RAM) is still taken, into RAM. The drive runs from its serial interface
  // (LUSTBUS manual 7.1): the same drive state for both faces.
  for (const Via v : {Via::interbus, Via::lustbus}) {
    SCOPED_TRACE(v == Via::interbus ? "INTERBUS" : "LUSTBUS");
    Rig r(true, true);
    for (const auto& [n, value] : {std::pair{pnr::kMode, Word{0}}, {pnr::kCsel, Word{3}},
                                   {pnr::kFssel, Word{8}}, {pnr::kFssio, Word{100}},
                                   {pnr::kCntl, Word{0x80}}}) {
      ASSERT_EQ(r.lb_write(n, value).kind, "written") << n;
    }
    r.wait(100ms);
    ASSERT_TRUE(r.drive->power_stage_enabled());
    EXPECT_EQ(untimed(write(r, v, pnr::kFmax1, 900)), (Result{"nak", 0, 0x40, {}}));
    EXPECT_EQ(r.drive->value(pnr::kFmax1), 1000);
    EXPECT_EQ(untimed(write(r, v, pnr::kFssio, 200)), (Result{"written", 0, 0, {}}));
    EXPECT_EQ(r.drive->value(pnr::kFssio), 200);
    // CSEL = 3: 5-FSSIO is a RAM variable (LUSTBUS manual 11.1 kind '3'; VF-E18), so neither the 100
    // written before the start nor the 200 reached the EEPROM.
    EXPECT_EQ(r.drive->eeprom_value(pnr::kFssio), 0);
  }
}

TEST(Vf1000Faces, ThePowerOnBitAfterPowerOnAndAfterAFaultReset) {
  // LUSTBUS manual 6 and 9.2; INTERBUS manual 6.1: the power-on bit after every new start, which refuses
  // value transfers until 85 is read; a fault reset is a new start (LUSTBUS manual 8.1.1: 11-STAT =
  // 000FH over LUSTBUS; INTERBUS manual 5.2.1: RESET FAULT over INTERBUS -- the one place the seeds
  // make the trigger differ by bus). The self-test lasts the drive's reset time either way
  // (VF-E13).
  for (const Via v : {Via::interbus, Via::lustbus}) {
    SCOPED_TRACE(v == Via::interbus ? "INTERBUS" : "LUSTBUS");
    auto r = rig_for(v);
    r->drive->power_cycle(r->now);
    r->wait(4100ms);
    EXPECT_EQ(untimed(read(*r, v, pnr::kSiof)), (Result{"value", 0x01, 0, {}}));
    EXPECT_EQ(r->drive->siof(), 0);

    ASSERT_EQ(write(*r, v, pnr::kSiow, 0x4321).kind, "written");  // a RAM value
    r->drive->set_fault(true, r->now);
    r->wait(50ms);
    r->drive->set_fault(false, r->now);
    r->wait(50ms);
    ASSERT_EQ(r->drive->state(), State::fault);
    const std::uint32_t resets = r->drive->software_resets();
    if (v == Via::interbus) {
      r->control(0x0080);  // bit 7: RESET FAULT
      r->wait(20ms);
      r->control(0x0000);
    } else {
      EXPECT_EQ(r->lb_write(pnr::kStat, vf::kStatReset).kind, "bad_answer");  // the cut ACK
    }
    EXPECT_EQ(r->drive->software_resets(), resets + 1);
    EXPECT_TRUE(r->drive->initialising(r->now));
    r->wait(4100ms);
    EXPECT_FALSE(r->drive->initialising(r->now));
    EXPECT_EQ(untimed(read(*r, v, pnr::kSiow)), (Result{"value", 0, 0, {}})) << "RAM starts anew";
    EXPECT_EQ(untimed(read(*r, v, pnr::kSiof)), (Result{"value", 0x01, 0, {}}));
    EXPECT_EQ(r->drive->state(), v == Via::interbus ? State::start_up_inhibit : State::ready);
  }
}

TEST(Vf1000Faces, Prog1LoadsTheFactoryDefaultsAndTakesTheDrivesTimeThroughEitherFace) {
  // LUSTBUS manual 10 exception 1: the ACK only once every parameter is initialised; the time is the
  // drive's (1.5 s, LB-D18) on INTERBUS too, where INTERBUS manual names no time (VF-E11). The
  // INTERBUS face holds its ACK for whole 8.2 ms samples.
  for (const Via v : {Via::interbus, Via::lustbus}) {
    SCOPED_TRACE(v == Via::interbus ? "INTERBUS" : "LUSTBUS");
    auto r = rig_for(v);
    ASSERT_EQ(write(*r, v, pnr::kFssel, 8).kind, "written");
    ASSERT_EQ(write(*r, v, pnr::kSiow, 0x55).kind, "written");
    const Result plain = write(*r, v, pnr::kSiow, 0x56);  // a RAM value: no storing time
    const Result prog = v == Via::interbus ? r->ib_write(pnr::kProg, 1) : r->lb_write(pnr::kProg, 1, 10s);
    EXPECT_EQ(prog.kind, "written");
    const Duration storing = r->drive->config().storing.factory_defaults;
    // The time the drive took, beyond a plain write, in the face's units: whole 8.2 ms samples
    // rounded up on INTERBUS (183), reaction time on LUSTBUS.
    const Duration extra = prog.took - plain.took;
    EXPECT_GE(extra, storing);
    EXPECT_LT(extra, storing + (v == Via::interbus ? kSample : Duration{1ms}));
    EXPECT_EQ(r->drive->value(pnr::kFssel), 25);
    EXPECT_EQ(r->drive->eeprom_value(pnr::kFssel), 25);
    EXPECT_EQ(r->drive->value(pnr::kProg), 0) << "a command, not a setting";
  }
}

TEST(Vf1000Faces, AChangedEepromValueTakesTheSameDriveTimeThroughEitherFace) {
  // LUSTBUS manual 10 exception 4: about 120 ms for a changed two-byte value, 60 ms for one byte; seed
  // 001, 7.1: 250 ms instead of 124 for the communication word, the same 120 ms give or take a
  // sample (VF-E12). An unchanged value costs nothing.
  for (const Via v : {Via::interbus, Via::lustbus}) {
    SCOPED_TRACE(v == Via::interbus ? "INTERBUS" : "LUSTBUS");
    auto r = rig_for(v);
    const Result two_changed = write(*r, v, pnr::kFmax1, 0x01F4);
    const Result two_same = write(*r, v, pnr::kFmax1, 0x01F4);
    const Result one_changed = write(*r, v, pnr::kSouta, 7);
    const Result one_same = write(*r, v, pnr::kSouta, 7);
    for (const Result* w : {&two_changed, &two_same, &one_changed, &one_same}) {
      EXPECT_EQ(w->kind, "written");
    }
    if (v == Via::interbus) {
      // In the face's units: whole samples, rounded up (120 ms: 15, 60 ms: 8).
      EXPECT_EQ(two_changed.took - two_same.took, 15 * kSample);
      EXPECT_EQ(one_changed.took - one_same.took, 8 * kSample);
    } else {
      // In reaction time (the simulated line: whole characters, so compare to the microsecond).
      using Ms = std::chrono::duration<double, std::milli>;
      EXPECT_NEAR(Ms(two_changed.took - two_same.took).count(), 120.0, 8.3);
      EXPECT_NEAR(Ms(one_changed.took - one_same.took).count(), 60.0, 8.3);
    }
  }
}

TEST(Vf1000Faces, FselVariablesAreRamVariablesWhileTheSerialInterfaceControls) {
  // LUSTBUS manual 11.1, parameter kind '3' (FSEL/ISEL variable): "if CSEL <= 3, they are RAM variables
  // (control via serial interface). If CSEL < 3, they are EEPROM-Variables"; INTERBUS manual 4.1.3.3:
  // "The inverter stores changes to EEPROM/RAM parameters in the RAM when the power stage is
  // enabled, and additionally in the EEPROM when the power stage is disabled." Decision VF-E18:
  // 2-CSEL = 3 (the serial interface's control location) keeps them in RAM whatever the power
  // stage does; any other CSEL follows 001's rule. 5-FSSIO is such a variable (kind 3).
  struct Row {
    Word csel;
    bool power_stage;
    Word eeprom_after;  // 5-FSSIO's EEPROM copy after writing 200 over the default 0
    Duration storing;   // LUSTBUS manual 10 exception 4: a changed two-byte EEPROM value ~120 ms
  };
  const Row rows[] = {
      {3, false, 0, Duration{0}},  {3, true, 0, Duration{0}},  // RAM variable (11.1)
      {0, false, 200, 120ms},      {2, true, 0, Duration{0}},  // CSEL < 3: 001's rule
      {5, false, 200, 120ms},      {5, true, 0, Duration{0}},  // the INTERBUS factory CSEL
  };
  for (const Row& row : rows) {
    SCOPED_TRACE("CSEL " + std::to_string(row.csel) + (row.power_stage ? ", running" : ", stopped"));
    vf::Drive d(vf::DriveConfig{}, DeviceStart::operational, Time{0});
    ASSERT_TRUE(d.set_value(pnr::kCsel, row.csel));
    const auto slot = static_cast<std::size_t>(d.table().slot(pnr::kFssio));
    ASSERT_EQ(d.check_write(d.find(pnr::kFssio), 200, row.power_stage), ibs::drive::WriteCheck::ok);
    const auto e = d.write(slot, 200, row.power_stage, Time{0});
    EXPECT_EQ(d.value(pnr::kFssio), 200);
    EXPECT_EQ(d.eeprom_value(pnr::kFssio), row.eeprom_after);
    EXPECT_EQ(e.storing, row.storing);
  }
  // The same through either face: with CSEL = 3 a stopped drive acknowledges 5-FSSIO as fast as a
  // RAM value (the 122 ms of an EEPROM write were the fault), and a power-on brings back the
  // EEPROM's value, not the RAM's.
  for (const Via v : {Via::interbus, Via::lustbus}) {
    SCOPED_TRACE(v == Via::interbus ? "INTERBUS" : "LUSTBUS");
    auto r = rig_for(v);
    ASSERT_EQ(write(*r, v, pnr::kCsel, 3).kind, "written");
    ASSERT_FALSE(r->drive->power_stage_enabled());
    const Result ram = write(*r, v, pnr::kSiow, 0x0101);
    const Result fssio = write(*r, v, pnr::kFssio, 463);
    EXPECT_EQ(fssio.kind, "written");
    EXPECT_EQ(fssio.took, ram.took) << "a RAM variable: no storing time";
    EXPECT_EQ(r->drive->eeprom_value(pnr::kFssio), 0);
    ASSERT_EQ(write(*r, v, pnr::kCsel, 5).kind, "written");
    const Result eeprom = write(*r, v, pnr::kFssio, 100);
    EXPECT_GT(eeprom.took - ram.took, 100ms) << "CSEL 5, stopped: an EEPROM write";
    EXPECT_EQ(r->drive->eeprom_value(pnr::kFssio), 100);
  }
}

TEST(Vf1000Faces, AtAReferenceOf0HzTheInverterShutsTheMotorDownThroughEitherFace) {
  // INTERBUS manual 5.2.3: "Important: At a reference value of 0 Hz the inverter shuts down the motor if
  // DC-Stop is not programmed !" Decision VF-E19: once the ramp has reached 0 Hz at a reference of
  // 0 Hz the power stage is off (11-STAT without 02H, EEPROM values writable as at standstill,
  // LUSTBUS manual 3 and 11.1 kind '2'); DRIVECOM stays ENABLED (the master's command; 5.1.1 has no
  // transition the reference makes) and a reference above 0 Hz starts the motor from 0 Hz. No
  // seed names DC-Stop's parameter: the model's configuration (Vf1000PdConfig::dc_stop) keeps the
  // power stage on.
  struct Row {
    Word reference;  // 0.05 Hz
    bool dc_stop;
    bool power_stage;  // after the ramp has settled
  };
  const Row rows[] = {{0, false, false}, {100, false, true}, {0, true, true}, {100, true, true}};
  for (const Via v : {Via::interbus, Via::lustbus}) {
    for (const Row& row : rows) {
      SCOPED_TRACE(std::string(v == Via::interbus ? "INTERBUS" : "LUSTBUS") + ", reference " +
                   std::to_string(row.reference) + (row.dc_stop ? ", DC-Stop" : ""));
      vf::DriveConfig config;
      config.pd.dc_stop = row.dc_stop;
      Rig r(v == Via::interbus, v == Via::lustbus, DeviceStart::operational, config);
      if (v == Via::interbus) {
        r.m2s[1] = row.reference;
        r.control(0x8000 | kRampBits | 0x0006);  // STR, SHUTDOWN
        r.wait(50ms);
        r.control(0x8000 | kRampBits | 0x000F);  // ENABLE OPERATION
      } else {
        // LUSTBUS manual 7.1: control and reference from the serial interface.
        for (const auto& [n, value] : {std::pair{pnr::kMode, Word{0}}, {pnr::kCsel, Word{3}},
                                       {pnr::kFssel, Word{8}}, {pnr::kFssio, row.reference},
                                       {pnr::kCntl, Word{0x80}}}) {
          ASSERT_EQ(r.lb_write(n, value).kind, "written") << n;
        }
      }
      r.wait(500ms);
      ASSERT_EQ(r.drive->state(), State::enabled);
      EXPECT_EQ(r.drive->power_stage_enabled(), row.power_stage);
      const Word running = row.power_stage ? vf::kStatRunning : Word{0};
      EXPECT_EQ(untimed(read(r, v, pnr::kStat)), (Result{"value", Word(vf::kStatReady | running), 0, {}}));
      // An EEPROM value: refused while the power stage runs (40H), taken while it is off.
      EXPECT_EQ(untimed(write(r, v, pnr::kFmax1, 900)),
                row.power_stage ? (Result{"nak", 0, 0x40, {}}) : (Result{"written", 0, 0, {}}));
    }
  }
  // Down to 0 Hz and up again: the ramp first, then off; a new reference starts it again.
  Rig r(true, false);
  r.m2s[1] = 200;  // 10 Hz
  r.control(0x8000 | kRampBits | 0x0006);
  r.wait(50ms);
  r.control(0x8000 | kRampBits | 0x000F);
  r.wait(1s);
  ASSERT_DOUBLE_EQ(r.drive->frequency_hz(), 10.0);
  r.m2s[1] = 0;
  r.wait(100ms);
  EXPECT_GT(r.drive->frequency_hz(), 0.0) << "on its ramp (20 Hz/s)";
  EXPECT_TRUE(r.drive->power_stage_enabled());
  r.wait(500ms);
  EXPECT_EQ(r.drive->frequency_hz(), 0.0);
  EXPECT_FALSE(r.drive->power_stage_enabled());
  EXPECT_EQ(r.drive->state(), State::enabled);
  r.m2s[1] = 200;
  r.wait(100ms);
  EXPECT_TRUE(r.drive->power_stage_enabled());
  EXPECT_GT(r.drive->frequency_hz(), 0.0);
}

TEST(Vf1000Faces, Stat000FResetsAFaultOverTheCommunicationWordToo) {
  // VF-E14: 11-STAT is the drive's parameter whatever carries it (LUSTBUS manual 8.1.1): 000FH with an
  // error boots the inverter; the transfer's ACK is lost to the reset, the master sees the
  // inverter restart (RESET distinction 0, INTERBUS manual 4.1.2.2) and its module error (6.1).
  Rig r(true, false);
  r.drive->set_fault(true, r.now);
  r.wait(50ms);
  r.drive->set_fault(false, r.now);
  r.wait(50ms);
  ASSERT_EQ(r.drive->state(), State::fault);
  EXPECT_EQ(r.ib_read(pnr::kStat).value, vf::kStatReady | vf::kStatError);
  const Result w = r.ib_write(pnr::kStat, vf::kStatReset);
  EXPECT_EQ(w.kind, "inverter restarted");
  EXPECT_EQ(r.drive->software_resets(), 1U);
  EXPECT_TRUE(r.ib->module_error(r.now));
  r.wait(4100ms);
  EXPECT_EQ(r.drive->state(), State::start_up_inhibit);
  EXPECT_EQ(r.ib_read(pnr::kSiof).value, 0x01);
  // Without an error 000FH is taken and resets nothing.
  EXPECT_EQ(r.ib_write(pnr::kStat, vf::kStatReset).kind, "written");
  EXPECT_EQ(r.drive->software_resets(), 1U);
}

// --- One drive, two faces -------------------------------------------------------------------

TEST(Vf1000Faces, TheSerialInterfaceControlsOnlyWhenModeAndCselGiveItControl) {
  // Decision VF-E16: the INTERBUS words control the drive (INTERBUS manual 6.1: INTERBUS operation)
  // unless 1-MODE = 0 and 2-CSEL = 3 hand control to the serial interface (LUSTBUS manual 7.1).
  Rig r;
  ASSERT_EQ(r.lb_write(pnr::kFssel, 8).kind, "written");
  ASSERT_EQ(r.lb_write(pnr::kFssio, 100).kind, "written");  // 5 Hz
  ASSERT_EQ(r.lb_write(pnr::kCntl, 0x80).kind, "written");  // start clockwise
  r.control(0x0000);  // the INTERBUS master disables the voltage
  r.wait(200ms);
  EXPECT_FALSE(r.drive->power_stage_enabled()) << "3-CNTL is not the control location";
  ASSERT_EQ(r.lb_write(pnr::kMode, 0).kind, "written");
  ASSERT_EQ(r.lb_write(pnr::kCsel, 3).kind, "written");
  r.wait(500ms);
  EXPECT_TRUE(r.drive->power_stage_enabled());
  EXPECT_DOUBLE_EQ(r.drive->frequency_hz(), 5.0);
  // Both faces read the same running drive: 11-STAT 03H, 12 = 100 (5 Hz).
  EXPECT_EQ(r.ib_read(pnr::kStat).value, vf::kStatReady | vf::kStatRunning);
  EXPECT_EQ(r.lb_read(pnr::kStat).value, vf::kStatReady | vf::kStatRunning);
  EXPECT_EQ(r.ib_read(pnr::kFout).value, 100);
  EXPECT_EQ(r.lb_read(pnr::kFout).value, 100);
}

TEST(Vf1000Faces, Mode4LocksTheSerialInterfaceWhileTheDriveIsOnInterbus) {
  // INTERBUS manual 6.1: "During operation on the INTERBUS-S (01-MODE = 4) the serial interface of the
  // inverter cannot be used." (VF-E16.) A service PC's ENQUIRY goes unanswered then; once the
  // master writes another MODE the drive answers, and at MODE 4 again it is deaf again.
  Rig r;
  ASSERT_EQ(r.ib_write(pnr::kMode, 4).kind, "written");
  EXPECT_EQ(r.lb_read(pnr::kFout).kind, "no_answer");
  EXPECT_EQ(r.lb_write(pnr::kFssio, 100).kind, "no_answer");
  ASSERT_EQ(r.ib_write(pnr::kMode, 2).kind, "written");
  EXPECT_EQ(r.lb_read(pnr::kMode).kind, "value");
  EXPECT_EQ(r.lb_read(pnr::kMode).value, 2);
  // Without the INTERBUS face (the drive served on LUSTBUS alone) MODE 4 locks nothing.
  Rig alone(false, true);
  ASSERT_EQ(alone.drive->value(pnr::kMode), 4);
  EXPECT_EQ(alone.lb_read(pnr::kMode).kind, "value");
}

TEST(Vf1000Faces, AResetOnOneFaceIsASelfTestOnTheOther) {
  // VF-E13: one software reset whatever triggers it. 11-STAT = 000FH over LUSTBUS: the INTERBUS
  // face shows its module error and RESET distinction 0 for the self-test (INTERBUS manual 6.1,
  // 4.1.2.2); RESET FAULT over INTERBUS: the LUSTBUS face is deaf for it (LUSTBUS manual 8.1.1).
  Rig r;
  r.drive->set_fault(true, r.now);
  r.wait(50ms);
  r.drive->set_fault(false, r.now);
  r.wait(50ms);
  ASSERT_EQ(r.drive->state(), State::fault);
  r.lb_write(pnr::kStat, vf::kStatReset);
  EXPECT_TRUE(r.ib->module_error(r.now));
  EXPECT_EQ(r.s2m[2], 0x0000);
  r.wait(4100ms);
  EXPECT_FALSE(r.ib->module_error(r.now));
  EXPECT_EQ(r.ib_read(pnr::kSiof).value, 0x01);

  r.drive->set_fault(true, r.now);
  r.wait(50ms);
  r.drive->set_fault(false, r.now);
  r.wait(50ms);
  r.control(0x0080);
  r.wait(20ms);
  EXPECT_FALSE(r.lbd->listening(r.now));
  EXPECT_EQ(r.lb_read(pnr::kSiof).kind, "no_answer");
  r.wait(4100ms);
  EXPECT_TRUE(r.lbd->listening(r.now));
  EXPECT_EQ(r.lb_read(pnr::kSiof).value, 0x01);
}

TEST(Vf1000Faces, TheSerialWatchdogMonitorsOnlyASerialLink) {
  // VF-E15: 84-SIOT watches the serial link (LUSTBUS manual 5.2): set through the communication word
  // of a drive without a LUSTBUS face it never runs out; with one it stops the drive and sets
  // 02H, which the INTERBUS master reads too. 906/907 set no bit in 85 (INTERBUS manual 4.1.1).
  Rig only_interbus(true, false);
  ASSERT_EQ(only_interbus.ib_write(pnr::kSiot, 100).kind, "written");
  only_interbus.wait(1s);
  EXPECT_FALSE(only_interbus.drive->serial_watchdog_fault());
  EXPECT_EQ(only_interbus.drive->siof(), 0);

  Rig both;
  ASSERT_EQ(both.ib_write(pnr::kSiot, 100).kind, "written");
  both.wait(300ms);
  EXPECT_TRUE(both.drive->serial_watchdog_fault());
  EXPECT_EQ(both.drive->state(), State::fault);
  EXPECT_EQ(both.ib_read(pnr::kSiof).value, 0x02);
}

TEST(Vf1000Faces, TheEmulatorsDriveComesCommissionedForItsRs485Line) {
  // VF-E20: `ibs lustbus emulate` and the test bench serve RS-485, where the drive answers only
  // with 61-SOUTA = 7 (LUSTBUS manual 4); like the line's rate in 81-SIOC the emulator sets it as a
  // commissioning step, in the EEPROM. Alone on LUSTBUS the drive has the standard factory values
  // (INTERBUS manual 3.1.1 does not apply, VF-E20); the bench's drive keeps its INTERBUS ones.
  const ibs::devices::LustbusFace& face = vf::lustbus_face();
  ibs::devices::LustbusEmulated alone = face.make(ibs::devices::LustbusFaceOptions{});
  auto& lone = dynamic_cast<vf::LustbusDevice&>(*alone.responder);
  EXPECT_EQ(lone.eeprom_value(pnr::kSouta), vf::kSoutaRs485);
  EXPECT_EQ(lone.value(pnr::kMode), 0);
  EXPECT_TRUE(lone.listening(Time{0}));
  // A host that writes another SOUTA loses the drive (its own ACK still goes out).
  lone.drive().read_siof();
  const auto code = lb::make_code(100U + pnr::kSouta);
  EXPECT_EQ(lone.select(code, lb::make_value("0000"), {1, Time{1s}}).reply, lb::Reply::ack);
  EXPECT_FALSE(lone.listening(Time{2s}));

  Vf1000Device ib(Vf1000DeviceConfig{}, DeviceStart::operational, Time{0});
  ibs::devices::LustbusEmulated bench = face.attach(ib, ibs::devices::LustbusFaceOptions{});
  EXPECT_EQ(ib.drive().eeprom_value(pnr::kSouta), vf::kSoutaRs485);
  EXPECT_EQ(ib.drive().value(pnr::kMode), 4) << "the INTERBUS package's value (INTERBUS manual 3.1.1)";
  auto& served = dynamic_cast<vf::LustbusDevice&>(*bench.responder);
  EXPECT_FALSE(served.listening(Time{0})) << "MODE 4 on the ring (VF-E16)";
  ib.drive().set_value(pnr::kMode, 1);
  EXPECT_TRUE(served.listening(Time{0}));
}

TEST(Vf1000Faces, ACopyOfAFaceIsAnIndependentDrive) {
  Rig r;
  ASSERT_EQ(r.ib_write(pnr::kFmax1, 0x0200).kind, "written");
  const auto copy = r.ib->clone();
  auto& c = dynamic_cast<Vf1000Device&>(*copy);
  EXPECT_NE(&c.drive(), r.drive.get());
  EXPECT_NE(&c.drive().store(), &r.drive->store());
  EXPECT_EQ(c.drive().value(pnr::kFmax1), 0x0200);
  EXPECT_EQ(&c.channel().parameters(), static_cast<const ibs::drive::ParameterAccess*>(&c.drive()));
  ASSERT_EQ(r.lb_write(pnr::kFmax1, 0x0300).kind, "written");
  EXPECT_EQ(c.drive().value(pnr::kFmax1), 0x0200);
  // The copy has only its own face: its drive takes the INTERBUS words, not 3-CNTL.
  EXPECT_TRUE(c.drive().attached(vf::Face::interbus));
  EXPECT_FALSE(c.drive().attached(vf::Face::serial));
}

}  // namespace

// --- Plant and fault events (issue 24; devices/plant_event.hpp) -------------------------------

ibs::devices::PlantEvent fault_event(std::optional<int> cause) {
  ibs::devices::PlantEvent e;
  e.kind = ibs::devices::PlantEvent::Kind::fault;
  e.cause = cause;
  return e;
}

TEST(Vf1000Events, ADeviceFaultWithItsCauseShowsOnBothFaces) {
  // INTERBUS manual 4.1.3.3: the inverter's error codes are 00H..0EH; LUSTBUS manual 8: errors show in the
  // status word and, over LUSTBUS, in 11-STAT's error bit 80H (LB-D19).
  Rig r(true, true);
  ASSERT_TRUE(r.ib->apply_event(fault_event(12), r.now));
  r.wait(50ms);
  EXPECT_EQ(r.drive->fault_cause(), 12);
  EXPECT_EQ(r.drive->state(), State::fault);
  EXPECT_NE(r.ib->status_word() & 0x0008U, 0U) << "DRIVECOM status word bit 3: fault (INTERBUS manual 5.2.2)";
  EXPECT_EQ(r.lb_read(pnr::kStat).value & vf::kStatError, vf::kStatError);
  EXPECT_EQ(r.ib_read(pnr::kStat).value & vf::kStatError, vf::kStatError);
  // The cause goes with the fault; the latched FAULT stays until its reset (8.1.1).
  ibs::devices::PlantEvent clear;
  clear.kind = ibs::devices::PlantEvent::Kind::fault_clear;
  ASSERT_TRUE(r.ib->apply_event(clear, r.now));
  r.wait(20ms);
  EXPECT_EQ(r.drive->fault_cause(), std::nullopt);
  EXPECT_EQ(r.drive->state(), State::fault);
}

TEST(Vf1000Events, MainsLossSilencesBothFacesAndTheReturnIsAPowerOn) {
  // VF-E17: mains lost = the inverter off: a module error on INTERBUS, no LUSTBUS answer; back =
  // a new start with 6.1's initialisation and the power-on bit (LUSTBUS manual 9.2, "a power failure").
  Rig r(true, true);
  ibs::devices::PlantEvent off;
  off.kind = ibs::devices::PlantEvent::Kind::mains_off;
  ASSERT_TRUE(r.ib->apply_event(off, r.now));
  r.wait(100ms);
  EXPECT_TRUE(r.ib->module_error(r.now));
  EXPECT_NE(r.lb_read(pnr::kStat).kind, "value") << "no answer without mains";
  r.wait(10s);
  EXPECT_TRUE(r.ib->module_error(r.now)) << "off stays off until the mains return";
  ibs::devices::PlantEvent on;
  on.kind = ibs::devices::PlantEvent::Kind::mains_on;
  ASSERT_TRUE(r.ib->apply_event(on, r.now));
  EXPECT_TRUE(r.ib->module_error(r.now)) << "initialising after the return";
  r.wait(r.drive->config().pd.init_time + 100ms);
  EXPECT_FALSE(r.ib->module_error(r.now));
  const Result siof = r.lb_read(pnr::kSiof);
  EXPECT_EQ(siof.kind, "value");
  EXPECT_EQ(siof.value & 0x01U, 0x01U) << "the power-on bit tells the host of the power failure";
}

TEST(Vf1000Events, NoLoad) {
  // VF-E17: the seeds give the VF1000 no load model (its frequency follows the ramp).
  Rig r(true, false);
  ibs::devices::PlantEvent load;
  load.kind = ibs::devices::PlantEvent::Kind::load;
  load.value = 1.0;
  EXPECT_FALSE(r.ib->apply_event(load, r.now));
  // A terminal beyond the drive's own list (kTerminalNames) is not taken either.
  ibs::devices::PlantEvent input;
  input.kind = ibs::devices::PlantEvent::Kind::input;
  input.input = vf::kTerminalCount;
  input.level = true;
  EXPECT_FALSE(r.ib->apply_event(input, r.now));
}

TEST(Vf1000Events, ASmartcardOperationDisablesBothBusesForItsTime) {
  // INTERBUS manual 6.1: "While the SMARTCARD is being read and written to bus operation is disabled";
  // LUSTBUS manual 10 exception 2: "While a SMARTCARD is being read in, no communications with the
  // device via the LUSTBUS is possible. This condition can last up to 10 seconds". Decision
  // VF-E21: for the operation's time the INTERBUS face shows a module error and takes no words
  // (its channel waits), the LUSTBUS face hears nothing; the values stay (the seeds give no card's
  // content); afterwards both answer as before, without a new start.
  struct Row {
    ibs::devices::PlantEvent::Kind kind;
    double seconds;
  };
  for (const Row row : {Row{ibs::devices::PlantEvent::Kind::card_read, 2.0},
                        Row{ibs::devices::PlantEvent::Kind::card_write, 3.0}}) {
    SCOPED_TRACE(row.kind == ibs::devices::PlantEvent::Kind::card_read ? "read" : "written");
    Rig r(true, true);
    ASSERT_EQ(r.ib_write(pnr::kFmax1, 0x01F4).kind, "written");
    const std::uint32_t starts = r.drive->starts();
    ibs::devices::PlantEvent card;
    card.kind = row.kind;
    card.value = row.seconds;
    const Time from = r.now;
    ASSERT_TRUE(r.ib->apply_event(card, r.now));
    r.wait(50ms);
    EXPECT_TRUE(r.ib->module_error(r.now));
    EXPECT_EQ(r.lb_read(pnr::kFmax1).kind, "no_answer");  // the host's retries included
    // The master's control word is not taken while the card is busy.
    r.control(0x8000 | kRampBits | 0x0006);
    r.wait(100ms);
    EXPECT_EQ(r.drive->state(), State::start_up_inhibit);
    const Duration card_time = std::chrono::duration_cast<Duration>(std::chrono::duration<double>(row.seconds));
    while (r.now < from + card_time) r.tick();
    r.wait(50ms);
    EXPECT_FALSE(r.ib->module_error(r.now));
    EXPECT_EQ(r.drive->state(), State::ready) << "the words count again";
    EXPECT_EQ(untimed(r.lb_read(pnr::kFmax1)), (Result{"value", 0x01F4, 0, {}}));
    EXPECT_EQ(untimed(r.ib_read(pnr::kFmax1)), (Result{"value", 0x01F4, 0, {}}));
    EXPECT_EQ(r.drive->starts(), starts) << "no new start: no power-on bit";
    EXPECT_EQ(r.drive->siof(), 0);
  }
}

// An `input` event on a terminal by the name the drive's facts list (what a scenario or a control
// line resolves), applied to the core or through the INTERBUS face.
ibs::devices::PlantEvent terminal_event(std::string_view name, bool high) {
  const auto index = ibs::devices::find_input(vf::descriptor().facts().events, name);
  EXPECT_TRUE(index.has_value()) << name;
  ibs::devices::PlantEvent e;
  e.kind = ibs::devices::PlantEvent::Kind::input;
  e.input = index.value_or(0);
  e.level = high;
  return e;
}

TEST(Vf1000Events, TheEventsNameTheTerminalsOfSeed001) {
  // INTERBUS manual 5.2.1 (control bits 12..15: S2IND, S1IND, STL, STR) and 5.2.2 (status bits 14 / 15:
  // S2OUT, S1OUT): the names a scenario writes are the manual's, in the order of vf1000::Terminal.
  const auto& inputs = vf::descriptor().facts().events.inputs;
  ASSERT_EQ(inputs.size(), vf::kTerminalCount);
  const std::pair<vf::Terminal, std::string_view> rows[] = {
      {vf::Terminal::s1ind, "S1IND"}, {vf::Terminal::s2ind, "S2IND"}, {vf::Terminal::str, "STR"},
      {vf::Terminal::stl, "STL"},     {vf::Terminal::s1out, "S1OUT"}, {vf::Terminal::s2out, "S2OUT"}};
  for (const auto& [t, name] : rows) EXPECT_EQ(inputs[static_cast<std::size_t>(t)], name);
  EXPECT_FALSE(ibs::devices::find_input(vf::descriptor().facts().events, "IS00").has_value());
}

TEST(Vf1000Events, OutputsS2outAndS1outShowInStatusBits14And15OnBothFaces) {
  // INTERBUS manual 5.2.2: "Bit 14 Status of output S2OUT, dependent on programmed function", "Bit 15
  // Status of output S1OUT". VF-E22: the seeds give no function, so the event states the level;
  // it shows in the INTERBUS status word and in 911-IBSTA (the DRIVECOM status word, INTERBUS manual
  // 4.1.1) over the communication word, whichever face the event came through. LUSTBUS shows
  // neither: its VF1000 CODE reaches parameters 00..99 only (LUSTBUS manual 2.4.1), and 11-STAT's bits
  // are the ready / running / direction / error of LB-D19.
  struct Row {
    bool via_interbus;  // the event through the INTERBUS face, else on the core (the LUSTBUS face's way)
    std::string_view s1out_level, s2out_level;
    Word bits;  // status word bits 14 / 15
  };
  const Row rows[] = {
      {true, "low", "low", 0x0000},   {true, "high", "low", 0x8000},  {true, "low", "high", 0x4000},
      {true, "high", "high", 0xC000}, {false, "high", "low", 0x8000}, {false, "low", "high", 0x4000},
  };
  for (const Row& row : rows) {
    SCOPED_TRACE(std::string(row.via_interbus ? "INTERBUS face" : "core") + ", S1OUT " +
                 std::string(row.s1out_level) + ", S2OUT " + std::string(row.s2out_level));
    Rig r(true, true);
    const auto s1 = terminal_event("S1OUT", row.s1out_level == "high");
    const auto s2 = terminal_event("S2OUT", row.s2out_level == "high");
    if (row.via_interbus) {
      ASSERT_TRUE(r.ib->apply_event(s1, r.now));
      ASSERT_TRUE(r.ib->apply_event(s2, r.now));
    } else {
      ASSERT_TRUE(r.drive->apply(s1, r.now));
      ASSERT_TRUE(r.drive->apply(s2, r.now));
    }
    r.wait(50ms);
    EXPECT_EQ(r.drive->terminal(vf::Terminal::s1out), (row.bits & 0x8000U) != 0);
    EXPECT_EQ(r.drive->terminal(vf::Terminal::s2out), (row.bits & 0x4000U) != 0);
    EXPECT_EQ(r.s2m[0] & 0xC000U, row.bits) << "the INTERBUS status word";
    EXPECT_EQ(r.ib_read(pnr::kIbsta).value & 0xC000U, row.bits) << "911-IBSTA over the communication word";
    EXPECT_EQ(untimed(r.lb_read(pnr::kStat)), (Result{"value", vf::kStatReady, 0, {}})) << "11-STAT unchanged";
  }
  // The LUSTBUS face alone (`ibs lustbus emulate --control`): the event reaches the core it serves,
  // whose status word carries the level (what 911 and an INTERBUS face would show).
  ibs::devices::LustbusEmulated alone = vf::lustbus_face().make(ibs::devices::LustbusFaceOptions{});
  ASSERT_TRUE(alone.apply_event(terminal_event("S2OUT", true), Time{1s}));
  alone.advance(Time{2s});
  auto& lone = dynamic_cast<vf::LustbusDevice&>(*alone.responder);
  EXPECT_TRUE(lone.drive().terminal(vf::Terminal::s2out));
  EXPECT_EQ(lone.drive().pd().status_word() & 0xC000U, 0x4000U);
  EXPECT_EQ(lone.drive().value(pnr::kIbsta) & 0xC000U, 0x4000U);

  // The level stays until the event changes it; low again clears the bit.
  Rig r(true, true);
  ASSERT_TRUE(r.ib->apply_event(terminal_event("S1OUT", true), r.now));
  r.wait(50ms);
  ASSERT_EQ(r.s2m[0] & 0xC000U, 0x8000U);
  ASSERT_TRUE(r.ib->apply_event(terminal_event("S1OUT", false), r.now));
  r.wait(50ms);
  EXPECT_EQ(r.s2m[0] & 0xC000U, 0U);
  // Without mains the output is dead (VF-E17: the inverter is off).
  ASSERT_TRUE(r.ib->apply_event(terminal_event("S2OUT", true), r.now));
  ibs::devices::PlantEvent off;
  off.kind = ibs::devices::PlantEvent::Kind::mains_off;
  ASSERT_TRUE(r.ib->apply_event(off, r.now));
  EXPECT_FALSE(r.drive->terminal(vf::Terminal::s2out));
}

TEST(Vf1000Events, ControlBits12And13OrTheTerminalsActivateTheFunctionOfS2indAndS1ind) {
  // INTERBUS manual 5.2.1: "Bit 12 Activates the parameter-set function of input S2IND", "Bit 13
  // Activates the parameter-set function of input S1IND". VF-E22: the function is active while the
  // terminal is high or the bus bit set; the seeds do not give what it does, so nothing else
  // changes -- the DRIVECOM status bits 0..13 and the frequency are those without it.
  struct Row {
    std::string_view terminal;  // set high before the run ("" none)
    Word bits;                  // control word bits 12 / 13
    bool s1ind, s2ind;          // input_function_active
  };
  const Row rows[] = {
      {"", 0x0000, false, false},      {"S1IND", 0x0000, true, false}, {"S2IND", 0x0000, false, true},
      {"", 0x2000, true, false},       {"", 0x1000, false, true},      {"S1IND", 0x2000, true, false},
      {"S2IND", 0x2000, true, true},   {"", 0x3000, true, true},
  };
  std::optional<Word> base_status;
  std::optional<double> base_frequency;
  for (const Row& row : rows) {
    SCOPED_TRACE(std::string(row.terminal.empty() ? "no terminal" : row.terminal) + ", bits " +
                 std::to_string(row.bits));
    Rig r(true, false);
    if (!row.terminal.empty()) {
      ASSERT_TRUE(r.ib->apply_event(terminal_event(row.terminal, true), r.now));
    }
    r.m2s[1] = 200;  // 10 Hz
    r.control(0x8000 | row.bits | kRampBits | 0x0006);
    r.wait(50ms);
    r.control(0x8000 | row.bits | kRampBits | 0x000F);
    r.wait(300ms);
    EXPECT_EQ(r.drive->input_function_active(vf::Terminal::s1ind), row.s1ind);
    EXPECT_EQ(r.drive->input_function_active(vf::Terminal::s2ind), row.s2ind);
    EXPECT_FALSE(r.drive->input_function_active(vf::Terminal::str)) << "no parameter-set function";
    const Word status = r.s2m[0] & 0x3FFFU;
    if (!base_status) {
      base_status = status;
      base_frequency = r.drive->frequency_hz();
      EXPECT_GT(*base_frequency, 0.0) << "STR: clockwise";
    }
    EXPECT_EQ(status, *base_status);
    EXPECT_EQ(r.drive->frequency_hz(), *base_frequency);
    EXPECT_EQ(r.s2m[0] & 0xC000U, 0U) << "inputs drive no output";
    // The bus bit counts from the word the drive acts on: gone with a new start, back with the
    // first word after it; without mains nothing is active.
    if (row.bits != 0 && row.terminal.empty()) {
      ibs::devices::PlantEvent cycle;
      cycle.kind = ibs::devices::PlantEvent::Kind::power_cycle;
      ASSERT_TRUE(r.ib->apply_event(cycle, r.now));
      EXPECT_FALSE(r.drive->input_function_active(vf::Terminal::s1ind));
      EXPECT_FALSE(r.drive->input_function_active(vf::Terminal::s2ind));
      r.wait(r.drive->config().pd.init_time + 100ms);
      EXPECT_EQ(r.drive->input_function_active(vf::Terminal::s1ind), row.s1ind);
      EXPECT_EQ(r.drive->input_function_active(vf::Terminal::s2ind), row.s2ind);
      ibs::devices::PlantEvent off;
      off.kind = ibs::devices::PlantEvent::Kind::mains_off;
      ASSERT_TRUE(r.ib->apply_event(off, r.now));
      EXPECT_FALSE(r.drive->input_function_active(vf::Terminal::s1ind));
      EXPECT_FALSE(r.drive->input_function_active(vf::Terminal::s2ind));
    }
  }
}

TEST(Vf1000Events, TerminalsStrAndStlAreRecordedButTheBusControls) {
  // INTERBUS manual 5.2.1: control bits 14 / 15 are the "function as input STL / STR" under INTERBUS
  // control; the model has no terminal control location (INTERBUS or serial only, INTERBUS manual 6.1,
  // LUSTBUS manual 7.1), so the terminals are recorded and change nothing (VF-E22).
  struct Row {
    std::string_view terminal;
    Word direction_bits;  // control bit 15 STR / 14 STL
    double sign;          // of the frequency reached
  };
  const Row rows[] = {{"STR", 0x0000, 0.0}, {"STL", 0x0000, 0.0}, {"STL", 0x8000, 1.0}, {"STR", 0x4000, -1.0}};
  for (const Row& row : rows) {
    SCOPED_TRACE(std::string(row.terminal) + ", bits " + std::to_string(row.direction_bits));
    Rig r(true, false);
    ASSERT_TRUE(r.ib->apply_event(terminal_event(row.terminal, true), r.now));
    r.m2s[1] = 200;  // 10 Hz
    r.control(row.direction_bits | kRampBits | 0x0006);
    r.wait(50ms);
    r.control(row.direction_bits | kRampBits | 0x000F);
    r.wait(300ms);
    EXPECT_TRUE(r.drive->terminal(row.terminal == "STR" ? vf::Terminal::str : vf::Terminal::stl));
    const double f = r.drive->frequency_hz();
    EXPECT_EQ(f > 0.0 ? 1.0 : (f < 0.0 ? -1.0 : 0.0), row.sign);
  }
}
