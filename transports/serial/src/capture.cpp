#include "ibs/serial/capture.hpp"

#include <algorithm>
#include <chrono>

namespace ibs::serial {

std::string_view to_string(LineProtocol p) { return p == LineProtocol::lustbus ? "LUSTBUS" : "DFS-1"; }

int linktype(LineProtocol p) { return p == LineProtocol::lustbus ? kLinktypeLustbus : kLinktypeDfs1; }

std::optional<LineProtocol> protocol_of_linktype(int linktype) {
  if (linktype == kLinktypeLustbus) return LineProtocol::lustbus;
  if (linktype == kLinktypeDfs1) return LineProtocol::dfs1;
  return std::nullopt;
}

namespace capture {

void encode(const base::LineTelegram& t, std::vector<std::uint8_t>& out) {
  out.clear();
  out.push_back(kVersion);
  out.push_back(static_cast<std::uint8_t>(t.from));
  const std::uint8_t known = base::kTelegramCheckBad | base::kTelegramCut | base::kTelegramNoise;
  out.push_back(static_cast<std::uint8_t>((t.flags & known) | (t.address ? kFlagAddress : 0U)));
  out.push_back(t.address.value_or(0));
  const auto us = std::chrono::duration_cast<std::chrono::microseconds>(t.last - t.first).count();
  const auto d = static_cast<std::uint32_t>(std::clamp<std::int64_t>(us, 0, 0xFFFFFFFF));
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<std::uint8_t>(d >> static_cast<unsigned>(shift)));
  out.insert(out.end(), t.bytes.begin(), t.bytes.end());
}

std::optional<Packet> decode(std::span<const std::uint8_t> data, Time at, std::string& why) {
  if (data.size() < kHeaderSize) {
    why = std::to_string(data.size()) + " bytes, shorter than the " + std::to_string(kHeaderSize) + "-byte header";
    return std::nullopt;
  }
  if (data[0] != kVersion) {
    why = "header version " + std::to_string(data[0]) + " (this ibs reads version " + std::to_string(kVersion) + ")";
    return std::nullopt;
  }
  if (data[1] > 1) {
    why = "direction " + std::to_string(data[1]) + " (0 from the host, 1 from a device)";
    return std::nullopt;
  }
  Packet p;
  p.at = at;
  p.from = static_cast<base::LineSide>(data[1]);
  p.flags = static_cast<std::uint8_t>(data[2] & ~kFlagAddress);
  if ((data[2] & kFlagAddress) != 0) p.address = data[3];
  const std::uint32_t us = (std::uint32_t{data[4]} << 24U) | (std::uint32_t{data[5]} << 16U) |
                           (std::uint32_t{data[6]} << 8U) | data[7];
  p.duration = std::chrono::microseconds(us);
  p.bytes.assign(data.begin() + kHeaderSize, data.end());
  return p;
}

}  // namespace capture

LineCaptureReading read_line_capture(std::span<const std::uint8_t> file) {
  LineCaptureReading r;
  const pcap::Reading pcap = pcap::read_pcap(file);
  if (pcap.linktype < 0) {
    r.error = LineCaptureError{0, "not a pcap file: " + pcap.error};
    return r;
  }
  const auto protocol = protocol_of_linktype(pcap.linktype);
  if (!protocol) {
    r.error = LineCaptureError{0, "link type " + std::to_string(pcap.linktype) + " is no serial line's (" +
                                      std::to_string(kLinktypeLustbus) + " LUSTBUS, " +
                                      std::to_string(kLinktypeDfs1) + " DFS-1)"};
    return r;
  }
  r.protocol = *protocol;
  for (std::size_t i = 0; i < pcap.records.size(); ++i) {
    const pcap::Record& rec = pcap.records[i];
    if (rec.data.size() < rec.original) {
      r.error = LineCaptureError{i + 1, "cut to " + std::to_string(rec.data.size()) + " of " +
                                            std::to_string(rec.original) + " bytes (the snap length)"};
      return r;
    }
    std::string why;
    auto p = capture::decode(rec.data, rec.at, why);
    if (!p) {
      r.error = LineCaptureError{i + 1, why};
      return r;
    }
    r.packets.push_back(std::move(*p));
  }
  if (!pcap.error.empty()) r.error = LineCaptureError{pcap.records.size() + 1, pcap.error};
  return r;
}

LineCapture::LineCapture(std::ostream& out, LineProtocol protocol, base::TelegramFramer& framer, Direction host,
                         Time epoch, std::function<Time()> clock, bool live)
    : file_(out, linktype(protocol), epoch), framer_(framer), host_(host), clock_(std::move(clock)), live_(live) {
  if (!clock_) {
    const auto t0 = std::chrono::steady_clock::now();
    clock_ = [t0] { return std::chrono::duration_cast<Time>(std::chrono::steady_clock::now() - t0); };
  }
}

void LineCapture::write_pending() {
  for (const base::LineTelegram& t : pending_) {
    capture::encode(t, buffer_);
    file_.write(t.first, buffer_);
  }
  if (live_ && !pending_.empty()) file_.flush();
  pending_.clear();
}

void LineCapture::record(base::LineSide side, std::span<const std::uint8_t> bytes, Time at) {
  framer_.feed(side, bytes, at, pending_);
  write_pending();
}

void LineCapture::bytes(Direction d, std::span<const std::uint8_t> bytes) {
  record(d == host_ ? base::LineSide::host : base::LineSide::device, bytes, clock_());
}

void LineCapture::finish() {
  framer_.finish(pending_);
  write_pending();
  file_.close();
}

}  // namespace ibs::serial
