#include "ibs/devices/mc6000/lustbus_device.hpp"

#include <memory>
#include <optional>

#include "ibs/devices/mc6000/service.hpp"
#include "ibs/lustbus/code.hpp"
#include "ibs/lustbus/description.hpp"
#include "ibs/lustbus/value.hpp"

namespace ibs::devices::mc6000 {

namespace lb = ibs::lustbus;

namespace {

DriveConfig drive_config(const LustbusTiming& t) {
  DriveConfig c;
  c.timing.eeprom_per_byte = t.eeprom_per_byte;
  c.timing.factory_defaults = t.factory_defaults;
  c.timing.download_check = t.download_check;
  return c;
}

}  // namespace

LustbusDevice::LustbusDevice(LustbusTiming timing)
    : LustbusDevice(std::make_shared<Drive>(drive_config(timing), DeviceStart::initialised), timing) {}

LustbusDevice::LustbusDevice(std::shared_ptr<Drive> drive, LustbusTiming timing)
    : drive_(std::move(drive)),
      reactions_(timing.reaction),
      line_baud_(drive_->parameters().raw(kParamSbaud)),
      baud_activations_(drive_->parameters().baud_activations()) {
  drive_->set_serial_face(true);
}

std::uint32_t LustbusDevice::eeprom_value(std::uint16_t number) const {
  const auto v = drive_->parameters().eeprom(number);
  return v ? v->raw : 0;
}

bool LustbusDevice::set_line_baud(std::uint32_t baud) {
  if (!drive::is_baud_step(baud, kHighestBaud) || !drive_->parameters().preset(kParamSbaud, baud)) return false;
  line_baud_ = baud;
  return true;
}

const pcp::ParameterInfo* LustbusDevice::resolve(const lb::Code& code, bool& description) const {
  description = false;
  const auto mc = lb::as_mc_code(code);  // 2.4.2, 5.2
  if (!mc) return nullptr;
  switch (mc->kind) {
    case lb::McCodeKind::value:
    case lb::McCodeKind::shared:
      break;
    case lb::McCodeKind::description:
      description = true;
      break;
    default:
      return nullptr;  // 11.3 texts and the PosMOD1 channel: enquiry() / select() themselves
  }
  return drive_->parameters().store().info(mc->parameter);
}

void LustbusDevice::restart(Time now) {
  drive_->power_on(now);  // 6: the power-on bit after every new start
  started(now);
}

void LustbusDevice::started(Time now) {
  line_baud_ = value(kParamSbaud);  // 11.5: a new rate is active after the restart
  baud_activations_ = drive_->parameters().baud_activations();
  posmod_.restart(now);
}

void LustbusDevice::advance(Time now) {
  drive_->advance(now);  // the watchdog of 5.2, the end of a download test, the plant
  posmod_.advance(now, running());
}

void LustbusDevice::telegram_received(const lb::Context& ctx) {
  drive_->serial_telegram(ctx.now);  // 5.2: a valid telegram resets the watchdog
  posmod_.advance(ctx.now, running());
}

lb::EnquiryAnswer LustbusDevice::describe(const pcp::ParameterInfo& p) {
  // 11.2: 43 characters; the service structure's elements from service.hpp (LB-D21).
  lb::McDescription d;
  for (std::size_t i = 0; i < p.name.size() && i < lb::kMcNameLength; ++i) d.name[i] = p.name[i];
  d.kind = static_cast<char>(p.category);
  d.type = static_cast<std::uint8_t>('0' + static_cast<int>(p.type));  // LB-D20
  d.min = pcp::ParameterStore::to_raw(p, p.min);
  d.max = pcp::ParameterStore::to_raw(p, p.max);
  d.reference = pcp::ParameterStore::default_raw(p);
  d.attribute = p.attributes;
  if (const ServiceEntry* e = service_entry(p.number)) {
    d.unit = e->unit;
    d.level = e->level;
    d.hardware_filter = e->hardware_filter;
    d.structure_filter = e->structure_filter;
    d.subject_area = static_cast<std::uint8_t>(e->subject);
    d.activity_area = static_cast<std::uint8_t>(e->activity);
  }
  const auto v = lb::format_mc_description(d);
  if (!v) return lb::EnquiryAnswer::nak(reaction());
  return lb::EnquiryAnswer::text(*v, reaction());
}

lb::EnquiryAnswer LustbusDevice::substitution_text(std::uint16_t parameter) {
  // 11.3: NAK when the parameter does not exist, has no substitution text (attribute ShowText),
  // or 108-STEXT is above the parameter's maximum — or names a value without a text (LB-D21).
  const pcp::ParameterInfo* p = drive_->parameters().store().info(parameter);
  if (p == nullptr || (p->attributes & pcp::kAttrShowText) == 0) return lb::EnquiryAnswer::nak(reaction());
  const std::uint32_t index = value(kStext);
  if (static_cast<std::int64_t>(index) > p->max) return lb::EnquiryAnswer::nak(reaction());
  const auto text = lb::Value::from(substitution_text_of(parameter, index));
  if (!text || text->empty()) return lb::EnquiryAnswer::nak(reaction());
  return lb::EnquiryAnswer::text(*text, reaction());
}

lb::EnquiryAnswer LustbusDevice::enquiry(const lb::Code& code, const lb::Context& ctx) {
  advance(ctx.now);
  // For a recording of the INTERBUS words, which do not carry this channel (parameter_journal.hpp).
  const drive::SiofNote<Drive> noted(*drive_, drive::kSiofNumber);
  if (const auto mc = lb::as_mc_code(code)) {
    if (mc->kind == lb::McCodeKind::posmod) {  // 11.6.2
      const auto v = posmod_.enquiry(ctx.now);
      return v ? lb::EnquiryAnswer::text(*v, reaction()) : lb::EnquiryAnswer::nak(reaction());
    }
    if (mc->kind == lb::McCodeKind::substitution_text) return substitution_text(mc->parameter);
  }
  bool description = false;
  const pcp::ParameterInfo* p = resolve(code, description);
  // 6.1 note: NAK for a parameter that is not there; an ENQUIRY enters nothing in 85-SERR.
  if (p == nullptr) return lb::EnquiryAnswer::nak(reaction());
  if (description) return describe(*p);
  // The core's read: 85-SERR clears (9.2), 80-SLOAD reads -1 while testing (11.4), 77-SPEED the
  // plant's speed as Q16 rpm (6.1.1.2).
  const auto read = drive_->read(ctx.now, p->number);
  const std::uint32_t bits = read ? read->raw : 0;
  // 2.3: leading zeros are optional; the servo sends the type's full width (two, four or eight
  // digits), as 6.1.1.2's answer and 10.1.1's 18 bytes show (LB-E4, LB-D20).
  const auto v = lb::format_raw_width(bits, lb::width_bits(lustbus_type(p->type)) / 4);
  if (!v.ok()) return lb::EnquiryAnswer::nak(reaction());
  return lb::EnquiryAnswer::text(v.value, reaction());
}

lb::SelectAnswer LustbusDevice::select(const lb::Code& code, const lb::Value& value,
                                       const lb::Context& ctx) {
  advance(ctx.now);
  const drive::SiofNote<Drive> noted(*drive_, drive::kSiofNumber);
  const auto mc = lb::as_mc_code(code);
  if (mc && mc->kind == lb::McCodeKind::posmod) {
    // 11.6.1: the option's own channel. Its refusals are read with %RDF, not from 85-SERR, and
    // the SERR latch, which guards the parameters (9.2), does not hold it (LB-D22).
    return posmod_.select(value.view(), ctx.now) ? lb::SelectAnswer::ack(reaction())
                                                 : lb::SelectAnswer::nak(reaction());
  }
  bool description = false;
  const pcp::ParameterInfo* p = resolve(code, description);
  // The core refuses while 85-SERR holds a bit (6, 9.2) and enters the cause of any other refusal.
  WriteResult r;
  if (p == nullptr) {
    r = drive_->refuse(Refusal::no_parameter);
  } else if (description) {
    r = drive_->refuse(Refusal::read_only);
  } else {
    const auto parsed = lb::parse_typed(lb::Family::enhanced, lustbus_type(p->type), value.view());
    r = drive_->write(ctx.now, p->number, parsed.ok() ? std::optional<std::uint32_t>(parsed.value) : std::nullopt);
    if (r.ok() && parsed.ok()) drive_->journal().note(p->number, parsed.value);
  }
  if (!r.ok()) return lb::SelectAnswer::nak(reaction());
  // 8.1.2: a reaction-5 error reset boots the servo "immediately after the receipt": only the ADR
  // of the ACK gets out (LUSTBUS's Reply::cut), then the servo is deaf for its boot.
  if (r.restarted) {
    started(ctx.now);
    return lb::SelectAnswer::cut(reaction());
  }
  const std::uint32_t activations = drive_->parameters().baud_activations();
  if (activations != baud_activations_) {
    // 11.5: 4-PROG = 111 takes the new 81-SBAUD at once, without a restart; the ACK still goes
    // out at the old rate.
    baud_activations_ = activations;
    line_baud_ = LustbusDevice::value(kParamSbaud);
  }
  // 10 exception 1: the ACK of 4-PROG = 1 only once every parameter is reset.
  return lb::SelectAnswer::ack(reaction() + r.busy_for);
}

void LustbusDevice::checksum_error(const lb::Context& ctx) {
  (void)ctx;
  const drive::SiofNote<Drive> noted(*drive_, drive::kSiofNumber);
  drive_->serial_checksum_error();  // 9.2 bit 3
}

// How the MC6000's table types read on LUSTBUS (LUSTBUS manual 2.3.2).
lb::DataType lustbus_type(pcp::DataType t) {
  switch (t) {
    case pcp::DataType::usign8:
      return lb::DataType::usign8;
    case pcp::DataType::usign16:
      return lb::DataType::usign16;
    case pcp::DataType::fixpoint16:
      return lb::DataType::fixpoint16;
    case pcp::DataType::integer16:
      return lb::DataType::integer16;
    case pcp::DataType::int32q16:
      return lb::DataType::int32q16;
    case pcp::DataType::float_ieee:
      return lb::DataType::float_ieee;
    case pcp::DataType::mc_error:
      return lb::DataType::mc_error;
    case pcp::DataType::password:
      return lb::DataType::password;
  }
  return lb::DataType::usign16;
}

}  // namespace ibs::devices::mc6000
