#include "ibs/devices/mc6000/device.hpp"

#include <algorithm>
#include <chrono>

#include "ibs/devices/mc6000/channel.hpp"
#include "ibs/devices/mc6000/parameters.hpp"
#include "ibs/devices/mc6000/settings.hpp"

namespace ibs::devices {

namespace {

using mc6000::kButwd;  // 409-BUTWD (3.2.4), the dictionary's
constexpr Word kResetFault = 0x0080;   // control word bit 7 (5.1.2)

mc6000::DriveConfig drive_config(const Mc6000DeviceConfig& c) {
  mc6000::DriveConfig d;
  d.timing = c.timing;
  d.pd = c.pd;
  return d;
}

}  // namespace

Mc6000Device::Mc6000Device(const Mc6000DeviceConfig& config, DeviceStart start, Time now)
    : Mc6000Device(config, std::make_shared<mc6000::Drive>(drive_config(config), start, now), start, now) {}

Mc6000Device::Mc6000Device(const Mc6000DeviceConfig& config, std::shared_ptr<mc6000::Drive> drive,
                           DeviceStart start, Time now)
    : layout_(devices::mc6000::make_layout(config.supi, config.ibcnf, config.bus)),
      drive_(std::move(drive)),
      served_(*drive_) {
  (void)now;
  attach(config, start);
}

Mc6000Device::Mc6000Device(const Mc6000Device& other)
    : DeviceEmulator(other),
      layout_(other.layout_),
      drive_(std::make_shared<mc6000::Drive>(*other.drive_)),
      served_(*drive_),
      pcp_(other.pcp_),
      last_control_(other.last_control_),
      held_(other.held_),
      reboots_seen_(other.reboots_seen_),
      configuration_mismatch_(other.configuration_mismatch_) {
  if (pcp_) pcp_->serve(served_);
}

void Mc6000Device::attach(const Mc6000DeviceConfig& config, DeviceStart start) {
  // The servo's EEPROM holds the configuration it was switched on with (3.2.2, 3.2.3, 3.2.4).
  auto& params = drive_->parameters();
  const auto butwd = std::chrono::duration_cast<std::chrono::milliseconds>(config.bus_watchdog).count();
  params.preset(devices::mc6000::kSupi, config.supi);
  params.preset(devices::mc6000::kIbcnf, config.ibcnf);
  params.preset(kButwd, butwd);
  // This face samples the drive every 1 ms (INTERBUS manual 7.2; docs/errata.md MC-D4).
  drive_->set_fieldbus_sampling(true);
  reboots_seen_ = drive_->reboots();
  const int words = layout_.pcp_words;
  if (words > 0) {
    pcp::ServerConfig sc = mc6000::server_config(words);
    sc.latency = config.pcp_latency;
    sc.workload = config.workload;
    sc.start = start == DeviceStart::operational ? pcp::StartMode::running : pcp::StartMode::power_on;
    pcp_.emplace(sc, served_);
  }
}

void Mc6000Device::set_bus_watchdog(Duration d) {
  drive_->parameters().preset(kButwd, std::chrono::duration_cast<std::chrono::milliseconds>(d).count());
}

void Mc6000Device::power_cycle(Time now) {
  drive_->power_on(now);
  last_control_ = 0;
  if (pcp_) pcp_->power_on(now);
  // 405/406 are read at power-on (3.2.2): values written through PCP since the ring was
  // configured give another layout and ID code, which the running ring cannot carry.
  const auto& params = drive_->parameters();
  configuration_mismatch_ = static_cast<int>(params.raw(devices::mc6000::kSupi)) != layout_.supi ||
                            static_cast<int>(params.raw(devices::mc6000::kIbcnf)) != static_cast<int>(layout_.ibcnf);
}

bool Mc6000Device::apply_event(const PlantEvent& e, Time now) {
  // A power cycle and the mains' return start the INTERBUS card and PCP over with the servo.
  const bool was_powered = drive_->powered();
  if (e.kind == PlantEvent::Kind::power_cycle ||
      (e.kind == PlantEvent::Kind::mains_on && !was_powered)) {
    if (e.kind == PlantEvent::Kind::mains_on) drive_->mains_on(now);
    power_cycle(now);
    return true;
  }
  return drive_->apply(e, now);
}

void Mc6000Device::output(std::span<Word> pd_s2m) const {
  write_pd_words(layout_, drive_->status_word(), drive_->actual_rpm(), drive_->torque_percent(), pd_s2m);
}

void Mc6000Device::output_pcp(Time now, std::span<Word> pcp_s2m) {
  if (pcp_ && !pcp_s2m.empty() && !deaf(now)) pcp_->show(now, pcp_s2m);
}

void Mc6000Device::pcp_cycle(Time now, std::span<const Word> pcp_m2s, std::span<Word> pcp_s2m) {
  if (pcp_ && !pcp_m2s.empty() && !deaf(now)) pcp_->cycle(now, pcp_m2s, pcp_s2m);
}

void Mc6000Device::sample_core(std::span<const Word> pd_m2s, Time first, Duration period, std::uint32_t count) {
  // SUPI 0: the INTERBUS CPU loops without exchanging data with the servo (3.2.2); without
  // process data the drive's machine does not move, its watchdog still runs out.
  if (layout_.pd_words == 0 || !layout_.exchanges_data) {
    for (std::uint32_t k = 0; k < count; ++k) drive_->watch(first + static_cast<std::int64_t>(k) * period);
    return;
  }
  const Word control = pd_m2s.empty() ? Word{0} : pd_m2s[0];
  const double reference = devices::mc6000::decode_reference(
      layout_, pd_m2s.subspan(1, static_cast<std::size_t>(layout_.reference_words)));
  // The master's reset acts while the fieldbus has the control location (MC-D4).
  if ((control & kResetFault) != 0 && (last_control_ & kResetFault) == 0 && !drive_->serial_control()) {
    drive_->fault_reset(first);
  }
  last_control_ = control;
  // A reaction-5 error's reset boots the servo (LUSTBUS manual 8.1.2), through either face: the
  // INTERBUS card boots with it and PCP starts over.
  if (drive_->reboots() != reboots_seen_) {
    reboots_seen_ = drive_->reboots();
    if (pcp_) pcp_->power_on(first);
  }
  drive_->sample(first, period, count, control, reference);
}

void Mc6000Device::step_held(std::span<const Word> pd_m2s, Time first, Duration period, std::uint32_t count) {
  if (pcp_ || deaf(first) || deaf(first + static_cast<std::int64_t>(count - 1) * period)) {
    // The channel is stepped sample by sample; so is a stretch the face is deaf in, which
    // step() samples with the words held.
    for (std::uint32_t k = 0; k < count; ++k) step(pd_m2s, first + static_cast<std::int64_t>(k) * period);
    return;
  }
  std::copy_n(pd_m2s.begin(), std::min(held_.size(), pd_m2s.size()), held_.begin());
  sample_core(pd_m2s, first, period, count);
}

void Mc6000Device::step(std::span<const Word> pd_m2s, Time now, std::span<const Word> pcp_m2s,
                        std::span<Word> pcp_s2m) {
  if (deaf(now)) {
    // A SMARTCARD operation (MC-D9) or no card (MC-D10): the words and frames of the bus do not
    // reach the servo, which runs on with the words it took last; the PCP channel waits.
    sample_core({held_.data(), std::min(held_.size(), pd_m2s.size())}, now, mc6000::kSamplePeriod, 1);
    return;
  }
  const std::size_t n = std::min(held_.size(), pd_m2s.size());
  std::copy_n(pd_m2s.begin(), n, held_.begin());
  sample_core(pd_m2s, now, mc6000::kSamplePeriod, 1);
  if (!pcp_) return;
  if (pcp_m2s.empty()) {
    pcp_->sample(now);  // the interface side runs in pcp_cycle()
  } else {
    pcp_->step(now, pcp_m2s, pcp_s2m);
  }
}

std::string Mc6000Device::write_parameter(std::uint16_t number, std::int64_t value, Time now) {
  mc6000::DriveParameters& params = drive_->parameters();
  const pcp::ParameterInfo* p = params.store().info(number);
  if (p == nullptr) return "parameter " + std::to_string(number) + " is not in the MC6000's table";
  if (number == mc6000::kSerr) {
    // No channel writes 85-SERR: a read erases its bits, a refusal sets one; it takes what the
    // channel left.
    if (value < 0 || value > 0xFF) return "85-SERR holds 8 bits, not " + std::to_string(value);
    drive_->advance(now);
    params.set_reading(number, static_cast<std::uint32_t>(value));
    return {};
  }
  // The raw value as PCP carries it; a negative one is a signed type's.
  const auto raw = mc6000::trace_raw(p->type, value);
  if (!raw) return std::to_string(value) + " is no value of " + std::to_string(number) + "'s type";
  const mc6000::WriteResult r = drive_->write(now, number, *raw);
  if (!r.ok()) {
    return "the MC6000 refuses " + std::to_string(number) + " = " + std::to_string(value) + " (85-SERR " +
           std::to_string(drive_->siof()) + "; " + pcp::to_string(mc6000::pcp_error(r.refusal)) + ")";
  }
  return {};
}

namespace mc6000 {

std::unique_ptr<DeviceEmulator> make_emulator(const Configuration& config, DeviceStart start, Time now) {
  const DeviceSettings& s = config.settings;
  Mc6000DeviceConfig c;
  c.supi = supi_of(s);
  c.ibcnf = ibcnf_of(s);
  c.bus = s.bus;
  if (s.watchdog_ms) c.bus_watchdog = std::chrono::milliseconds(*s.watchdog_ms);
  return std::make_unique<Mc6000Device>(c, start, now);
}

}  // namespace mc6000

}  // namespace ibs::devices
