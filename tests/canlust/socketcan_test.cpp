// SocketCAN: the real transport. This project's build machine has no CAN in its kernel, so the
// tests skip there with the reason; on a machine with `vcan0` they run.
#include <gtest/gtest.h>

#include <string>

#include "ibs/can/socketcan.hpp"

namespace ibs::can {
namespace {

TEST(SocketCan, OpenFailsWithAReasonWithoutCanInTheKernel) {
  std::string why;
  if (socketcan_available(&why)) GTEST_SKIP() << "this kernel has SocketCAN; see VcanLoopback";
  const auto t = SocketCan::open("can0");
  EXPECT_FALSE(t);
  EXPECT_NE(t.error.find("socket(PF_CAN)"), std::string::npos) << t.error;
}

TEST(SocketCan, VcanLoopback) {
  std::string why;
  if (!socketcan_available(&why)) GTEST_SKIP() << "no SocketCAN in this kernel: " << why;
  auto a = SocketCan::open("vcan0");
  if (!a) GTEST_SKIP() << "no vcan0: " << a.error;
  auto b = SocketCan::open("vcan0");
  ASSERT_TRUE(b) << b.error;
  const auto f = CanFrame::make(1103, {0x68, 0x01, 0x05, 0, 0, 0, 0, 0});
  ASSERT_EQ(a.transport->send(f), IoStatus::ok) << a.transport->last_error();
  const auto r = b.transport->receive(std::chrono::milliseconds(500));
  ASSERT_EQ(r.status, IoStatus::ok);
  EXPECT_EQ(r.frame, f);
}

TEST(SocketCan, BadInterfaceName) {
  EXPECT_FALSE(SocketCan::open(""));
  EXPECT_FALSE(SocketCan::open("an-interface-name-far-too-long"));
}

}  // namespace
}  // namespace ibs::can
