#include "ibs/devices/mc6000/drive_parameters.hpp"

#include "ibs/devices/mc6000/parameters.hpp"

namespace ibs::devices::mc6000 {

using drive::SiofBit;

std::uint8_t serr_bit(Refusal r) {
  switch (r) {
    case Refusal::none:
    case Refusal::latched:
      return 0;
    case Refusal::no_parameter:
      return drive::siof_mask(SiofBit::no_parameter);
    case Refusal::read_only:
    case Refusal::not_now:
      return drive::siof_mask(SiofBit::no_change);
    case Refusal::eeprom_busy:
      return drive::siof_mask(SiofBit::eeprom_busy);
    case Refusal::bad_value:
    case Refusal::too_high:
    case Refusal::too_low:
      return drive::siof_mask(SiofBit::invalid_value);
  }
  return 0;
}

DriveParameters::DriveParameters(const DriveParametersConfig& config)
    : store_(config.table), card_writeable_(config.card_writeable), timing_(config.timing) {
  store_.set(kSerrNumber, drive::siof_mask(SiofBit::power_on));
}

std::uint32_t DriveParameters::raw(std::uint16_t number) const {
  const auto v = store_.get(number);
  return v ? v->raw : 0;
}

void DriveParameters::set_serr(SiofBit b) {
  store_.set(kSerrNumber, static_cast<std::uint32_t>(serr() | drive::siof_mask(b)));
}

WriteResult DriveParameters::refused(Refusal r) {
  store_.set(kSerrNumber, static_cast<std::uint32_t>(serr() | serr_bit(r)));
  return {r, Duration::zero()};
}

WriteResult DriveParameters::refuse(Refusal r) {
  if (serr() != 0) return {Refusal::latched, Duration::zero()};
  return refused(r);
}

bool DriveParameters::preset(std::uint16_t number, std::int64_t value) {
  const pcp::ParameterInfo* p = store_.info(number);
  if (p == nullptr || value < p->min || value > p->max) return false;
  const std::uint32_t raw = pcp::ParameterStore::to_raw(*p, value);
  store_.set(number, raw);
  store_.commit_eeprom(number, raw);
  return true;
}

void DriveParameters::power_on(Time now) {
  store_.power_on();  // an unfinished EEPROM save is lost: the EEPROM keeps the old value
  store_.set(kSerrNumber, drive::siof_mask(SiofBit::power_on));
  eeprom_pending_ = false;
  eeprom_busy_until_ = now;
  download_ = Download::idle;
}

void DriveParameters::advance_pending(Time now) {
  if (eeprom_pending_ && now >= eeprom_busy_until_) {
    store_.commit_eeprom(eeprom_number_, eeprom_value_);
    eeprom_pending_ = false;
    ++eeprom_saves_;
  }
  if (download_ == Download::testing && now >= download_done_at_) finish_download();
}

void DriveParameters::finish_download() {
  // 11.4 step 3: the whole dataset is tested; the first invalid parameter's number goes to
  // SLOAD and the old dataset comes back, or SLOAD = 0 and the dataset goes to EEPROM. Only the
  // CardWriteable parameters belong to the dataset (11.4 "Important").
  const auto table = store_.table();
  std::uint32_t rejected = 0;
  for (const pcp::ParameterInfo& p : table) {
    if (p.number == kSload || card_writeable_ == nullptr || !card_writeable_(p.number)) continue;
    const std::uint32_t v = raw(p.number);
    if (pcp::compare(p.type, v, pcp::ParameterStore::to_raw(p, p.min)) < 0 ||
        pcp::compare(p.type, v, pcp::ParameterStore::to_raw(p, p.max)) > 0) {
      rejected = p.number;
      break;
    }
  }
  for (std::size_t i = 0; i < table.size(); ++i) {
    const pcp::ParameterInfo& p = table[i];
    if (p.number == kSload || card_writeable_ == nullptr || !card_writeable_(p.number)) continue;
    if (rejected != 0) {
      store_.set(p.number, saved_[i]);
    } else if (p.category == pcp::Category::eeprom) {
      store_.commit_eeprom(p.number, raw(p.number));
    }
  }
  store_.set(kSload, rejected);
  // 11.4 steps 3-4: a valid dataset is taken and "The drive is freed and can be started": its
  // controller is calculated for it (READY mode, MC-D11); a rejected one brings the old dataset
  // back, and the mode it had.
  if (rejected == 0) store_.set(kPlrdy, 1);
  download_ = Download::idle;
}

std::optional<pcp::Value> DriveParameters::read(Time now, std::uint16_t number) {
  advance(now);
  const auto v = store_.get(number);
  // 6, 9.2: "The set error bits in SIOF/SERR are erased after reading from SIOF".
  if (v && number == kSerrNumber) store_.set(kSerrNumber, 0);
  return v;
}

WriteResult DriveParameters::write(Time now, std::uint16_t number, std::optional<std::uint32_t> raw_in,
                                   bool running) {
  advance(now);
  // 9.2: "All further SELECT-telegrams are rejected as long as bits within this parameter are
  // set" -- before the request is looked at, and without a cause of its own (docs/errata.md MC-D3).
  if (serr() != 0) return {Refusal::latched, Duration::zero()};
  const pcp::ParameterInfo* p = store_.info(number);
  if (p == nullptr) return refused(Refusal::no_parameter);
  if (!p->writable()) return refused(Refusal::read_only);
  if (!raw_in) return refused(Refusal::bad_value);
  const std::uint32_t raw_value = *raw_in;
  const std::int64_t n = pcp::signed_raw(pcp::Value{p->type, raw_value});

  if (number == kSload) {  // 11.4
    if (n == kSloadBegin) {
      // "Write accessing this parameter is possible only when the system is in a stillstand".
      if (running || download_ != Download::idle) return refused(Refusal::not_now);
      const auto table = store_.table();
      for (std::size_t i = 0; i < table.size(); ++i) saved_[i] = raw(table[i].number);
      download_ = Download::receiving;
      store_.set(kSload, raw_value);
      return {};
    }
    if (n == kSloadEnd) {
      if (download_ != Download::receiving) return refused(Refusal::not_now);
      download_ = Download::testing;
      download_done_at_ = now + timing_.download_check;
      // Step 4: "If SLOAD = (-1) ..., the servocontroller is still busy testing and saving".
      store_.set(kSload, pcp::value_from_signed_raw(p->type, kSloadBegin)->raw);
      return {};
    }
    return refused(n < kSloadEnd ? Refusal::too_low : Refusal::too_high);  // 0.. are answers
  }
  if (download_ == Download::testing) return refused(Refusal::not_now);
  const bool receiving = download_ == Download::receiving;
  // 11.4 step 2: during a download the values are taken without the plausibility test -- only
  // those of CardWriteable parameters; any other write is acknowledged and its value dropped
  // (11.4 "Important"), a start through 416-SCTL1 included: the drive stays disengaged.
  if (receiving) {
    if (card_writeable_ == nullptr || !card_writeable_(number)) return {};
  } else {
    if (pcp::compare(p->type, raw_value, pcp::ParameterStore::to_raw(*p, p->max)) > 0) {
      return refused(Refusal::too_high);
    }
    if (pcp::compare(p->type, raw_value, pcp::ParameterStore::to_raw(*p, p->min)) < 0) {
      return refused(Refusal::too_low);
    }
  }
  // LUSTBUS manual 4: the servo's rates "in steps ... from 2400 Baud to 57600 Baud", in baud as the
  // inverter's 81 (1: numerically compatible; LB-E18). A number between the steps is refused as
  // too high, as 80-SLOAD's numbers the host may not write (80H in 85-SERR either way).
  if (number == kParamSbaud && !receiving && !drive::is_baud_step(raw_value, kHighestBaud)) {
    return refused(Refusal::too_high);
  }
  const bool eeprom = p->category == pcp::Category::eeprom && !receiving;
  if (eeprom && eeprom_busy(now)) return refused(Refusal::eeprom_busy);  // 3: wait and repeat

  WriteResult result{};
  const bool changed = raw(number) != raw_value;
  store_.set(number, raw_value);
  if (eeprom) {
    // 3, 10.2.2: RAM at once, the EEPROM copy in the background, data width x 3 x 5 ms.
    eeprom_pending_ = true;
    eeprom_number_ = number;
    eeprom_value_ = raw_value;
    eeprom_busy_until_ = now + timing_.eeprom_per_byte * static_cast<Duration::rep>(pcp::size_of(p->type));
  }
  if (number == kProg) {
    if (n == kProgFactoryDefaults) {
      // 10 exception 1: every parameter back to its factory setting; the answer once done.
      // 85-SERR is the drive's error flags, not a setting: it keeps its bits.
      const std::uint8_t flags = serr();
      store_.factory_defaults();
      store_.set(kSerrNumber, flags);
      eeprom_pending_ = false;
      result.busy_for = timing_.factory_defaults;
    } else if (n == kProgActivateBaudrate) {
      ++baud_activations_;  // 11.5: the serial face takes the new 81-SBAUD
    }
    store_.set(kProg, 0);  // a command, not a setting
  } else if (number == kPlrdy) {
    // INTERBUS manual 4.2: "15-PLRDY should be set to 1 to trigger recalculation of the controller
    // parameters and set the servocontroller to 'READY' mode"; 0 (the attribute InitControl of
    // its own) registers an initialization. It reads the mode (MC-D11).
    if (n == 1) ++plrdy_requests_;
  } else if (changed && !receiving && (p->attributes & pcp::kAttrInitControl) != 0) {
    // LUSTBUS manual 11.2.1, InitControl: "If a parameter is overwritten with the attribute, then the
    // [drive] will register a[n] ... initialization because it must calculate its initialization
    // value anew": out of READY mode until 15-PLRDY = 1 (MC-D11).
    store_.set(kPlrdy, 0);
  }
  return result;
}

}  // namespace ibs::devices::mc6000
