// can-utils' text forms besides the candump log (candump.hpp), for `ibs canlust send`, `monitor`
// and `play` (docs/canlust.md, "CAN tools"):
//
//   cansend's frame   ID#DATA        "373#4002.0000.0000", "609#", "123#R2"
//   candump's filters ID:MASK, ID~MASK (inverted), j (join: all must match), comma-separated
//   candump's time    SECONDS.FRACTION, as the log's "(1795431275.322679)"
//
// Identifiers, masks and data are hex, as can-utils writes and reads them. CANLust (CM-CAN1) uses
// 11-bit identifiers and classic frames only: an extended identifier or a CAN FD frame is refused
// with why. Floor 4 beside the transports; no I/O: text in, a value or what is wrong and where out.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ibs/canlust/frame.hpp"

namespace ibs::can {

// What is wrong with a text, and where: `column` is 1-based into the text given (one past its end
// when something is missing at the end).
struct TextError {
  std::size_t column = 0;
  std::string what;
};

// cansend's `<can_id>#{data}` / `<can_id>#R{len}`: three hex digits 000..7FF, '#', 0..8 bytes of
// two hex digits each, '.' allowed between bytes; `R` (or `R0`..`R8`) a remote frame.
struct FrameText {
  std::optional<canlust::CanFrame> frame;
  TextError error;  // when there is no frame
};
FrameText parse_cansend(std::string_view text);

// The frame as cansend takes it (and candump logs it): "373#400200000000", "123#R2".
std::string cansend_text(const canlust::CanFrame& f);

// SocketCAN's can_id flags, as candump's filters compare them.
inline constexpr std::uint32_t kCanEffFlag = 0x80000000U;  // an extended (29-bit) identifier
inline constexpr std::uint32_t kCanRtrFlag = 0x40000000U;  // a remote frame
inline constexpr std::uint32_t kCanErrFlag = 0x20000000U;  // an error frame (masked off, as candump does)

// One filter of candump (include/linux/can.h, struct can_filter): a frame matches when
// (can_id & mask) == (id & mask), an inverted one when they differ. can_id carries the flags above,
// so `123:C00007FF` matches only 123 as a standard data frame, an 8-digit ID only extended frames.
struct CanFilter {
  std::uint32_t id = 0;
  std::uint32_t mask = 0;
  bool inverted = false;
  [[nodiscard]] bool matches(const canlust::CanFrame& f) const;
};

// The filters of a monitor: none lets every frame through (candump's default 0:0); otherwise a
// frame passes when it matches one of them, with `join` when it matches all of them
// (CAN_RAW_JOIN_FILTERS).
struct CanFilterSet {
  std::vector<CanFilter> filters;
  bool join = false;
  [[nodiscard]] bool passes(const canlust::CanFrame& f) const;
};

// Adds the comma-separated filters of `text` to `set`: `ID:MASK`, `ID~MASK`, `~ID:MASK` (the
// inverted one written with the '~' first), `j` / `J`; ID and MASK 1..8 hex digits (an ID of
// exactly 8 digits is an extended one, as candump reads it). candump's error filter `#MASK` is
// refused: these buses carry no error frames. nullopt when all were good; else the first error
// (nothing of `text` is added then).
std::optional<TextError> add_candump_filters(std::string_view text, CanFilterSet& set);

// candump's SECONDS.FRACTION (the log's time, without the parentheses) in microseconds, digits
// only (1..6 after the point; "1.5" is 1.500000 s); nullopt when it is none or beyond the year 2^63 us.
std::optional<std::int64_t> candump_time_us(std::string_view text);

}  // namespace ibs::can
