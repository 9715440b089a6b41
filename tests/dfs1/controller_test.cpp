// The emulated DFS-1 controller: every command, every error code, the status bytes, the speed
// plant, the E-stop rule of 8D, parameters 1 and 56 (docs/dfs1.md, "Emulator").
#include "ibs/devices/dfs1/controller.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "ibs/dfs1/host.hpp"

namespace ibs::devices::dfs1 {
namespace {

namespace proto = ::ibs::dfs1;
using proto::ErrorCode;
using proto::Frame;
namespace request = proto::request;

// Sends `f` to `c` at `now` and decodes its reply once due (nullopt: no answer).
std::optional<Frame> exchange(Controller& c, const Frame& f, Time now = 0ms) {
  const proto::EncodedFrame e = proto::encode(f);
  c.receive(e.span(), now);
  const auto due = c.next_deadline();
  if (!due) return std::nullopt;
  proto::FrameDecoder d;
  std::optional<Frame> out;
  for (std::uint8_t b : c.pending(*due)) {
    if (d.push(b).status == proto::DecodeStatus::frame) out = d.frame();
  }
  c.consume(c.pending(*due).size());
  return out;
}

void expect_ack(Controller& c, const Frame& f, Time now = 0ms) {
  const auto r = exchange(c, f, now);
  ASSERT_TRUE(r);
  EXPECT_TRUE(r->is_ack()) << proto::to_string(static_cast<proto::Command>(f.code)) << ": NAK "
                           << proto::error_name(r->size > 0 ? r->data[0] : 0);
}

void expect_nak(Controller& c, const Frame& f, ErrorCode e, Time now = 0ms) {
  const auto r = exchange(c, f, now);
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->is_nak());
  EXPECT_EQ(r->data[0], static_cast<std::uint8_t>(e)) << proto::error_name(r->data[0]);
}

std::uint32_t ack_value(Controller& c, const Frame& f, Time now = 0ms) {
  const auto r = exchange(c, f, now);
  EXPECT_TRUE(r && r->is_ack() && r->size == 4);
  return r ? r->value_at(0) : 0;
}

Controller remote_controller(std::uint8_t uid = 1) {
  Controller c({uid});
  expect_ack(c, request::write_parameter(uid, kRemoteFunctions, kRemoteAll));
  return c;
}

TEST(Dfs1Controller, DefaultsFromTheParameterTable) {
  Controller c({7});
  EXPECT_EQ(ack_value(c, request::read_parameter(7, kUnitId)), 7U);
  for (const ParameterInfo& p : kParameters) {
    if (p.number == kUnitId) continue;
    EXPECT_EQ(ack_value(c, request::read_parameter(7, p.number)), p.default_value) << p.name;
  }
  EXPECT_EQ(c.turnaround(), 2ms);
}

TEST(Dfs1Controller, ParameterOutsideTheTableIsNak82) {
  Controller c({1});
  expect_nak(c, request::read_parameter(1, 5), ErrorCode::illegal_parameter_number);
  expect_nak(c, request::write_parameter(1, 200, 0), ErrorCode::illegal_parameter_number);
}

TEST(Dfs1Controller, ValueOutsideTheRangeIsNak83) {
  Controller c({1});
  expect_nak(c, request::write_parameter(1, kUnitId, 0), ErrorCode::illegal_parameter_value);
  expect_nak(c, request::write_parameter(1, kBaudCode, 8), ErrorCode::illegal_parameter_value);
  expect_nak(c, request::write_parameter(1, kJumpOrMop, 2), ErrorCode::illegal_parameter_value);
  expect_ack(c, request::write_parameter(1, kJumpOrMop, 1));
  EXPECT_EQ(c.parameter(kJumpOrMop), 1U);
}

TEST(Dfs1Controller, UnknownCommandIsNak86) {
  Controller c({1});
  expect_nak(c, proto::make_frame(1, 0x80), ErrorCode::illegal_command);
  expect_nak(c, proto::make_frame(1, 0x90), ErrorCode::illegal_command);
  expect_nak(c, proto::make_frame(1, 0x01), ErrorCode::illegal_command);
}

TEST(Dfs1Controller, SpeedCommandsNeedRemoteOrNak80) {
  Controller c({1});
  expect_nak(c, request::set_speed(1, 100), ErrorCode::not_in_remote);
  expect_nak(c, request::execute_speed(1), ErrorCode::not_in_remote);
  expect_nak(c, request::set_and_execute_speed(1, 100), ErrorCode::not_in_remote);
  expect_nak(c, request::write_analog_output(1, 1, 5), ErrorCode::not_in_remote);
  expect_nak(c, request::write_digital_output(1, 1, 1), ErrorCode::not_in_remote);
  expect_ack(c, request::write_parameter(1, kRemoteFunctions, kRemoteSpeedReference));
  expect_ack(c, request::set_speed(1, 100));
  expect_nak(c, request::execute_speed(1), ErrorCode::not_in_remote);
}

TEST(Dfs1Controller, SpeedBeyondParameter6IsNak81) {
  Controller c = remote_controller();
  expect_nak(c, request::set_speed(1, 1751), ErrorCode::illegal_speed);
  expect_nak(c, request::set_and_execute_speed(1, -1751), ErrorCode::illegal_speed);
  expect_ack(c, request::set_speed(1, -1750));
}

TEST(Dfs1Controller, SetThenExecuteRunsThePlant) {
  Controller c = remote_controller();
  expect_ack(c, request::set_speed(1, 1000), 0ms);
  EXPECT_EQ(c.preset_speed(), 1000);
  EXPECT_EQ(c.commanded_speed(), 0);
  expect_ack(c, request::execute_speed(1), 0ms);
  EXPECT_EQ(c.commanded_speed(), 1000);
  c.step(100ms);  // parameter 62 = 4: the contactor closes after 100 ms
  EXPECT_DOUBLE_EQ(c.actual_speed(), 0.0);
  c.step(600ms);  // one time constant (500 ms) after the contactor closed
  EXPECT_NEAR(c.actual_speed(), 1000.0 * (1.0 - std::exp(-1.0)), 1e-6);
  c.step(5100ms);
  EXPECT_NEAR(c.actual_speed(), 1000.0, 0.1);
}

TEST(Dfs1Controller, StatusCarriesSpeedsLoadAndBothStatusBytes) {
  Controller c = remote_controller();
  // At rest: remote, forward, at speed (0 of 0), zero speed, not enabled.
  auto r = exchange(c, request::status(1), 0ms);
  ASSERT_TRUE(r && r->is_ack());
  ASSERT_EQ(r->size, 16U);
  EXPECT_EQ(r->value_at(0), 0U);
  EXPECT_EQ(r->value_at(4), 0U);
  EXPECT_EQ(r->value_at(8), 0U);
  EXPECT_EQ(r->value_at(12),
            std::uint32_t{kSt2Remote | kSt2AtSpeed | kSt2Forward | kSt2ZeroSpeed} << 8);

  expect_ack(c, request::set_and_execute_speed(1, -1000), 0ms);
  r = exchange(c, request::status(1), 10s);
  ASSERT_TRUE(r && r->is_ack());
  EXPECT_EQ(proto::to_signed(r->value_at(0)), -1000);
  EXPECT_EQ(proto::to_signed(r->value_at(4)), -1000);
  EXPECT_EQ(r->value_at(8), 0U);
  EXPECT_EQ(r->data[14], kSt2Remote | kSt2AtSpeed | kSt2Enabled);  // reverse: no Fwd
  EXPECT_EQ(r->data[15], 0);

  c.set_faults(kSt1Overvolt);
  r = exchange(c, request::status(1), 10s);
  EXPECT_EQ(r->data[14] & kSt2Fault, kSt2Fault);
  EXPECT_EQ(r->data[14] & kSt2Enabled, 0);
  EXPECT_EQ(r->data[15], kSt1Overvolt);
}

// 004, status list: "at speed" is the drive at its commanded speed (issue 25.12, DFS1-D21). The
// reply's first value is that commanded speed, its second the actual one: the bit says they agree.
TEST(Dfs1Controller, AtSpeedMeansAtTheCommandedSpeedNotAtRestAfterAStart) {
  Controller c = remote_controller();
  struct Row {
    Time at;
    bool at_speed;
    bool zero_speed;
    const char* why;
  };
  expect_ack(c, request::set_speed(1, -500), 0ms);
  expect_ack(c, request::execute_speed(1), 0ms);
  const Row rows[] = {
      {0ms, false, true, "right after Execute Speed -500 from rest: actual 0"},
      {50ms, false, true, "the contactor is still closing (parameter 62 = 4: 100 ms)"},
      {600ms, false, false, "one time constant after the contactor closed: about -316 rpm"},
      {10s, true, false, "settled at -500 rpm"},
  };
  for (const Row& row : rows) {
    const auto r = exchange(c, request::status(1), row.at);
    ASSERT_TRUE(r && r->is_ack()) << row.why;
    EXPECT_EQ(proto::to_signed(r->value_at(0)), -500) << row.why;
    EXPECT_EQ((r->data[14] & kSt2AtSpeed) != 0, row.at_speed) << row.why;
    EXPECT_EQ((r->data[14] & kSt2ZeroSpeed) != 0, row.zero_speed) << row.why;
  }
  // A fault stops the motor but not the command: at 0 rpm with -500 commanded it is not at speed.
  c.set_faults(kSt1Overvolt);
  auto r = exchange(c, request::status(1), 30s);
  ASSERT_TRUE(r && r->is_ack());
  EXPECT_EQ(r->data[14] & (kSt2AtSpeed | kSt2ZeroSpeed), kSt2ZeroSpeed);
  // Commanding 0 makes standstill the commanded speed again.
  expect_ack(c, request::set_and_execute_speed(1, 0), 30s);
  r = exchange(c, request::status(1), 30s);
  ASSERT_TRUE(r && r->is_ack());
  EXPECT_EQ(r->data[14] & (kSt2AtSpeed | kSt2ZeroSpeed), kSt2AtSpeed | kSt2ZeroSpeed);
}

TEST(Dfs1Controller, AnalogAndDigitalIo) {
  Controller c = remote_controller();
  c.set_analog_input(2, 512);
  EXPECT_EQ(ack_value(c, request::read_analog_input(1, 2)), 512U);
  expect_nak(c, request::read_analog_input(1, 3), ErrorCode::illegal_channel);
  expect_nak(c, request::read_analog_input(1, 0), ErrorCode::illegal_channel);

  expect_ack(c, request::write_analog_output(1, 1, 1023));
  EXPECT_EQ(ack_value(c, request::read_analog_output(1, 1)), 1023U);
  expect_nak(c, request::write_analog_output(1, 1, 1024), ErrorCode::illegal_channel_value);
  expect_nak(c, request::write_analog_output(1, 3, 0), ErrorCode::illegal_channel);
  expect_nak(c, request::read_analog_output(1, 3), ErrorCode::illegal_channel);

  c.set_digital_input(4, true);
  EXPECT_EQ(ack_value(c, request::read_digital_input(1, 4)), 1U);
  EXPECT_EQ(ack_value(c, request::read_digital_input(1, 5)), 0U);
  expect_nak(c, request::read_digital_input(1, 8), ErrorCode::illegal_channel);

  expect_ack(c, request::write_digital_output(1, 4, 1));
  EXPECT_EQ(ack_value(c, request::read_digital_output(1, 4)), 1U);
  expect_nak(c, request::write_digital_output(1, 4, 2), ErrorCode::illegal_channel_value);
  expect_nak(c, request::write_digital_output(1, 5, 1), ErrorCode::illegal_channel);
  expect_nak(c, request::read_digital_output(1, 5), ErrorCode::illegal_channel);
}

TEST(Dfs1Controller, OperationalModeNeverMakesTheEstopRemote) {
  Controller c({1});
  expect_ack(c, request::set_operational_mode(1, 0x0006));
  EXPECT_EQ(ack_value(c, request::read_operational_mode(1)), 0x0006U);
  EXPECT_EQ(ack_value(c, request::read_digital_input(1, 2)), 1U);  // remote-on
  // Notes: input 1 is the E-stop and must be 0; the largest mask is 00 00 FF FE.
  expect_nak(c, request::set_operational_mode(1, 0x0001), ErrorCode::illegal_parameter_value);
  expect_nak(c, request::set_operational_mode(1, 0xFFFF), ErrorCode::illegal_parameter_value);
  expect_ack(c, request::set_operational_mode(1, 0xFFFE));
  Frame too_big = request::set_operational_mode(1, 0);
  too_big.data[1] = 0x01;  // 00 01 00 00
  expect_nak(c, too_big, ErrorCode::illegal_parameter_value);
  EXPECT_EQ(ack_value(c, request::read_operational_mode(1)), 0xFFFEU);
}

TEST(Dfs1Controller, AnOpenEstopStopsTheMotor) {
  Controller c = remote_controller();
  expect_ack(c, request::set_and_execute_speed(1, 1500), 0ms);
  c.step(5s);
  EXPECT_NEAR(c.actual_speed(), 1500.0, 1.0);
  c.set_digital_input(kEstopInput, false);
  EXPECT_EQ(ack_value(c, request::read_digital_input(1, kEstopInput)), 0U);
  c.step(10s);
  EXPECT_NEAR(c.actual_speed(), 0.0, 1.0);
  EXPECT_FALSE(c.enabled());
}

TEST(Dfs1Controller, ApplicationModeSelectsMasterOrSlave) {
  Controller c({1});
  expect_ack(c, request::application_mode(1, 1, 0));
  EXPECT_EQ(c.application_mode(), 1);
  EXPECT_EQ(c.st2() & kSt2Slave, kSt2Slave);
  expect_nak(c, request::application_mode(1, 2, 0), ErrorCode::illegal_parameter_value);
  expect_ack(c, request::application_mode(1, 0, 0));
  EXPECT_EQ(c.st2() & kSt2Slave, 0);
}

TEST(Dfs1Controller, DecisionD5NewUidAppliesAfterItsAck) {
  Controller c({1});
  const auto r = exchange(c, request::write_parameter(1, kUnitId, 9));
  ASSERT_TRUE(r && r->is_ack());
  EXPECT_EQ(r->uid, 1);  // answered as asked
  EXPECT_EQ(c.uid(), 9);
  EXPECT_FALSE(exchange(c, request::status(1)));
  EXPECT_TRUE(exchange(c, request::status(9)));
}

TEST(Dfs1Controller, DecisionD2Parameter56IsTheTurnaroundInMilliseconds) {
  Controller c({1});
  expect_ack(c, request::write_parameter(1, kTurnaroundDelay, 25), 0ms);
  c.receive(proto::encode(request::status(1)).span(), 100ms);
  EXPECT_EQ(c.next_deadline(), Time(125ms));
  EXPECT_TRUE(c.pending(124ms).empty());
  EXPECT_FALSE(c.pending(125ms).empty());
}

TEST(Dfs1Controller, EveryCommandIsServed) {
  Controller c = remote_controller();
  const std::vector<Frame> all = {
      request::status(1),
      request::set_speed(1, 5),
      request::execute_speed(1),
      request::set_and_execute_speed(1, 5),
      request::read_parameter(1, 1),
      request::write_parameter(1, 48, 1),
      request::read_analog_input(1, 1),
      request::read_analog_output(1, 1),
      request::write_analog_output(1, 1, 2),
      request::read_digital_input(1, 1),
      request::read_digital_output(1, 1),
      request::write_digital_output(1, 1, 1),
      request::set_operational_mode(1, 0x0006),
      request::read_operational_mode(1),
      request::application_mode(1, 1, 0),
  };
  for (const Frame& f : all) {
    const auto r = exchange(c, f);
    ASSERT_TRUE(r);
    EXPECT_TRUE(r->is_ack()) << proto::to_string(static_cast<proto::Command>(f.code));
    EXPECT_EQ(r->size, proto::command_info(static_cast<proto::Command>(f.code)).response_size);
  }
}

TEST(Dfs1Controller, UidZeroIsRefusedAtConfiguration) {
  EXPECT_THROW(Controller({0}), std::invalid_argument);
}

}  // namespace
}  // namespace ibs::devices::dfs1
