// The cycle path allocates nothing: every step of both DRIVECOM sides and of the drives' process-
// data models runs with a counting operator new that must stay at zero.
#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <cstdlib>
#include <new>

#include "ibs/devices/drive_pd.hpp"
#include "ibs/drivecom/device_state_machine.hpp"
#include "ibs/drivecom/sequencer.hpp"

namespace {
std::atomic<bool> g_counting{false};
std::atomic<long> g_allocations{0};
}  // namespace

void* operator new(std::size_t n) {
  if (g_counting.load()) g_allocations.fetch_add(1);
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) { return operator new(n); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
// The nothrow forms too, so that every allocation and its release go through malloc/free.
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  if (g_counting.load()) g_allocations.fetch_add(1);
  return std::malloc(n == 0 ? 1 : n);
}
void* operator new[](std::size_t n, const std::nothrow_t& t) noexcept { return operator new(n, t); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }

namespace ibs {
namespace {

struct Counting {
  Counting() {
    g_allocations = 0;
    g_counting = true;
  }
  ~Counting() { g_counting = false; }
  long count() const { return g_allocations.load(); }
};

TEST(CyclePath, CounterSeesAnAllocation) {
  // Proves the counter works, so the zero below means something.
  Counting c;
  auto* p = new int(4);
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
    if (i % 8 == 0) vf.sample(vf_out, vf_in, kVf1000SamplePeriod);
    mc_master.cycle(mc_in, mc_out, now);
    vf_master.cycle(vf_in, vf_out, now, 0);
    now += 1ms;
  }
  EXPECT_EQ(c.count(), 0);
  EXPECT_EQ(mc.state(), drivecom::State::emergency_stop_active);
}

}  // namespace
}  // namespace ibs
