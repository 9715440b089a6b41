// RESET FAULT on the VF1000 is a software reset (INTERBUS manual 5.2.1, bit 7: "The inverter performs a
// software reset !"): the inverter boots again, the link is gone during the self-test (LUSTBUS manual,
// 8.1.1) and the power-on bit of 85-SIOF is set afterwards (LUSTBUS manual 9.2).
#include <gtest/gtest.h>

#include <array>

#include "ibs/devices/vf1000/device.hpp"
#include "ibs/devices/vf1000/parameters.hpp"
#include "ibs/drive/siof.hpp"

namespace ibs::devices {
namespace {

using drivecom::State;

constexpr Duration kSample = vf1000::kSamplePeriod;

struct Rig {
  explicit Rig(Vf1000DeviceConfig c = {}) : d(c, DeviceStart::operational, Time{0}) {}
  // Samples with `control` (reference 0, idle channel) until `until`, feeding the watchdog.
  void run(Word control, Time until) {
    m2s[0] = control;
    while (now < until) {
      now += kSample;
      d.bus_cycle(now);
      d.sample(m2s, s2m, now);
    }
  }
  void sample(Word control) { run(control, now + kSample); }
  // Samples without any bus cycle reaching the inverter: what the bus delivers while the inverter
  // shows its module error (the simulator, as a board, carries no data then).
  void run_silent(Word control, Time until) {
    m2s[0] = control;
    while (now < until) {
      now += kSample;
      d.sample(m2s, s2m, now);
    }
  }
  Vf1000Device d;
  std::array<Word, 3> m2s{0x0000, 0x0000, 0x0000};
  std::array<Word, 3> s2m{};
  Time now{0};
};

// Brings the inverter into FAULT through a fault cause, then removes the cause.
void fault_and_clear(Rig& r) {
  r.d.set_fault(true);
  r.run(0x0000, r.now + 50ms);
  ASSERT_EQ(r.d.state(), State::fault);
  r.d.set_fault(false);
  r.run(0x0000, r.now + 50ms);
  ASSERT_EQ(r.d.state(), State::fault);
}

TEST(Vf1000Reset, ResetFaultRebootsTheInverterWithAModuleErrorForItsSelfTest) {
  Rig r;
  r.run(0x0000, 100ms);
  // 85-SIOF read and clear at the start (operational).
  EXPECT_EQ(r.d.channel().siof(), 0);
  fault_and_clear(r);
  r.sample(0x0080);  // the rising edge of bit 7
  const Time reset_at = r.now;
  EXPECT_EQ(r.d.software_resets(), 1U);
  EXPECT_EQ(r.d.state(), State::not_ready);
  EXPECT_TRUE(r.d.module_error(r.now));
  EXPECT_EQ(r.s2m[0] & 0x004FU, 0x0000U) << "NOT READY";
  EXPECT_EQ(r.s2m[2], 0x0000) << "RESET distinction 0 during the self-test (4.1.2.2)";
  // The self-test lasts the reset time (default 4 s, as 6.1's boot).
  r.run(0x0000, reset_at + 3900ms);
  EXPECT_TRUE(r.d.module_error(r.now));
  EXPECT_EQ(r.d.state(), State::not_ready);
  r.run(0x0000, reset_at + 4100ms);
  EXPECT_FALSE(r.d.module_error(r.now));
  EXPECT_EQ(r.d.state(), State::start_up_inhibit);
  EXPECT_EQ(r.s2m[2], 0x8000) << "wait mode again";
  // 9.2: after the new start the power-on bit is set; the master reads 85 before its next value
  // transfer (the server refuses transfers until then: vf1000_comm_power_on_refusal.trace).
  EXPECT_TRUE(drive::siof_has(r.d.channel().siof(), drive::SiofBit::power_on));
  EXPECT_EQ(r.d.software_resets(), 1U);
}

// The reset restarts the inverter's firmware: like a power-on, 906-IB-WD monitors the bus again
// only from the first data cycle after the self-test. Before, the watchdog went on running through
// the self-test (no data reach an inverter with a module error), ran out, and the inverter came
// back in FAULT (E-IBS) after every reset the master sent.
TEST(Vf1000Reset, TheBusWatchdogStartsAgainAfterTheSelfTestNotDuringIt) {
  Rig r;
  ASSERT_TRUE(r.d.channel().set_value(vf1000::pnr::kIbWd, 200));
  ASSERT_TRUE(r.d.channel().set_value(vf1000::pnr::kIbcod, static_cast<Word>(vf1000::IbCod::shutdown_e_ibs)));
  r.run(0x0000, 100ms);  // data flows: the watchdog is armed
  fault_and_clear(r);
  r.sample(0x0080);
  ASSERT_EQ(r.d.software_resets(), 1U);
  const Time reset_at = r.now;
  r.run_silent(0x0000, reset_at + 4100ms);
  EXPECT_FALSE(r.d.module_error(r.now));
  EXPECT_FALSE(r.d.watchdog_tripped()) << "no watchdog during the self-test";
  EXPECT_EQ(r.d.state(), State::start_up_inhibit) << "back from the reset, not in FAULT again";
  EXPECT_EQ(r.d.error_number(), std::nullopt);
  // Data flows again, then stops: the watchdog monitors as before and trips after 200 ms.
  r.run(0x0000, r.now + 100ms);
  const Time last_data = r.now;
  r.run_silent(0x0000, last_data + 150ms);
  EXPECT_FALSE(r.d.watchdog_tripped());
  r.run_silent(0x0000, last_data + 300ms);
  EXPECT_TRUE(r.d.watchdog_tripped());
  EXPECT_EQ(r.d.state(), State::fault);
}

TEST(Vf1000Reset, ABitHeldHighRestartsTheInverterOnlyOnce) {
  Rig r;
  r.run(0x0000, 100ms);
  fault_and_clear(r);
  r.run(0x0080, r.now + 5s);  // bit 7 held high through the reset and after it
  EXPECT_EQ(r.d.software_resets(), 1U);
  EXPECT_EQ(r.d.state(), State::start_up_inhibit);
  // The fault comes back while bit 7 is still high: FAULT again, and no new reset without an edge.
  r.d.set_fault(true);
  r.run(0x0080, r.now + 100ms);
  r.d.set_fault(false);
  r.run(0x0080, r.now + 5s);
  EXPECT_EQ(r.d.state(), State::fault);
  EXPECT_EQ(r.d.software_resets(), 1U);
  // A new edge resets it again.
  r.run(0x0000, r.now + 50ms);
  r.run(0x0080, r.now + 50ms);
  EXPECT_EQ(r.d.software_resets(), 2U);
  EXPECT_EQ(r.d.state(), State::not_ready);
}

TEST(Vf1000Reset, AResetWhileTheCauseIsPresentIsNotTaken) {
  // Transition 15 needs the cause gone (erratum PD4, DeviceStateMachine): without it the inverter
  // stays in FAULT and does not boot (decision D13).
  Rig r;
  r.run(0x0000, 100ms);
  r.d.set_fault(true);
  r.run(0x0000, 200ms);
  r.run(0x0080, r.now + 100ms);
  EXPECT_EQ(r.d.software_resets(), 0U);
  EXPECT_EQ(r.d.state(), State::fault);
  EXPECT_FALSE(r.d.module_error(r.now));
}

TEST(Vf1000Reset, TheSelfTestTimeIsASetting) {
  Vf1000DeviceConfig c;
  c.pd.reset_time = 1s;
  Rig r(c);
  r.run(0x0000, 100ms);
  fault_and_clear(r);
  r.sample(0x0080);
  const Time reset_at = r.now;
  r.run(0x0000, reset_at + 950ms);
  EXPECT_TRUE(r.d.module_error(r.now));
  r.run(0x0000, reset_at + 1050ms);
  EXPECT_FALSE(r.d.module_error(r.now));
  EXPECT_EQ(r.d.state(), State::start_up_inhibit);
}

}  // namespace
}  // namespace ibs::devices
