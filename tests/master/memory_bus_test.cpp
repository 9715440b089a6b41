// The bus seam (master/bus.hpp): the in-memory bus carries the words both ways and reports what
// the far side says; the master loop brings an MC6000 and a VF1000 to ENABLED through it against
// the drives' emulators, reads a parameter from each, and allocates nothing in the cycle.
#include <gtest/gtest.h>

#include <memory>
#include <optional>
#include <vector>

#include "ibs/devices/mc6000/descriptor.hpp"
#include "ibs/devices/mc6000/device.hpp"
#include "ibs/devices/vf1000/descriptor.hpp"
#include "ibs/devices/vf1000/device.hpp"
#include "ibs/master/master_loop.hpp"
#include "ibs/master/memory_bus.hpp"

#include "../support/counting_new.hpp"

namespace ibs::master {
namespace {

using namespace std::chrono_literals;

interbus::BusConfig two_drives() {
  const devices::Configuration mc = devices::mc6000::descriptor().configure({});
  const devices::Configuration vf = devices::vf1000::descriptor().configure({});
  const std::vector<interbus::DeviceSpec> specs{{"servo", mc.id_code, mc.bus}, {"fan", vf.id_code, vf.bus}};
  return interbus::make_bus_config(specs);
}

TEST(MemoryBus, CarriesTheMastersWordsOutAndTheDevicesWordsIn) {
  MemoryBus bus(two_drives());
  interbus::ProcessImage image;
  const auto& servo = bus.config().devices[0];
  const auto& fan = bus.config().devices[1];
  image.out[servo.out.offset] = 0x000F;
  image.out[fan.out.offset] = 0x0006;
  image.pcp_out[servo.pcp.offset] = 0x1234;
  bus.device_sends(0)[0] = 0x0637;
  bus.device_sends(1)[0] = 0x0231;
  bus.device_sends_pcp(0)[0] = 0x5678;

  const Exchange ex = bus.exchange(image, 5ms);
  EXPECT_TRUE(ex.data_valid);
  EXPECT_EQ(ex.links.size(), 2U);
  EXPECT_EQ(bus.device_receives(0)[0], 0x000F);
  EXPECT_EQ(bus.device_receives(1)[0], 0x0006);
  EXPECT_EQ(bus.device_receives_pcp(0)[0], 0x1234);
  EXPECT_EQ(image.in[servo.in.offset], 0x0637);
  EXPECT_EQ(image.in[fan.in.offset], 0x0231);
  EXPECT_EQ(image.pcp_in[servo.pcp.offset], 0x5678);
  EXPECT_EQ(bus.exchanges(), 1U);
  EXPECT_EQ(bus.last_exchange(), Time{5ms});
  EXPECT_TRUE(bus.device_sends(2).empty()) << "a position past the ring has no words";
}

TEST(MemoryBus, AnInvalidCycleCarriesNothingAndSaysSo) {
  MemoryBus bus(two_drives());
  interbus::ProcessImage image;
  const auto& servo = bus.config().devices[0];
  image.in[servo.in.offset] = 0x0240;
  bus.device_sends(0)[0] = 0x0637;
  image.out[servo.out.offset] = 0x000F;
  bus.set_valid(false);
  const Exchange ex = bus.exchange(image, 1ms);
  EXPECT_FALSE(ex.data_valid);
  EXPECT_FALSE(ex.link(0).data_valid) << "the whole cycle's failure reaches every device";
  EXPECT_EQ(image.in[servo.in.offset], 0x0240) << "the master keeps what it had";
  EXPECT_EQ(bus.device_receives(0)[0], 0x0000) << "the device got nothing";
  bus.set_valid(true);
  EXPECT_TRUE(bus.exchange(image, 2ms).data_valid);
  EXPECT_EQ(image.in[servo.in.offset], 0x0637);
}

TEST(MemoryBus, ReportsEachDevicesModuleError) {
  MemoryBus bus(two_drives());
  interbus::ProcessImage image;
  bus.set_link(1, {true, true});
  const Exchange ex = bus.exchange(image, 1ms);
  EXPECT_FALSE(ex.link(0).module_error);
  EXPECT_TRUE(ex.link(1).module_error);
  EXPECT_TRUE(ex.link(1).data_valid);
}

// A driver that records what the loop hands it.
class Recorder final : public devices::DeviceDriver, private devices::ParameterAccess {
 public:
  void cycle(const devices::DriverIo& io, Time now) override {
    seen_valid = io.data_valid;
    seen_module_error = io.module_error;
    seen_status = io.pd_in.empty() ? std::nullopt : std::optional<Word>(io.pd_in[0]);
    last = now;
  }
  void initial(const devices::DriverIo& io) override { io.pd_out[0] = 0x0006; }
  void restart(Time) override {}
  drivecom::Sequencer& sequencer() override { return sequencer_; }
  devices::ParameterAccess& parameters() override { return *this; }
  void set_reference(double) override {}
  [[nodiscard]] double reference() const override { return 0.0; }
  [[nodiscard]] double actual() const override { return 0.0; }
  [[nodiscard]] std::string_view unit() const override { return ""; }
  devices::ParamId submit(devices::ParamOp, std::uint16_t, std::int64_t) override { return 0; }
  [[nodiscard]] devices::ParamStatus status(devices::ParamId) const override { return {}; }
  [[nodiscard]] std::string describe(devices::ParamId) const override { return ""; }

  bool seen_valid = false;
  bool seen_module_error = false;
  std::optional<Word> seen_status;
  Time last{0};

 private:
  drivecom::Sequencer sequencer_;
};

TEST(MasterLoopOverABus, ExchangesFirstThenStepsEachDriverOnWhatTheBusSaid) {
  interbus::BusConfig config = two_drives();
  std::vector<std::unique_ptr<devices::DeviceDriver>> drivers;
  drivers.push_back(std::make_unique<Recorder>());
  drivers.push_back(std::make_unique<Recorder>());
  auto* a = dynamic_cast<Recorder*>(drivers[0].get());
  auto* b = dynamic_cast<Recorder*>(drivers[1].get());
  MasterLoop loop(config, std::move(drivers));
  MemoryBus bus(config);
  interbus::ProcessImage image;
  loop.initial(image);
  bus.device_sends(0)[0] = 0x0231;
  bus.set_link(1, {true, true});

  const Exchange ex = loop.cycle(bus, image, 3ms);
  EXPECT_TRUE(ex.data_valid);
  EXPECT_EQ(a->seen_status, Word{0x0231}) << "the driver reads the words of this cycle's exchange";
  EXPECT_TRUE(a->seen_valid);
  EXPECT_FALSE(a->seen_module_error);
  EXPECT_TRUE(b->seen_module_error);
  EXPECT_EQ(a->last, Time{3ms});
  EXPECT_EQ(bus.device_receives(0)[0], 0x0006) << "the initial words went out with the first exchange";

  bus.set_valid(false);
  loop.cycle(bus, image, 4ms);
  EXPECT_FALSE(a->seen_valid);
  EXPECT_FALSE(b->seen_valid);
}

// The far side of the seam as examples/embed has it: each drive's emulator samples at its own
// period on the bus's device-side words.
struct Emulated {
  std::unique_ptr<devices::DeviceEmulator> emulator;
  Duration period;
  Time next{0};
};

void feed(MemoryBus& bus, std::vector<Emulated>& drives, Time now) {
  for (std::size_t i = 0; i < drives.size(); ++i) {
    Emulated& d = drives[i];
    const devices::EmulatorIo io{bus.device_receives(i), bus.device_sends(i), bus.device_receives_pcp(i),
                                 bus.device_sends_pcp(i)};
    for (; d.next <= now; d.next += d.period) d.emulator->sample(io, d.next);
    const bool module_error = d.emulator->module_error(now);
    bus.set_link(i, {true, module_error});
    if (module_error) std::fill(io.pd_out.begin(), io.pd_out.end(), Word{0});
    else d.emulator->bus_cycle(now);
  }
}

TEST(MasterLoopOverABus, BringsBothDrivesToEnabledAndReadsAParameterFromEachWithoutAllocating) {
  const devices::Configuration mc = devices::mc6000::descriptor().configure({});
  const devices::Configuration vf = devices::vf1000::descriptor().configure({});
  interbus::BusConfig config = two_drives();
  std::vector<std::unique_ptr<devices::DeviceDriver>> drivers;
  drivers.push_back(devices::mc6000::descriptor().make_driver(mc));
  drivers.push_back(devices::vf1000::descriptor().make_driver(vf));
  MasterLoop loop(config, std::move(drivers));
  MemoryBus bus(config);
  std::vector<Emulated> drives;
  drives.push_back({devices::mc6000::make_emulator(mc, DeviceStart::initialised, 0ns),
                    devices::mc6000::descriptor().facts().sample_period});
  drives.push_back({devices::vf1000::make_emulator(vf, DeviceStart::initialised, 0ns),
                    devices::vf1000::descriptor().facts().sample_period});
  interbus::ProcessImage image;
  loop.initial(image);

  long allocations = -1;
  devices::ParamStatus servo_read, fan_read;
  {
    test::AllocationCounter counter;
    for (std::size_t i = 0; i < 2; ++i) loop.driver(i).sequencer().request(drivecom::Target::enabled, 0ns);
    const devices::ParamId a = loop.driver(0).parameters().submit(devices::ParamOp::read, 85, 0);
    const devices::ParamId b = loop.driver(1).parameters().submit(devices::ParamOp::read, 85, 0);
    for (Time t = 2ms; t <= Time{8s}; t += 2ms) {
      feed(bus, drives, t);
      loop.cycle(bus, image, t);
    }
    servo_read = loop.driver(0).parameters().status(a);
    fan_read = loop.driver(1).parameters().status(b);
    allocations = counter.count();
  }
  EXPECT_EQ(allocations, 0);
  EXPECT_EQ(drives[0].emulator->state(), drivecom::State::enabled);
  EXPECT_EQ(drives[1].emulator->state(), drivecom::State::enabled);
  for (std::size_t i = 0; i < 2; ++i) EXPECT_EQ(loop.driver(i).sequencer().report().phase, drivecom::Phase::reached);
  EXPECT_EQ(servo_read.kind, devices::ParamKind::value);
  EXPECT_EQ(fan_read.kind, devices::ParamKind::value);
}

}  // namespace
}  // namespace ibs::master
