#include "ibs/devices/mc6000/device.hpp"

#include <algorithm>

#include "ibs/devices/mc6000/channel.hpp"
#include "ibs/devices/mc6000/parameters.hpp"

namespace ibs::devices {

namespace {

constexpr std::uint16_t kButwd = 409;  // 409-BUTWD (3.2.4)

}  // namespace

Mc6000PdConfig Mc6000Device::pd_config(const Mc6000DeviceConfig& c) {
  Mc6000PdConfig p = c.pd;
  p.layout = devices::mc6000::make_layout(c.supi, c.ibcnf, c.bus);
  return p;
}

Mc6000Device::Mc6000Device(const Mc6000DeviceConfig& config, DeviceStart start, Time now)
    : config_(config), pd_(pd_config(config)) {
  switch (start) {
    case DeviceStart::power_on: pd_.power_on(); break;
    case DeviceStart::initialised:
    case DeviceStart::operational: pd_.start(DeviceStart::operational); break;
    case DeviceStart::fault: pd_.start(DeviceStart::fault); break;
  }
  const int words = pd_.layout().pcp_words;
  if (words > 0) {
    pcp::ServerConfig sc = mc6000::server_config(words);
    sc.latency = config.pcp_latency;
    sc.workload = config.workload;
    sc.start = start == DeviceStart::operational ? pcp::StartMode::running : pcp::StartMode::power_on;
    pcp_.emplace(sc, mc6000::parameters());
    // The servo's EEPROM holds the configuration it was switched on with (3.2.2, 3.2.3, 3.2.4).
    auto& store = pcp_->parameters();
    const auto butwd = std::chrono::duration_cast<std::chrono::milliseconds>(config.bus_watchdog).count();
    for (const auto& [n, v] : {std::pair<std::uint16_t, std::int64_t>{devices::mc6000::kSupi, config.supi},
                               {devices::mc6000::kIbcnf, config.ibcnf},
                               {kButwd, butwd}}) {
      if (const auto* info = store.info(n)) {
        const auto raw = pcp::ParameterStore::to_raw(*info, v);
        store.set(n, raw);
        store.commit_eeprom(n, raw);
      }
    }
    if (start == DeviceStart::power_on) pcp_->power_on(now);
  }
}

void Mc6000Device::power_cycle(Time now) {
  pd_.power_on();
  armed_ = false;
  watchdog_fault_ = false;
  if (!pcp_) return;
  pcp_->power_on(now);
  // 405/406 are read at power-on (3.2.2): values written through PCP since the ring was
  // configured give another layout and ID code, which the running ring cannot carry.
  const auto& store = pcp_->parameters();
  const auto supi = store.get(devices::mc6000::kSupi);
  const auto ibcnf = store.get(devices::mc6000::kIbcnf);
  const auto& l = pd_.layout();
  configuration_mismatch_ = (supi && static_cast<int>(supi->raw) != l.supi) ||
                            (ibcnf && static_cast<int>(ibcnf->raw) != static_cast<int>(l.ibcnf));
}

void Mc6000Device::bus_cycle(Time now) {
  armed_ = true;
  last_cycle_ = now;
}

void Mc6000Device::output_pcp(Time now, std::span<Word> pcp_s2m) {
  if (pcp_ && !pcp_s2m.empty()) pcp_->show(now, pcp_s2m);
}

void Mc6000Device::step_held(std::span<const Word> pd_m2s, Time first, Duration period, std::uint32_t count) {
  if (pcp_ || watchdog_fault_ || period <= Duration{0}) {
    // The channel's parameters (409-BUTWD among them) and the watchdog's reset are looked at
    // sample by sample.
    for (std::uint32_t k = 0; k < count; ++k) step(pd_m2s, first + static_cast<std::int64_t>(k) * period);
    return;
  }
  // 3.2.4: the monitoring time runs out at the first sample more than 409-BUTWD after the last
  // cycle; from there on every sample of this stretch sees the watchdog fault.
  std::uint32_t in_time = count;
  if (armed_ && config_.bus_watchdog > Duration{0}) {
    const Duration left = config_.bus_watchdog - (first - last_cycle_);
    in_time = left < Duration{0} ? 0U : static_cast<std::uint32_t>(std::min<std::int64_t>(count, left / period + 1));
  }
  const bool pd = pd_.layout().pd_words > 0;
  pd_.set_fault(external_fault_);
  if (pd) pd_.step_held(pd_m2s, mc6000::kSamplePeriod, in_time);
  if (in_time < count) {
    watchdog_fault_ = true;
    pd_.set_fault(true);
    if (pd) pd_.step_held(pd_m2s, mc6000::kSamplePeriod, count - in_time);
  }
}

void Mc6000Device::step(std::span<const Word> pd_m2s, Time now, std::span<const Word> pcp_m2s,
                        std::span<Word> pcp_s2m) {
  if (pcp_) {
    // 409-BUTWD as the servo holds it now (the master may have written it through PCP).
    if (const auto v = pcp_->parameters().get(kButwd)) config_.bus_watchdog = std::chrono::milliseconds(v->raw);
  }
  // 3.2.4: monitoring time 409-BUTWD in ms, 0 deactivates; running out is error 16 (E-OP1),
  // location 1, a device fault that stays until it is reset once data flows again.
  const bool expired = armed_ && config_.bus_watchdog > Duration{0} &&
                       (now - last_cycle_) > config_.bus_watchdog;
  if (expired) watchdog_fault_ = true;
  pd_.set_fault(external_fault_ || expired);
  if (pcp_) pd_.set_enable_locked(pcp_->engage_locked());
  if (pd_.layout().pd_words > 0) pd_.step(pd_m2s, mc6000::kSamplePeriod);
  if (watchdog_fault_ && !expired && pd_.state() == drivecom::State::start_up_inhibit) {
    watchdog_fault_ = false;  // reset by the master after the data came back
  }
  if (pcp_ && !pcp_m2s.empty()) {
    pcp_->set_drive_running(drivecom::power_stage_enabled(pd_.state()));
    pcp_->set_fault(pd_.state() == drivecom::State::fault || pd_.state() == drivecom::State::fault_response_active);
    // 408-IBSTA mirrors the status word, 77-SPEED the actual speed (Q16 rpm, seed 000 6.1.1.2).
    pcp_->parameters().set(devices::mc6000::kIbsta, pd_.status_word());
    pcp_->parameters().set(devices::mc6000::kSpeed, static_cast<std::uint32_t>(devices::mc6000::to_q16(pd_.actual_rpm())));
    pcp_->step(now, pcp_m2s, pcp_s2m);
  }
}

namespace mc6000 {

std::unique_ptr<DeviceEmulator> make_emulator(const Configuration& config, DeviceStart start, Time now) {
  const DeviceSettings& s = config.settings;
  Mc6000DeviceConfig c;
  c.supi = s.supi;
  c.ibcnf = s.ibcnf;
  c.bus = s.bus;
  if (s.watchdog_ms) c.bus_watchdog = std::chrono::milliseconds(*s.watchdog_ms);
  return std::make_unique<Mc6000Device>(c, start, now);
}

}  // namespace mc6000

}  // namespace ibs::devices
