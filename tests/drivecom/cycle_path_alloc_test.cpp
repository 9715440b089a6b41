// The cycle path allocates nothing: every step of both DRIVECOM sides and of the drives' process-
// data models runs with a counting operator new that must stay at zero.
#include <gtest/gtest.h>

#include <array>

#include "ibs/devices/mc6000/pd_device.hpp"
#include "ibs/devices/mc6000/pd_master.hpp"
#include "ibs/devices/vf1000/pd_device.hpp"
#include "ibs/devices/vf1000/pd_master.hpp"
#include "ibs/drivecom/device_state_machine.hpp"
#include "ibs/drivecom/sequencer.hpp"

#include "../support/counting_new.hpp"

namespace ibs {
namespace {

using Counting = test::AllocationCounter;

TEST(CyclePath, CounterSeesAnAllocation) {
  // Proves the counter works, so the zero below means something.
  Counting c;
  auto* p = new int(4);
  test::escape(p);
  delete p;
  EXPECT_EQ(c.count(), 1);
}

TEST(CyclePath, DrivecomBothSidesAllocateNothing) {
  using namespace drivecom;
  DeviceStateMachine device(EmergencyStopExit::on_block_power_only, State::fault);
  Sequencer seq;
  Word status = status_word(State::fault, 0, {});
  Counting c;
  seq.request(Target::enabled, 0ms);
  Time now{0};
  for (int i = 0; i < 2000; ++i) {
    if (i == 500) seq.request_emergency_stop(now);
    if (i == 700) seq.request_block_power(now);
    if (i == 900) seq.request(Target::enabled, now);
    DeviceInputs in;
    in.control = seq.step(status, now);
    in.fault_present = i >= 1200 && i < 1250;
    device.sample(in);
    status = status_word(device.state(), device.last_control(), {});
    now += 1ms;
  }
  EXPECT_EQ(c.count(), 0);
}

TEST(CyclePath, DriveModelsAndMasterDriversAllocateNothing) {
  devices::Mc6000PdDevice mc;
  devices::Vf1000PdDevice vf;
  devices::Mc6000PdMaster mc_master(mc.layout());
  devices::Vf1000PdMaster vf_master;
  std::array<Word, 3> mc_out{}, mc_in{}, vf_out{}, vf_in{};
  Counting c;
  mc.power_on();
  vf.power_on();
  mc_master.sequencer().request(drivecom::Target::enabled, 0ms);
  vf_master.sequencer().request(drivecom::Target::enabled, 0ms);
  mc_master.set_reference_rpm(1500.0);
  vf_master.set_frequency_hz(-30.0);
  Time now{0};
  for (int i = 0; i < 8000; ++i) {
    if (i == 6000) {
      mc_master.sequencer().request_emergency_stop(now);
      vf_master.sequencer().request_emergency_stop(now);
    }
    mc.sample(mc_out, mc_in, 1ms);
    if (i % 8 == 0) vf.sample(vf_out, vf_in, ibs::devices::vf1000::kSamplePeriod);
    mc_master.cycle(mc_in, mc_out, now);
    vf_master.cycle(vf_in, vf_out, now, 0);
    now += 1ms;
  }
  EXPECT_EQ(c.count(), 0);
  EXPECT_EQ(mc.state(), drivecom::State::emergency_stop_active);
}

}  // namespace
}  // namespace ibs
