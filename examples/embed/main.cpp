// One MC6000 and one VF1000 on an in-memory bus fed by their emulators: the master brings both to
// ENABLED and reads 85-SIOF from each. Exits 0 only when all of that happened.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "ibs/devices/mc6000/device.hpp"
#include "ibs/devices/vf1000/device.hpp"
#include "ibs/master/master_loop.hpp"
#include "ibs/master/memory_bus.hpp"

using namespace ibs;
using namespace std::chrono_literals;

int main() {
  const devices::DriveDescriptor* kinds[] = {&devices::mc6000::descriptor(), &devices::vf1000::descriptor()};
  std::vector<interbus::DeviceSpec> ring;
  std::vector<std::unique_ptr<devices::DeviceDriver>> drivers;
  std::vector<std::unique_ptr<devices::DeviceEmulator>> drives;
  for (const auto* kind : kinds) {
    const devices::Configuration c = kind->configure({});
    ring.push_back({std::string(kind->name()), c.id_code, c.bus});
    drivers.push_back(kind->make_driver(c));
    drives.push_back(kind == kinds[0] ? devices::mc6000::make_emulator(c, DeviceStart::initialised, 0ns)
                                      : devices::vf1000::make_emulator(c, DeviceStart::initialised, 0ns));
  }
  const interbus::BusConfig config = interbus::make_bus_config(ring);
  master::MasterLoop loop(config, std::move(drivers));
  master::MemoryBus bus(config);  // a board driver would stand here
  interbus::ProcessImage image;
  loop.initial(image);
  devices::ParamId reads[2];
  for (std::size_t i = 0; i < 2; ++i) {
    loop.driver(i).sequencer().request(drivecom::Target::enabled, 0ns);
    reads[i] = loop.driver(i).parameters().submit(devices::ParamOp::read, 85, 0);
  }
  Time next_sample[2] = {};
  for (Time t = 2ms; t <= Time{8s}; t += 2ms) {  // a 2 ms bus cycle, time passed in
    for (std::size_t i = 0; i < 2; ++i) {        // the devices' side: each at its sample period
      const devices::EmulatorIo io{bus.device_receives(i), bus.device_sends(i), bus.device_receives_pcp(i),
                                   bus.device_sends_pcp(i)};
      for (; next_sample[i] <= t; next_sample[i] += kinds[i]->facts().sample_period) drives[i]->sample(io, next_sample[i]);
      const bool module_error = drives[i]->module_error(t);
      bus.set_link(i, {true, module_error});
      if (!module_error) drives[i]->bus_cycle(t);
    }
    loop.cycle(bus, image, t);  // exchange, then every driver
  }
  bool ok = true;
  for (std::size_t i = 0; i < 2; ++i) {
    const devices::ParamStatus s = loop.driver(i).parameters().status(reads[i]);
    const bool enabled = drives[i]->state() == drivecom::State::enabled;
    std::printf("%s: %s, 85 = %s\n", ring[i].name.c_str(), enabled ? "ENABLED" : "not enabled",
                loop.driver(i).parameters().describe(reads[i]).c_str());
    ok = ok && enabled && s.kind == devices::ParamKind::value;
  }
  return ok ? 0 : 1;
}
