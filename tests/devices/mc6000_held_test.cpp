// Between two bus cycles the MC6000 sees the same words, so the simulator steps it through all
// its samples of that stretch at once (Mc6000Device::step_held). That must be exactly -- bit for
// bit -- what one step() per sample does, through start-up, acceleration, faults, power cycles
// and a bus watchdog that runs out in the middle of a stretch.
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cstdint>
#include <random>

#include "ibs/devices/mc6000/device.hpp"

namespace ibs::devices {
namespace {

using drivecom::State;

struct Pair {
  Mc6000Device held;
  Mc6000Device single;
};

void expect_same(const Mc6000Device& a, const Mc6000Device& b, int window) {
  ASSERT_EQ(a.state(), b.state()) << "window " << window;
  ASSERT_EQ(a.status_word(), b.status_word()) << "window " << window;
  // Bit for bit, not within a tolerance: the same arithmetic in the same order.
  const auto bits = [](double v) { return std::bit_cast<std::uint64_t>(v); };
  ASSERT_EQ(bits(a.actual_rpm()), bits(b.actual_rpm()))
      << "window " << window << ": " << a.actual_rpm() << " vs " << b.actual_rpm();
  ASSERT_EQ(bits(a.torque_nm()), bits(b.torque_nm())) << "window " << window;
  ASSERT_EQ(a.watchdog_tripped(), b.watchdog_tripped()) << "window " << window;
  ASSERT_EQ(a.last_sample().packed, b.last_sample().packed) << "window " << window;
  ASSERT_EQ(a.last_sample().count, b.last_sample().count) << "window " << window;
  std::array<Word, 4> wa{};
  std::array<Word, 4> wb{};
  a.output(wa);
  b.output(wb);
  ASSERT_EQ(wa, wb) << "window " << window;
}

TEST(Mc6000HeldSteps, EqualOneStepPerSampleThroughAWholeRun) {
  for (const int ibcnf : {1, 2, 3}) {
    SCOPED_TRACE("IBCNF " + std::to_string(ibcnf));
    Mc6000DeviceConfig c;
    c.supi = 12;
    c.ibcnf = ibcnf;
    c.bus_watchdog = 20ms;
    Pair p{Mc6000Device(c, DeviceStart::power_on, Time{0}), Mc6000Device(c, DeviceStart::power_on, Time{0})};
    std::mt19937 rng(static_cast<std::uint32_t>(ibcnf));
    // Control words the master sends on the way up and down, and a reset-fault edge.
    const std::array<Word, 7> commands{0x0000, 0x0006, 0x0007, 0x000F, 0x0002, 0x0080, 0x0006};
    constexpr Duration kPeriod = 1ms;
    Time t{0};
    std::array<Word, 4> m2s{};
    int faults = 0;
    int watchdogs = 0;
    for (int w = 0; w < 3000; ++w) {
      // A stretch of 1..30 samples with the same words; the cycle at its start is valid most of
      // the time (arming and feeding the watchdog), sometimes lost so that it runs out.
      const auto n = static_cast<std::uint32_t>(1 + rng() % 30);
      if (rng() % 8 != 0) {
        p.held.bus_cycle(t);
        p.single.bus_cycle(t);
      }
      if (rng() % 5 == 0) m2s[0] = commands[rng() % commands.size()];
      if (w % 40 < 25 && m2s[0] != 0x0080) m2s[0] = 0x000F;  // mostly running
      if (rng() % 6 == 0) {
        const auto q16 = static_cast<std::uint32_t>(devices::mc6000::to_q16(static_cast<double>(rng() % 7000) - 3500.0));
        m2s[1] = high_word(q16);
        m2s[2] = low_word(q16);
      }
      if (ibcnf == 1) m2s[1] = static_cast<Word>(rng() % 4000);
      if (rng() % 97 == 0) {
        const bool f = rng() % 2 == 0;
        p.held.set_fault(f);
        p.single.set_fault(f);
        faults += f ? 1 : 0;
      }
      if (rng() % 31 == 0) {
        const double load = static_cast<double>(rng() % 6) - 2.0;
        p.held.set_load_torque(load);
        p.single.set_load_torque(load);
      }
      if (rng() % 400 == 0) {
        p.held.power_cycle(t);
        p.single.power_cycle(t);
      }
      p.held.step_held(m2s, t, kPeriod, n);
      for (std::uint32_t k = 0; k < n; ++k) p.single.step(m2s, t + static_cast<std::int64_t>(k) * kPeriod);
      t += static_cast<std::int64_t>(n) * kPeriod;
      watchdogs += p.held.watchdog_tripped() ? 1 : 0;
      expect_same(p.held, p.single, w);
    }
    // The run went through the cases that matter.
    EXPECT_GT(faults, 0);
    EXPECT_GT(watchdogs, 0);
  }
}

TEST(Mc6000HeldSteps, TheWatchdogRunsOutAtTheFirstSampleLaterThanItsTime) {
  // 409-BUTWD = 20 ms, the last cycle at 0: samples at 1..20 ms are within the time, the one at
  // 21 ms is not (3.2.4: more than the monitoring time without a cycle).
  Mc6000DeviceConfig c;
  c.supi = 12;
  c.bus_watchdog = 20ms;
  Mc6000Device d(c, DeviceStart::operational, Time{0});
  d.bus_cycle(Time{0});
  const std::array<Word, 4> m2s{0x0006, 0, 0, 0};
  d.step_held(m2s, 1ms, 1ms, 20);
  EXPECT_FALSE(d.watchdog_tripped());
  EXPECT_EQ(d.state(), State::ready);
  d.step_held(m2s, 21ms, 1ms, 1);
  EXPECT_TRUE(d.watchdog_tripped());
  EXPECT_EQ(d.error_number(), ibs::devices::mc6000::kWatchdogError);
}

TEST(Mc6000Watchdog, ErrorSixteenAtLocationOneOf324UntilTheMasterResetsIt) {
  // INTERBUS manual 3.2.4: "The watchdog error number is 16 ('E-OP1'), with error location 1."
  Mc6000DeviceConfig c;
  c.supi = 12;
  c.bus_watchdog = 20ms;
  Mc6000Device d(c, DeviceStart::operational, Time{0});
  std::array<Word, 4> m2s{0x0006, 0, 0, 0};
  std::array<Word, 4> s2m{};
  d.bus_cycle(Time{0});
  d.sample(m2s, s2m, 1ms);
  EXPECT_EQ(d.error_number(), std::nullopt);
  EXPECT_EQ(d.error_location(), std::nullopt);
  // No cycle for more than 20 ms: the fault.
  Time t = 1ms;
  while (t <= Time{25ms}) {
    t += 1ms;
    d.sample(m2s, s2m, t);
  }
  EXPECT_EQ(d.error_number(), 16);
  EXPECT_EQ(d.error_location(), 1);
  EXPECT_EQ(d.error_location(), ibs::devices::mc6000::kWatchdogLocation);
  EXPECT_EQ(d.state(), State::fault);
  // Data flows again: the error stays latched until the master resets it (5.1.2, RESET FAULT).
  for (int k = 0; k < 5; ++k) {
    t += 1ms;
    d.bus_cycle(t);
    d.sample(m2s, s2m, t);
  }
  EXPECT_EQ(d.error_location(), 1);
  m2s[0] = 0x0080;
  t += 1ms;
  d.bus_cycle(t);
  d.sample(m2s, s2m, t);
  EXPECT_EQ(d.state(), State::start_up_inhibit);
  EXPECT_EQ(d.error_number(), std::nullopt);
  EXPECT_EQ(d.error_location(), std::nullopt);
}

}  // namespace
}  // namespace ibs::devices
