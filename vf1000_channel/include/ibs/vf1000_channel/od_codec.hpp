// The communication word's codec of the object dictionary (issue 38, K1): how an od::Entry and its
// values travel on the VF1000's parameter channel (INTERBUS manual 4.1.3, 4.1.4). A value is one 16-bit
// word, high byte first (4.1.3.1); the description record of a description scan is 18 bytes --
// name and unit (5 ASCII each, blank-padded), the category character '0'..'7', the type character
// '1'..'7' and min, max, default as words (4.1.3.3); a refused access is a NAK whose cause enters
// 85-SIOF (4.1.4). Drive-neutral: it encodes whatever dictionary the server serves. Allocation-free
// and constexpr but for check(), which names what it refuses.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

#include "ibs/base/error.hpp"
#include "ibs/base/words.hpp"
#include "ibs/od/dictionary.hpp"
#include "ibs/od/served.hpp"
#include "ibs/vf1000_channel/comm_word.hpp"
#include "ibs/vf1000_channel/server.hpp"

namespace ibs::vf1000_channel {

// The name and the unit each take five characters of the record (4.1.3.3).
inline constexpr std::size_t kTextLength = 5;

// The type character of the record (4.1.3.3): '1' BINARY8, '2' FIXPOINT16, '3' USIGN16, '4' USIGN8,
// '5' VF_ERROR, '6' PASSWORD; '7' INT16, for 901-912's "Integer 16" (INTERBUS manual 4.1.1), which the
// seed's list lacks (a project decision, docs/vf1000_channel.md). nullopt: the type cannot travel
// in one word (32 bits, text) or has no character.
constexpr std::optional<char> type_code(od::Type t) {
  switch (t) {
    case od::Type::binary8:
      return '1';
    case od::Type::fixpoint16:
      return '2';
    case od::Type::usign16:
      return '3';
    case od::Type::usign8:
      return '4';
    case od::Type::error16:
      return '5';
    case od::Type::password:
      return '6';
    case od::Type::int16:
      return '7';
    default:
      return std::nullopt;
  }
}

// The category character (4.1.3.3; LUSTBUS manual 11.1): '0' RAM control value, '1' RAM actual value,
// '2' EEPROM, '3' EEPROM/RAM variable, '4'..'7' the same of an inverter-specific parameter.
// nullopt: the channel has no category for it (flash, or a kept value only the drive sets).
constexpr std::optional<char> category_code(const od::Entry& e) {
  if (e.read_only && e.storage != od::Storage::ram_actual) return std::nullopt;
  char c = '0';
  switch (e.storage) {
    case od::Storage::ram_control:
      c = '0';
      break;
    case od::Storage::ram_actual:
      c = '1';
      break;
    case od::Storage::eeprom:
      c = '2';
      break;
    case od::Storage::eeprom_ram:
      c = '3';
      break;
    case od::Storage::flash:
      return std::nullopt;
  }
  return static_cast<char>(c + (e.specific ? 4 : 0));
}

// Why an entry cannot travel on the channel (nullptr: it can): the number above 3FFH, a name of
// more than five characters or a unit of more than five, no category or no type character.
constexpr const char* unfit(const od::Entry& e) {
  if (e.number > kMaxParameterNumber) return "number above 3FFH (4.1.2.1)";
  if (e.name.empty() || e.name.size() > kTextLength) return "name of more than 5 characters (4.1.3.3)";
  if (e.unit.size() > kTextLength) return "unit of more than 5 characters (4.1.3.3)";
  if (!category_code(e)) return "no category on the communication word (4.1.3.3: RAM, EEPROM, EEPROM/RAM)";
  if (!type_code(e.type)) return "a data type the communication word does not carry (one word, 4.1.3.3)";
  return nullptr;
}
// Every entry fit for the channel, and 85-SIOF there (Role::error_flags), on which every value
// transfer depends (4.1.4): ErrorCode::table_* naming the entry ("dictionary entry 3 (36-RSTOP):
// ..."), table_lacks_siof without it.
[[nodiscard]] Error check(const od::Dictionary& d);

// Byte `index` (< 18) of the description record of an entry unfit() accepts: name, unit, category,
// type, then min, max and `default_raw` -- the factory default as the drive has it
// (od::ServedParameters::factory_default: an overlay's, VF-E20) -- as the type's 16-bit patterns,
// high byte first.
constexpr std::uint8_t description_byte(const od::Entry& e, std::size_t index, od::Raw default_raw) {
  const auto text = [](std::string_view s, std::size_t i) -> std::uint8_t {
    return i < s.size() ? static_cast<std::uint8_t>(s[i]) : std::uint8_t{' '};
  };
  if (index < kTextLength) return text(e.name, index);
  if (index < 2 * kTextLength) return text(e.unit, index - kTextLength);
  if (index == 10) return static_cast<std::uint8_t>(category_code(e).value_or('?'));
  if (index == 11) return static_cast<std::uint8_t>(type_code(e.type).value_or('?'));
  const od::Raw r = index < 14 ? e.min_raw() : index < 16 ? e.max_raw() : default_raw;
  const auto w = static_cast<Word>(od::pattern(e.type, r));
  return (index % 2 == 0) ? high_byte(w) : low_byte(w);
}
constexpr std::uint8_t description_byte(const od::Entry& e, std::size_t index) {
  return description_byte(e, index, e.default_raw());
}
std::array<std::uint8_t, kDescriptionLength> description(const od::Entry& e, od::Raw default_raw);
inline std::array<std::uint8_t, kDescriptionLength> description(const od::Entry& e) {
  return description(e, e.default_raw());
}

// A value as the word a value inquiry sends (the type's pattern, 4.1.3.1) ...
constexpr Word value_word(const od::Entry& e, od::Raw r) {
  return static_cast<Word>(od::pattern(e.type, r) & 0xFFFFU);
}
// ... and the word of a value transfer (DAT1, DAT2: 4.1.3.2) as the Raw the drive checks: a signed
// type's word sign-extended, an unsigned one as it came (0105H for a USIGN8 stays 261 and is
// refused 80H, not masked into range: od::from_bus).
constexpr od::Raw value_of(const od::Entry& e, Word w) {
  return od::from_bus(e.type, w, 16);
}

// The NAK of a refused access and the reason the server reports (4.1.4): 85-SIOF pending for
// `latched`, no parameter (20H), no change (40H: read-only, not now, a text, EEPROM busy), invalid
// value (80H), a transfer error for the channel's unintended control bits (08H). `none` is no
// refusal: invalid_value, never asked.
constexpr NakReason nak_reason(od::Refusal r) {
  switch (r) {
    case od::Refusal::latched:
      return NakReason::siof_pending;
    case od::Refusal::no_parameter:
      return NakReason::no_parameter;
    case od::Refusal::read_only:
    case od::Refusal::not_now:
    case od::Refusal::wrong_kind:
    case od::Refusal::busy:
      return NakReason::no_change;
    case od::Refusal::transfer_error:
      return NakReason::unintended_control_bits;
    case od::Refusal::none:
    case od::Refusal::bad_value:
    case od::Refusal::too_high:
    case od::Refusal::too_low:
    case od::Refusal::not_a_choice:
      break;
  }
  return NakReason::invalid_value;
}
// The 85-SIOF bits the refusal of a value transfer enters (LUSTBUS manual 9.2; 0 for `latched`).
constexpr std::uint8_t siof_bits(od::Refusal r) {
  return od::error_flag(r);
}

}  // namespace ibs::vf1000_channel
