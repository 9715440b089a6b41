#include "ibs/devices/mc6000/lustbus_device.hpp"

#include <cmath>

#include "ibs/devices/mc6000/service.hpp"
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

// Longest stretch the plant is run in one advance(): after a longer silence only its last part
// is simulated (a speed loop has settled long before; 60 s x 1 ms samples are 60 000 steps).
constexpr Duration kPlantCatchUp = std::chrono::seconds(60);

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
      saved_(table_.size()),
      reactions_(timing.reaction) {
  for (std::size_t i = 0; i < table_.size(); ++i) {
    ram_[i] = eeprom_[i] = bits_of(table_[i].type, table_[i].default_value);
  }
  line_baud_ = value(kParamSbaud);
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

bool LustbusDevice::set_line_baud(std::uint32_t baud) {
  const int s = slot(kParamSbaud);
  const pcp::ParameterInfo& p = table_[static_cast<std::size_t>(s)];
  if (static_cast<std::int64_t>(baud) < p.min || static_cast<std::int64_t>(baud) > p.max) return false;
  ram_[static_cast<std::size_t>(s)] = eeprom_[static_cast<std::size_t>(s)] = baud;
  line_baud_ = baud;
  return true;
}

bool LustbusDevice::running() const { return machine_.state() == drivecom::State::enabled; }

double LustbusDevice::reference_rpm() const {
  double rpm = 0.0;
  for (const std::uint16_t sel : {kRssl1, kRssl2, kRssl3, kRssl4}) {
    if (value(sel) == kRsslRsio) {
      rpm += static_cast<double>(static_cast<std::int32_t>(value(kRsio))) / 65536.0;
    }
  }
  return rpm;
}

void LustbusDevice::drive_control(bool reset_edge) {
  // 7.2: the serial interface commands the drive when 402-CLSEL = SIO; the emulator's plant is a
  // speed loop, so only 300-CFCON = SCON engages it (LB-D19).
  const bool start = value(kClsel) == static_cast<std::uint32_t>(kClselSio) &&
                     value(kCfcon) == static_cast<std::uint32_t>(kCfconScon) &&
                     (value(kSctl1) & kSctl1Start) != 0;
  drivecom::DeviceInputs in;
  in.fault_present = watchdog_fault_;
  in.fault_reaction_done = true;
  in.enable_locked = download_ != Download::idle;  // 11.4: "secured against being engaged"
  // The drive walks DRIVECOM's sequence itself: SHUTDOWN before ENABLE OPERATION, the reset edge
  // of 8.1.2 first. A handful of samples reach a stable state.
  for (int i = 0; i < 4; ++i) {
    const drivecom::State s = machine_.state();
    if (reset_edge && i == 0) {
      in.control = static_cast<Word>(drivecom::command_word(drivecom::Command::shutdown) | 0x0080U);
    } else if (start && s != drivecom::State::start_up_inhibit) {
      in.control = drivecom::command_word(drivecom::Command::enable);
    } else {
      in.control = drivecom::command_word(drivecom::Command::shutdown);
    }
    const auto r = machine_.sample(in);
    if (r.count == 0 && i > 0) break;
  }
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
  line_baud_ = value(kParamSbaud);  // 11.5: a new rate is active after the restart
  machine_.force(drivecom::State::start_up_inhibit);
  plant_.reset();
  plant_time_ = now;
  posmod_.restart(now);
}

void LustbusDevice::finish_download(Time now) {
  if (download_ != Download::testing || now < download_ready_) return;
  // 11.4 step 3: the whole dataset is tested; the first invalid parameter's number goes to
  // SLOAD and the old dataset comes back, or SLOAD = 0 and the dataset goes to EEPROM.
  // Only the CardWriteable parameters belong to the dataset (11.4 "Important").
  std::uint32_t rejected = 0;
  for (std::size_t i = 0; i < table_.size() && rejected == 0; ++i) {
    if (card_writeable(table_[i].number) && !in_range(table_[i], ram_[i])) {
      rejected = table_[i].number;
    }
  }
  const auto s = static_cast<std::size_t>(slot(kSload));
  for (std::size_t i = 0; i < table_.size(); ++i) {
    if (i == s || !card_writeable(table_[i].number)) continue;
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
  // The plant runs up to `now` with what held since the last call (7.2: reference from the
  // selectors, the power stage from DRIVECOM).
  if (now > plant_time_) {
    Duration dt = now - plant_time_;
    plant_time_ = now;
    const bool on = running();
    if (on || std::abs(plant_.speed_rpm()) > 1e-9) {
      if (dt > kPlantCatchUp) dt = kPlantCatchUp;
      plant_.advance(dt, PlantInput{reference_rpm(), 0.0, on});
    }
  }
  posmod_.advance(now, running());
  finish_download(now);
  // 5.2: no valid telegram within 84-SWDGT ms: the error state, 02H in 85-SERR; the drive stops.
  if (!watchdog_fault_ && watchdog_.expired_at(now, static_cast<std::uint16_t>(value(kSwdgt)))) {
    watchdog_fault_ = true;
    serr_.set(SiofBit::watchdog);
  }
  drive_control(false);
}

void LustbusDevice::telegram_received(const lb::Context& ctx) {
  advance(ctx.now);
  watchdog_.telegram(ctx.now, static_cast<std::uint16_t>(value(kSwdgt)));
}

lb::EnquiryAnswer LustbusDevice::describe(const pcp::ParameterInfo& p) {
  // 11.2: 43 characters; the service structure's elements from service.hpp (LB-D21).
  lb::McDescription d;
  for (std::size_t i = 0; i < p.name.size() && i < lb::kMcNameLength; ++i) d.name[i] = p.name[i];
  d.kind = static_cast<char>(p.category);
  d.type = static_cast<std::uint8_t>('0' + static_cast<int>(p.type));  // LB-D20
  d.min = bits_of(p.type, p.min);
  d.max = bits_of(p.type, p.max);
  d.reference = bits_of(p.type, p.default_value);
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
  const pcp::ParameterInfo* p = pcp::find_parameter(table_, parameter);
  if (p == nullptr || (p->attributes & pcp::kAttrShowText) == 0) return lb::EnquiryAnswer::nak(reaction());
  const std::uint32_t index = value(kStext);
  if (static_cast<std::int64_t>(index) > p->max) return lb::EnquiryAnswer::nak(reaction());
  const auto text = lb::Value::from(substitution_text_of(parameter, index));
  if (!text || text->empty()) return lb::EnquiryAnswer::nak(reaction());
  return lb::EnquiryAnswer::text(*text, reaction());
}

lb::EnquiryAnswer LustbusDevice::enquiry(const lb::Code& code, const lb::Context& ctx) {
  advance(ctx.now);
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
  const auto s = static_cast<std::size_t>(slot(p->number));
  if (description) return describe(*p);
  std::uint32_t bits = ram_[s];
  if (p->number == kSerr) {
    bits = serr_.read_and_clear();  // 9.2: reading erases the bits
  } else if (p->number == kSload && download_ == Download::testing) {
    bits = bits_of(p->type, kSloadBegin);  // 11.4 step 4: -1 while testing and saving
  } else if (p->number == kSpeed) {
    // 6.1.1.2: the motor speed, the plant's, as Q16 rpm.
    bits = static_cast<std::uint32_t>(static_cast<std::int32_t>(std::llround(plant_.speed_rpm() * 65536.0)));
  }
  // 2.3: leading zeros are optional; the servo sends the type's full width (two, four or eight
  // digits), as 6.1.1.2's answer and 10.1.1's 18 bytes show (LB-E4, LB-D20).
  const auto v = lb::format_raw_width(bits, lb::width_bits(lustbus_type(p->type)) / 4);
  if (!v.ok()) return lb::EnquiryAnswer::nak(reaction());
  return lb::EnquiryAnswer::text(v.value, reaction());
}

lb::SelectAnswer LustbusDevice::refuse(SiofBit b) {
  serr_.set(b);  // 9.2: the cause of the refusal
  return lb::SelectAnswer::nak(reaction());
}

lb::SelectAnswer LustbusDevice::select(const lb::Code& code, const lb::Value& value,
                                       const lb::Context& ctx) {
  advance(ctx.now);
  const auto mc = lb::as_mc_code(code);
  if (mc && mc->kind == lb::McCodeKind::posmod) {
    // 11.6.1: the option's own channel. Its refusals are read with %RDF, not from 85-SERR, and
    // the SERR latch, which guards the parameters (9.2), does not hold it (LB-D22).
    return posmod_.select(value.view(), ctx.now) ? lb::SelectAnswer::ack(reaction())
                                                 : lb::SelectAnswer::nak(reaction());
  }
  // 6, 9.2: every SELECT is refused while a bit is set.
  if (serr_.blocks_select()) return lb::SelectAnswer::nak(reaction());
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
      drive_control(false);
      return lb::SelectAnswer::ack(reaction());
    }
    if (n == kSloadEnd) {
      if (download_ != Download::receiving) return refuse(SiofBit::no_change);
      download_ = Download::testing;
      download_ready_ = ctx.now + timing_.download_check;
      return lb::SelectAnswer::ack(reaction());
    }
    return refuse(SiofBit::invalid_value);  // only -1 and -2 are commands
  }
  if (download_ == Download::testing) return refuse(SiofBit::no_change);
  const bool receiving = download_ == Download::receiving;
  // 11.4 step 2: during a download the values are taken without the plausibility test — only
  // those of CardWriteable parameters; any other SELECT is acknowledged and its value dropped
  // (11.4 "Important"), a start through 416-SCTL1 included: the drive stays disengaged.
  if (receiving) {
    if (!card_writeable(p->number)) return lb::SelectAnswer::ack(reaction());
  } else if (!in_range(*p, bits)) {
    return refuse(SiofBit::invalid_value);
  }
  if (p->number == kProg && bits == kProgFactoryDefaults) {
    // 10 exception 1: every parameter back to its factory setting; ACK once done.
    for (std::size_t i = 0; i < table_.size(); ++i) {
      ram_[i] = eeprom_[i] = bits_of(table_[i].type, table_[i].default_value);
    }
    drive_control(false);
    return lb::SelectAnswer::ack(reaction() + timing_.factory_defaults);
  }
  if (p->number == kProg && bits == kProgActivateBaudrate) {
    // 11.5: the new 81-SBAUD at once, without a restart; the ACK still goes out at the old rate.
    line_baud_ = LustbusDevice::value(kParamSbaud);
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
  bool reset = false;
  if (p->number == kSctl1 && (bits & kSctl1Reset) != 0) {
    watchdog_fault_ = false;  // 8.1.2: bit 7 resets the error
    reset = true;
    ram_[s] = bits & ~kSctl1Reset;
  }
  drive_control(reset);
  return lb::SelectAnswer::ack(reaction());
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
