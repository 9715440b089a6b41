// The master's cycle loop: one driver per ring device, slices of the process image, no
// allocation per cycle.
#include <gtest/gtest.h>


#include <array>

#include "ibs/devices/mc6000/device.hpp"
#include "ibs/devices/mc6000/driver.hpp"
#include "ibs/devices/vf1000/device.hpp"
#include "ibs/devices/vf1000/driver.hpp"
#include "ibs/master/master_loop.hpp"

#include "../support/counting_new.hpp"

namespace ibs::sim {
namespace {

using master::MasterLoop;

TEST(MasterLoop, FullBusOf64ServosCyclesWithoutAllocating) {
  std::vector<interbus::DeviceSpec> specs;
  std::vector<std::unique_ptr<devices::DeviceDriver>> drivers;
  const auto layout = devices::mc6000::make_layout(12, 2);  // 4 process-data words, no PCP
  for (int i = 0; i < 64; ++i) {
    specs.push_back({"mc" + std::to_string(i), interbus::IdCode{layout.id_code}, std::nullopt});
    drivers.push_back(std::make_unique<devices::Mc6000Driver>(layout));
  }
  MasterLoop loop(interbus::make_bus_config(specs), std::move(drivers));
  EXPECT_EQ(loop.config().in_words, 256U);
  interbus::ProcessImage image;
  loop.initial(image);
  std::vector<master::LinkState> links(64);
  for (std::size_t i = 0; i < 64; ++i) {
    loop.driver(i).sequencer().request(drivecom::Target::enabled, 0ns);
    loop.driver(i).set_reference(100.0 * static_cast<double>(i));
  }
  for (std::size_t i = 0; i < 64; ++i) image.in[4 * i] = 0x0231;  // every servo READY
  long allocations = 0;
  {
    test::AllocationCounter counter;
    for (int c = 0; c < 100; ++c) loop.cycle(image, std::chrono::milliseconds(c), master::Exchange{true, links});
    allocations = counter.count();
  }
  EXPECT_EQ(allocations, 0);
  // Each servo got ENABLE and its own reference in its own slice (Q16, high word first).
  for (std::size_t i = 0; i < 64; ++i) {
    EXPECT_EQ(image.out[4 * i], 0x000F) << i;
    EXPECT_EQ(make_dword(image.out[4 * i + 1], image.out[4 * i + 2]),
              static_cast<std::uint32_t>(100 * i) << 16U)
        << i;
  }
}

TEST(MasterLoop, DeviceModelsAndDriversWithParameterTrafficAllocateNothing) {
  // Both device models with their parameter channels, both drivers, requests on both channels.
  devices::Mc6000Device mc({}, DeviceStart::initialised, 0ns);
  devices::Vf1000Device vf({}, DeviceStart::initialised, 0ns);
  devices::Mc6000Driver mc_driver(mc.layout());
  devices::Vf1000Driver vf_driver;
  std::array<Word, 3> mc_out{}, mc_in{}, vf_out{}, vf_in{};
  std::array<Word, 1> pcp_out{}, pcp_in{};
  const devices::DriverIo mc_io{mc_in, mc_out, pcp_in, pcp_out, true, false};
  const devices::DriverIo vf_io{vf_in, vf_out, {}, {}, true, false};
  mc_driver.initial(mc_io);
  vf_driver.initial(vf_io);
  long allocations = 0;
  {
    test::AllocationCounter counter;
    mc_driver.sequencer().request(drivecom::Target::enabled, 0ns);
    vf_driver.sequencer().request(drivecom::Target::enabled, 0ns);
    mc_driver.set_reference(1000.0);
    vf_driver.set_reference(-20.0);
    const auto a = mc_driver.parameters().submit(devices::ParamOp::read, 85, 0);
    const auto b = mc_driver.parameters().submit(devices::ParamOp::describe, 409, 0);
    const auto c = vf_driver.parameters().submit(devices::ParamOp::read, 85, 0);
    const auto d = vf_driver.parameters().submit(devices::ParamOp::write, 905, 100);
    for (int ms = 1; ms < 3000; ++ms) {
      const Time now = std::chrono::milliseconds(ms);
      mc.bus_cycle(now);
      mc.sample(mc_out, mc_in, now, pcp_out, pcp_in);
      mc_driver.cycle(mc_io, now);
      if (ms % 8 == 0) {
        vf.bus_cycle(now);
        vf.sample(vf_out, vf_in, now);
      }
      vf_driver.cycle(vf_io, now);
    }
    for (const auto id : {a, b}) EXPECT_TRUE(mc_driver.parameters().status(id).done());
    for (const auto id : {c, d}) EXPECT_TRUE(vf_driver.parameters().status(id).done());
    allocations = counter.count();
  }
  EXPECT_EQ(allocations, 0);
  EXPECT_EQ(mc.state(), drivecom::State::enabled);
  EXPECT_EQ(vf.state(), drivecom::State::enabled);
}

TEST(MasterLoop, RefusesMismatchedDrivers) {
  std::vector<interbus::DeviceSpec> specs{{"vf", interbus::IdCode{0x033B}, std::nullopt}};
  EXPECT_THROW(MasterLoop(interbus::make_bus_config(specs), {}), std::invalid_argument);
}

}  // namespace
}  // namespace ibs::sim
