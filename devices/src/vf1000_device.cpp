#include "ibs/devices/vf1000_device.hpp"

#include "ibs/vf1000_channel/comm_word.hpp"
#include "ibs/vf1000_channel/parameters.hpp"

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

}  // namespace

Vf1000Device::Vf1000Device(const Vf1000DeviceConfig& config, DeviceStart start, Time now)
    : config_(config), pd_(config.pd), server_(config.channel, server_start(start), now) {
  switch (start) {
    case DeviceStart::power_on:
      pd_.power_on();
      shown_ = 0x0000;
      break;
    case DeviceStart::initialised:
    case DeviceStart::operational:
      pd_.start(InitState::operational);
      shown_ = server_.output();
      break;
    case DeviceStart::fault:
      pd_.start(InitState::fault);
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

void Vf1000Device::bus_cycle(Time now) {
  armed_ = true;
  last_cycle_ = now;
}

void Vf1000Device::apply_parameters() {
  // 36-RSTOP: stop ramp in 0.05 Hz/s (0: the power stage is switched off, 5.2.1); 22-FMAX1.
  const Word rstop = server_.value(vc::pnr::kRstop).value_or(0);
  pd_.set_stop_ramp(static_cast<double>(rstop) * 0.05);
  const Word fmax = server_.value(vc::pnr::kFmax1).value_or(8000);
  pd_.set_max_frequency(static_cast<double>(fmax) * 0.05);
}

void Vf1000Device::mirror_parameters(Word control, Word reference) {
  // 901-ICNTL and 911-IBSTA mirror the DRIVECOM words, 905-FDRIV and 912-FIST the frequencies
  // (4.1.1; signed 0.05 Hz, a modelling choice).
  server_.set_value(vc::pnr::kIcntl, control);
  server_.set_value(vc::pnr::kIbsta, pd_.status_word());
  server_.set_value(vc::pnr::kFdriv, vf1000_actual_word(pd_.setpoint_hz()));
  server_.set_value(vc::pnr::kFist, vf1000_actual_word(pd_.frequency_hz()));
  static_cast<void>(reference);
}

void Vf1000Device::run_watchdog(Time now) {
  // 906-IB-WD: monitoring time in 50 ms steps, 65535 = off; 907-IBCOD: the reaction (4.1.1).
  const auto limit = vc::ib_wd_monitoring_time(server_.value(vc::pnr::kIbWd).value_or(0xFFFF));
  const bool expired = armed_ && limit && (now - last_cycle_) > *limit;
  if (expired && !tripped_) {
    tripped_ = true;
    switch (static_cast<vc::IbCod>(server_.value(vc::pnr::kIbcod).value_or(0))) {
      case vc::IbCod::no_action: break;
      case vc::IbCod::shutdown_e_ibs: watchdog_fault_ = true; break;
      case vc::IbCod::block_power: pd_.override_control(Word{0x0000}); break;
      case vc::IbCod::emergency_stop: pd_.override_control(Word{0x0002}); break;
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
  }
  if (pending_ > 0 && --pending_ == 0) {
    const Word answer = server_.step(from_master, now, powered);
    taken_ = from_master;
    const auto& e = server_.last_event();
    if (e.kind == vc::ServerEvent::Kind::value_written) {
      apply_parameters();
      if (e.eeprom_changed && config_.eeprom_change_extra_samples > 0) {
        held_answer_ = answer;
        hold_ = config_.eeprom_change_extra_samples;
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
  pd_.sample(m2s, s2m, kVf1000SamplePeriod, comm);
  if (watchdog_fault_ && !tripped_ && pd_.state() == drivecom::State::start_up_inhibit) {
    watchdog_fault_ = false;  // reset by the master after the data came back
  }
  mirror_parameters(m2s[0], m2s[1]);
}

}  // namespace ibs::devices
