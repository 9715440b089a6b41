#include "ibs/od/stored_served.hpp"

#include <algorithm>

namespace ibs::od {

std::string_view to_string(Refusal r) {
  switch (r) {
    case Refusal::none:
      return "none";
    case Refusal::latched:
      return "85-SIOF/SERR holds error bits";
    case Refusal::no_parameter:
      return "no parameter";
    case Refusal::read_only:
      return "read-only";
    case Refusal::not_now:
      return "no change permitted now";
    case Refusal::wrong_kind:
      return "a text and a number are not each other";
    case Refusal::busy:
      return "EEPROM busy";
    case Refusal::transfer_error:
      return "error in the data transfer";
    case Refusal::bad_value:
      return "no value of its data type";
    case Refusal::too_high:
      return "above the maximum";
    case Refusal::too_low:
      return "below the minimum";
    case Refusal::not_a_choice:
      return "not one of its substitution texts";
  }
  return "?";
}

StoredServed::StoredServed(const Dictionary& d, const StoredServedConfig& config)
    : store_(d, config.defaults),
      timing_(config.timing),
      flags_slot_(d.slot_of(Role::error_flags)),
      sload_slot_(d.slot_of(Role::download)) {
  power_on();
}

void StoredServed::power_on() {
  store_.power_on();
  if (flags_slot_ != kNoSlot) store_.set(flags_slot_, siof_mask(SiofBit::power_on));
  download_ = Download::idle;
}

void StoredServed::raise_error_flags(std::uint8_t bits) {
  if (flags_slot_ != kNoSlot) store_.set(flags_slot_, store_.ram(flags_slot_) | bits);
}

void StoredServed::clear_error_flags(std::uint8_t bits) {
  if (flags_slot_ != kNoSlot) store_.set(flags_slot_, store_.ram(flags_slot_) & ~Raw{bits} & 0xFFU);
}

Answer StoredServed::refused(Refusal r) {
  raise_error_flags(error_flag(r));
  return {r};
}

Answer StoredServed::refuse(Refusal r) {
  if (error_flags() != 0) return {Refusal::latched};
  return refused(r);
}

Reading StoredServed::read(Slot s, Time now) {
  advance(now);
  if (s >= store_.size()) return {0, Refusal::no_parameter};
  if (store_.is_text(s)) return {0, Refusal::wrong_kind};
  const Raw v = store_.ram(s);
  // 9.2: "The set error bits in SIOF/SERR are erased after reading"; bits set since stay.
  if (s == flags_slot_) clear_error_flags(static_cast<std::uint8_t>(v));
  return {v, Refusal::none};
}

// The checks before the value: the latch, the kind, the permission, the moment.
Refusal StoredServed::access(const Entry& e, Time now) const {
  if (error_flags() != 0) return Refusal::latched;
  if (e.is_text()) return Refusal::wrong_kind;
  if (!e.writable()) return Refusal::read_only;
  if (e.role == Role::download) return Refusal::none;
  if (download_ != Download::idle) {
    // 11.4: refused while the set is tested; meanwhile taken untested, or dropped.
    return download_ == Download::testing && now < download_done_at_ ? Refusal::not_now
                                                                     : Refusal::none;
  }
  // INTERBUS manual 4.1.3.2: EEPROM parameters only with the power stage disabled.
  if (e.storage == Storage::eeprom && power_stage_) return Refusal::not_now;
  return Refusal::none;
}

Refusal StoredServed::value_check(const Entry& e, Raw r, Time now) const {
  const Refusal a = access(e, now);
  if (a != Refusal::none) return a;
  if (e.role == Role::download) {
    const std::int64_t n = number(e.type, r);
    if (!is_canonical(e.type, r)) return Refusal::bad_value;
    if (n == kDownloadBegin)
      return power_stage_ || download_ != Download::idle ? Refusal::not_now : Refusal::none;
    if (n == kDownloadEnd)
      return download_ == Download::receiving ? Refusal::none : Refusal::not_now;
    return n < kDownloadEnd ? Refusal::too_low : Refusal::too_high;
  }
  if (download_ == Download::receiving)
    return is_canonical(e.type, r) ? Refusal::none : Refusal::bad_value;
  return refusal_of(fit(e, r));
}

Refusal StoredServed::check(Slot s, std::optional<Raw> r, Time now) const {
  if (s >= store_.size()) return error_flags() != 0 ? Refusal::latched : Refusal::no_parameter;
  const Entry& e = store_.dictionary()[s];
  return r ? value_check(e, *r, now) : access(e, now);
}

Answer StoredServed::write(Slot s, Raw r, Time now) {
  advance(now);
  if (s >= store_.size())
    return error_flags() != 0 ? Answer{Refusal::latched} : refused(Refusal::no_parameter);
  const Entry& e = store_.dictionary()[s];
  const Refusal c = value_check(e, r, now);
  if (c == Refusal::latched) return {c};
  if (c != Refusal::none) return refused(c);
  if (e.role == Role::download) return download(s, r, now);
  if (download_ == Download::receiving) {
    // 11.4 step 2: the data set's values without the plausibility test, into RAM; any other
    // write "still answers acknowledge ... but does not take the new value" ("Important").
    if (e.in_data_set) store_.set(s, r);
    return {};
  }
  Answer a;
  a.kept_changed = store_.write(s, r, e.storage, power_stage_);
  if (a.kept_changed) a.after = timing_.eeprom_per_byte * static_cast<Duration::rep>(bytes(e.type));
  a.init_control = e.has(attr::kInitControl);
  if (e.role == Role::value) return a;
  const bool one = number(e.type, r) == 1;
  if (e.role == Role::load_defaults) {
    if (one) {
      // 10 exception 1: every parameter back to its factory setting; 85 is the drive's error
      // flags, not a setting: it keeps its bits.
      const std::uint8_t flags = error_flags();
      store_.factory_defaults();
      if (flags_slot_ != kNoSlot) store_.set(flags_slot_, flags);
      a.after = timing_.factory_defaults;
    }
    store_.preset(s, store_.default_raw(s));  // a command, not a setting
  } else if (e.role == Role::save) {
    if (one) {
      store_.save(Storage::flash);
      a.after = timing_.save;
    }
    store_.preset(s, store_.default_raw(s));
  }
  return a;
}

Answer StoredServed::download(Slot s, Raw r, Time now) {
  const Type t = store_.dictionary()[s].type;
  if (number(t, r) == kDownloadBegin) {
    store_.snapshot();  // the old data set, should the new one be refused
    download_ = Download::receiving;
    store_.set(s, r);
    return {};
  }
  // kDownloadEnd (check() let nothing else through): "SLOAD = (-1) ... still busy testing".
  download_ = Download::testing;
  download_done_at_ = now + timing_.download_check;
  store_.set(s, raw(t, kDownloadBegin));
  advance(now);
  return {};
}

void StoredServed::finish_download() {
  // 11.4 step 3: the first implausible value names itself in SLOAD and the old data set comes
  // back; else SLOAD = 0 and the data set goes to EEPROM.
  const auto entries = store_.dictionary().entries();
  Raw rejected = 0;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    if (entries[i].in_data_set && fit(entries[i], store_.ram(static_cast<Slot>(i))) != Fit::ok) {
      rejected = entries[i].number;
      break;
    }
  }
  if (rejected != 0) {
    store_.restore_data_set();
  } else {
    store_.keep_data_set();
  }
  store_.set(sload_slot_, rejected);
  download_ = Download::idle;
}

TextAnswer StoredServed::read_text(Slot s, std::span<char> out, Time now) {
  advance(now);
  if (s >= store_.size()) return {0, Refusal::no_parameter};
  if (!store_.dictionary()[s].is_text()) return {0, Refusal::wrong_kind};
  const std::string_view t = store_.text(s);
  const std::size_t n = std::min(t.size(), out.size());
  std::copy_n(t.data(), n, out.data());
  return {n};
}

Answer StoredServed::write_text(Slot s, std::string_view text, Time now) {
  advance(now);
  if (error_flags() != 0) return {Refusal::latched};
  if (s >= store_.size()) return refused(Refusal::no_parameter);
  const Entry& e = store_.dictionary()[s];
  if (!e.is_text()) return refused(Refusal::wrong_kind);
  if (!e.writable()) return refused(Refusal::read_only);
  if (e.storage == Storage::eeprom && power_stage_) return refused(Refusal::not_now);
  const auto n = static_cast<std::int64_t>(text.size());
  if (n > e.max) return refused(Refusal::too_high);
  if (n < e.min || text.find('\0') != std::string_view::npos) return refused(Refusal::bad_value);
  Answer a;
  const std::string_view before = store_.kept_text(s);
  const bool same = before == text;
  store_.write_text(s, text, power_stage_);
  a.kept_changed = !same && store_.kept_text(s) == text;
  if (a.kept_changed) a.after = timing_.eeprom_per_byte * static_cast<Duration::rep>(text.size());
  return a;
}

}  // namespace ibs::od
