#include "ibs/devices/vf1000/lustbus_device.hpp"

#include "ibs/lustbus/code.hpp"
#include "ibs/lustbus/description.hpp"
#include "ibs/lustbus/value.hpp"

namespace ibs::devices::vf1000 {

namespace lb = ibs::lustbus;
using drive::SiofBit;

namespace {

constexpr Word kStartClockwise = 0x80;         // seed 000, 7.1.1: CNTL = 128
constexpr Word kStartCounterClockwise = 0x40;  // the other direction (LB-D19)

bool one_byte(drive::DataType t) {
  return t == drive::DataType::binary8 || t == drive::DataType::usign8;
}

}  // namespace

LustbusDevice::LustbusDevice(LustbusTiming timing)
    : timing_(timing), table_(parameters()), store_(parameters()) {}

const drive::ParameterInfo* LustbusDevice::resolve(const lb::Code& code, bool& description) const {
  const auto vc = lb::as_vf_code(code);  // 2.4.1: S 0 D P P
  if (!vc) return nullptr;
  description = vc->specifier == lb::VfSpecifier::description;
  const drive::ParameterInfo* p = table_.find(vc->parameter);
  if (p == nullptr) return nullptr;
  // 11.1, "Parameter kind": device digit 0 only for basis parameters (kinds '0'..'3').
  if (vc->device == 0 && static_cast<int>(p->category) > 3) return nullptr;
  return p;
}

Word LustbusDevice::value(std::uint16_t number) const {
  const int s = table_.slot(number);
  return s < 0 ? 0 : store_.value(static_cast<std::size_t>(s));
}

Word LustbusDevice::eeprom_value(std::uint16_t number) const {
  const int s = table_.slot(number);
  return s < 0 ? 0 : store_.eeprom_value(static_cast<std::size_t>(s));
}

bool LustbusDevice::power_stage_enabled() const {
  return !watchdog_fault_ &&
         (value(pnr::kCntl) & (kStartClockwise | kStartCounterClockwise)) != 0;
}

void LustbusDevice::restart(Time now) {
  store_.power_on();
  siof_.power_on();  // 6: after every new start
  watchdog_.restart(now);
  watchdog_fault_ = false;
}

void LustbusDevice::advance(Time now) {
  // 5.2: no valid telegram within 84-SIOT ms: the error state, bit 02H in 85-SIOF; 8: the
  // inverter blocks its power stage.
  if (!watchdog_fault_ && watchdog_.expired_at(now, value(pnr::kSiot))) {
    watchdog_fault_ = true;
    siof_.set(SiofBit::watchdog);
  }
}

void LustbusDevice::telegram_received(const lb::Context& ctx) {
  advance(ctx.now);
  watchdog_.telegram(ctx.now, value(pnr::kSiot));
}

lb::EnquiryAnswer LustbusDevice::enquiry(const lb::Code& code, const lb::Context& ctx) {
  (void)ctx;
  bool description = false;
  const drive::ParameterInfo* p = resolve(code, description);
  // 6.1 note: NAK for a parameter that is not there; no cause enters 85-SIOF on an ENQUIRY.
  if (p == nullptr) return lb::EnquiryAnswer::nak(timing_.reaction);
  if (description) {  // 11.1: 26 characters
    const auto d = lb::format_vf_description(p->name, p->unit, drive::category_code(p->category),
                                             drive::type_code(p->type), p->min, p->max,
                                             p->default_value);
    if (!d) return lb::EnquiryAnswer::nak(timing_.reaction);
    return lb::EnquiryAnswer::text(*d, timing_.reaction);
  }
  Word raw = store_.value(static_cast<std::size_t>(table_.slot(p->number)));
  if (p->number == pnr::kSiof) {
    raw = siof_.read_and_clear();  // 9.2: reading erases the bits
  } else if (p->number == pnr::kFout) {
    // 6.1.1.1: the rotary-field frequency; without a motor model it follows 5-FSSIO while the
    // power stage runs (LB-D19).
    raw = power_stage_enabled() ? value(pnr::kFssio) : 0;
  }
  const auto v = lb::format_raw(lb::Family::vf1000, raw);  // 2.3.1: "%04X"
  if (!v.ok()) return lb::EnquiryAnswer::nak(timing_.reaction);
  return lb::EnquiryAnswer::text(v.value, timing_.reaction);
}

lb::SelectAnswer LustbusDevice::refuse(SiofBit b) {
  siof_.set(b);  // 9.2: the cause of the refusal
  return lb::SelectAnswer::nak(timing_.reaction);
}

lb::SelectAnswer LustbusDevice::select(const lb::Code& code, const lb::Value& value,
                                       const lb::Context& ctx) {
  // 6, 9.2: every SELECT is refused while a bit is set; the bits stay as they are.
  if (siof_.blocks_select()) return lb::SelectAnswer::nak(timing_.reaction);
  bool description = false;
  const drive::ParameterInfo* p = resolve(code, description);
  if (p == nullptr) return refuse(SiofBit::no_parameter);
  if (description) return refuse(SiofBit::no_change);  // a description cannot be written
  const auto raw = lb::parse_raw(lb::Family::vf1000, value.view());  // exactly four hex digits
  if (!raw.ok()) return refuse(SiofBit::invalid_value);
  const auto w = static_cast<Word>(raw.value);
  // 3, "Access limitations depend on the type of operation": 40H for a read-only parameter or an
  // EEPROM parameter while the power stage runs; then the value's range (80H).
  const drive::WriteCheck check = drive::check_write(p, w, power_stage_enabled());
  if (check != drive::WriteCheck::ok) {
    return refuse(check == drive::WriteCheck::invalid_value ? SiofBit::invalid_value
                                                            : SiofBit::no_change);
  }
  const auto slot = static_cast<std::size_t>(table_.slot(p->number));
  if (p->number == pnr::kProg && w == drive::kLoadDefaults) {
    // 10 exception 1: every parameter back to its factory setting; ACK once done.
    store_.factory_defaults();
    return lb::SelectAnswer::ack(timing_.reaction + timing_.factory_defaults);
  }
  if (p->number == pnr::kStat && w == kStatReset) {
    // 8.1.1: the reset restarts the inverter (self test); 85-SIOF shows the power-on bit.
    restart(ctx.now);
    return lb::SelectAnswer::ack(timing_.reaction);
  }
  const Word eeprom_before = store_.eeprom_value(slot);
  store_.write(slot, w, power_stage_enabled());
  if (p->number == pnr::kSiot) watchdog_.restart(ctx.now);
  Duration r = timing_.reaction;
  // 3: "SMARTDRIVE inverters delay the answer until the value is stored in EEPROM"; 10
  // exception 4: only a changed value costs the time.
  if (store_.eeprom_value(slot) != eeprom_before) {
    r += one_byte(p->type) ? timing_.eeprom_one_byte : timing_.eeprom_two_bytes;
  }
  return lb::SelectAnswer::ack(r);
}

void LustbusDevice::checksum_error(const lb::Context& ctx) {
  (void)ctx;
  siof_.set(SiofBit::checksum);  // 9.2 bit 3
}

// How the VF1000's table types read on LUSTBUS (seed 000, 2.3.1).
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
