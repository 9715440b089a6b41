// CODE strings (LUSTBUS manual 2.4): five ASCII decimal digits, highest first, whose meaning depends
// on the family. The receiver passes a Code on unread; the drive interprets it with the helpers
// here, which know the coding of 2.4.1 / 2.4.2, the shared codes of 5.2, 61xxx (11.3) and
// 49999 (11.6) — protocol, not any drive's parameter list.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

namespace ibs::lustbus {

inline constexpr std::size_t kCodeLength = 5;

class Code {
 public:
  constexpr Code() = default;
  // 0..99999; nullopt above.
  static constexpr std::optional<Code> from_number(std::uint32_t n) {
    if (n > 99999) return std::nullopt;
    Code c;
    for (std::size_t i = kCodeLength; i-- > 0;) {
      c.digits_[i] = static_cast<char>('0' + n % 10);
      n /= 10;
    }
    return c;
  }
  // Exactly five decimal digits.
  static constexpr std::optional<Code> parse(std::string_view s) {
    if (s.size() != kCodeLength) return std::nullopt;
    Code c;
    for (std::size_t i = 0; i < kCodeLength; ++i) {
      if (s[i] < '0' || s[i] > '9') return std::nullopt;
      c.digits_[i] = s[i];
    }
    return c;
  }
  // Digit `i` (< 5) set to `c` when `c` is a decimal digit; false, and nothing changed, when not:
  // a receiver takes the CODE character by character with this one check (6.1, 6.2).
  constexpr bool set_digit(std::size_t i, std::uint8_t c) {
    if (c < '0' || c > '9') return false;
    digits_[i] = static_cast<char>(c);
    return true;
  }
  [[nodiscard]] constexpr std::uint32_t number() const {
    std::uint32_t n = 0;
    for (const char d : digits_) n = n * 10 + static_cast<std::uint32_t>(d - '0');
    return n;
  }
  [[nodiscard]] constexpr char digit(std::size_t i) const { return digits_[i]; }
  [[nodiscard]] std::string_view text() const { return {digits_.data(), kCodeLength}; }
  friend constexpr bool operator==(const Code&, const Code&) = default;

 private:
  std::array<char, kCodeLength> digits_{'0', '0', '0', '0', '0'};
};

// Code of a number known to be in range (a constant); 0 for an out-of-range number.
constexpr Code make_code(std::uint32_t n) { return Code::from_number(n).value_or(Code{}); }

// ---- 2.4.1 SMARTDRIVE VF1000: S 0 D P P ------------------------------------------------------
enum class VfSpecifier : std::uint8_t {
  value = 0,        // value request or transfer
  description = 1,  // the parameter description of 11.1
};
struct VfCode {
  VfSpecifier specifier = VfSpecifier::value;
  // Device digit: 1 = the VF1000; 0 = "general for basis parameters" (11.1, parameter kind), as
  // the telegram list of 7.1.1 uses (00001..00005).
  std::uint8_t device = 1;
  std::uint8_t parameter = 0;  // 00..99
  friend constexpr bool operator==(const VfCode&, const VfCode&) = default;
};
// nullopt when the digits do not follow 2.4.1 (the drive answers NAK: "improper CODE", 3).
std::optional<VfCode> as_vf_code(Code c);
// nullopt for a parameter above 99 or a device digit other than 0/1.
std::optional<Code> vf_code(unsigned parameter, VfSpecifier s = VfSpecifier::value,
                            std::uint8_t device = 1);

// ---- 2.4.2 MASTERCONTROL MC6000/7000: S 0 P P P, plus 5.2, 11.3, 11.6 -----------------------
enum class McCodeKind : std::uint8_t {
  value,              // 2 0 ppp: value request / transfer
  description,        // 3 0 ppp: the 43-character description of 11.2
  special,            // 6 0 ppp: "special functions of the MASTERCONTROL" (2.4.2)
  substitution_text,  // 6 1 ppp: the value substitution text of ppp (11.3)
  shared,             // 0 0 0 xx with xx in 81-85, 91: the codes both families answer (5.2)
  posmod,             // 49999: the PosMOD1 channel (11.6)
};
struct McCode {
  McCodeKind kind = McCodeKind::value;
  std::uint16_t parameter = 0;  // 0..999 (posmod: 0)
  friend constexpr bool operator==(const McCode&, const McCode&) = default;
};
std::optional<McCode> as_mc_code(Code c);
// nullopt for a parameter above 999, or a shared code for a parameter not in 5.2's list.
std::optional<Code> mc_code(McCodeKind k, unsigned parameter);

// ---- 5.2: the numerically compatible parameters, CODE 000xx on both families ------------------
inline constexpr std::uint8_t kSharedParameters[] = {81, 82, 83, 84, 85, 91};
inline constexpr unsigned kParamBaud = 81;      // SIOC / SBAUD
inline constexpr unsigned kParamAddress = 82;   // SIOA / SADDR
inline constexpr unsigned kParamDummy = 83;     // SIOW / SDMMY
inline constexpr unsigned kParamWatchdog = 84;  // SIOT / SWDGT
inline constexpr unsigned kParamSiof = 85;      // SIOF / SERR
inline constexpr unsigned kParamType = 91;      // TYPE
constexpr bool is_shared_parameter(unsigned p) {
  for (const auto s : kSharedParameters) {
    if (s == p) return true;
  }
  return false;
}
constexpr Code shared_code(unsigned p) { return make_code(p % 100); }  // "000xx"
inline constexpr Code kSiofCode = make_code(kParamSiof);                // "00085"
inline constexpr Code kTypeCode = make_code(kParamType);                // "00091"
// 11.6: the one CODE of the PosMOD1 channel.
inline constexpr Code kPosmodCode = make_code(49999);
// The enhanced-protocol probe of the network scan: TYPE with specifier 2 (2.4.2). A servo
// answers it; an inverter, which knows only 2.4.1, answers NAK (docs/lustbus.md, D5).
inline constexpr Code kServoProbeCode = make_code(20091);

// 11.6.3: the status byte leading the PosMOD1 user data: bit 0 request (1) / data (0) telegram,
// bit 1 always 0, bit 2 multiblock, bits 4 and 5 always 1, bits 6 and 7 always 0 (bit 3 is not
// named: left as sent).
struct PosmodStatus {
  bool request = false;
  bool multiblock = false;
  friend constexpr bool operator==(const PosmodStatus&, const PosmodStatus&) = default;
};
constexpr char posmod_status_char(PosmodStatus s) {
  return static_cast<char>(0x30 | (s.request ? 0x01 : 0) | (s.multiblock ? 0x04 : 0));
}
constexpr std::optional<PosmodStatus> parse_posmod_status(char c) {
  const auto b = static_cast<unsigned char>(c);
  if ((b & 0xF2U) != 0x30U) return std::nullopt;
  return PosmodStatus{(b & 0x01U) != 0, (b & 0x04U) != 0};
}
// Whether user data led by status byte `first` is a request telegram, whose answer the host
// fetches with an ENQUIRY (bit 0); nullopt when `first` is no status byte. The form a
// BlockTransferProcedure's asks_answer takes.
constexpr std::optional<bool> posmod_asks_answer(char first) {
  const auto st = parse_posmod_status(first);
  if (!st) return std::nullopt;
  return st->request;
}

// Whether an ENQUIRY of `c` reads 85-SIOF/SERR (and so clears it, 9.2): 00085, 00185, 20085.
constexpr bool reads_siof(Code c) {
  const auto n = c.number();
  return n == 85 || n == 185 || n == 20085;
}

}  // namespace ibs::lustbus
