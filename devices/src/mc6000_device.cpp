#include "ibs/devices/mc6000_device.hpp"

namespace ibs::devices {

Mc6000PdConfig Mc6000Device::pd_config(const Mc6000DeviceConfig& c) {
  Mc6000PdConfig p = c.pd;
  p.layout = interbus::mc6000::make_layout(c.supi, c.ibcnf, c.bus);
  return p;
}

Mc6000Device::Mc6000Device(const Mc6000DeviceConfig& config, DeviceStart start, Time)
    : config_(config), pd_(pd_config(config)) {
  switch (start) {
    case DeviceStart::power_on: pd_.power_on(); break;
    case DeviceStart::initialised:
    case DeviceStart::operational: pd_.start(InitState::operational); break;
    case DeviceStart::fault: pd_.start(InitState::fault); break;
  }
}

void Mc6000Device::power_cycle(Time) {
  pd_.power_on();
  armed_ = false;
  watchdog_fault_ = false;
}

void Mc6000Device::bus_cycle(Time now) {
  armed_ = true;
  last_cycle_ = now;
}

void Mc6000Device::sample(std::span<const Word> pd_m2s, std::span<Word> pd_s2m, Time now) {
  // 3.2.4: monitoring time 409-BUTWD in ms, 0 deactivates; running out is error 16 (E-OP1),
  // location 1, a device fault that stays until it is reset once data flows again.
  const bool expired = armed_ && config_.bus_watchdog > Duration{0} &&
                       (now - last_cycle_) > config_.bus_watchdog;
  if (expired) watchdog_fault_ = true;
  pd_.set_fault(external_fault_ || expired);
  pd_.sample(pd_m2s, pd_s2m, kMc6000SamplePeriod);
  if (watchdog_fault_ && !expired && pd_.state() == drivecom::State::start_up_inhibit) {
    watchdog_fault_ = false;  // reset by the master after the data came back
  }
}

}  // namespace ibs::devices
