// Issue 41: what a drive's channels change that its INTERBUS process-data words do not carry --
// the MC6000's PCP, a LUSTBUS face serving the same drive core (a test bench's second bus) -- is
// kept for a recording (DeviceEmulator::take_changes, drive/parameter_journal.hpp) and written as
// `! write PNR VALUE` events; a replay applies them with write_parameter, through the drive's own
// checks (../shared/specs/trace-format.md, "Events"). 85-SIOF/SERR, which no channel writes,
// travels as the bits a channel's requests left.
#include <gtest/gtest.h>

#include <array>
#include <memory>
#include <span>
#include <vector>

#include "ibs/devices/mc6000/device.hpp"
#include "ibs/devices/mc6000/lustbus_device.hpp"
#include "ibs/devices/registry.hpp"
#include "ibs/devices/vf1000/device.hpp"
#include "ibs/devices/vf1000/lustbus_device.hpp"
#include "ibs/devices/vf1000/parameters.hpp"
#include "ibs/lustbus/code.hpp"
#include "ibs/lustbus/value.hpp"

namespace ibs::devices {
namespace {

using namespace std::chrono_literals;
namespace lb = ibs::lustbus;

std::vector<drive::ParameterChange> taken(DeviceEmulator& d) {
  std::array<drive::ParameterChange, drive::ParameterJournal::kCapacity> out{};
  const std::size_t n = d.take_changes(out);
  return {out.begin(), out.begin() + static_cast<std::ptrdiff_t>(n)};
}

using Changes = std::vector<drive::ParameterChange>;

TEST(ChannelChanges, AServosLustbusWritesAndItsSerrReadAreKeptForTheRecording) {
  auto core = std::make_shared<mc6000::Drive>(mc6000::DriveConfig{}, DeviceStart::initialised, Time{0});
  Mc6000DeviceConfig config;
  config.supi = 9;
  config.ibcnf = 1;
  Mc6000Device interbus(config, core, DeviceStart::initialised, Time{0});
  mc6000::LustbusDevice serial(core);
  const lb::Context at{3, Time{10ms}};
  // Nothing is kept before the recording asks for it.
  serial.enquiry(lb::make_code(20085), at);
  EXPECT_TRUE(taken(interbus).empty());
  interbus.record_changes(true);
  // A SELECT refused while 85-SERR holds the power-on bit changes nothing.
  core->power_on(Time{20ms});
  EXPECT_EQ(serial.select(lb::make_code(20409), lb::make_value("14"), {3, Time{30ms}}).reply, lb::Reply::nak);
  EXPECT_TRUE(taken(interbus).empty());
  // The host reads 85-SERR (its bits erased), writes 409-BUTWD = 20, and sends a value out of
  // range (80H enters 85-SERR).
  EXPECT_EQ(serial.enquiry(lb::make_code(20085), {3, Time{40ms}}).reply, lb::Reply::text);
  EXPECT_EQ(serial.select(lb::make_code(20409), lb::make_value("14"), {3, Time{50ms}}).reply, lb::Reply::ack);
  EXPECT_EQ(serial.select(lb::make_code(20406), lb::make_value("09"), {3, Time{60ms}}).reply, lb::Reply::nak);
  const Changes want{{85, 0}, {409, 20}, {85, core->siof()}};
  EXPECT_NE(core->siof(), 0);
  EXPECT_EQ(taken(interbus), want);
  EXPECT_TRUE(taken(interbus).empty()) << "taken once";

  // The replay: a servo of the same start takes them as PCP would.
  Mc6000Device replayed(config, DeviceStart::initialised, Time{0});
  EXPECT_NE(replayed.write_parameter(409, 20, Time{1ms}), "") << "refused: 85-SERR holds the power-on bit";
  for (const auto& c : want) EXPECT_EQ(replayed.write_parameter(c.number, c.value, Time{2ms}), "") << c.number;
  EXPECT_EQ(replayed.drive().parameters().raw(409), 20U);
  EXPECT_EQ(replayed.drive().siof(), core->siof());
  EXPECT_NE(replayed.write_parameter(85, 256, Time{3ms}), "");
  EXPECT_NE(replayed.write_parameter(409, 70000, Time{3ms}), "") << "wider than 409's 16 bits";
  EXPECT_NE(replayed.write_parameter(999, 1, Time{3ms}), "");
}

TEST(ChannelChanges, AServosPcpWritesAreKeptAndItsProcessDataChangeNothing) {
  Mc6000DeviceConfig config;
  config.supi = 9;
  config.ibcnf = 1;
  Mc6000Device servo(config, DeviceStart::operational, Time{0});
  servo.record_changes(true);
  // Samples with process data only: no parameter changes.
  std::array<Word, 2> m2s{0x0006, 0};
  std::array<Word, 2> s2m{};
  for (int i = 1; i <= 20; ++i) servo.sample(m2s, s2m, Time{std::chrono::milliseconds(i)});
  EXPECT_TRUE(taken(servo).empty());
  // The PCP face's writes go through the same core, noted by the face (PcpServed).
  EXPECT_EQ(servo.drive().journal().size(), 0U);
}

TEST(ChannelChanges, AnInvertersLustbusWritesAreKeptItsCommunicationWordIsInTheWords) {
  auto core = std::make_shared<vf1000::Drive>(vf1000::DriveConfig{}, DeviceStart::initialised, Time{0});
  // INTERBUS manual 6.1 (VF-E16): with the factory 1-MODE = 4 the serial interface is locked on INTERBUS.
  core->set_value(vf1000::pnr::kMode, 1);
  Vf1000Device interbus(Vf1000DeviceConfig{}, core, Time{0});
  vf1000::LustbusDevice serial(core);
  interbus.record_changes(true);
  EXPECT_EQ(serial.enquiry(lb::make_code(85), {1, Time{10ms}}).reply, lb::Reply::text);
  // LUSTBUS reaches 00..99 (LUSTBUS manual): 22-FMAX1 = 1000 (50.00 Hz).
  EXPECT_EQ(serial.select(lb::make_code(22), lb::make_value("03E8"), {1, Time{20ms}}).reply, lb::Reply::ack);
  EXPECT_EQ(taken(interbus), (Changes{{85, 0}, {22, 1000}}));

  Vf1000Device replayed(Vf1000DeviceConfig{}, DeviceStart::initialised, Time{0});
  EXPECT_NE(replayed.write_parameter(906, 200, Time{1ms}), "") << "refused: 85-SIOF holds the power-on bit";
  EXPECT_EQ(replayed.write_parameter(85, 0, Time{1ms}), "");
  EXPECT_EQ(replayed.write_parameter(906, 200, Time{1ms}), "");
  EXPECT_EQ(replayed.drive().value(906), 200);
  EXPECT_NE(replayed.write_parameter(906, 70000, Time{1ms}), "");
  EXPECT_NE(replayed.write_parameter(85, 300, Time{1ms}), "");
}

// The registry's wings judge a `! write` against their tables for decode and replay alike.
TEST(ChannelChanges, EveryWingJudgesATraceWriteAgainstItsTable) {
  for (const DriveKind& k : drive_kinds()) {
    SCOPED_TRACE(std::string(k->name()));
    EXPECT_EQ(k->check_trace_write(85, 0), std::nullopt);
    EXPECT_NE(k->check_trace_write(85, 256), std::nullopt);
    EXPECT_NE(k->check_trace_write(9999, 0), std::nullopt);
    EXPECT_NE(k->check_trace_write(85, -1), std::nullopt);
  }
  const DriveKind* mc = find_drive_kind("mc6000");
  ASSERT_NE(mc, nullptr);
  EXPECT_EQ((*mc)->check_trace_write(409, 20), std::nullopt);
  EXPECT_NE((*mc)->check_trace_write(409, 70000), std::nullopt);
  EXPECT_NE((*mc)->check_trace_write(77, 1), std::nullopt) << "77-SPEED is an actual value";
  const DriveKind* vf = find_drive_kind("vf1000");
  ASSERT_NE(vf, nullptr);
  EXPECT_EQ((*vf)->check_trace_write(22, 1000), std::nullopt);
}

}  // namespace
}  // namespace ibs::devices
