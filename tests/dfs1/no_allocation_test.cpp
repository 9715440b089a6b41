// The cycle path allocates nothing (design.md): encode, decode, host transactions, the
// controller's receiver and emulator, the master's queue and the simulated line all run between
// two readings of the shared allocation counter (tests/support/counting_new.hpp).
#include <gtest/gtest.h>

#include "../support/counting_new.hpp"
#include "ibs/devices/dfs1/line.hpp"
#include "ibs/devices/dfs1/served_controller.hpp"
#include "ibs/dfs1/host.hpp"

namespace ibs::devices::dfs1 {
namespace {

namespace proto = ::ibs::dfs1;
namespace request = proto::request;

TEST(Dfs1CyclePath, AllocatesNothing) {
  Master master({50ms, 5ms});
  Controller a({1});
  Controller b({2});
  SimulatedLine line(master, {&a, &b}, 19200);
  std::size_t acks = 0;
  std::size_t others = 0;

  test::AllocationCounter counting;
  for (int round = 0; round < 50; ++round) {
    (void)master.submit(request::write_parameter(1, 3, 15));
    (void)master.submit(request::set_and_execute_speed(1, 100 + round));
    (void)master.submit(request::status(1));
    (void)master.submit(request::status(2));
    (void)master.submit(request::read_parameter(2, 99));  // NAK 82
    (void)master.submit(request::status(9));              // timeout
    (void)master.submit(request::execute_speed(0));       // global
    (void)master.submit(proto::request::read_digital_input(2, 1));
    line.run_until_idle(line.now() + 10s);
    while (auto c = master.take_completion()) {
      (c->result.outcome == proto::Outcome::ack ? acks : others) += 1;
    }
    proto::FrameDecoder d;
    const auto frame = proto::encode(request::set_speed(1, 4096));  // outlives the loop over its bytes
    for (std::uint8_t byte : frame.span()) (void)d.push(byte);
  }
  EXPECT_EQ(counting.count(), 0);
  EXPECT_EQ(acks, 50U * 5U);
  EXPECT_EQ(others, 50U * 3U);
}

// Events (events.hpp) are applied inside the serve loop's turn: no allocation there either.
TEST(Dfs1CyclePath, ApplyingAndServingEventsAllocatesNothing) {
  Controller c({1});
  ServedController d{c};
  test::AllocationCounter counting;
  Time t{};
  for (int i = 0; i < 20; ++i) {
    (void)c.apply(Event::fault(FaultCause::stall, 10ms), t += 1ms);
    (void)c.apply(Event::mains(i % 2 == 0), t += 1ms);
    (void)c.apply(Event::input_level(1, i % 2 == 0), t += 1ms);
    (void)c.apply(Event::load(static_cast<std::uint32_t>(i)), t += 1ms);
    (void)c.apply(Event::power_cycle(), t += 1ms);
    (void)d.post(Event::fault(FaultCause::micro_fault));
    d.advance(t += 1ms);
    (void)d.take_report();
  }
  EXPECT_EQ(counting.count(), 0);
}

}  // namespace
}  // namespace ibs::devices::dfs1
