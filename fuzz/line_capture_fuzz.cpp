// The serial lines' captures (serial/capture.hpp, docs/pcap.md "Serial lines"): the reader of a
// capture file given arbitrary bytes, and the recording itself given an arbitrary line -- the
// protocol's framer (lustbus::CaptureFramer, dfs1::CaptureFramer), the packet header, the pcap
// file through libpcap and the reader, end to end -- with `ibs decode`'s explainers on what was
// read.
//
// Asserts:
// - reading never crashes: a file is read or refused with why, the packets before a refusal kept;
//   every packet read has a direction of 0 or 1 and no bytes beyond its record;
// - a recorded line reads back whole: no error, the protocol's link type, one packet per telegram,
//   none empty, times never going back, only the header's known flag bits, and each side's packets
//   joined are every byte that side sent, in order (the framing only cuts, it loses nothing);
// - a LUSTBUS telegram flagged BCC-wrong ends with a byte after ETX that is not the XOR of 2.2; a
//   DFS-1 frame flagged CSM-wrong is one the protocol's decoder refuses for its checksum;
// - the explainers of `ibs decode` (lustbus::explain_line, devices::dfs1::FrameExplainer) read
//   every packet, whatever it holds.
//
// Input: byte 0 bit 0 the mode: 0 the rest is a capture file; 1 the rest is a line: byte 1 bit 0
// the protocol (0 LUSTBUS, 1 DFS-1), then chunks, each a byte (bit 7 the side: 0 host, 1 device;
// bits 0-6 the length) and that many bytes, 1 ms apart.
#include <cstddef>
#include <cstdint>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz_support.hpp"
#include "ibs/devices/dfs1/frame_text.hpp"
#include "ibs/dfs1/capture_framer.hpp"
#include "ibs/dfs1/frame.hpp"
#include "ibs/lustbus/byte_log.hpp"
#include "ibs/lustbus/capture_framer.hpp"
#include "ibs/lustbus/chars.hpp"
#include "ibs/serial/capture.hpp"

namespace {

using namespace ibs;
using Bytes = std::vector<std::uint8_t>;

void explain(const serial::LineCaptureReading& r) {
  if (r.protocol == serial::LineProtocol::lustbus) {
    std::vector<lustbus::LineBytes> chunks;
    for (const auto& p : r.packets) chunks.push_back({"0", p.from == base::LineSide::host, p.bytes});
    (void)lustbus::explain_line(chunks, {});
    return;
  }
  devices::dfs1::FrameExplainer e;
  for (const auto& p : r.packets) (void)e.explain(p.from == base::LineSide::host, p.bytes);
}

void read_file(std::span<const std::uint8_t> file) {
  const serial::LineCaptureReading r = serial::read_line_capture(file);
  for (const auto& p : r.packets) {
    IBS_FUZZ_REQUIRE(p.from == base::LineSide::host || p.from == base::LineSide::device, "a direction of 0 or 1");
    IBS_FUZZ_REQUIRE(p.bytes.size() + serial::capture::kHeaderSize <= file.size(), "bytes beyond the record");
  }
  explain(r);
}

// The XOR of 2.2 over what follows the first STX up to the ETX before the last byte.
bool lustbus_bcc_right(const Bytes& t) {
  std::size_t stx = 0;
  while (stx < t.size() && t[stx] != lustbus::kStx) ++stx;
  if (stx + 2 >= t.size()) return true;
  return lustbus::bcc(std::span<const std::uint8_t>(t).subspan(stx + 1, t.size() - stx - 2)) == t.back();
}

bool dfs1_checksum_refused(const Bytes& t) {
  dfs1::FrameDecoder d;
  for (const std::uint8_t b : t) {
    const dfs1::DecodeResult r = d.push(b);
    if (r.status == dfs1::DecodeStatus::frame) return false;
    if (r.status == dfs1::DecodeStatus::error) return r.error == dfs1::DecodeError::bad_checksum;
  }
  return false;
}

void record_line(fuzz::Input& in) {
  const bool lustbus = (in.ConsumeIntegral<std::uint8_t>() & 1U) == 0;
  const auto protocol = lustbus ? serial::LineProtocol::lustbus : serial::LineProtocol::dfs1;
  lustbus::CaptureFramer lb;
  dfs1::CaptureFramer df;
  base::TelegramFramer& framer = lustbus ? static_cast<base::TelegramFramer&>(lb) : df;
  std::ostringstream out;
  serial::LineCapture cap(out, protocol, framer, serial::Direction::tx, Time{0});
  Bytes sent[2];
  Time t{0};
  while (in.remaining_bytes() > 0) {
    const auto head = in.ConsumeIntegral<std::uint8_t>();
    const auto side = (head & 0x80U) != 0 ? base::LineSide::device : base::LineSide::host;
    const Bytes chunk = in.ConsumeBytes<std::uint8_t>(head & 0x7FU);
    cap.record(side, chunk, t);
    Bytes& s = sent[static_cast<int>(side)];
    s.insert(s.end(), chunk.begin(), chunk.end());
    t += std::chrono::milliseconds(1);
  }
  cap.finish();
  const std::string file = out.str();
  const serial::LineCaptureReading r =
      serial::read_line_capture(std::span(reinterpret_cast<const std::uint8_t*>(file.data()), file.size()));
  IBS_FUZZ_REQUIRE(!r.error, "a recorded line reads back: " + (r.error ? r.error->what : std::string()));
  IBS_FUZZ_REQUIRE(r.protocol == protocol, "the protocol's link type");
  IBS_FUZZ_REQUIRE(r.packets.size() == cap.packets(), "one packet per telegram written");
  Bytes got[2];
  Time last{0};
  constexpr std::uint8_t kKnown = base::kTelegramCheckBad | base::kTelegramCut | base::kTelegramNoise;
  for (const auto& p : r.packets) {
    IBS_FUZZ_REQUIRE(!p.bytes.empty(), "no empty packet");
    IBS_FUZZ_REQUIRE(p.at >= last, "times never go back");
    IBS_FUZZ_REQUIRE((p.flags & ~kKnown) == 0, "only the header's flags");
    last = p.at;
    if ((p.flags & base::kTelegramCheckBad) != 0) {
      if (lustbus) {
        IBS_FUZZ_REQUIRE(!lustbus_bcc_right(p.bytes), "a BCC flagged wrong is wrong");
      } else {
        IBS_FUZZ_REQUIRE(dfs1_checksum_refused(p.bytes), "a CSM flagged wrong is refused by the decoder");
      }
    }
    Bytes& g = got[static_cast<int>(p.from)];
    g.insert(g.end(), p.bytes.begin(), p.bytes.end());
  }
  IBS_FUZZ_REQUIRE(got[0] == sent[0], "every byte the host sent, in order");
  IBS_FUZZ_REQUIRE(got[1] == sent[1], "every byte the devices sent, in order");
  explain(r);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  if ((data[0] & 1U) == 0) {
    read_file(std::span(data + 1, size - 1));
    return 0;
  }
  fuzz::Input in(data + 1, size - 1);
  record_line(in);
  return 0;
}
