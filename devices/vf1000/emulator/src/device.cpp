#include "ibs/devices/vf1000/device.hpp"

#include "ibs/vf1000_channel/comm_word.hpp"
#include "ibs/devices/vf1000/parameters.hpp"

namespace ibs::devices {

namespace {

namespace vc = vf1000_channel;

vc::ServerStart server_start(DeviceStart s) {
  switch (s) {
    case DeviceStart::power_on: return vc::ServerStart::power_on;
    case DeviceStart::initialised: return vc::ServerStart::initialised;
    case DeviceStart::operational:
    case DeviceStart::fault: return vc::ServerStart::operational;
  }
  return vc::ServerStart::operational;
}

// The CODE field of a master communication word (4.1.2.1: bits 2-4 of the high byte).
unsigned code_of(Word w) { return (static_cast<unsigned>(w) >> 10U) & 0x7U; }

// Transition 15 (FAULT -> START-UP INHIBIT on RESET FAULT) among those of a sample.
bool reset_fault_taken(const drivecom::SampleResult& r) {
  for (std::uint8_t i = 0; i < r.count; ++i) {
    if (r.transition(i) == 15) return true;
  }
  return false;
}

}  // namespace

Vf1000Device::Vf1000Device(const Vf1000DeviceConfig& config, DeviceStart start, Time now)
    : config_(config), pd_(config.pd), server_(config.channel, server_start(start), now, vf1000::parameters()) {
  switch (start) {
    case DeviceStart::power_on:
      pd_.power_on();
      shown_ = 0x0000;
      break;
    case DeviceStart::initialised:
    case DeviceStart::operational:
      pd_.start(DeviceStart::operational);
      shown_ = server_.output();
      break;
    case DeviceStart::fault:
      pd_.start(DeviceStart::fault);
      shown_ = server_.output();
      break;
  }
  taken_ = vc::kMasterIdleWord;
  apply_parameters();
}

void Vf1000Device::power_cycle(Time now) {
  server_.power_on(now);
  pd_.power_on();
  pending_ = 0;
  hold_ = 0;
  taken_ = vc::kMasterIdleWord;
  shown_ = 0x0000;
  armed_ = false;
  tripped_ = false;
  watchdog_fault_ = false;
  apply_parameters();
}

void Vf1000Device::software_reset(Word control, Time now) {
  // Seed 001, 5.2.1, bit 7: "The inverter performs a software reset !" Seed 000, 8.1.1: the link
  // is gone for the boot-up (self test); 9.2: the power-on bit of 85-SIOF is set afterwards, so
  // the master reads 85 before its next value transfer. The unfinished telegram is lost.
  const Duration self_test = config_.pd.reset_time;
  server_.power_on(now, self_test);
  pd_.software_reset(control);
  pending_ = 0;
  hold_ = 0;
  taken_ = vc::kMasterIdleWord;
  shown_ = 0x0000;
  // An E-IBS fault was reset with it. The firmware starts again: as after a power-on, 906-IB-WD
  // monitors the bus from the first data cycle after the self-test (no data reach an inverter
  // that shows a module error), not through it.
  watchdog_fault_ = false;
  armed_ = false;
  if (tripped_) pd_.override_control(std::nullopt);
  tripped_ = false;
  ++software_resets_;
  apply_parameters();
}

void Vf1000Device::bus_cycle(Time now) {
  armed_ = true;
  last_cycle_ = now;
}

void Vf1000Device::apply_parameters() {
  // 36-RSTOP: stop ramp in 0.05 Hz/s (0: the power stage is switched off, 5.2.1); 22-FMAX1.
  const Word rstop = server_.value(vf1000::pnr::kRstop).value_or(0);
  pd_.set_stop_ramp(static_cast<double>(rstop) * 0.05);
  const Word fmax = server_.value(vf1000::pnr::kFmax1).value_or(8000);
  pd_.set_max_frequency(static_cast<double>(fmax) * 0.05);
}

void Vf1000Device::mirror_parameters(Word control, Word reference) {
  // 901-ICNTL and 911-IBSTA mirror the DRIVECOM words, 905-FDRIV and 912-FIST the frequencies
  // (4.1.1; signed 0.05 Hz, a modelling choice).
  server_.set_value(vf1000::pnr::kIcntl, control);
  server_.set_value(vf1000::pnr::kIbsta, pd_.status_word());
  server_.set_value(vf1000::pnr::kFdriv, vf1000::actual_word(pd_.setpoint_hz()));
  server_.set_value(vf1000::pnr::kFist, vf1000::actual_word(pd_.frequency_hz()));
  static_cast<void>(reference);
}

void Vf1000Device::run_watchdog(Time now) {
  // 906-IB-WD: monitoring time in 50 ms steps, 65535 = off; 907-IBCOD: the reaction (4.1.1).
  const auto limit = vf1000::ib_wd_monitoring_time(server_.value(vf1000::pnr::kIbWd).value_or(0xFFFF));
  const bool expired = armed_ && limit && (now - last_cycle_) > *limit;
  if (expired && !tripped_) {
    tripped_ = true;
    switch (static_cast<vf1000::IbCod>(server_.value(vf1000::pnr::kIbcod).value_or(0))) {
      case vf1000::IbCod::no_action: break;
      case vf1000::IbCod::shutdown_e_ibs: watchdog_fault_ = true; break;
      case vf1000::IbCod::block_power: pd_.override_control(Word{0x0000}); break;
      case vf1000::IbCod::emergency_stop: pd_.override_control(Word{0x0002}); break;
    }
  } else if (!expired && tripped_) {
    // Data flows again: the master's words count again; an E-IBS fault stays latched until the
    // master resets it (its cause, the missing data, has gone).
    tripped_ = false;
    pd_.override_control(std::nullopt);
  }
}

Word Vf1000Device::channel_word(Word from_master, Time now) {
  const bool powered = drivecom::power_stage_enabled(pd_.state());
  if (server_.initialising(now) || server_.state() == vc::ServerState::initialising) {
    shown_ = server_.step(from_master, now, powered);
    taken_ = from_master;
    pending_ = 0;
    return shown_;
  }
  if (hold_ > 0) {
    if (--hold_ == 0) shown_ = held_answer_;
    return shown_;
  }
  if (pending_ == 0 && from_master != taken_) {
    pending_ = code_of(from_master) == 3 ? config_.description_step_samples : config_.value_step_samples;
    // 7.1: with a KEYPAD the start of a value inquiry waits for the keypad's service.
    if (config_.keypad && server_.state() == vc::ServerState::wait && code_of(from_master) == 1) {
      pending_ += config_.keypad_inquiry_extra_samples;
    }
  }
  if (pending_ > 0 && --pending_ == 0) {
    const Word answer = server_.step(from_master, now, powered);
    taken_ = from_master;
    const auto& e = server_.last_event();
    if (e.kind == vc::ServerEvent::Kind::value_written) {
      apply_parameters();
      // 7.1: the ACK of a transfer comes later with the motor running, with a KEYPAD, and when an
      // EEPROM value changed (the value in brackets).
      int extra = 0;
      if (powered) extra += config_.running_transfer_extra_samples;
      if (config_.keypad) extra += config_.keypad_transfer_extra_samples;
      if (e.eeprom_changed) extra += config_.eeprom_change_extra_samples;
      if (extra > 0) {
        held_answer_ = answer;
        hold_ = extra;
        return shown_;
      }
    }
    shown_ = answer;
  }
  return shown_;
}

void Vf1000Device::sample(std::span<const Word> m2s, std::span<Word> s2m, Time now) {
  run_watchdog(now);
  pd_.set_fault(external_fault_ || watchdog_fault_);
  const Word comm = channel_word(m2s[2], now);
  pd_.sample(m2s, s2m, vf1000::kSamplePeriod, comm);
  if (reset_fault_taken(pd_.last_sample())) {
    software_reset(m2s[0], now);
    pd_.output(s2m);
    return;
  }
  if (watchdog_fault_ && !tripped_ && pd_.state() == drivecom::State::start_up_inhibit) {
    watchdog_fault_ = false;  // reset by the master after the data came back
  }
  mirror_parameters(m2s[0], m2s[1]);
}

namespace vf1000 {

std::unique_ptr<DeviceEmulator> make_emulator(const Configuration& config, DeviceStart start, Time now) {
  const DeviceSettings& s = config.settings;
  Vf1000DeviceConfig c;
  if (s.keypad) c.keypad = *s.keypad;
  if (s.reset_time) c.pd.reset_time = *s.reset_time;
  auto d = std::make_unique<Vf1000Device>(c, start, now);
  if (s.watchdog_ms) d->channel().set_value(pnr::kIbWd, static_cast<Word>(*s.watchdog_ms));
  if (s.watchdog_reaction) d->channel().set_value(pnr::kIbcod, static_cast<Word>(*s.watchdog_reaction));
  return d;
}

}  // namespace vf1000

}  // namespace ibs::devices
