// The frame path allocates nothing: node, master, parameter server and client, telegram codecs,
// the virtual bus and the cannelloni codec, through whole exchanges after construction.
#include <gtest/gtest.h>

#include "../support/counting_new.hpp"
#include "harness.hpp"
#include "ibs/can/cannelloni.hpp"

namespace ibs::canlust {
namespace {

TEST(CanlustFramePath, NoAllocationAfterConstruction) {
  test::Harness h;
  h.add_drive(test::node_config(1, 10ms, 50ms));
  h.add_drive(test::node_config(2, 10ms, 50ms));
  auto& c = h.master().parameters();
  c.submit(read(1, test::kParamDisp));
  h.run_until(Time{300ms});  // warm-up (the harness's own vectors grow here)
  ibs::test::AllocationCounter counter;
  h.master().system_start();
  for (int round = 0; round < 5; ++round) {
    c.submit(read(1, test::kParamDisp));
    c.submit(write(2, test::kParamDisp, 12));
    c.submit(write_string(1, test::kParamText, "no allocation here"));
    c.submit(read_string(2, test::kParamName));
    c.submit(describe(1, test::kParamDisp, 1));
    h.master().send_control(1, {0x000F, q16_from_double(20.5)});
    h.master().send_control(2, {0x0006, 0});
    h.run_for(100ms);
  }
  std::array<std::uint8_t, 64> buf{};
  std::array<CanFrame, 4> out{};
  const auto f = CanFrame::make(1323, {0x68, 0x01, 0x00, 0x96, 0x01, 0x00, 0x00, 0x00});
  const auto n = can::cannelloni::encode(std::span(&f, 1), 1, buf);
  can::cannelloni::decode(std::span(buf.data(), *n), out);
  EXPECT_EQ(counter.count(), 0);
  EXPECT_TRUE(c.idle());
  EXPECT_GT(h.drive(0).watchdog_events.size(), 0U);
}

}  // namespace
}  // namespace ibs::canlust
