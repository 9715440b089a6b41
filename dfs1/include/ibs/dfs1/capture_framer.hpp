// The DFS-1 line cut into frames for a capture (docs/pcap.md, "Serial lines"; DFS-1 manual 6.0):
// DLE STX UID CMD [data] DLE ETX CSM, found by the protocol's own FrameDecoder on each side, and
// kept as they were on the line (DLE doubling included). A frame whose checksum does not match is
// flagged; one a new DLE STX, a broken escape, the other side (the line is half duplex) or the
// end of the recording interrupts is cut; bytes outside DLE STX ... CSM are noise. The address is
// the frame's UID. Sans-I/O: bytes and time in, frames out.
#pragma once

#include "ibs/base/line_telegram.hpp"
#include "ibs/dfs1/frame.hpp"

namespace ibs::dfs1 {

class CaptureFramer final : public base::TelegramFramer {
 public:
  void feed(base::LineSide side, std::span<const std::uint8_t> bytes, Time at,
            std::vector<base::LineTelegram>& out) override;
  void finish(std::vector<base::LineTelegram>& out) override;

 private:
  struct Side {
    FrameDecoder decoder;
    base::LineTelegram t;  // the bytes since the last boundary
  };
  void byte(Side& s, base::LineSide from, std::uint8_t b, Time at, std::vector<base::LineTelegram>& out);
  // Ends what `s` holds: `flags` added (a frame still open is cut, bytes outside one are noise).
  static void emit(Side& s, std::uint8_t flags, std::vector<base::LineTelegram>& out);
  static void flush(Side& s, std::vector<base::LineTelegram>& out);

  Side host_;
  Side device_;
};

}  // namespace ibs::dfs1
