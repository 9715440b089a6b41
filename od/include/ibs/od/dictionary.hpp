// A drive's object dictionary: its entries (entry.hpp) and their index by number. A wing writes
//
//   inline constexpr std::array kEntries{od::Entry{...}, ...};
//   inline constexpr od::Dictionary kDictionary{kEntries, od::Profile::lust_standard};
//
// and the index is made at compile time: slot(number) is one bounds compare and one indexed load,
// on every request of every bus. A dictionary the checks refuse does not compile (constant
// evaluation), throws std::invalid_argument (made at run time) or, in the embedded build, aborts
// with validate()'s message -- as drive::ParameterTable did.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "ibs/base/error.hpp"
#include "ibs/od/entry.hpp"

namespace ibs::od {

// Numbers run from 0 to 3FFH: the most the VF1000 communication word addresses (10 bits, seed
// 001 4.1.2.1). PCP and LUSTBUS (999, LUSTBUS manual 2.4.2) and the DFS-1 (255) check their own.
inline constexpr std::uint16_t kMaxNumber = 0x3FF;

// A parameter's position in its dictionary's entries: what a store, a core and a served
// interface are indexed by. kNoSlot: the dictionary has no such parameter.
using Slot = std::uint16_t;
inline constexpr Slot kNoSlot = 0xFFFF;

// Which family's conventions a dictionary follows (LUSTBUS manual 1): the standard protocol (the
// inverters: the communication word, LUSTBUS standard), the enhanced one (the servos: PCP,
// LUSTBUS enhanced), or neither (CANLust, DFS-1). The codecs read it; od's rules do not.
enum class Profile : std::uint8_t { none, lust_standard, lust_enhanced };
std::string_view to_string(Profile p);

// Another factory default for one parameter (a drive without the INTERBUS software, INTERBUS manual
// 3.1.1 VF-E20; an MC6000 without the option card, 3.2.1 MC-D10): a number of the entry's type.
struct DefaultOverride {
  std::uint16_t number = 0;
  std::int64_t value = 0;
};

// The first thing the checks refuse: its code, the entry's position and what is wrong (a constant
// string: usable at compile time).
struct Finding {
  ErrorCode code = ErrorCode::none;
  std::size_t entry = 0;
  std::string_view what;
  [[nodiscard]] constexpr bool ok() const { return code == ErrorCode::none; }
};

namespace detail {
constexpr char upper(char c) {
  return c >= 'a' && c <= 'z' ? static_cast<char>(c - 'a' + 'A') : c;
}
constexpr bool iequal(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (upper(a[i]) != upper(b[i])) return false;
  }
  return true;
}
constexpr bool printable(std::string_view s) {
  for (const char c : s) {
    if (c < 0x20 || c > 0x7E) return false;
  }
  return true;
}
constexpr bool is_digit(char c) {
  return c >= '0' && c <= '9';
}
constexpr bool in_entry_range(const Entry& e, std::int64_t n) {
  if (e.type == Type::float_ieee) {
    return compare(e.type, raw(e.type, n), e.min_raw()) >= 0 &&
           compare(e.type, raw(e.type, n), e.max_raw()) <= 0;
  }
  return n >= e.min && n <= e.max;
}
constexpr Finding check_entry(const Entry& e, std::size_t i);
}  // namespace detail

// Every check of a dictionary, usable in a static_assert. Numbers unique and <= kMaxNumber;
// names printable, without a leading digit, blank or '-' at either end, unique in any case; units
// printable; min <= default <= max, all numbers of the type (float_ieee: by value); a finite,
// positive scale; texts (string) with lengths 0 <= min <= max <= kMaxTextLength and a printable
// default text of such a length; elements >= 1; choices with codes of the type and unique,
// non-empty printable names, present when attr::kShowText or choices_only asks for them; each role
// but `value` at most once -- 85-SIOF/SERR at number 85, an 8-bit unsigned actual value; SLOAD a
// signed type; PROG and SAVE writable -- and a KEYPAD activity area exactly where the entry is in
// the data set (LUSTBUS manual 11.2.1: "If the value does not equal 0, ... appropriate for data
// exchange").
constexpr Finding check(std::span<const Entry> entries) {
  if (entries.size() > std::size_t{kMaxNumber} + 1)
    return {ErrorCode::table_too_large, 0, "more entries than numbers 0..3FFH"};
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const Finding f = detail::check_entry(entries[i], i);
    if (!f.ok()) return f;
    for (std::size_t j = 0; j < i; ++j) {
      if (entries[j].number == entries[i].number)
        return {ErrorCode::table_number_repeated, i, "number used twice"};
      if (detail::iequal(entries[j].name, entries[i].name))
        return {ErrorCode::table_bad_name, i, "name used twice"};
      if (entries[i].role != Role::value && entries[j].role == entries[i].role) {
        return {ErrorCode::table_bad_role, i, "a second entry of the same role"};
      }
    }
  }
  return {};
}

constexpr Finding detail::check_entry(const Entry& e, std::size_t i) {
  if (e.number > kMaxNumber) return {ErrorCode::table_number_out_of_range, i, "number above 3FFH"};
  if (e.name.empty() || !printable(e.name) || is_digit(e.name.front()) || e.name.front() == ' ' ||
      e.name.back() == ' ' || e.name.front() == '-' || e.name.back() == '-') {
    return {ErrorCode::table_bad_name, i,
            "name must be printable, start with no digit and neither start nor end with a blank or "
            "'-'"};
  }
  if (!printable(e.unit)) return {ErrorCode::table_bad_unit, i, "unit must be printable"};
  if (!(e.scale > 0.0) || e.scale > 1.0e300)
    return {ErrorCode::table_scale_not_positive, i, "scale must be positive and finite"};
  if (e.elements == 0)
    return {ErrorCode::table_bad_elements, i, "an entry has at least one element"};
  if (e.is_text()) {
    if (e.min < 0 || e.max > kMaxTextLength)
      return {ErrorCode::table_limits_outside_type, i, "text lengths outside 0..255"};
    if (e.min > e.max) return {ErrorCode::table_min_above_max, i, "min above max"};
    const auto n = static_cast<std::int64_t>(e.default_text.size());
    if (n < e.min || n > e.max || !printable(e.default_text) || e.default_value != 0) {
      return {ErrorCode::table_default_outside_limits, i,
              "the default text's length outside min..max, or not printable"};
    }
  } else {
    if (!fits(e.type, e.min) || !fits(e.type, e.max) || !fits(e.type, e.default_value)) {
      return {ErrorCode::table_limits_outside_type, i, "min, max or default outside the data type"};
    }
    if (compare(e.type, e.min_raw(), e.max_raw()) > 0)
      return {ErrorCode::table_min_above_max, i, "min above max"};
    if (!in_entry_range(e, e.default_value))
      return {ErrorCode::table_default_outside_limits, i, "default outside min..max"};
    if (!e.default_text.empty())
      return {ErrorCode::table_default_outside_limits, i, "a default text for a number"};
  }
  for (std::size_t c = 0; c < e.choices.size(); ++c) {
    const Choice& ch = e.choices[c];
    if (e.is_text() || !is_canonical(e.type, ch.code))
      return {ErrorCode::table_bad_choices, i, "a choice's code is no value of the type"};
    if (ch.name.empty() || !printable(ch.name) || !printable(ch.text)) {
      return {ErrorCode::table_bad_choices, i, "a choice's name must be printable and not empty"};
    }
    for (std::size_t d = 0; d < c; ++d) {
      if (e.choices[d].code == ch.code || iequal(e.choices[d].name, ch.name)) {
        return {ErrorCode::table_bad_choices, i, "a choice's code or name used twice"};
      }
    }
  }
  if ((e.choices_only || e.has(attr::kShowText)) && e.choices.empty()) {
    return {ErrorCode::table_bad_choices, i, "ShowText or choices_only without choices"};
  }
  if (e.choices_only && !e.is_choice(e.default_raw()))
    return {ErrorCode::table_bad_choices, i, "the default is none of the choices"};
  switch (e.role) {
    case Role::value:
      break;
    case Role::error_flags:
      if (e.number != 85 || (e.type != Type::usign8 && e.type != Type::binary8) || e.writable()) {
        return {ErrorCode::table_bad_role, i,
                "85-SIOF/SERR is number 85, an 8-bit unsigned value, not writable"};
      }
      break;
    case Role::download:
      if (!is_signed(e.type) || !e.writable())
        return {ErrorCode::table_bad_role, i, "SLOAD is a writable signed value (-1, -2)"};
      break;
    case Role::load_defaults:
    case Role::save:
      if (e.is_text() || !e.writable() || !fits(e.type, 1) || !in_entry_range(e, 1)) {
        return {ErrorCode::table_bad_role, i, "PROG and SAVE are writable numbers that take 1"};
      }
      break;
  }
  if (e.keypad != nullptr && (e.keypad->activity != 0) != e.in_data_set) {
    return {ErrorCode::table_bad_role, i,
            "a KEYPAD activity area exactly where the entry is in the data set (11.2.1)"};
  }
  if (e.in_data_set && (e.is_text() || !e.writable() || e.role != Role::value)) {
    return {ErrorCode::table_bad_role, i, "only writable values can be in the data set"};
  }
  return {};
}

class Dictionary {
 public:
  // check() with a message that names the entry: "dictionary entry 3 (574-CAWDG): min above max".
  [[nodiscard]] static Error validate(std::span<const Entry> entries);

  // The index of entries that check() accepts; `entries` must outlive the dictionary.
  constexpr explicit Dictionary(std::span<const Entry> entries, Profile profile = Profile::none)
      : entries_(entries), profile_(profile) {
    const Finding f = check(entries);
    if (!f.ok()) refused(entries);  // a compile error in constant evaluation
    index_.fill(kNoSlot);
    roles_.fill(kNoSlot);
    for (std::size_t i = 0; i < entries.size(); ++i) {
      index_[entries[i].number] = static_cast<Slot>(i);
      if (entries[i].role != Role::value)
        roles_[static_cast<std::size_t>(entries[i].role)] = static_cast<Slot>(i);
    }
  }

  // One compare and one indexed load.
  [[nodiscard]] constexpr Slot slot(std::uint16_t number) const {
    return number > kMaxNumber ? kNoSlot : index_[number];
  }
  [[nodiscard]] constexpr const Entry& operator[](Slot s) const { return entries_[s]; }
  [[nodiscard]] constexpr const Entry* find(std::uint16_t number) const {
    const Slot s = slot(number);
    return s == kNoSlot ? nullptr : &entries_[s];
  }
  // "574", "0574", "CAWDG" / "cawdg", "574-CAWDG", "04-PROG", "906-IB-WD": a number, a name in any
  // case, or both (which must agree); nullptr for none.
  [[nodiscard]] constexpr const Entry* find(std::string_view text) const;
  [[nodiscard]] constexpr Slot slot(std::string_view text) const {
    const Entry* e = find(text);
    return e == nullptr ? kNoSlot : static_cast<Slot>(e - entries_.data());
  }
  // The entry of a role (PROG, SLOAD, 85, SAVE); kNoSlot when the dictionary has none.
  [[nodiscard]] constexpr Slot slot_of(Role r) const {
    return r == Role::value ? kNoSlot : roles_[static_cast<std::size_t>(r)];
  }
  [[nodiscard]] constexpr std::span<const Entry> entries() const { return entries_; }
  [[nodiscard]] constexpr std::size_t size() const { return entries_.size(); }
  [[nodiscard]] constexpr Profile profile() const { return profile_; }

 private:
  // Not constexpr: reached only for a refused dictionary, which throws or aborts (never at compile
  // time, where calling it is the error).
  static void refused(std::span<const Entry> entries);

  std::span<const Entry> entries_;
  Profile profile_;
  std::array<Slot, std::size_t{kMaxNumber} + 1> index_{};
  std::array<Slot, kRoleCount> roles_{};
};

constexpr const Entry* Dictionary::find(std::string_view text) const {
  std::size_t digits = 0;
  while (digits < text.size() && detail::is_digit(text[digits])) ++digits;
  if (digits > 0 && (digits == text.size() || text[digits] == '-')) {
    std::uint32_t n = 0;
    for (std::size_t i = 0; i < digits; ++i) {
      n = n * 10U + static_cast<std::uint32_t>(text[i] - '0');
      if (n > kMaxNumber) return nullptr;
    }
    const Entry* e = find(static_cast<std::uint16_t>(n));
    if (e == nullptr || digits == text.size()) return e;
    return detail::iequal(text.substr(digits + 1), e->name) ? e : nullptr;
  }
  for (const Entry& e : entries_) {
    if (detail::iequal(text, e.name)) return &e;
  }
  return nullptr;
}

}  // namespace ibs::od
