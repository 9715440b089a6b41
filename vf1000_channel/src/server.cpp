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
        "depends on (INTERBUS manual 4.1.4)"};
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
  ch_.state = ServerState::wait;
  ch_.ready_at = now;
  ch_.out = kInverterWaitWord;
  if (start == ServerStart::operational) own_->clear_siof(0xFF);
}

Server::Server(const ServerConfig& config, ServerStart start, Time now,
               drive::ParameterAccess& drive)
    : config_(checked(config, drive.table().params())), drive_(&drive) {
  restart(now, config_.init_duration);
  if (start == ServerStart::power_on) return;
  ch_.state = ServerState::wait;
  ch_.ready_at = now;
  ch_.out = kInverterWaitWord;
}

Server::Server(const Server& other)
    : config_(other.config_),
      own_(other.own_),
      drive_(own_ ? &*own_ : other.drive_),
      ch_(other.ch_) {}

Server& Server::operator=(const Server& other) {
  if (this == &other) return *this;
  config_ = other.config_;
  own_ = other.own_;
  drive_ = own_ ? &*own_ : other.drive_;
  ch_ = other.ch_;
  return *this;
}

void Server::power_on(Time now, Duration init) {
  restart(now, init);
  if (own_) own_->power_on();  // 6.1: RAM from EEPROM, the power-on bit
}

void Server::restart(Time now, Duration init) {
  ch_.state = ServerState::initialising;
  ch_.ready_at = now + init;
  ch_.out = 0;  // RESET distinction 0 (4.1.2.2)
  ch_.toggle = false;
  ch_.code = Code::reset;
  ch_.slot = -1;
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
  ch_.event.kind = ServerEvent::Kind::none;
  if (ch_.state == ServerState::initialising) {
    if (now < ch_.ready_at) return ch_.out;  // RESET distinction 0 (4.1.2.2, 6.1)
    ch_.state = ServerState::wait;
    ch_.toggle = false;
    ch_.out = kInverterWaitWord;
    const Word w = process(m, power_stage_enabled, now);
    if (ch_.event.kind == ServerEvent::Kind::none) ch_.event = {ServerEvent::Kind::initialised};
    return w;
  }
  return process(m, power_stage_enabled, now);
}

Word Server::process(Word m, bool power_stage_enabled, Time now) {
  const std::uint8_t code = master_code(m);
  if (code == 0) {
    // The master's starting position ends every telegram (4.1.3.1.1 row 6): wait mode. A transfer
    // not yet complete is dropped here, so no value is ever half-written.
    if (ch_.state == ServerState::sending || ch_.state == ServerState::transfer_high ||
        ch_.state == ServerState::transfer_low) {
      ch_.event = {ServerEvent::Kind::aborted, ch_.code, ch_.number, 0, NakReason{}, 0};
    }
    ch_.state = ServerState::wait;
    ch_.toggle = false;
    ch_.code = Code::reset;
    ch_.out = kInverterWaitWord;
    return ch_.out;
  }
  // No new data without a toggle change (4.1.2.1 bit 5): keep showing the last answer.
  if (master_toggle(m) == ch_.toggle) return ch_.out;
  ch_.toggle = master_toggle(m);

  const bool control_ok = !master_unused_bits(m) && code == static_cast<std::uint8_t>(ch_.code);
  // An error inside a value transfer is entered in 85-SIOF (4.1.4); on this channel "unintended
  // control bits" take the transmission-error bit 3.
  const std::uint8_t transfer_bit = siof_mask(SiofBit::checksum);
  switch (ch_.state) {
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
  return ch_.out;
}

Word Server::start_telegram(Word m, bool power_stage_enabled) {
  const std::uint8_t code = master_code(m);
  ch_.number = master_number(m);
  ch_.code = is_telegram_code(code) ? static_cast<Code>(code) : Code::reset;
  if (master_unused_bits(m)) {
    return nak(NakReason::unintended_control_bits,
               ch_.code == Code::value_transfer ? siof_mask(SiofBit::checksum) : 0);
  }
  if (ch_.code == Code::reset) return nak(NakReason::undefined_code, 0);

  const drive::ParameterTable& table = drive_->table();
  const int s = table.slot(ch_.number);
  switch (ch_.code) {
    case Code::value_inquiry:
      // Missing parameter: NAK on receipt of the PNR, no 85-SIOF entry (4.1.3.1, 4.1.4).
      if (s < 0) return nak(NakReason::no_parameter, 0);
      ch_.slot = static_cast<std::int16_t>(s);
      // The whole value is taken now, so the two bytes always belong to one value.
      ch_.latched = drive_->read(static_cast<std::size_t>(s));
      ch_.length = 2;
      ch_.index = 0;
      ch_.state = ServerState::sending;
      return next_byte();
    case Code::description_scan:
      if (s < 0) return nak(NakReason::no_parameter, 0);
      ch_.slot = static_cast<std::int16_t>(s);
      ch_.length = static_cast<std::uint8_t>(kDescriptionLength);
      ch_.index = 0;
      ch_.state = ServerState::sending;
      return next_byte();
    case Code::value_transfer: {
      // 85-SIOF <> 0 refuses every value transfer (4.1.4; power-on bit, 6.1).
      if (siof() != 0) return nak(NakReason::siof_pending, 0);
      const WriteCheck access = drive::check_access(
          s < 0 ? nullptr : &table.params()[static_cast<std::size_t>(s)], power_stage_enabled);
      if (access != WriteCheck::ok) return nak(reason_for(access), drive::siof_bits_for(access));
      ch_.slot = static_cast<std::int16_t>(s);
      ch_.state = ServerState::transfer_high;
      return send(0, Flag::none);  // 4.1.3.2.1 row 2: PNR read, waiting for DAT1
    }
    case Code::reset:
      break;
  }
  return nak(NakReason::undefined_code, 0);
}

Word Server::next_byte() {
  const auto slot = static_cast<std::size_t>(ch_.slot);
  const std::uint8_t byte = ch_.code == Code::value_inquiry
                                ? (ch_.index == 0 ? high_byte(ch_.latched) : low_byte(ch_.latched))
                                : description_byte(drive_->table().params()[slot], ch_.index);
  ++ch_.index;
  if (ch_.index < ch_.length) return send(byte, Flag::none);

  // The last byte carries ACK (4.1.3.1.1 row 4, 4.1.3.3.1 row 36).
  ch_.state = ServerState::done;
  if (ch_.code == Code::value_inquiry) {
    ch_.event = {ServerEvent::Kind::value_read, ch_.code, ch_.number, ch_.latched, NakReason{}, 0};
    // Reading 85-SIOF clears the bits it returned (4.1.4); bits set meanwhile stay.
    if (ch_.number == drive::kSiofNumber) drive_->clear_siof(static_cast<std::uint8_t>(ch_.latched & 0xFFU));
  } else {
    ch_.event = {ServerEvent::Kind::description_read, ch_.code, ch_.number, 0, NakReason{}, 0};
  }
  return send(byte, Flag::ack);
}

Word Server::take_high(Word m) {
  ch_.high = low_byte(m);
  ch_.state = ServerState::transfer_low;
  return send(0, Flag::none);  // 4.1.3.2.1 row 4
}

Word Server::take_low(Word m, bool power_stage_enabled, Time now) {
  const Word value = make_word(ch_.high, low_byte(m));
  const auto slot = static_cast<std::size_t>(ch_.slot);
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
  ch_.state = ServerState::done;
  ch_.event = {ServerEvent::Kind::value_written, ch_.code, ch_.number, value, NakReason{}, 0,
            effect.eeprom_changed, effect.storing};
  return send(0, Flag::ack);
}

Word Server::nak(NakReason reason, std::uint8_t siof_bits) {
  if (siof_bits != 0) raise_siof(siof_bits);
  ch_.state = ServerState::done;
  ch_.event = {ServerEvent::Kind::nak, ch_.code, ch_.number, 0, reason, siof_bits};
  return send(0, Flag::nak);
}

Word Server::send(std::uint8_t data, Flag flag) {
  ch_.out = inverter_word(ch_.toggle, flag, data);
  return ch_.out;
}

}  // namespace ibs::vf1000_channel
