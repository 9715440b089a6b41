// Parameter descriptions (LUSTBUS manual 11.1 VF1000, 11.2 MC6000) and value substitution texts
// (11.3), as VALUE strings: parsed by the host, built by a drive (a Responder) from its table.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

#include "ibs/lustbus/code.hpp"
#include "ibs/lustbus/value.hpp"

namespace ibs::lustbus {

// ---- 11.1: the VF1000's 26 characters -----------------------------------------------------------
inline constexpr std::size_t kVfDescriptionLength = 26;
inline constexpr std::size_t kVfNameLength = 6;  // right-justified, blank-padded

struct VfDescription {
  std::array<char, kVfNameLength + 1> name{};  // without the padding, NUL-terminated
  std::array<char, kVfNameLength + 1> unit{};
  char kind = '0';  // '0'..'7' (11.1 "Parameter kind"), the channel's Category codes
  char type = '1';  // '1'..'6' (11.1 "Parameter type")
  std::uint16_t min = 0;
  std::uint16_t max = 0;
  std::uint16_t basis = 0;  // default (factory setting)

  [[nodiscard]] std::string_view name_view() const { return name.data(); }
  [[nodiscard]] std::string_view unit_view() const { return unit.data(); }
};

enum class DescriptionError : std::uint8_t {
  none,
  wrong_length,
  bad_name,   // a character outside digits, capitals, '_', '-' (or not right-justified)
  bad_unit,   // not printable, or not right-justified
  bad_kind,   // VF: not '0'..'7'; MC: not '0'..'2'
  bad_type,   // VF: not '1'..'6'
  bad_value,  // min / max / default not capital hex
  not_7bit,   // an MC binary element that a 7-bit line cannot carry (>= 80H)
};
std::string_view to_string(DescriptionError e);

template <typename T>
struct Parsed {
  T value{};
  DescriptionError error = DescriptionError::none;
  [[nodiscard]] bool ok() const { return error == DescriptionError::none; }
};

Parsed<VfDescription> parse_vf_description(std::string_view value);
// The 26 characters; refuses a name or unit longer than 6 or with characters 11.1 does not allow.
std::optional<Value> format_vf_description(std::string_view name, std::string_view unit,
                                           char kind, char type, std::uint16_t min,
                                           std::uint16_t max, std::uint16_t basis);
std::optional<Value> format_vf_description(const VfDescription& d);
// The data type of a VF type character ('1'..'6', 11.1).
std::optional<DataType> vf_type_from_char(char c);

// ---- 11.2: the MC6000's description ----------------------------------------------------------
// The element table adds up to 42 characters; the text says 43 twice (LB-E9). Parsing reads the
// elements at the table's offsets and accepts 42 or 43 characters; formatting writes 43, the last
// one a NUL.
inline constexpr std::size_t kMcDescriptionElements = 42;
inline constexpr std::size_t kMcDescriptionLength = 43;
inline constexpr std::size_t kMcNameLength = 5;  // "five characters ending with '\0'"

struct McDescription {
  std::array<char, kMcNameLength + 1> name{};
  std::uint8_t unit = 0;  // index into 107-UNIT's substitution texts (11.2.1)
  char kind = '0';        // '0' RAM actual, '1' RAM control, '2' EEPROM (11.2.1)
  std::uint8_t type = 0;  // the servo's type code (the seed gives no coding: raw)
  std::uint32_t min = 0;  // 8 hex characters each (11.2.1 "eight characters are transferred")
  std::uint32_t max = 0;
  std::uint32_t reference = 0;
  // The extended description (11.2.1), binary bytes, 2-byte elements high byte first (LB-D10).
  std::uint8_t level = 0;  // low nibble read level, high nibble write level
  std::uint16_t attribute = 0;
  std::uint16_t hardware_filter = 0;
  std::uint16_t structure_filter = 0;
  std::uint8_t subject_area = 0;
  std::uint8_t activity_area = 0;

  [[nodiscard]] std::string_view name_view() const { return name.data(); }
  [[nodiscard]] std::uint8_t read_level() const { return level & 0x0FU; }
  [[nodiscard]] std::uint8_t write_level() const { return static_cast<std::uint8_t>(level >> 4); }
};

// 11.2.1 attribute bits.
inline constexpr std::uint16_t kAttrShowParaText = 0x0004;
inline constexpr std::uint16_t kAttrShowNoFract = 0x0008;
inline constexpr std::uint16_t kAttrShowFract1 = 0x0010;
inline constexpr std::uint16_t kAttrShowText = 0x0020;  // has a value substitution text (11.3)
inline constexpr std::uint16_t kAttrInitControl = 0x0040;
inline constexpr std::uint16_t kAttrNoInit = 0x0080;
inline constexpr std::uint16_t kAttrShowHex = 0x0100;
inline constexpr std::uint16_t kAttrPassword = 0x0200;
// 11.2.1 hardware flags; MPTC is 4000H (bit 14), the table's 8000H is an erratum (LB-E8).
inline constexpr std::uint16_t kHwMptc = 0x4000;
inline constexpr std::uint16_t kHwBrake = 0x8000;

// 11.2.1's tables, row by row: the attribute bits, the hardware flags and the structure word's
// flags ("Bit-position", "Bit-mask"), the subject areas and the activity areas ("Sequential
// Number", "Value"). Each mask is 1 << bit; the printed table gives MPTC the mask 8000H beside its
// bit position 14 (LB-E8): here 4000H.
struct FlagRow {
  std::string_view name;
  std::uint8_t bit;
  std::uint16_t mask;
};
inline constexpr std::array<FlagRow, 8> kAttributeFlags{{
    {"ShowParaText", 2, kAttrShowParaText}, {"ShowNoFract", 3, kAttrShowNoFract},
    {"ShowFract1", 4, kAttrShowFract1},     {"ShowText", 5, kAttrShowText},
    {"InitControl", 6, kAttrInitControl},   {"NoInit", 7, kAttrNoInit},
    {"ShowHex", 8, kAttrShowHex},           {"Password", 9, kAttrPassword},
}};
inline constexpr std::array<FlagRow, 16> kHardwareFlags{{
    {"Resolver", 0, 0x0001},       {"EncoderSin", 1, 0x0002},     {"EncoderRec", 2, 0x0004},
    {"EncdSsiSingle", 3, 0x0008},  {"EncdSsiMulti", 4, 0x0010},   {"Option1", 5, 0x0020},
    {"Option2", 6, 0x0040},        {"ASM", 7, 0x0080},            {"SM", 8, 0x0100},
    {"Special-drive", 9, 0x0200},  {"EA1", 10, 0x0400},           {"EA2", 11, 0x0800},
    {"CAN", 12, 0x1000},           {"Extended Memory", 13, 0x2000}, {"MPTC", 14, kHwMptc},
    {"Brake", 15, kHwBrake},
}};
inline constexpr std::array<FlagRow, 6> kStructureFlags{{
    {"TorqueCtrl", 0, 0x0001}, {"SpeedCtrl", 1, 0x0002}, {"PosCtrl", 2, 0x0004},
    {"VF_Conv", 3, 0x0008},    {"EMaster", 4, 0x0010},   {"ESlave", 5, 0x0020},
}};
struct AreaRow {
  std::string_view name;
  std::uint8_t code;
};
inline constexpr std::array<AreaRow, 22> kSubjectAreas{{
    {"CONF", 0},  {"ENCD", 1}, {"OPT1", 2},  {"OPT2", 3},  {"MOT", 4},   {"TCON", 5},
    {"SCON", 6},  {"PCON", 7}, {"VFCN", 8},  {"SIO", 9},   {"KPAD", 10}, {"PWM", 11},
    {"SCTY", 12}, {"USER", 13}, {"SYS", 14}, {"REF", 15},  {"IO1", 16},  {"IO2", 17},
    {"CAN", 18},  {"PMOD", 19}, {"MENU", 20}, {"VAL", 21},
}};
inline constexpr std::array<AreaRow, 9> kActivityAreas{{
    {"SC_Nothing", 0}, {"SC_OPT1", 1}, {"SC_OPT2", 2}, {"SC_APP", 3},  {"SC_SYS", 4},
    {"SC_DRIVE", 5},   {"SC_REF", 6},  {"SC_CAN", 7},  {"SC_PMOD", 8},
}};

Parsed<McDescription> parse_mc_description(std::string_view value);
// How many VALUE characters of the answer to an ENQUIRY of `c` are binary, to be taken as they
// come (LB-D10): an MC6000 description (specifier 3, 2.4.2) has its 42 elements; others none.
constexpr std::size_t answer_binary_prefix(const Code& c) {
  return c.digit(0) == '3' ? kMcDescriptionElements : 0;
}
// nullopt when an element cannot travel: a binary byte >= 80H (LB-D10; frame characters do, read
// by length), or a name longer than 5 / with characters 11.2.1 does not allow.
std::optional<Value> format_mc_description(const McDescription& d);

// ---- 11.3: value substitution text --------------------------------------------------------------
// The text of an ENQUIRY of 61xxx: the VALUE with trailing blanks and NULs removed.
std::string_view substitution_text(std::string_view value);

}  // namespace ibs::lustbus
