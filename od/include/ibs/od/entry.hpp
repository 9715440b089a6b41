// One parameter of a drive's object dictionary, with every field any bus needs: the communication
// word's description record (INTERBUS manual 4.1.3.3), PCP's Get-OV (INTERBUS manual 4.2), LUSTBUS's 11.1-11.3
// descriptions and texts and the 11.4 download (LUSTBUS manual), CANLust's description items and
// substitution texts (CANLust manual 4.1, decision D10), the DFS-1's ranges (DFS-1 manual), and what the
// reports, the campaign and the command line show. A drive's wing writes its entries once, as a
// constexpr array; each bus only encodes them (its codec checks its own limits: five-character
// names on the communication word and LUSTBUS, numbers up to 255 on the DFS-1, ...).
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

#include "ibs/od/types.hpp"

namespace ibs::od {

// Where a value lives (LUSTBUS manual 11.1 kinds '0'-'3', 11.2.1 kinds '0'-'2'; CANLust manual 4.3 "Memory
// type"): what a write changes, what power-on brings back, what a save keeps.
enum class Storage : std::uint8_t {
  ram_control,  // RAM; power-on: the default (unless attr::kNoInit)
  ram_actual,   // RAM, the drive's own reading: never written over a bus
  eeprom,       // RAM and EEPROM on every write; power-on: the EEPROM copy
  eeprom_ram,   // RAM; EEPROM too while the power stage is disabled (INTERBUS manual 4.1.3.3, VF-E18)
  flash,  // RAM; kept only by a save (the CDA3000's 150-SAVE, CANLust manual 3.5.1); power-on: flash
};
std::string_view to_string(Storage s);
// Whether the kind has a kept (EEPROM or flash) copy that power-on brings back.
constexpr bool is_kept(Storage s) {
  return s == Storage::eeprom || s == Storage::eeprom_ram || s == Storage::flash;
}

// When a written value acts.
enum class Effect : std::uint8_t {
  at_once,
  at_restart,  // after a mains reset (CDA3000 489-CLBDR, CANLust manual 7.1.1; MC6000 405-SUPI, 81-SBAUD)
};

// Parameters whose writes the family's rules act on (StoredServed, and every core).
enum class Role : std::uint8_t {
  value,          // a value, nothing more
  load_defaults,  // PROG: 1 loads every factory default (LUSTBUS manual 10 exception 1; CANLust manual p. 13)
  download,       // SLOAD: the data-set download handshake (LUSTBUS manual 11.4; CDA3000 D39)
  error_flags,    // 85-SIOF/SERR (siof.hpp; LUSTBUS manual 9.2)
  save,           // SAVE: 1 keeps the flash values (CDA3000 150-SAVE, CANLust manual 3.5.1)
};
inline constexpr std::size_t kRoleCount = 5;
std::string_view to_string(Role r);

// The attribute word of the LUSTBUS manual 11.2.1 ("The attribute"), written once here: PCP's Get-OV and
// LUSTBUS's 11.2 description carry it.
namespace attr {
inline constexpr std::uint16_t kShowParaText = 0x0004;  // the value names another parameter
inline constexpr std::uint16_t kShowNoFract = 0x0008;
inline constexpr std::uint16_t kShowFract1 = 0x0010;
inline constexpr std::uint16_t kShowText = 0x0020;  // has value substitution texts (11.3): choices
inline constexpr std::uint16_t kInitControl = 0x0040;  // a write makes the drive initialise anew
inline constexpr std::uint16_t kNoInit = 0x0080;       // RAM control value kept at power-on
inline constexpr std::uint16_t kShowHex = 0x0100;
inline constexpr std::uint16_t kPassword = 0x0200;
}  // namespace attr

// A value substitution text (LUSTBUS manual 11.3: "the text of value 0, 1, ..."; CANLust manual 4.1:
// "numerical value = substitution text"): "6 OPTN2".
struct Choice {
  Raw code = 0;             // the value, as its canonical Raw (raw(type, number))
  std::string_view name{};  // "OPTN2", "TCON"
  std::string_view text{};  // what it means ("" when the manual gives only the name)
};

// The KEYPAD service structure of the LUSTBUS manual 11.2.1 (the extended description of the enhanced
// family, LB-D10): unit index into 107-UNIT's texts, user level, hardware and structure filters,
// subject area and activity area (sc_group: non-zero = the parameter belongs to a data set).
struct Keypad {
  std::uint8_t unit = 0;             // 107-UNIT text index; 0 = "-"
  std::uint8_t level = 0x21;         // read level (low nibble), write level (high nibble)
  std::uint16_t hardware = 0;        // hardware filter
  std::uint16_t structure = 0x003F;  // structure filter: every control type
  std::uint8_t subject = 0;          // subject area
  std::uint8_t activity = 0;         // activity area; 0: no data set's
};

struct Entry {
  std::uint16_t number = 0;  // <= kMaxNumber (dictionary.hpp)
  std::string_view name{};   // "VB2", "CAWDG": printable, no leading digit; unique in any case
  std::string_view text{};   // what it is, for reports: "Voltage boost 2"
  Type type = Type::usign16;
  // Limits and default as numbers of the type (float_ieee: the float's pattern; string: lengths
  // 0..kMaxTextLength and no default number).
  std::int64_t min = 0;
  std::int64_t max = 0;
  std::int64_t default_value = 0;   // the factory default (a wing's overlay may change it)
  std::string_view default_text{};  // string: the factory text
  std::string_view unit{};          // "Hz", "" for none
  double scale = 1.0;  // engineering value = number / per_unit(type) x scale (FDRIV: 0.05)
  Storage storage = Storage::ram_control;
  bool read_only = false;  // besides ram_actual (a kept value only the drive sets)
  bool specific = false;   // inverter-specific (the standard family's categories '4'-'7')
  Effect effect = Effect::at_once;
  Role role = Role::value;
  std::uint16_t attributes = 0;  // attr::k*
  std::uint8_t elements = 1;  // subindices (PCP) / field entries (CANLust index); 1: a plain value
  bool in_data_set = false;   // CardWriteable (LUSTBUS manual 11.4; CANLust manual "Card Writeable")
  std::span<const Choice> choices{};  // substitution texts
  bool choices_only = false;       // a value must be one of the choices (the CDA3000's selectors)
  const Keypad* keypad = nullptr;  // the 11.2.1 service structure; nullptr: none
  bool invented = false;           // some of the row is a modelling choice, not the manual's
  std::string_view source{};       // the manual's section, and what was invented

  [[nodiscard]] constexpr bool writable() const {
    return !read_only && storage != Storage::ram_actual;
  }
  [[nodiscard]] constexpr bool is_text() const { return type == Type::string; }
  [[nodiscard]] constexpr bool kept() const { return is_kept(storage); }
  [[nodiscard]] constexpr bool has(std::uint16_t attribute) const {
    return (attributes & attribute) != 0;
  }
  // The limits and the default as Raws of the type.
  [[nodiscard]] constexpr Raw min_raw() const { return raw(type, min); }
  [[nodiscard]] constexpr Raw max_raw() const { return raw(type, max); }
  [[nodiscard]] constexpr Raw default_raw() const {
    return is_text() ? 0 : raw(type, default_value);
  }
  // The substitution text of `code` (any image of the number); nullptr when it has none.
  [[nodiscard]] constexpr const Choice* choice(Raw code) const {
    const Raw c = canonical(type, code);
    for (const Choice& ch : choices) {
      if (ch.code == c) return &ch;
    }
    return nullptr;
  }
  // Whether `code` is one of the choices: choice() != nullptr without comparing a pointer, which
  // GCC's -fsanitize=undefined cannot do in a constant expression (the dictionaries' checks).
  [[nodiscard]] constexpr bool is_choice(Raw code) const {
    const Raw c = canonical(type, code);
    for (const Choice& ch : choices) {
      if (ch.code == c) return true;
    }
    return false;
  }
};

// Where a value stands against its entry: in range, or why not, in the order the drives check
// (the CDA3000's check_value, CANLust manual 4.5: the limits on the Raw read at 32 bits -- which also
// refuse a Raw wider than the type -- then the substitution texts). A codec hands in the Raw as
// from_bus() makes it: a zero-extended 0xFFFF of an INT16 reads as 65535 here, above any INT16
// maximum. wrong_type: a text.
enum class Fit : std::uint8_t { ok, wrong_type, too_low, too_high, not_a_choice };
constexpr std::string_view to_string(Fit f) {
  switch (f) {
    case Fit::ok:
      return "ok";
    case Fit::wrong_type:
      return "does not fit the data type";
    case Fit::too_low:
      return "below the minimum";
    case Fit::too_high:
      return "above the maximum";
    case Fit::not_a_choice:
      return "not one of the substitution texts";
  }
  return "?";
}
constexpr Fit fit(const Entry& e, Raw r) {
  if (e.is_text()) return Fit::wrong_type;
  if (e.type == Type::float_ieee) {
    if (compare(e.type, r, e.min_raw()) < 0) return Fit::too_low;
    if (compare(e.type, r, e.max_raw()) > 0) return Fit::too_high;
  } else {
    // min and max lie within the type (Dictionary's check), so a Raw within them is canonical.
    const std::int64_t n =
        is_signed(e.type) ? std::int64_t{static_cast<std::int32_t>(r)} : std::int64_t{r};
    if (n < e.min) return Fit::too_low;
    if (n > e.max) return Fit::too_high;
  }
  if (e.choices_only && !e.is_choice(r)) return Fit::not_a_choice;
  return Fit::ok;
}

}  // namespace ibs::od
