// The drives' process-data behaviour around the state machine: INTERBUS manual 5.2 (VF1000), 5.3 (MC6000).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <span>
#include <vector>

#include "ibs/devices/mc6000/pd_device.hpp"
#include "ibs/devices/mc6000/pd_master.hpp"
#include "ibs/devices/vf1000/pd_device.hpp"
#include "ibs/devices/vf1000/pd_master.hpp"

namespace ibs::devices {
namespace {

using drivecom::State;

struct Vf {
  Vf1000PdDevice dev;
  std::array<Word, 3> out{}, in{};
  void samples(int n) {
    for (int i = 0; i < n; ++i) dev.sample(out, in, ibs::devices::vf1000::kSamplePeriod);
  }
};

TEST(Vf1000Pd, InitialisesForAboutFourSecondsWithTheResetDistinctionBitLow) {
  Vf v;
  v.dev.power_on();
  v.out = {0x0006, 0, 0};
  v.samples(487);  // 487 * 8.2 ms = 3.99 s
  EXPECT_EQ(v.dev.state(), State::not_ready);
  EXPECT_EQ(v.in[0] & 0x4FU, 0U);
  EXPECT_EQ(v.in[2], 0x0000);  // 4.1.2.2 bit 7 of the high byte = 0 while initialising
  v.samples(1);
  EXPECT_EQ(v.dev.state(), State::ready);  // 1 then 2: SHUTDOWN was waiting
  EXPECT_EQ(v.in[2], 0x8000);
}

TEST(Vf1000Pd, RunsClockwiseWithStrAndCounterClockwiseWithStl) {
  Vf v;
  v.out = {0x8076, 400, 0};  // SHUTDOWN, ramp bits, STR, 20 Hz
  v.samples(2);
  v.out[0] = 0x807F;
  v.samples(200);
  EXPECT_DOUBLE_EQ(v.dev.frequency_hz(), 20.0);
  EXPECT_EQ(v.in[1], 400);
  EXPECT_EQ(v.in[0] & 0x0400U, 0x0400U);  // reference reached
  v.out[0] = 0x407F;                      // STL: the same reference counter-clockwise
  v.samples(400);
  EXPECT_DOUBLE_EQ(v.dev.frequency_hz(), -20.0);
  EXPECT_EQ(v.in[1], static_cast<Word>(-400));
  v.out[0] = 0xC07F;  // both: no direction
  v.samples(400);
  EXPECT_DOUBLE_EQ(v.dev.frequency_hz(), 0.0);
}

TEST(Vf1000Pd, RampGeneratorBits4To6) {
  Vf v;
  v.out = {0x8076, 1000, 0};
  v.samples(2);
  v.out[0] = 0x807F;
  v.samples(100);  // ramping up, 0.82 s * 20 Hz/s
  const double f = v.dev.frequency_hz();
  EXPECT_GT(f, 15.0);
  EXPECT_LT(f, 50.0);
  v.out[0] = 0x805F;  // bit 5 = 0: the ramp stops at its current value
  v.samples(50);
  EXPECT_DOUBLE_EQ(v.dev.frequency_hz(), f);
  v.out[0] = 0x803F;  // bit 6 = 0: ramp to 0 Hz
  v.samples(300);
  EXPECT_DOUBLE_EQ(v.dev.frequency_hz(), 0.0);
  EXPECT_EQ(v.dev.state(), State::enabled);
  v.out[0] = 0x807F;
  v.samples(50);
  EXPECT_GT(v.dev.frequency_hz(), 0.0);  // bit 6 back to 1: the ramp restarts
  v.out[0] = 0x806F;                     // bit 4 = 0: the stop function (36-RSTOP)
  v.samples(300);
  EXPECT_DOUBLE_EQ(v.dev.frequency_hz(), 0.0);
}

TEST(Vf1000Pd, EmergencyStopWithoutStopRampSwitchesOffAtOnce) {
  Vf v;
  v.dev.set_stop_ramp(0.0);  // 36-RSTOP = 0
  v.out = {0x8076, 1000, 0};
  v.samples(2);
  v.out[0] = 0x807F;
  v.samples(100);
  ASSERT_GT(v.dev.frequency_hz(), 0.0);
  v.out[0] = 0x807B;
  v.samples(1);
  EXPECT_EQ(v.dev.state(), State::start_up_inhibit);
  ASSERT_EQ(v.dev.last_sample().count, 2);
  EXPECT_EQ(v.dev.last_sample().transition(0), 11);
  EXPECT_EQ(v.dev.last_sample().transition(1), 12);
}

TEST(Vf1000Pd, ReferenceWordIsAnAbsoluteValueIn005Hz) {
  EXPECT_EQ(ibs::devices::vf1000::reference_word(50.0), 1000);
  EXPECT_EQ(ibs::devices::vf1000::reference_word(-50.0), 1000);
  EXPECT_DOUBLE_EQ(ibs::devices::vf1000::reference_hz(0x03E8), 50.0);
  EXPECT_EQ(ibs::devices::vf1000::reference_word(1e9), 0xFFFF);
}

TEST(Mc6000Pd, EmergencyStopBrakesAndStaysUntilBlockPower) {
  Mc6000PdDevice dev;
  std::array<Word, 3> out{0x0006, 0x03E8, 0x0000}, in{};  // 1000 rpm
  dev.sample(out, in, 1ms);
  out[0] = 0x000F;
  for (int i = 0; i < 1000; ++i) dev.sample(out, in, 1ms);
  ASSERT_NEAR(dev.actual_rpm(), 1000.0, 0.01);  // the plant's speed loop has settled
  EXPECT_EQ(in[0], 0x0637);
  out[0] = 0x000B;
  for (int i = 0; i < 200; ++i) dev.sample(out, in, 1ms);
  EXPECT_NEAR(dev.actual_rpm(), 0.0, 0.5);  // braked at the torque limit to standstill
  EXPECT_EQ(dev.state(), State::emergency_stop_active);
  EXPECT_EQ(in[0], 0x0217);
  out[0] = 0x0000;
  dev.sample(out, in, 1ms);
  EXPECT_EQ(dev.state(), State::start_up_inhibit);
}

TEST(Mc6000Pd, FaultReactionBrakesThenFault) {
  Mc6000PdDevice dev;
  std::array<Word, 3> out{0x0006, 0x03E8, 0x0000}, in{};
  dev.sample(out, in, 1ms);
  out[0] = 0x000F;
  for (int i = 0; i < 100; ++i) dev.sample(out, in, 1ms);
  dev.set_fault(true);
  dev.sample(out, in, 1ms);
  EXPECT_EQ(dev.state(), State::fault_response_active);
  for (int i = 0; i < 100; ++i) dev.sample(out, in, 1ms);
  EXPECT_EQ(dev.state(), State::fault);
  EXPECT_EQ(in[0] & 0x4FU, 0x08U);
}

TEST(Mc6000Pd, ReferenceBeyondTheSpeedLimitSetsLimitValue) {
  Mc6000PdDevice dev;
  std::array<Word, 3> out{0x0006, 0x2710, 0x0000}, in{};  // 10000 rpm > 6000
  dev.sample(out, in, 1ms);
  out[0] = 0x000F;
  for (int i = 0; i < 2000; ++i) dev.sample(out, in, 1ms);
  EXPECT_NEAR(dev.actual_rpm(), 6000.0, 0.1);
  EXPECT_EQ(in[0] & 0x0800U, 0x0800U);
  EXPECT_EQ(in[0] & 0x0400U, 0U);
}

TEST(Mc6000Pd, Ibcnf3SendsSpeedAndTorqueInTheirOwnWords) {
  // 3.2.3: IBCNF 3 answers with a 16-bit speed (1st word) and a 16-bit torque (2nd word); the
  // torque reads in % of the rated torque (docs/bus.md).
  Mc6000PdConfig c;
  c.layout = devices::mc6000::make_layout(10, 3);
  Mc6000PdDevice dev(c);
  const auto q16 = static_cast<std::uint32_t>(devices::mc6000::to_q16(2500.25));
  std::array<Word, 3> out{0x0006, high_word(q16), low_word(q16)}, in{};
  dev.sample(out, in, 1ms);
  out[0] = 0x000F;
  for (int i = 0; i < 50; ++i) dev.sample(out, in, 1ms);
  // Accelerating in the torque limit: 10 Nm of 4 Nm rated.
  EXPECT_EQ(static_cast<std::int16_t>(in[1]), static_cast<std::int16_t>(std::lround(dev.actual_rpm())));
  EXPECT_EQ(static_cast<std::int16_t>(in[2]), 250);
  for (int i = 0; i < 2000; ++i) dev.sample(out, in, 1ms);
  // At speed the torque only covers friction: 0.1 Nm + 2e-4 Nm s/rad * 261.8 rad/s = 0.152 Nm, 4 %.
  EXPECT_EQ(static_cast<std::int16_t>(in[1]), 2500);
  EXPECT_EQ(static_cast<std::int16_t>(in[2]), 4);
  const auto a = devices::mc6000::decode_actual(c.layout, std::span<const Word>(in).subspan(1));
  EXPECT_EQ(a.value, 2500.0);
  EXPECT_EQ(a.torque, 4.0);
}

TEST(Mc6000Pd, Supi0ExchangesNoData) {
  Mc6000PdConfig c;
  c.layout = devices::mc6000::make_layout(0, 0);
  Mc6000PdDevice dev(c);
  std::array<Word, 1> out{0x000F}, in{0xFFFF};
  dev.sample(out, in, 1ms);
  EXPECT_EQ(in[0], 0x0000);
}

TEST(PdMasters, Mc6000MasterWritesQ16AndReadsActual) {
  Mc6000PdMaster m(devices::mc6000::make_layout(11, 2));
  m.set_reference_rpm(2500.25);
  std::array<Word, 3> s2m{0x0637, 0x09C4, 0x4000}, m2s{};
  m.sequencer().request(drivecom::Target::enabled, 0ms);
  m.cycle(s2m, m2s, 0ms);
  EXPECT_EQ(m2s[0], 0x000F);
  EXPECT_EQ(m2s[1], 0x09C4);
  EXPECT_EQ(m2s[2], 0x4000);
  EXPECT_DOUBLE_EQ(m.actual_rpm(), 2500.25);
}

TEST(PdMasters, Vf1000MasterSetsDirectionAndRampBits) {
  Vf1000PdMaster m;
  m.set_frequency_hz(-12.5);
  std::array<Word, 3> s2m{0x0231, 0, 0x8000}, m2s{};
  m.sequencer().request(drivecom::Target::enabled, 0ms);
  m.cycle(s2m, m2s, 0ms, 0x2416);
  EXPECT_EQ(m2s[0], 0x407F);  // STL, ramp bits 4-6, ENABLE
  EXPECT_EQ(m2s[1], 250);
  EXPECT_EQ(m2s[2], 0x2416);
}

// Mc6000PdMaster::cycle skips cycle_general's calls when the actual words, the reference and the
// sequencer's hold are unchanged (docs/performance.md, "Issue 26"). Two masters, one through
// cycle() and one through cycle_general(), get the same random words, references, requests and
// layouts; the words written, the actual decoded and the sequencer's report must be the same.
TEST(Mc6000PdMasterShortcut, CycleWritesAndDecodesAsTheGeneralCycleOverRandomRuns) {
  const std::array<std::pair<int, int>, 5> layouts{{{11, 2}, {12, 2}, {12, 3}, {10, 2}, {8, 1}}};
  for (std::uint32_t seed = 1; seed <= 40; ++seed) {
    std::mt19937 rng(seed);
    const auto [supi, ibcnf] = layouts[seed % layouts.size()];
    const auto layout = devices::mc6000::make_layout(supi, ibcnf);
    Mc6000PdMaster fast(layout), general(layout);
    const std::size_t words = static_cast<std::size_t>(layout.pd_words);
    std::vector<Word> s2m(words, 0), out_fast(words, 0), out_general(words, 0);
    const std::array<Word, 6> statuses{0x0240, 0x0221, 0x0223, 0x0637, 0x0208, 0x0627};
    Time now{0};
    for (int i = 0; i < 3000; ++i) {
      const auto r = static_cast<unsigned>(rng() % 100);
      if (r < 3) {
        const auto t = static_cast<drivecom::Target>(rng() % 4);
        fast.sequencer().request(t, now);
        general.sequencer().request(t, now);
      } else if (r < 6) {
        const double rpm = static_cast<double>(static_cast<int>(rng() % 8000) - 4000) / 3.0;
        fast.set_reference_rpm(rpm);
        general.set_reference_rpm(rpm);
      } else if (r < 12) {
        for (std::size_t w = 1; w < words; ++w) s2m[w] = static_cast<Word>(rng());
      } else if (r < 30) {
        s2m[0] = statuses[rng() % statuses.size()];
      }
      // Fewer words now and then: a short slice takes the general cycle in both.
      const std::size_t n = rng() % 50 == 0 ? rng() % (words + 1) : words;
      fast.cycle(std::span<const Word>(s2m.data(), n), std::span<Word>(out_fast.data(), n), now);
      general.cycle_general(std::span<const Word>(s2m.data(), n), std::span<Word>(out_general.data(), n), now);
      ASSERT_EQ(out_fast, out_general) << "seed " << seed << " cycle " << i;
      ASSERT_EQ(fast.actual().value, general.actual().value) << "seed " << seed << " cycle " << i;
      ASSERT_EQ(fast.actual().torque, general.actual().torque);
      ASSERT_EQ(fast.sequencer().last_control(), general.sequencer().last_control());
      ASSERT_EQ(fast.sequencer().report().phase, general.sequencer().report().phase);
      ASSERT_EQ(fast.sequencer().report().status_seen, general.sequencer().report().status_seen);
      now += 1ms;
    }
  }
}

}  // namespace
}  // namespace ibs::devices
