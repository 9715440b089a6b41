#include "ibs/devices/vf1000/lustbus_device.hpp"

#include <cmath>

#include "ibs/lustbus/code.hpp"
#include "ibs/lustbus/description.hpp"
#include "ibs/lustbus/value.hpp"

namespace ibs::devices::vf1000 {

namespace lb = ibs::lustbus;
using drive::SiofBit;

namespace {

DriveConfig standalone(DriveConfig c) {
  c.interbus_software = false;
  return c;
}

// 2.3.1: the value as "%04X", formatted into the answer itself (the one object returned, so the
// caller's answer is this one); NAK should it not format.
lb::EnquiryAnswer value_answer(Word raw, Duration reaction) {
  lb::EnquiryAnswer a{lb::Reply::text, reaction, {}};
  if (lb::format_raw(a.value, lb::Family::standard, raw) != lb::ValueError::none) a = lb::EnquiryAnswer::nak(reaction);
  return a;
}

}  // namespace

LustbusDevice::LustbusDevice(LustbusTiming timing, const DriveConfig& drive)
    : LustbusDevice(std::make_shared<Drive>(standalone(drive), DeviceStart::initialised, Time{0}), timing) {}

LustbusDevice::LustbusDevice(std::shared_ptr<Drive> drive, LustbusTiming timing)
    : timing_(timing),
      drive_(std::move(drive)),
      reactions_(timing.reaction),
      seen_starts_(drive_->starts()) {
  drive_->attach(Face::serial);
  line_baud_ = drive_->value(pnr::kSioc);
}

LustbusDevice::LustbusDevice(const LustbusDevice& other)
    : lustbus::Responder(other),
      timing_(other.timing_),
      drive_(std::make_shared<Drive>(*other.drive_)),
      reactions_(other.reactions_),
      seen_starts_(other.seen_starts_),
      line_baud_(other.line_baud_) {
  drive_->attach(Face::serial);
}

LustbusDevice::~LustbusDevice() { drive_->detach(Face::serial); }

bool LustbusDevice::set_line_baud(std::uint32_t baud) {
  if (!drive::is_baud_step(baud, kHighestBaud)) return false;
  drive_->set_value(pnr::kSioc, static_cast<Word>(baud));
  line_baud_ = baud;
  return true;
}

void LustbusDevice::set_fault(bool present, Time now) {
  advance(now);
  drive_->set_fault(present, now);
}

void LustbusDevice::follow_starts() {
  // 11.5: a new rate is active after a restart, once the drive is back.
  if (drive_->starts() == seen_starts_ || drive_->starting()) return;
  seen_starts_ = drive_->starts();
  line_baud_ = drive_->value(pnr::kSioc);
}

void LustbusDevice::restart(Time now) {
  drive_->restart(now);
  follow_starts();
}

void LustbusDevice::advance(Time now) {
  drive_->advance(now);
  follow_starts();
}

void LustbusDevice::telegram_received(const lb::Context& ctx) {
  advance(ctx.now);
  drive_->serial_telegram(ctx.now);  // 5.2: any valid telegram resets the watchdog
}

const drive::ParameterInfo* LustbusDevice::resolve(const lb::Code& code, bool& description) const {
  const auto vc = lb::as_vf_code(code);  // 2.4.1: S 0 D P P
  if (!vc) return nullptr;
  description = vc->specifier == lb::VfSpecifier::description;
  const drive::ParameterInfo* p = drive_->find(vc->parameter);
  if (p == nullptr) return nullptr;
  // 11.1, "Parameter kind": device digit 0 only for basis parameters (kinds '0'..'3').
  if (vc->device == 0 && static_cast<int>(p->category) > 3) return nullptr;
  return p;
}

lb::EnquiryAnswer LustbusDevice::enquiry(const lb::Code& code, const lb::Context& ctx) {
  advance(ctx.now);
  // For a recording of the INTERBUS words, which do not carry this channel (parameter_journal.hpp).
  const drive::SiofNote<Drive> noted(*drive_, pnr::kSiof);
  bool description = false;
  const drive::ParameterInfo* p = resolve(code, description);
  // 6.1 note: NAK for a parameter that is not there; no cause enters 85-SIOF on an ENQUIRY.
  if (p == nullptr) return lb::EnquiryAnswer::nak(reaction());
  if (description) {  // 11.1: 26 characters
    const auto d = lb::format_vf_description(p->name, p->unit, drive::category_code(p->category),
                                             drive::type_code(p->type), p->min, p->max,
                                             p->default_value);
    if (!d) return lb::EnquiryAnswer::nak(reaction());
    return lb::EnquiryAnswer::text(*d, reaction());
  }
  // 9.2: reading 85 erases the bits; 11-STAT and 12 are the drive's state (drive.hpp).
  const Word raw = p->number == pnr::kSiof ? Word{drive_->read_siof()} : drive_->reading(p->number);
  return value_answer(raw, reaction());
}

lb::SelectAnswer LustbusDevice::refuse(SiofBit b) {
  drive_->raise_siof(drive::siof_mask(b));  // 9.2: the cause of the refusal
  return lb::SelectAnswer::nak(reaction());
}

lb::SelectAnswer LustbusDevice::select(const lb::Code& code, const lb::Value& value,
                                       const lb::Context& ctx) {
  advance(ctx.now);
  const drive::SiofNote<Drive> noted(*drive_, pnr::kSiof);
  // 6, 9.2: every SELECT is refused while a bit is set; the bits stay as they are.
  if (drive_->siof() != 0) return lb::SelectAnswer::nak(reaction());
  bool description = false;
  const drive::ParameterInfo* p = resolve(code, description);
  if (p == nullptr) return refuse(SiofBit::no_parameter);
  if (description) return refuse(SiofBit::no_change);  // a description cannot be written
  const auto raw = lb::parse_raw(lb::Family::standard, value.view());  // exactly four hex digits
  if (!raw.ok()) return refuse(SiofBit::invalid_value);
  const auto w = static_cast<Word>(raw.value);
  // 3, "Access limitations depend on the type of operation": 40H for a read-only parameter or an
  // EEPROM parameter while the power stage runs; then the value's range (80H); the drive's own
  // rules (11-STAT: 000FH only).
  const bool powered = drive_->power_stage_enabled();
  const drive::WriteCheck check = drive_->check_write(p, w, powered);
  if (check != drive::WriteCheck::ok) {
    return refuse(check == drive::WriteCheck::invalid_value ? SiofBit::invalid_value
                                                            : SiofBit::no_change);
  }
  const std::uint32_t starts = drive_->starts();
  const drive::WriteEffect effect =
      drive_->write(static_cast<std::size_t>(drive_->table().slot(p->number)), w, powered, ctx.now);
  drive_->journal().note(p->number, w);
  if (drive_->starts() != starts) {
    // 8.1.1: 11-STAT = 000FH reset a fault: "the reset happens immediately after the receipt",
    // the inverter boots (deaf meanwhile) and the ACK may not get out whole.
    switch (timing_.reset_answer) {
      case lb::Reply::ack:
        return lb::SelectAnswer::ack(reaction());
      case lb::Reply::none:
        return {lb::Reply::none, {}};
      default:
        return lb::SelectAnswer::cut(reaction());
    }
  }
  // 3: "SMARTDRIVE inverters delay the answer telegram until the parameter value is stored";
  // 10 exceptions 1 and 4: the drive's storing time.
  return lb::SelectAnswer::ack(reaction() + effect.storing);
}

void LustbusDevice::checksum_error(const lb::Context& ctx) {
  (void)ctx;
  const drive::SiofNote<Drive> noted(*drive_, pnr::kSiof);
  drive_->raise_siof(drive::siof_mask(SiofBit::checksum));  // 9.2 bit 3
}

// How the VF1000's table types read on LUSTBUS (LUSTBUS manual 2.3.1).
lustbus::DataType lustbus_type(drive::DataType t) {
  switch (t) {
    case drive::DataType::binary8:
      return lustbus::DataType::binary8;
    case drive::DataType::fixpoint16:
      return lustbus::DataType::fixpoint16;
    case drive::DataType::usign16:
      return lustbus::DataType::usign16;
    case drive::DataType::usign8:
      return lustbus::DataType::usign8;
    case drive::DataType::vf_error:
      return lustbus::DataType::vf_error;
    case drive::DataType::password:
      return lustbus::DataType::password;
    case drive::DataType::integer16:
      return lustbus::DataType::integer16;
  }
  return lustbus::DataType::usign16;
}

}  // namespace ibs::devices::vf1000
