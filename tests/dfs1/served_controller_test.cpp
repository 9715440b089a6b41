// The controller as a serving loop sees it (base::LineDevice): its reply comes out once the
// turnaround of parameter 56 has passed (D2), is consumed as written, and the plant follows the
// loop's time; and the names of the status bits that `ibs dfs1 status` prints.
#include "ibs/devices/dfs1/served_controller.hpp"

#include <gtest/gtest.h>

#include <string_view>
#include <vector>

#include "ibs/devices/dfs1/status.hpp"
#include "ibs/dfs1/host.hpp"

namespace ibs::devices::dfs1 {
namespace {

namespace proto = ::ibs::dfs1;
namespace request = proto::request;
using Names = std::vector<std::string_view>;

TEST(Dfs1ServedController, ReplyAfterTheTurnaroundThenConsumed) {
  Controller c({1});
  ServedController d{c};
  EXPECT_EQ(d.line_baud(), 0U);  // the DFS-1 runs at the port's rate
  d.receive(proto::encode(request::write_parameter(1, kTurnaroundDelay, 25)).span(), Time{0ms});
  const auto ack = d.output(Time{25ms});
  ASSERT_FALSE(ack.empty());
  d.written(ack.size());
  d.receive(proto::encode(request::status(1)).span(), Time{100ms});
  EXPECT_EQ(d.next_due(), Time(125ms));
  EXPECT_TRUE(d.output(Time{124ms}).empty());
  const auto reply = d.output(Time{125ms});
  ASSERT_FALSE(reply.empty());
  d.written(reply.size() - 1);  // a partial write leaves the rest due
  EXPECT_EQ(d.output(Time{125ms}).size(), 1U);
  d.written(1);
  EXPECT_TRUE(d.output(Time{200ms}).empty());
  EXPECT_FALSE(d.next_due());
}

TEST(Dfs1ServedController, ReceivingNothingStillStepsThePlant) {
  Controller c({1});
  ServedController d{c};
  d.receive(proto::encode(request::write_parameter(1, kRemoteFunctions, kRemoteAll)).span(), Time{0ms});
  d.written(d.output(Time{1s}).size());
  d.receive(proto::encode(request::set_and_execute_speed(1, 1000)).span(), Time{1s});
  d.written(d.output(Time{2s}).size());
  d.receive({}, Time{10s});  // no bytes: time passes all the same
  EXPECT_NEAR(c.actual_speed(), 1000.0, 1.0);
}

TEST(Dfs1StatusNames, BitSevenDownAsDocumented) {
  EXPECT_EQ(st2_flags(0), Names{});
  EXPECT_EQ(st1_flags(0), Names{});
  EXPECT_EQ(st2_flags(kSt2AtSpeed | kSt2Forward | kSt2ZeroSpeed), (Names{"at-speed", "forward", "zero-speed"}));
  EXPECT_EQ(st2_flags(0xFF), (Names{"remote", "slave", "at-speed", "forward", "fault", "enabled", "uP-fault",
                                    "zero-speed"}));
  EXPECT_EQ(st1_flags(0xFF), (Names{"bus-not-charged", "IOC", "stall", "I2t", "heatsink-overtemp", "commutation",
                                    "overvolt", "undervolt"}));
  EXPECT_EQ(st1_flags(kSt1Overvolt), Names{"overvolt"});
}

}  // namespace
}  // namespace ibs::devices::dfs1
