// MasterLoop::validate (docs/embedding.md, "An embedded build"): the check the constructor throws
// by, as an error code with the constructor's message; a loop it accepts runs.
#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "ibs/devices/mc6000/descriptor.hpp"
#include "ibs/devices/vf1000/descriptor.hpp"
#include "ibs/base/error.hpp"
#include "ibs/master/master_loop.hpp"
#include "ibs/master/memory_bus.hpp"

namespace ibs::master {
namespace {

using namespace std::chrono_literals;

interbus::BusConfig servo_and_fan() {
  const devices::Configuration mc = devices::mc6000::descriptor().configure({});
  const devices::Configuration vf = devices::vf1000::descriptor().configure({});
  const std::vector<interbus::DeviceSpec> specs{{"servo", mc.id_code, mc.bus},
                                                {"fan", vf.id_code, vf.bus}};
  return interbus::make_bus_config(specs);
}

std::vector<std::unique_ptr<devices::DeviceDriver>> drivers(std::size_t n) {
  std::vector<std::unique_ptr<devices::DeviceDriver>> v;
  const auto& mc = devices::mc6000::descriptor();
  const auto& vf = devices::vf1000::descriptor();
  for (std::size_t i = 0; i < n; ++i) {
    v.push_back(i % 2 == 0 ? mc.make_driver(mc.configure({})) : vf.make_driver(vf.configure({})));
  }
  return v;
}

std::string thrown(const interbus::BusConfig& config, std::size_t n) {
  try {
    const MasterLoop loop(config, drivers(n));
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(MasterLoopValidate, RefusesADriverCountThatIsNotTheDevices) {
  const interbus::BusConfig config = servo_and_fan();
  for (const std::size_t n : {0U, 1U, 3U}) {
    const Error e = MasterLoop::validate(config, n);
    EXPECT_EQ(e.code, ErrorCode::master_driver_count) << n;
    EXPECT_EQ(e.message, "master loop: " + std::to_string(n) + " drivers for 2 devices");
    EXPECT_EQ(e.message, thrown(config, n));
  }
}

TEST(MasterLoopValidate, RefusesADeviceOutsideTheProcessImage) {
  interbus::BusConfig config = servo_and_fan();
  config.devices[1].out =
      interbus::Slice{interbus::kMaxProcessWords - 1, 3};  // not as make_bus_config places it
  const Error e = MasterLoop::validate(config, 2);
  EXPECT_EQ(e.code, ErrorCode::master_device_outside_image);
  EXPECT_EQ(e.message, "master loop: device 'fan' lies outside the process image");
  EXPECT_EQ(e.message, thrown(config, 2));
  config = servo_and_fan();
  config.devices[0].pcp = interbus::Slice{interbus::kMaxPcpWords, 1};
  EXPECT_EQ(MasterLoop::validate(config, 2).message,
            "master loop: device 'servo' lies outside the process image");
}

TEST(MasterLoopValidate, AnAcceptedConfigurationMakesALoopThatRuns) {
  const interbus::BusConfig config = servo_and_fan();
  ASSERT_FALSE(MasterLoop::validate(config, 2));
  MasterLoop loop(config, drivers(2));
  MemoryBus bus(config);
  interbus::ProcessImage image;
  loop.initial(image);
  loop.driver(0).sequencer().request(drivecom::Target::ready, Time{0});
  bus.device_sends(0)[0] = 0x0240;  // START-UP INHIBIT
  (void)loop.cycle(bus, image, Time{1ms});
  (void)loop.cycle(bus, image, Time{2ms});
  EXPECT_EQ(bus.device_receives(0)[0], 0x0006);  // SHUTDOWN, on its way to READY
}

}  // namespace
}  // namespace ibs::master
