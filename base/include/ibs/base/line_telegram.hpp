// A serial byte line (LUSTBUS, DFS-1) cut into telegrams, for captures (docs/pcap.md, "Serial
// lines"): each protocol's framer (lustbus::CaptureFramer, dfs1::CaptureFramer) is told the bytes
// each side put on the line with the time they came and hands back whole telegrams, each with the
// side that sent it, its first and last byte's time and what is wrong with it. The bytes are kept
// as they were on the line: the telegrams of one side, joined, are every byte that side sent.
// Sans-I/O (time passed in); recording, not the cycle path: it allocates.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "ibs/base/time.hpp"

namespace ibs::base {

// Who put the bytes on the line: the host (the master, which asks) or a device (which answers).
enum class LineSide : std::uint8_t { host = 0, device = 1 };

// What is wrong with a telegram (bits of LineTelegram::flags, as a capture's packet header
// carries them, docs/pcap.md).
inline constexpr std::uint8_t kTelegramCheckBad = 0x01;  // the check character (BCC, CSM) does not match
inline constexpr std::uint8_t kTelegramCut = 0x02;       // it ended before it was complete
inline constexpr std::uint8_t kTelegramNoise = 0x04;     // bytes that are no telegram of the protocol

struct LineTelegram {
  LineSide from = LineSide::host;
  std::vector<std::uint8_t> bytes;  // as on the line (DLE doubling and all)
  Time first{0};                    // when its first byte came (was read or written)
  Time last{0};                     // when its last byte came
  std::uint8_t flags = 0;
  std::optional<std::uint8_t> address;  // the device it is for or from: LUSTBUS ADR 0..31, DFS-1 UID
};

// A protocol's framer. feed() takes the bytes one side sent at `at` (in the order they came; the
// times never go back) and appends the telegrams they complete to `out`; a telegram the other side
// interrupts (the line is half duplex) is ended as cut. finish() ends the recording: what is
// pending goes to `out`, cut.
class TelegramFramer {
 public:
  TelegramFramer() = default;
  TelegramFramer(const TelegramFramer&) = default;
  TelegramFramer& operator=(const TelegramFramer&) = default;
  virtual ~TelegramFramer() = default;

  virtual void feed(LineSide side, std::span<const std::uint8_t> bytes, Time at, std::vector<LineTelegram>& out) = 0;
  virtual void finish(std::vector<LineTelegram>& out) = 0;
};

}  // namespace ibs::base
