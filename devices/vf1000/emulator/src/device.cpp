#include "ibs/devices/vf1000/device.hpp"

#include <algorithm>

#include "ibs/devices/vf1000/parameters.hpp"
#include "ibs/devices/vf1000/settings.hpp"
#include "ibs/vf1000_channel/comm_word.hpp"

namespace ibs::devices {

namespace {

namespace vc = vf1000_channel;

// The CODE field of a master communication word (4.1.2.1: bits 2-4 of the high byte).
unsigned code_of(Word w) { return (static_cast<unsigned>(w) >> 10U) & 0x7U; }

vf1000::DriveConfig drive_config(const Vf1000DeviceConfig& c) {
  vf1000::DriveConfig d;
  d.pd = c.pd;
  d.storing = c.storing;
  return d;
}

// The drive's storing time in whole 8.2 ms samples of the inverter, rounded up (7.1: 120 ms of
// a changed two-byte EEPROM value are 15 samples).
int samples_for(Duration d) {
  if (d <= Duration{0}) return 0;
  return static_cast<int>((d + vf1000::kSamplePeriod - Duration{1}) / vf1000::kSamplePeriod);
}

}  // namespace

Vf1000Device::Vf1000Device(const Vf1000DeviceConfig& config, DeviceStart start, Time now)
    : Vf1000Device(config, std::make_shared<vf1000::Drive>(drive_config(config), start, now), now) {}

Vf1000Device::Vf1000Device(const Vf1000DeviceConfig& config, std::shared_ptr<vf1000::Drive> drive,
                           Time now)
    : config_(config),
      drive_(std::move(drive)),
      server_(config.channel,
              drive_->initialising(now) ? vc::ServerStart::power_on : vc::ServerStart::initialised,
              now, *drive_),
      seen_starts_(drive_->starts()),
      last_sample_(now) {
  drive_->attach(vf1000::Face::interbus);
  // The channel initialises as long as the drive does (6.1).
  if (drive_->initialising(now)) server_.restart(now, drive_->ready_at() - now);
  shown_ = server_.output();
  taken_ = vc::kMasterIdleWord;
}

Vf1000Device::Vf1000Device(const Vf1000Device& other)
    : DeviceEmulator(other),
      config_(other.config_),
      drive_(std::make_shared<vf1000::Drive>(*other.drive_)),
      server_(other.server_),
      seen_starts_(other.seen_starts_),
      last_sample_(other.last_sample_),
      pending_(other.pending_),
      hold_(other.hold_),
      taken_(other.taken_),
      shown_(other.shown_),
      held_answer_(other.held_answer_) {
  server_.rebind(*drive_);
  drive_->attach(vf1000::Face::interbus);
}

Vf1000Device::~Vf1000Device() { drive_->detach(vf1000::Face::interbus); }

void Vf1000Device::reset_channel(Time now) {
  // A new start of the drive (power cycle, software reset, from whichever face): the unfinished
  // telegram is lost, the channel initialises with the drive (RESET distinction 0, 4.1.2.2).
  server_.restart(now, std::max(Duration{0}, drive_->ready_at() - now));
  pending_ = 0;
  hold_ = 0;
  taken_ = vc::kMasterIdleWord;
  shown_ = 0x0000;
  seen_starts_ = drive_->starts();
}

bool Vf1000Device::sync(Time now) {
  if (drive_->starts() == seen_starts_) return false;
  reset_channel(now);
  return true;
}

bool Vf1000Device::apply_event(const PlantEvent& e, Time now) {
  if (e.kind == PlantEvent::Kind::power_cycle) {
    power_cycle(now);
    return true;
  }
  // A fault acts at the drive's next sample (the time of its last one, as set_fault); mains off
  // and on are new starts, which the channel follows at once.
  const bool taken = drive_->apply(e, e.kind == PlantEvent::Kind::fault || e.kind == PlantEvent::Kind::fault_clear
                                              ? last_sample_
                                              : now);
  sync(now);
  return taken;
}

void Vf1000Device::power_cycle(Time now) {
  drive_->power_cycle(now);
  reset_channel(now);
}

void Vf1000Device::bus_cycle(Time now) { drive_->interbus_cycle(now); }

Word Vf1000Device::channel_word(Word from_master, Time now) {
  const bool powered = drive_->power_stage_enabled();
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
      // 7.1: the ACK of a transfer comes later with the motor running, with a KEYPAD, and while
      // the drive stores the value (the value in brackets; 71-PROG: LUSTBUS manual 10 exception 1).
      int extra = 0;
      if (powered) extra += config_.running_transfer_extra_samples;
      if (config_.keypad) extra += config_.keypad_transfer_extra_samples;
      extra += samples_for(e.storing);
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
  last_sample_ = now;
  // INTERBUS manual 6.1: "While the SMARTCARD is being read and written to bus operation is disabled":
  // the drive takes no words and its channel waits; the words it shows stay (VF-E21).
  if (drive_->card_busy(now)) {
    drive_->output(s2m);
    return;
  }
  drive_->begin_sample(now);
  sync(now);  // a new start another face caused
  Word comm = channel_word(m2s[2], now);
  // The channel's own transfer reset the drive (11-STAT = 000FH, LUSTBUS manual 8.1.1): its ACK is lost.
  if (sync(now)) comm = shown_;
  drive_->sample(m2s, s2m, now, comm);
  // RESET FAULT: the software reset of the INTERBUS manual 5.2.1; the words show the booting inverter.
  if (sync(now)) drive_->output(s2m);
}

namespace vf1000 {

std::unique_ptr<DeviceEmulator> make_emulator(const Configuration& config, DeviceStart start, Time now) {
  const DeviceSettings& s = config.settings;
  Vf1000DeviceConfig c;
  c.keypad = s.drive.boolean(kKeypadSetting);
  c.pd.reset_time = s.drive.duration(kResetTimeSetting);
  auto d = std::make_unique<Vf1000Device>(c, start, now);
  if (s.watchdog_ms) d->channel().set_value(pnr::kIbWd, static_cast<Word>(*s.watchdog_ms));
  if (s.watchdog_reaction) d->channel().set_value(pnr::kIbcod, static_cast<Word>(*s.watchdog_reaction));
  return d;
}

}  // namespace vf1000

std::string Vf1000Device::write_parameter(std::uint16_t number, std::int64_t value, Time now) {
  const drive::ParameterInfo* p = drive_->find(number);
  if (p == nullptr) return "parameter " + std::to_string(number) + " is not in the VF1000's table";
  if (value < 0 || value > 0xFFFF) return "the VF1000's values are 16-bit words (0..65535), not " + std::to_string(value);
  const auto w = static_cast<Word>(value);
  drive_->advance(now);
  const std::uint8_t bits = drive_->siof();
  if (number == vf1000::pnr::kSiof) {
    // No channel writes 85-SIOF: a read erases its bits, a refusal sets one; it takes what the
    // channel left.
    if (w > 0xFF) return "85-SIOF holds 8 bits, not " + std::to_string(w);
    drive_->clear_siof(static_cast<std::uint8_t>(bits & ~w));
    drive_->raise_siof(static_cast<std::uint8_t>(w & ~bits));
    return {};
  }
  // LUSTBUS manual 6 and 9.2; INTERBUS manual 4.1.4: every value transfer is refused while a bit is set.
  if (bits != 0) return "85-SIOF holds " + std::to_string(bits) + ": every value transfer is refused until it is read";
  const bool powered = drive_->power_stage_enabled();
  const drive::WriteCheck check = drive_->check_write(p, w, powered);
  if (check != drive::WriteCheck::ok) {
    return "the VF1000 refuses " + std::to_string(number) + " = " + std::to_string(w) + ": " +
           std::string(drive::to_string(check));
  }
  drive_->write(static_cast<std::size_t>(drive_->table().slot(number)), w, powered, now);
  return {};
}

}  // namespace ibs::devices
