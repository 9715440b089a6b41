// Captures of a serial line for Wireshark (docs/pcap.md, "Serial lines"): every telegram of a
// LUSTBUS or DFS-1 line as one packet of a pcap file, with its direction, time and what is wrong
// with it, under a link type of its own -- LINKTYPE_USER1 (148) for LUSTBUS, LINKTYPE_USER2 (149)
// for DFS-1 (USER0, 147, is the INTERBUS capture's) -- read by tools/wireshark/lustbus.lua and
// dfs1.lua and by `ibs decode`.
//
// Each packet is an 8-byte header, then the telegram's bytes as they were on the line:
//
//   0  version, 1
//   1  direction: 0 from the host, 1 from a device
//   2  flags: bit 0 check character wrong (BCC, CSM), bit 1 cut, bit 2 noise (no telegram),
//      bit 7 byte 3 holds the address
//   3  address: LUSTBUS 0..31 (ADR - 40H), DFS-1 UID
//   4  the telegram's duration, first byte to last, in microseconds (big-endian, saturated)
//
// The packet's timestamp is its first byte's time. LineCapture records a port (a ByteTap of
// SerialPort) through the protocol's framer (base::TelegramFramer: lustbus::CaptureFramer,
// dfs1::CaptureFramer); read_line_capture() reads a file back. Recording and reading allocate and
// throw; they are not a cycle path.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <ostream>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "ibs/base/line_telegram.hpp"
#include "ibs/pcap/pcap_file.hpp"
#include "ibs/serial/byte_log.hpp"

namespace ibs::serial {

enum class LineProtocol : std::uint8_t { lustbus, dfs1 };
std::string_view to_string(LineProtocol p);

// LINKTYPE_USER1 / DLT_USER1 and LINKTYPE_USER2 / DLT_USER2 (reserved for private use; the
// Wireshark user's DLT_USER table or our dissectors map them, docs/pcap.md).
inline constexpr int kLinktypeLustbus = 148;
inline constexpr int kLinktypeDfs1 = 149;
int linktype(LineProtocol p);
// The protocol a link type stands for; nullopt for another.
std::optional<LineProtocol> protocol_of_linktype(int linktype);

namespace capture {

inline constexpr std::uint8_t kVersion = 1;
inline constexpr std::size_t kHeaderSize = 8;
// Header byte 2: base::kTelegramCheckBad, kTelegramCut, kTelegramNoise and this one.
inline constexpr std::uint8_t kFlagAddress = 0x80;

// One packet: the header, then the telegram's bytes, into `out` (cleared first).
void encode(const base::LineTelegram& t, std::vector<std::uint8_t>& out);

struct Packet {
  Time at{0};  // the pcap timestamp: the first byte's time (since 1970 in a recorded file)
  base::LineSide from = base::LineSide::host;
  std::uint8_t flags = 0;  // base::kTelegram* bits
  std::optional<std::uint8_t> address;
  Duration duration{0};
  std::vector<std::uint8_t> bytes;
};

// One packet read back; nullopt with `why` set for one this format cannot be (shorter than its
// header, another version, a direction that is neither 0 nor 1).
std::optional<Packet> decode(std::span<const std::uint8_t> data, Time at, std::string& why);

}  // namespace capture

struct LineCaptureError {
  std::size_t packet = 0;  // 1-based; 0: the file as a whole
  std::string what;
};

struct LineCaptureReading {
  LineProtocol protocol = LineProtocol::lustbus;
  std::vector<capture::Packet> packets;  // every packet read before an error
  std::optional<LineCaptureError> error;
};

// A whole capture file in memory. Never throws for bad input: a file that is no pcap, a link type
// other than 148 and 149, a packet cut by the snap length or malformed all end in `error`, naming
// the packet.
LineCaptureReading read_line_capture(std::span<const std::uint8_t> file);

// Records a serial port's line as a capture: set it as the port's tap (SerialPort::set_tap). The
// port's bytes in `host` direction are the host's (tx for a host program, rx for an emulator),
// the others a device's; each read or write is stamped with `clock()` (by default the steady
// clock since construction) plus `epoch` (wall_clock_epoch() for Wireshark's absolute time).
class LineCapture final : public ByteTap {
 public:
  // `framer` is the protocol's and must outlive this; `live`: flush after every telegram (a
  // capture read as it is written, through a pipe). Throws pcap::PcapError when libpcap refuses.
  LineCapture(std::ostream& out, LineProtocol protocol, base::TelegramFramer& framer, Direction host,
              Time epoch = pcap::wall_clock_epoch(), std::function<Time()> clock = {}, bool live = false);

  void bytes(Direction d, std::span<const std::uint8_t> bytes) override;
  // The bytes of one side at `at` (for a caller that has no port in between).
  void record(base::LineSide side, std::span<const std::uint8_t> bytes, Time at);
  // Writes what is still pending (cut) and closes the file; throws pcap::PcapError when the
  // stream failed.
  void finish();
  [[nodiscard]] std::uint64_t packets() const { return file_.packets(); }

 private:
  void write_pending();

  pcap::PcapFile file_;
  base::TelegramFramer& framer_;
  Direction host_;
  std::function<Time()> clock_;
  bool live_ = false;
  std::vector<base::LineTelegram> pending_;
  std::vector<std::uint8_t> buffer_;
};

}  // namespace ibs::serial
