#include "ibs/devices/mc6000/lustbus_device.hpp"

#include "ibs/lustbus/code.hpp"
#include "ibs/lustbus/description.hpp"
#include "ibs/lustbus/value.hpp"

namespace ibs::devices::mc6000 {

namespace lb = ibs::lustbus;
using drive::SiofBit;

namespace {

// A table number (signed_raw) as the type's bit pattern.
std::uint32_t bits_of(pcp::DataType t, std::int64_t n) {
  const unsigned w = lb::width_bits(lustbus_type(t));
  const auto u = static_cast<std::uint64_t>(n);
  return static_cast<std::uint32_t>(w == 32 ? (u & 0xFFFFFFFFULL) : (u & ((1ULL << w) - 1ULL)));
}

// A bit pattern as the number the table's limits compare with.
std::int64_t number_of(pcp::DataType t, std::uint32_t bits) {
  switch (t) {
    case pcp::DataType::integer16:
      return static_cast<std::int16_t>(bits);
    case pcp::DataType::int32q16:
    case pcp::DataType::float_ieee:
    case pcp::DataType::mc_error:
      return static_cast<std::int32_t>(bits);
    default:
      return bits;
  }
}

bool in_range(const pcp::ParameterInfo& p, std::uint32_t bits) {
  if (p.type == pcp::DataType::float_ieee) return true;  // limits are patterns, not numbers
  const std::int64_t n = number_of(p.type, bits);
  return n >= p.min && n <= p.max;
}

}  // namespace

LustbusDevice::LustbusDevice(LustbusTiming timing)
    : timing_(timing),
      table_(parameters()),
      ram_(table_.size()),
      eeprom_(table_.size()),
      saved_(table_.size()) {
  for (std::size_t i = 0; i < table_.size(); ++i) {
    ram_[i] = eeprom_[i] = bits_of(table_[i].type, table_[i].default_value);
  }
}

int LustbusDevice::slot(std::uint16_t number) const {
  for (std::size_t i = 0; i < table_.size(); ++i) {
    if (table_[i].number == number) return static_cast<int>(i);
  }
  return -1;
}

std::uint32_t LustbusDevice::value(std::uint16_t number) const {
  const int s = slot(number);
  return s < 0 ? 0 : ram_[static_cast<std::size_t>(s)];
}

std::uint32_t LustbusDevice::eeprom_value(std::uint16_t number) const {
  const int s = slot(number);
  return s < 0 ? 0 : eeprom_[static_cast<std::size_t>(s)];
}

bool LustbusDevice::running() const {
  return !watchdog_fault_ && (value(kSctl1) & kSctl1Start) != 0;
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
      return nullptr;  // 11.3 texts and the PosMOD1 channel: not fitted (LB-D20)
  }
  return pcp::find_parameter(table_, mc->parameter);
}

void LustbusDevice::restart(Time now) {
  for (std::size_t i = 0; i < table_.size(); ++i) {
    ram_[i] = table_[i].category == pcp::Category::eeprom
                  ? eeprom_[i]
                  : bits_of(table_[i].type, table_[i].default_value);
  }
  serr_.power_on();  // 6: after every new start
  watchdog_.restart(now);
  watchdog_fault_ = false;
  download_ = Download::idle;
}

void LustbusDevice::finish_download(Time now) {
  if (download_ != Download::testing || now < download_ready_) return;
  // 11.4 step 3: the whole dataset is tested; the first invalid parameter's number goes to
  // SLOAD and the old dataset comes back, or SLOAD = 0 and the dataset goes to EEPROM.
  std::uint32_t rejected = 0;
  for (std::size_t i = 0; i < table_.size() && rejected == 0; ++i) {
    if (table_[i].number != kSload && !in_range(table_[i], ram_[i])) rejected = table_[i].number;
  }
  const auto s = static_cast<std::size_t>(slot(kSload));
  for (std::size_t i = 0; i < table_.size(); ++i) {
    if (i == s) continue;
    if (rejected != 0) {
      ram_[i] = saved_[i];
    } else if (table_[i].category == pcp::Category::eeprom) {
      eeprom_[i] = ram_[i];
    }
  }
  ram_[s] = rejected;
  download_ = Download::idle;
}

void LustbusDevice::advance(Time now) {
  finish_download(now);
  // 5.2: no valid telegram within 84-SWDGT ms: the error state, 02H in 85-SERR; the drive stops.
  if (!watchdog_fault_ && watchdog_.expired_at(now, static_cast<std::uint16_t>(value(kSwdgt)))) {
    watchdog_fault_ = true;
    serr_.set(SiofBit::watchdog);
  }
}

void LustbusDevice::telegram_received(const lb::Context& ctx) {
  advance(ctx.now);
  watchdog_.telegram(ctx.now, static_cast<std::uint16_t>(value(kSwdgt)));
}

lb::EnquiryAnswer LustbusDevice::enquiry(const lb::Code& code, const lb::Context& ctx) {
  advance(ctx.now);
  bool description = false;
  const pcp::ParameterInfo* p = resolve(code, description);
  // 6.1 note: NAK for a parameter that is not there; an ENQUIRY enters nothing in 85-SERR.
  if (p == nullptr) return lb::EnquiryAnswer::nak(timing_.reaction);
  const auto s = static_cast<std::size_t>(slot(p->number));
  if (description) {  // 11.2: 43 characters
    lb::McDescription d;
    for (std::size_t i = 0; i < p->name.size() && i < lb::kMcNameLength; ++i) d.name[i] = p->name[i];
    d.kind = static_cast<char>(p->category);
    d.type = static_cast<std::uint8_t>('0' + static_cast<int>(p->type));  // LB-D20
    d.min = bits_of(p->type, p->min);
    d.max = bits_of(p->type, p->max);
    d.reference = bits_of(p->type, p->default_value);
    d.level = 0x21;  // read level 1, write level 2 (LB-D20)
    d.attribute = p->attributes;
    const auto v = lb::format_mc_description(d);
    if (!v) return lb::EnquiryAnswer::nak(timing_.reaction);
    return lb::EnquiryAnswer::text(*v, timing_.reaction);
  }
  std::uint32_t bits = ram_[s];
  if (p->number == kSerr) {
    bits = serr_.read_and_clear();  // 9.2: reading erases the bits
  } else if (p->number == kSload && download_ == Download::testing) {
    bits = bits_of(p->type, kSloadBegin);  // 11.4 step 4: -1 while testing and saving
  } else if (p->number == kSpeed) {
    // 6.1.1.2: the motor speed; without the plant it follows 428-RSIO while the drive runs.
    bits = running() ? value(kRsio) : 0;
  }
  // 2.3: leading zeros are optional; the servo sends the type's full width (two, four or eight
  // digits), as 6.1.1.2's answer and 10.1.1's 18 bytes show (LB-E4, LB-D20).
  const auto v = lb::format_raw_width(bits, lb::width_bits(lustbus_type(p->type)) / 4);
  if (!v.ok()) return lb::EnquiryAnswer::nak(timing_.reaction);
  return lb::EnquiryAnswer::text(v.value, timing_.reaction);
}

lb::SelectAnswer LustbusDevice::refuse(SiofBit b) {
  serr_.set(b);  // 9.2: the cause of the refusal
  return lb::SelectAnswer::nak(timing_.reaction);
}

lb::SelectAnswer LustbusDevice::select(const lb::Code& code, const lb::Value& value,
                                       const lb::Context& ctx) {
  advance(ctx.now);
  // 6, 9.2: every SELECT is refused while a bit is set.
  if (serr_.blocks_select()) return lb::SelectAnswer::nak(timing_.reaction);
  bool description = false;
  const pcp::ParameterInfo* p = resolve(code, description);
  if (p == nullptr) return refuse(SiofBit::no_parameter);
  if (description || !p->writable()) return refuse(SiofBit::no_change);
  const auto parsed = lb::parse_typed(lb::Family::mc6000, lustbus_type(p->type), value.view());
  if (!parsed.ok()) return refuse(SiofBit::invalid_value);
  const std::uint32_t bits = parsed.value;
  const auto s = static_cast<std::size_t>(slot(p->number));

  if (p->number == kSload) {  // 11.4
    const std::int64_t n = number_of(p->type, bits);
    if (n == kSloadBegin) {
      // "Write accessing this parameter is possible only when the system is in a stillstand".
      if (running() || download_ != Download::idle) return refuse(SiofBit::no_change);
      saved_ = ram_;  // same size: no allocation
      download_ = Download::receiving;
      ram_[s] = bits;
      return lb::SelectAnswer::ack(timing_.reaction);
    }
    if (n == kSloadEnd) {
      if (download_ != Download::receiving) return refuse(SiofBit::no_change);
      download_ = Download::testing;
      download_ready_ = ctx.now + timing_.download_check;
      return lb::SelectAnswer::ack(timing_.reaction);
    }
    return refuse(SiofBit::invalid_value);  // only -1 and -2 are commands
  }
  if (download_ == Download::testing) return refuse(SiofBit::no_change);
  const bool receiving = download_ == Download::receiving;
  // 11.4 step 2: during a download the values are taken without the plausibility test; the
  // drive is "secured against being engaged" (no start through SCTL1).
  if (!receiving && !in_range(*p, bits)) return refuse(SiofBit::invalid_value);
  if (receiving && p->number == kSctl1 && (bits & kSctl1Start) != 0) {
    return refuse(SiofBit::no_change);
  }
  if (p->number == kProg && bits == kProgFactoryDefaults) {
    // 10 exception 1: every parameter back to its factory setting; ACK once done.
    for (std::size_t i = 0; i < table_.size(); ++i) {
      ram_[i] = eeprom_[i] = bits_of(table_[i].type, table_[i].default_value);
    }
    return lb::SelectAnswer::ack(timing_.reaction + timing_.factory_defaults);
  }
  if (p->category == pcp::Category::eeprom && !receiving) {
    // 3: RAM at once, ACK at once, EEPROM in the background at 15 ms per byte (10.2.2); a new
    // EEPROM value while the last is still being saved overloads the routine: 04H.
    if (ctx.now < eeprom_busy_until_) return refuse(SiofBit::eeprom_busy);
    const unsigned bytes = lb::width_bits(lustbus_type(p->type)) / 8;
    eeprom_busy_until_ = ctx.now + timing_.eeprom_per_byte * bytes;
    eeprom_[s] = bits;
  }
  ram_[s] = bits;
  if (p->number == kSwdgt) watchdog_.restart(ctx.now);
  if (p->number == kSctl1 && (bits & kSctl1Reset) != 0) {
    watchdog_fault_ = false;  // 8.1.2: bit 7 resets the error
    ram_[s] = bits & ~kSctl1Reset;
  }
  return lb::SelectAnswer::ack(timing_.reaction);
}

void LustbusDevice::checksum_error(const lb::Context& ctx) {
  (void)ctx;
  serr_.set(SiofBit::checksum);  // 9.2 bit 3
}

// How the MC6000's table types read on LUSTBUS (seed 000, 2.3.2).
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
