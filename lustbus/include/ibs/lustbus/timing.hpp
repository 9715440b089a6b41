// Telegram durations (LUSTBUS manual 10, 10.1). A character is 10 bits on the line — start, 7 data,
// parity, stop (2.1) — not the 8 bits the tables of 10.1 count (LB-E10).
#pragma once

#include <cstddef>
#include <cstdint>

#include "ibs/base/time.hpp"
#include "ibs/lustbus/code.hpp"

namespace ibs::lustbus {

inline constexpr unsigned kBitsPerCharacter = 10;
// 4: 2400..9600 Bd for inverters, 2400..57600 Bd for servos; 9600 is the factory setting.
inline constexpr std::uint32_t kFactoryBaud = 9600;
// 5.1: the standard rate first, then "all possible transfer rates" (LB-D7: this order).
inline constexpr std::uint32_t kBaudScanOrder[] = {9600, 19200, 38400, 57600, 4800, 2400};

// One character at `baud`, rounded to the nearest nanosecond.
constexpr Duration character_time(std::uint32_t baud) {
  return Duration{(std::int64_t{kBitsPerCharacter} * 1'000'000'000 + baud / 2) / baud};
}
constexpr Duration transfer_time(std::size_t characters, std::uint32_t baud) {
  return Duration{(static_cast<std::int64_t>(characters) * kBitsPerCharacter * 1'000'000'000 +
                   baud / 2) / baud};
}

// A device's receiver drops a telegram fragment after this much silence (docs/lustbus.md LB-D23):
// 20 characters at the line's rate, and never less than 50 ms, so that a host writing byte by byte
// through a USB adapter (latency timers of 16 ms) is not cut. LUSTBUS manual 3's device has no timeout.
inline constexpr Duration kInterCharTimeoutFloor = std::chrono::milliseconds(50);
constexpr Duration inter_char_timeout(std::uint32_t baud) {
  const Duration twenty = transfer_time(20, baud);
  return twenty > kInterCharTimeoutFloor ? twenty : kInterCharTimeoutFloor;
}

// Telegram lengths of 10.1 (including the host's leading EOT).
inline constexpr std::size_t kEnquiryLength = 3 + kCodeLength;  // EOT ADR CODE ENQ = 8
constexpr std::size_t text_answer_length(std::size_t value_length) {
  return 5 + kCodeLength + value_length;  // ADR STX CODE = VALUE ETX BCC
}
constexpr std::size_t select_length(std::size_t value_length) {
  return 1 + text_answer_length(value_length);  // EOT ADR STX CODE = VALUE ETX BCC
}
inline constexpr std::size_t kShortAnswerLength = 2;  // ADR ACK / ADR NAK

// One row set of the tables of 10.1: steps 1-5 of section 10 and their sum.
struct TelegramTime {
  Duration host_telegram{};  // 1
  Duration reaction{};       // 2 device reaction
  Duration answer{};         // 3
  Duration host_reaction{};  // 4
  Duration eot{};            // 5
  [[nodiscard]] constexpr Duration total() const {
    return host_telegram + reaction + answer + host_reaction + eot;
  }
  // Telegrams per second, rounded down as the manual does ("=> 12 telegrams/sec").
  [[nodiscard]] constexpr unsigned per_second() const {
    const auto t = total().count();
    return t <= 0 ? 0U : static_cast<unsigned>(1'000'000'000 / t);
  }
};
TelegramTime enquiry_time(std::size_t value_length, std::uint32_t baud, Duration reaction,
                          Duration host_reaction);
TelegramTime select_time(std::size_t value_length, std::uint32_t baud, Duration reaction,
                         Duration host_reaction);

// 10.2.2: memory time = data width x 3 x per-byte time; the wait before the next SELECT is the
// memory time less the telegram sequence's duration, when positive. The per-byte time is the
// drive's (5 ms in 10.2.2's formula, 15 ms per byte in 3: docs/pcp.md PCP-E9).
constexpr Duration eeprom_wait(unsigned width_bytes, Duration per_write, Duration sequence) {
  const Duration memory = per_write * (3 * width_bytes);
  return memory > sequence ? memory - sequence : Duration{0};
}

}  // namespace ibs::lustbus
