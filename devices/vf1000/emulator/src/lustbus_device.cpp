#include "ibs/devices/vf1000/lustbus_device.hpp"

#include <cmath>

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

// 7.1: 1-MODE = 0 and 2-CSEL = 3 put control on the serial interface; 4-FSSEL = 8 takes the
// reference from 5-FSSIO.
constexpr Word kModeSio = 0;
constexpr Word kCselSio = 3;
constexpr Word kFsselFssio = 8;
// After a longer silence only this much of the inverter's sampling is run (the ramp has long
// ended): 60 s are about 7 300 samples of 8.2 ms.
constexpr Duration kCatchUp = std::chrono::seconds(60);

Vf1000PdConfig pd_config(const LustbusTiming& t) {
  Vf1000PdConfig c;
  c.reset_time = t.self_test;
  return c;
}

}  // namespace

LustbusDevice::LustbusDevice(LustbusTiming timing)
    : timing_(timing),
      table_(parameters()),
      store_(parameters()),
      reactions_(timing.reaction),
      pd_(pd_config(timing)) {
  line_baud_ = sioc_baud(value(pnr::kSioc));
}

Word LustbusDevice::control_word() const {
  const bool sio = value(pnr::kMode) == kModeSio && value(pnr::kCsel) == kCselSio;
  const Word cntl = sio && !booting_ ? value(pnr::kCntl) : Word{0};
  ControlBits b;
  b.ramp_enable = b.ramp_run = b.ramp_follow = true;  // the ramp generator runs freely
  b.str = (cntl & kStartClockwise) != 0;
  b.stl = (cntl & kStartCounterClockwise) != 0;
  Word w = encode_control_bits(b);
  const drivecom::State s = pd_.state();
  // The inverter walks DRIVECOM itself: SHUTDOWN before ENABLE OPERATION; without a start bit
  // the ramp brings the frequency down first, then SHUTDOWN (READY TO SWITCH ON).
  if (b.str || b.stl) {
    w |= s == drivecom::State::start_up_inhibit ? drivecom::command_word(drivecom::Command::shutdown)
                                                : drivecom::command_word(drivecom::Command::enable);
  } else if (s == drivecom::State::enabled && pd_.frequency_hz() != 0.0) {
    w |= drivecom::command_word(drivecom::Command::enable);
  } else {
    w |= drivecom::command_word(drivecom::Command::shutdown);
  }
  return w;
}

void LustbusDevice::run_samples(Time now) {
  if (now <= pd_time_) return;
  if (now - pd_time_ > kCatchUp) pd_time_ = now - kCatchUp;
  pd_.set_fault(fault_ || watchdog_fault_);
  while (now - pd_time_ >= kSamplePeriod) {
    pd_time_ += kSamplePeriod;
    sample(kSamplePeriod);
  }
}

void LustbusDevice::sample(Duration dt) {
  // Words 1 and 2 as 7.1 forms them: the control word of 3-CNTL, the reference of 5-FSSIO in
  // 0.05 Hz steps (with 4-FSSEL = 8); the communication word is not used over LUSTBUS.
  const std::array<Word, Vf1000PdDevice::kWords> m2s{
      control_word(), value(pnr::kFssel) == kFsselFssio ? value(pnr::kFssio) : Word{0}, 0};
  std::array<Word, Vf1000PdDevice::kWords> s2m{};
  pd_.sample(m2s, s2m, dt);
}

bool LustbusDevice::set_line_baud(std::uint32_t baud) {
  for (Word code = 0; code <= 2; ++code) {
    if (sioc_baud(code) != baud) continue;
    const auto s = static_cast<std::size_t>(table_.slot(pnr::kSioc));
    store_.set(s, code);
    line_baud_ = baud;
    return true;
  }
  return false;
}

void LustbusDevice::set_fault(bool present, Time now) {
  advance(now);
  fault_ = present;
  sample_now();
}

Word LustbusDevice::status() const {
  Word w = 0;
  if (pd_.initialised() && !booting_) w |= kStatReady;
  if (power_stage_enabled()) w |= kStatRunning;
  if (pd_.frequency_hz() < 0.0) w |= kStatCounterClockwise;
  const drivecom::State s = pd_.state();
  if (fault_ || watchdog_fault_ || s == drivecom::State::fault ||
      s == drivecom::State::fault_response_active) {
    w |= kStatError;
  }
  return w;
}

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
  return drivecom::power_stage_enabled(pd_.state());
}

void LustbusDevice::restart(Time now) {
  store_.power_on();
  siof_.power_on();  // 6: after every new start
  watchdog_.restart(now);
  watchdog_fault_ = false;
  booting_ = false;
  line_baud_ = sioc_baud(value(pnr::kSioc));  // 11.5: a new rate is active after a restart
  pd_.start(DeviceStart::operational);
  pd_time_ = now;
}

void LustbusDevice::advance(Time now) {
  // The inverter samples up to the moment its watchdog ran out, so that the fault acts from then.
  const Word siot = value(pnr::kSiot);
  if (!booting_ && !watchdog_fault_ && watchdog_.expired_at(now, siot)) {
    run_samples(watchdog_.last() + std::chrono::milliseconds(siot) + Duration{1});
  }
  run_samples(now);
  if (booting_) {
    // 8.1.1: after the self-test the inverter is back, as after power-on.
    if (now >= boot_until_) restart(now);
    return;
  }
  // 5.2: no valid telegram within 84-SIOT ms: the error state, bit 02H in 85-SIOF; 8: the
  // inverter blocks its power stage.
  if (!watchdog_fault_ && watchdog_.expired_at(now, siot)) {
    watchdog_fault_ = true;
    siof_.set(SiofBit::watchdog);
    sample_now();  // 8: the power stage blocks at once
  }
}

void LustbusDevice::sample_now() {
  pd_.set_fault(fault_ || watchdog_fault_);
  sample(Duration{0});
}

void LustbusDevice::telegram_received(const lb::Context& ctx) {
  advance(ctx.now);
  watchdog_.telegram(ctx.now, value(pnr::kSiot));
}

lb::EnquiryAnswer LustbusDevice::enquiry(const lb::Code& code, const lb::Context& ctx) {
  advance(ctx.now);
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
  Word raw = store_.value(static_cast<std::size_t>(table_.slot(p->number)));
  if (p->number == pnr::kSiof) {
    raw = siof_.read_and_clear();  // 9.2: reading erases the bits
  } else if (p->number == pnr::kFout) {
    // 6.1.1.1: the rotary-field frequency, the ramp generator's output, in 0.05 Hz (LB-D19).
    raw = static_cast<Word>(std::lround(std::fabs(pd_.frequency_hz()) / kHzPerBit));
  } else if (p->number == pnr::kStat) {
    raw = status();
  }
  const auto v = lb::format_raw(lb::Family::vf1000, raw);  // 2.3.1: "%04X"
  if (!v.ok()) return lb::EnquiryAnswer::nak(reaction());
  return lb::EnquiryAnswer::text(v.value, reaction());
}

lb::SelectAnswer LustbusDevice::refuse(SiofBit b) {
  siof_.set(b);  // 9.2: the cause of the refusal
  return lb::SelectAnswer::nak(reaction());
}

lb::SelectAnswer LustbusDevice::select(const lb::Code& code, const lb::Value& value,
                                       const lb::Context& ctx) {
  advance(ctx.now);
  // 6, 9.2: every SELECT is refused while a bit is set; the bits stay as they are.
  if (siof_.blocks_select()) return lb::SelectAnswer::nak(reaction());
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
    return lb::SelectAnswer::ack(reaction() + timing_.factory_defaults);
  }
  if (p->number == pnr::kStat) {
    // 8.1.1: 000FH is the reset; 11-STAT is otherwise the inverter's status (LB-D19).
    if (w != kStatReset) return refuse(SiofBit::invalid_value);
    if ((status() & kStatError) == 0) return lb::SelectAnswer::ack(reaction());  // nothing to reset
    // "The reset happens immediately after the receipt": the inverter boots (self test), deaf
    // until it is back with the power-on bit in 85-SIOF; the ACK may not get out whole.
    watchdog_fault_ = false;
    booting_ = true;
    boot_until_ = ctx.now + timing_.self_test;
    pd_.set_fault(fault_);
    pd_.software_reset(control_word());
    switch (timing_.reset_answer) {
      case lb::Reply::ack:
        return lb::SelectAnswer::ack(reaction());
      case lb::Reply::none:
        return {lb::Reply::none, {}};
      default:
        return lb::SelectAnswer::cut(reaction());
    }
  }
  const Word eeprom_before = store_.eeprom_value(slot);
  store_.write(slot, w, power_stage_enabled());
  if (p->number == pnr::kSiot) watchdog_.restart(ctx.now);
  Duration r = reaction();
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
