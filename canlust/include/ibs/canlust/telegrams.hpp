// Encoding and decoding of every CANLust telegram (CANLust manual 4.5, 5.5; public-facts "CANLust").
// All multi-byte fields are Intel order (low byte first). Decoders check the identifier's kind
// only through the caller (IdentifierMap::classify) and the length here: a DLC longer than the
// nominal one is accepted and the extra bytes ignored (the examples of 7.1.2 print 7 bytes where
// 5.5.5 says 6: public-facts "Control / status telegrams"); a shorter one is refused, since the
// missing bytes cannot be invented (decision D4). RTR frames are refused by every decoder
// (broadcasts never set RTR; CANLust uses no remote frames).
#pragma once

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

#include "ibs/canlust/data_types.hpp"
#include "ibs/canlust/frame.hpp"
#include "ibs/canlust/identifiers.hpp"

namespace ibs::canlust {

enum class DecodeError : std::uint8_t {
  none,
  wrong_kind,   // the identifier is not this telegram's (or not a CANLust one)
  remote,       // an RTR frame
  too_short,    // fewer bytes than the telegram needs
  bad_value,    // e.g. a System Start/Stop byte other than 00H / 01H
};
std::string_view to_string(DecodeError e);

template <typename T>
struct Decoded {
  T value{};
  DecodeError error = DecodeError::none;
  explicit operator bool() const { return error == DecodeError::none; }
};

// ---- System Start / Stop, identifier 221 (5.2, 5.5.4) -------------------------------------

enum class SystemCommand : std::uint8_t {
  stop = 0x00,   // decision D3: the Stop value is not public; 00H
  start = 0x01,  // 5.5.4 / public-facts: data byte 01H
};
std::string_view to_string(SystemCommand c);
CanFrame encode_system(SystemCommand c);
Decoded<SystemCommand> decode_system(const CanFrame& f);

// ---- Logon, 1543 + address, no data (5.2, 5.5.4) -----------------------------------------

CanFrame encode_logon(const IdentifierMap& ids, Address a);

// ---- Control and status, 661 / 881 + address (5.4, 5.5.5, 5.5.6; 4.3.2 492-CACNF) ---------

// How bytes 0..5 of the control and status telegrams are read. 492-CACNF picks one
// (process_layout_for_cacnf); the core never looks at the word's bits beyond the telegram.
enum class WordMode : std::uint8_t {
  drivecom,   // bytes 0-1 the DRIVECOM control / status word (5.4.2)
  easydrive,  // bytes 0-1 the EasyDrive direct-control bits (5.4.1)
};
enum class ValueWidth : std::uint8_t {
  int16q0 = 2,   // 16-bit reference / actual value (5.5.5: "CACNF = 1 ... Int16Q0")
  int32q16 = 4,  // 32-bit Q16 reference / actual frequency (5.5.5, 5.5.6)
};
struct ProcessLayout {
  WordMode mode = WordMode::drivecom;
  ValueWidth reference = ValueWidth::int32q16;  // in the control telegram
  ValueWidth actual = ValueWidth::int32q16;     // in the status telegram
  friend constexpr bool operator==(const ProcessLayout&, const ProcessLayout&) = default;
};
// 492-CACNF -> layout; nullopt for values the manual does not describe (decision D5: 1 DRIVECOM
// 16/16 bit, 2 DRIVECOM Q16/Q16, 3 DRIVECOM Q16 reference with the 16-bit actual value that the
// fragment of 5.5.6 names for "CACNF 1, 3", 4 EasyDrive Q16/Q16 as example 7.1.1).
std::optional<ProcessLayout> process_layout_for_cacnf(std::uint8_t cacnf);

constexpr std::uint8_t nominal_length(ValueWidth w) { return static_cast<std::uint8_t>(2U + static_cast<unsigned>(w)); }

struct ControlTelegram {
  std::uint16_t word = 0;       // bytes 0-1
  std::int32_t reference = 0;   // bytes 2-3 (int16q0, sign-extended here) or 2-5 (Q16 raw)
  friend constexpr bool operator==(const ControlTelegram&, const ControlTelegram&) = default;
};
struct StatusTelegram {
  std::uint16_t word = 0;
  std::int32_t actual = 0;
  friend constexpr bool operator==(const StatusTelegram&, const StatusTelegram&) = default;
};
// A 16-bit layout keeps the low 16 bits of the value (the caller scales and clamps).
std::optional<CanFrame> encode_control(const IdentifierMap& ids, Address a,
                                       const ProcessLayout& layout, const ControlTelegram& t);
std::optional<CanFrame> encode_status(const IdentifierMap& ids, Address a,
                                      const ProcessLayout& layout, const StatusTelegram& t);
Decoded<ControlTelegram> decode_control(const CanFrame& f, const ProcessLayout& layout);
Decoded<StatusTelegram> decode_status(const CanFrame& f, const ProcessLayout& layout);

// ---- Error message, 441 + address, 3 bytes (5.5; 6.2 table 5.9) ---------------------------

// Byte 0 the error number of table 5.9 ("Bus" column), byte 1 the error location, byte 2: not
// public; decision D6: the error reaction the drive took (ErrorReaction code, errors.hpp).
struct ErrorTelegram {
  std::uint8_t number = 0;
  std::uint8_t location = 0;
  std::uint8_t reaction = 0;
  friend constexpr bool operator==(const ErrorTelegram&, const ErrorTelegram&) = default;
};
std::optional<CanFrame> encode_error(const IdentifierMap& ids, Address a, const ErrorTelegram& e);
Decoded<ErrorTelegram> decode_error(const CanFrame& f);

// ---- Parameter channel, 1101 / 1321 + address, 8 bytes (4.5) -------------------------------

// Byte 0-1 parameter number (low, high; 4.4), byte 2 mode (request) / status (reply), bytes 3-6
// data (32 bits, Intel order), byte 7 block counter or field index.
struct ParameterTelegram {
  std::uint16_t parameter = 0;
  std::uint8_t code = 0;  // the mode of a request, the status of a reply
  std::uint32_t data = 0;
  std::uint8_t block = 0;
  friend constexpr bool operator==(const ParameterTelegram&, const ParameterTelegram&) = default;
};
inline constexpr std::uint8_t kParameterTelegramLength = 8;

// Inline, and the 8 bytes as one 64-bit word (issue 26: every parameter read encodes and decodes
// two of these; byte by byte it cost about 65 instructions a frame). The byte order is the
// telegram's (4.5, Intel order), whatever the machine's; the compiler merges the byte stores and
// loads into single 64-bit ones on a little-endian machine.
namespace detail {
constexpr std::uint64_t parameter_word(const ParameterTelegram& t) {
  return static_cast<std::uint64_t>(t.parameter) | (static_cast<std::uint64_t>(t.code) << 16U) |
         (static_cast<std::uint64_t>(t.data) << 24U) | (static_cast<std::uint64_t>(t.block) << 56U);
}
// The frame for an identifier already checked (what encode_parameter_request / _reply give).
constexpr CanFrame parameter_frame(std::uint16_t id, const ParameterTelegram& t) {
  CanFrame f;
  f.id = id;
  f.dlc = kParameterTelegramLength;
  const std::uint64_t w = parameter_word(t);
  if constexpr (std::endian::native == std::endian::little) {
    f.data = std::bit_cast<std::array<std::uint8_t, kMaxDlc>>(w);
  } else {
    for (std::size_t i = 0; i < kParameterTelegramLength; ++i) {
      f.data[i] = static_cast<std::uint8_t>(w >> (8U * i));
    }
  }
  return f;
}
constexpr std::optional<CanFrame> encode_parameter(std::optional<std::uint16_t> id,
                                                   const ParameterTelegram& t) {
  if (!id) return std::nullopt;
  return parameter_frame(*id, t);
}
}  // namespace detail

constexpr std::optional<CanFrame> encode_parameter_request(const IdentifierMap& ids, Address a,
                                                           const ParameterTelegram& t) {
  return detail::encode_parameter(ids.id(TelegramKind::parameter_request, a), t);
}
constexpr std::optional<CanFrame> encode_parameter_reply(const IdentifierMap& ids, Address a,
                                                         const ParameterTelegram& t) {
  return detail::encode_parameter(ids.id(TelegramKind::parameter_reply, a), t);
}
// The 8 bytes whatever the identifier (the caller classified it).
constexpr Decoded<ParameterTelegram> decode_parameter(const CanFrame& f) {
  if (f.rtr) return {{}, DecodeError::remote};
  if (f.dlc < kParameterTelegramLength) return {{}, DecodeError::too_short};
  std::uint64_t w = 0;
  if constexpr (std::endian::native == std::endian::little) {
    w = std::bit_cast<std::uint64_t>(f.data);
  } else {
    for (std::size_t i = 0; i < kParameterTelegramLength; ++i) {
      w |= static_cast<std::uint64_t>(f.data[i]) << (8U * i);
    }
  }
  return {{static_cast<std::uint16_t>(w & 0xFFFFU), static_cast<std::uint8_t>((w >> 16U) & 0xFFU),
           static_cast<std::uint32_t>((w >> 24U) & 0xFFFF'FFFFU), static_cast<std::uint8_t>(w >> 56U)},
          DecodeError::none};
}

}  // namespace ibs::canlust
