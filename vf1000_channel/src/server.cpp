#include "ibs/vf1000_channel/server.hpp"

#include <algorithm>
#include <stdexcept>

namespace ibs::vf1000_channel {

namespace {

using drive::siof_mask;
using drive::SiofBit;
using drive::WriteCheck;

constexpr NakReason reason_for(WriteCheck c) {
  switch (c) {
    case WriteCheck::no_parameter:
      return NakReason::no_parameter;
    case WriteCheck::no_change:
      return NakReason::no_change;
    case WriteCheck::invalid_value:
    case WriteCheck::ok:
      break;
  }
  return NakReason::invalid_value;
}

const ServerConfig& checked(const ServerConfig& config,
                            std::span<const drive::ParameterInfo> params) {
  detail::require<std::invalid_argument>(Server::validate(params));
  return config;
}

}  // namespace

Error Server::validate(std::span<const drive::ParameterInfo> params) {
  if (Error e = drive::ParameterTable::validate(params)) return e;
  const bool has_siof =
      std::any_of(params.begin(), params.end(),
                  [](const drive::ParameterInfo& p) { return p.number == drive::kSiofNumber; });
  if (!has_siof) {
    return {
        ErrorCode::table_lacks_siof,
        "vf1000_channel::Server: the parameter table has no 85-SIOF, which every value transfer "
        "depends on (seed 001, 4.1.4)"};
  }
  return {};
}

std::string_view to_string(ServerState s) {
  switch (s) {
    case ServerState::initialising:
      return "initialising";
    case ServerState::wait:
      return "wait";
    case ServerState::sending:
      return "sending";
    case ServerState::transfer_high:
      return "transfer, waiting for DAT1";
    case ServerState::transfer_low:
      return "transfer, waiting for DAT2";
    case ServerState::done:
      return "done, waiting for CODE 0";
  }
  return "?";
}

std::string_view to_string(NakReason r) {
  switch (r) {
    case NakReason::unintended_control_bits:
      return "unintended control bits";
    case NakReason::undefined_code:
      return "undefined CODE";
    case NakReason::no_parameter:
      return "no parameter";
    case NakReason::no_change:
      return "no change permitted";
    case NakReason::invalid_value:
      return "invalid value";
    case NakReason::siof_pending:
      return "85-SIOF not read";
    case NakReason::after_end:
      return "toggle after the last byte";
  }
  return "?";
}

Server::Server(const ServerConfig& config, ServerStart start, Time now,
               std::span<const drive::ParameterInfo> params)
    : config_(checked(config, params)) {
  own_.emplace(params, config.factory_defaults_parameter);
  drive_ = &*own_;
  power_on(now);
  if (start == ServerStart::power_on) return;
  state_ = ServerState::wait;
  ready_at_ = now;
  out_ = kInverterWaitWord;
  if (start == ServerStart::operational) own_->clear_siof(0xFF);
}

Server::Server(const ServerConfig& config, ServerStart start, Time now,
               drive::ParameterAccess& drive)
    : config_(checked(config, drive.table().params())), drive_(&drive) {
  restart(now, config_.init_duration);
  if (start == ServerStart::power_on) return;
  state_ = ServerState::wait;
  ready_at_ = now;
  out_ = kInverterWaitWord;
}

Server::Server(const Server& other)
    : config_(other.config_),
      own_(other.own_),
      drive_(own_ ? &*own_ : other.drive_),
      state_(other.state_),
      ready_at_(other.ready_at_),
      out_(other.out_),
      toggle_(other.toggle_),
      code_(other.code_),
      number_(other.number_),
      slot_(other.slot_),
      index_(other.index_),
      length_(other.length_),
      high_(other.high_),
      latched_(other.latched_),
      event_(other.event_) {}

Server& Server::operator=(const Server& other) {
  if (this == &other) return *this;
  config_ = other.config_;
  own_ = other.own_;
  drive_ = own_ ? &*own_ : other.drive_;
  state_ = other.state_;
  ready_at_ = other.ready_at_;
  out_ = other.out_;
  toggle_ = other.toggle_;
  code_ = other.code_;
  number_ = other.number_;
  slot_ = other.slot_;
  index_ = other.index_;
  length_ = other.length_;
  high_ = other.high_;
  latched_ = other.latched_;
  event_ = other.event_;
  return *this;
}

void Server::power_on(Time now, Duration init) {
  restart(now, init);
  if (own_) own_->power_on();  // 6.1: RAM from EEPROM, the power-on bit
}

void Server::restart(Time now, Duration init) {
  state_ = ServerState::initialising;
  ready_at_ = now + init;
  out_ = 0;  // RESET distinction 0 (4.1.2.2)
  toggle_ = false;
  code_ = Code::reset;
  slot_ = -1;
}

std::optional<Word> Server::value(std::uint16_t number) const {
  const int s = drive_->table().slot(number);
  if (s < 0) return std::nullopt;
  return drive_->read(static_cast<std::size_t>(s));
}

bool Server::set_value(std::uint16_t number, Word raw) {
  const int s = drive_->table().slot(number);
  if (s < 0) return false;
  drive_->set(static_cast<std::size_t>(s), raw);
  return true;
}

Word Server::step(Word m, Time now, bool power_stage_enabled) {
  event_.kind = ServerEvent::Kind::none;
  if (state_ == ServerState::initialising) {
    if (now < ready_at_) return out_;  // RESET distinction 0 (4.1.2.2, 6.1)
    state_ = ServerState::wait;
    toggle_ = false;
    out_ = kInverterWaitWord;
    const Word w = process(m, power_stage_enabled, now);
    if (event_.kind == ServerEvent::Kind::none) event_ = {ServerEvent::Kind::initialised};
    return w;
  }
  return process(m, power_stage_enabled, now);
}

Word Server::process(Word m, bool power_stage_enabled, Time now) {
  const std::uint8_t code = master_code(m);
  if (code == 0) {
    // The master's starting position ends every telegram (4.1.3.1.1 row 6): wait mode. A transfer
    // not yet complete is dropped here, so no value is ever half-written.
    if (state_ == ServerState::sending || state_ == ServerState::transfer_high ||
        state_ == ServerState::transfer_low) {
      event_ = {ServerEvent::Kind::aborted, code_, number_, 0, NakReason{}, 0};
    }
    state_ = ServerState::wait;
    toggle_ = false;
    code_ = Code::reset;
    out_ = kInverterWaitWord;
    return out_;
  }
  // No new data without a toggle change (4.1.2.1 bit 5): keep showing the last answer.
  if (master_toggle(m) == toggle_) return out_;
  toggle_ = master_toggle(m);

  const bool control_ok = !master_unused_bits(m) && code == static_cast<std::uint8_t>(code_);
  // An error inside a value transfer is entered in 85-SIOF (4.1.4); on this channel "unintended
  // control bits" take the transmission-error bit 3.
  const std::uint8_t transfer_bit = siof_mask(SiofBit::checksum);
  switch (state_) {
    case ServerState::wait:
      return start_telegram(m, power_stage_enabled);
    case ServerState::sending:
      if (!control_ok) return nak(NakReason::unintended_control_bits, 0);
      return next_byte();
    case ServerState::transfer_high:
      if (!control_ok) return nak(NakReason::unintended_control_bits, transfer_bit);
      return take_high(m);
    case ServerState::transfer_low:
      if (!control_ok) return nak(NakReason::unintended_control_bits, transfer_bit);
      return take_low(m, power_stage_enabled, now);
    case ServerState::done:
      return nak(NakReason::after_end, 0);
    case ServerState::initialising:
      break;
  }
  return out_;
}

Word Server::start_telegram(Word m, bool power_stage_enabled) {
  const std::uint8_t code = master_code(m);
  number_ = master_number(m);
  code_ = is_telegram_code(code) ? static_cast<Code>(code) : Code::reset;
  if (master_unused_bits(m)) {
    return nak(NakReason::unintended_control_bits,
               code_ == Code::value_transfer ? siof_mask(SiofBit::checksum) : 0);
  }
  if (code_ == Code::reset) return nak(NakReason::undefined_code, 0);

  const drive::ParameterTable& table = drive_->table();
  const int s = table.slot(number_);
  switch (code_) {
    case Code::value_inquiry:
      // Missing parameter: NAK on receipt of the PNR, no 85-SIOF entry (4.1.3.1, 4.1.4).
      if (s < 0) return nak(NakReason::no_parameter, 0);
      slot_ = static_cast<std::int16_t>(s);
      // The whole value is taken now, so the two bytes always belong to one value.
      latched_ = drive_->read(static_cast<std::size_t>(s));
      length_ = 2;
      index_ = 0;
      state_ = ServerState::sending;
      return next_byte();
    case Code::description_scan:
      if (s < 0) return nak(NakReason::no_parameter, 0);
      slot_ = static_cast<std::int16_t>(s);
      length_ = static_cast<std::uint8_t>(kDescriptionLength);
      index_ = 0;
      state_ = ServerState::sending;
      return next_byte();
    case Code::value_transfer: {
      // 85-SIOF <> 0 refuses every value transfer (4.1.4; power-on bit, 6.1).
      if (siof() != 0) return nak(NakReason::siof_pending, 0);
      const WriteCheck access = drive::check_access(
          s < 0 ? nullptr : &table.params()[static_cast<std::size_t>(s)], power_stage_enabled);
      if (access != WriteCheck::ok) return nak(reason_for(access), drive::siof_bits_for(access));
      slot_ = static_cast<std::int16_t>(s);
      state_ = ServerState::transfer_high;
      return send(0, Flag::none);  // 4.1.3.2.1 row 2: PNR read, waiting for DAT1
    }
    case Code::reset:
      break;
  }
  return nak(NakReason::undefined_code, 0);
}

Word Server::next_byte() {
  const auto slot = static_cast<std::size_t>(slot_);
  const std::uint8_t byte = code_ == Code::value_inquiry
                                ? (index_ == 0 ? high_byte(latched_) : low_byte(latched_))
                                : description_byte(drive_->table().params()[slot], index_);
  ++index_;
  if (index_ < length_) return send(byte, Flag::none);

  // The last byte carries ACK (4.1.3.1.1 row 4, 4.1.3.3.1 row 36).
  state_ = ServerState::done;
  if (code_ == Code::value_inquiry) {
    event_ = {ServerEvent::Kind::value_read, code_, number_, latched_, NakReason{}, 0};
    // Reading 85-SIOF clears the bits it returned (4.1.4); bits set meanwhile stay.
    if (number_ == drive::kSiofNumber) drive_->clear_siof(static_cast<std::uint8_t>(latched_ & 0xFFU));
  } else {
    event_ = {ServerEvent::Kind::description_read, code_, number_, 0, NakReason{}, 0};
  }
  return send(byte, Flag::ack);
}

Word Server::take_high(Word m) {
  high_ = low_byte(m);
  state_ = ServerState::transfer_low;
  return send(0, Flag::none);  // 4.1.3.2.1 row 4
}

Word Server::take_low(Word m, bool power_stage_enabled, Time now) {
  const Word value = make_word(high_, low_byte(m));
  const auto slot = static_cast<std::size_t>(slot_);
  const drive::ParameterInfo& p = drive_->table().params()[slot];
  // 85-SIOF <> 0 refuses every value transfer (4.1.4): a bit set since the PNR arrived (a
  // watchdog, the device) refuses it here, where the value is taken.
  if (siof() != 0) return nak(NakReason::siof_pending, 0);
  // The power stage may have been enabled since the PNR arrived: checked again here.
  const WriteCheck c = drive_->check_write(&p, value, power_stage_enabled);
  if (c != WriteCheck::ok) return nak(reason_for(c), drive::siof_bits_for(c));

  // The value takes effect whole, now, after its last byte (4.1.3.2.1 row 6); what else it does
  // (71-PROG, the EEPROM) is the drive's.
  const drive::WriteEffect effect = drive_->write(slot, value, power_stage_enabled, now);
  state_ = ServerState::done;
  event_ = {ServerEvent::Kind::value_written, code_, number_, value, NakReason{}, 0,
            effect.eeprom_changed, effect.storing};
  return send(0, Flag::ack);
}

Word Server::nak(NakReason reason, std::uint8_t siof_bits) {
  if (siof_bits != 0) raise_siof(siof_bits);
  state_ = ServerState::done;
  event_ = {ServerEvent::Kind::nak, code_, number_, 0, reason, siof_bits};
  return send(0, Flag::nak);
}

Word Server::send(std::uint8_t data, Flag flag) {
  out_ = inverter_word(toggle_, flag, data);
  return out_;
}

}  // namespace ibs::vf1000_channel
