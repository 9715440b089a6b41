#include "serial_decode.hpp"

#include <chrono>
#include <cstdio>
#include <ctime>
#include <ostream>
#include <vector>

#include "ibs/base/text_file.hpp"
#include "ibs/devices/dfs1/frame_text.hpp"
#include "ibs/devices/drives.hpp"
#include "ibs/lustbus/byte_log.hpp"
#include "ibs/pcap/pcap_file.hpp"
#include "ibs/serial/capture.hpp"

namespace ibs::cli {

namespace lb = ::ibs::lustbus;

namespace {

constexpr int kExitOk = 0;
constexpr int kExitBadInput = 2;

// How much of a file is read to tell its kind.
constexpr std::size_t kSniffBytes = 64 * 1024;

// Seconds since the first packet, as a byte log counts them: "0.020601".
std::string seconds(Time t) {
  const auto us = std::chrono::duration_cast<std::chrono::microseconds>(t).count();
  char b[32];
  std::snprintf(b, sizeof b, "%lld.%06lld", static_cast<long long>(us / 1000000), static_cast<long long>(us % 1000000));
  return b;
}

// A pcap timestamp (nanoseconds since 1970) as UTC: "2025-03-01 10:15:02.123456 UTC".
std::string utc(Time t) {
  const auto us = std::chrono::duration_cast<std::chrono::microseconds>(t).count();
  const std::time_t s = us / 1000000;
  std::tm tm{};
  char date[40] = "";
  if (gmtime_r(&s, &tm) != nullptr) std::strftime(date, sizeof date, "%Y-%m-%d %H:%M:%S", &tm);
  char b[64];
  std::snprintf(b, sizeof b, "%s.%06lld UTC", date, static_cast<long long>(us % 1000000));
  return b;
}

}  // namespace

std::optional<int> decode_lustbus_log(const std::string& file, std::ostream& out, std::ostream& err) {
  // The first line tells; only then is the file read whole (bounded, regular files only), so that
  // a 2 GiB file of another kind is not read to look at its first line.
  try {
    const std::string head = read_text_head(file, kSniffBytes);
    const auto first = lines_of(head, head.size() < kSniffBytes);
    if (first.empty() || first.front() != lb::kByteLogHeader) return std::nullopt;
  } catch (const FileReadError&) {
    return std::nullopt;  // not looked at (not a regular file, unreadable): the trace reader says why
  }
  std::vector<std::string> lines;
  try {
    lines = lines_of(read_text_file(file));
  } catch (const FileReadError& e) {
    err << "ibs decode: " << file << ": " << e.what() << "\n";
    return kExitBadInput;
  }
  lines.erase(lines.begin());  // the header
  // The names, units and types of the parameters: the drives' tables, through the registry.
  const lb::ByteLogReading r = lb::read_byte_log(lines, devices::lustbus_parameter_lookup());
  if (r.error && r.error->line == 0) {
    err << "ibs decode: " << file << ": " << r.error->what << "; DFS-1 logs are read by eye\n";
    return kExitBadInput;
  }
  if (r.error) {
    err << "ibs decode: " << file << ":" << r.error->line << ": " << r.error->what
        << " (the byte log of docs/dfs1.md: <seconds> <tx|rx> <PORT> <hex bytes>)\n";
    return kExitBadInput;
  }
  out << file << ": LUSTBUS byte log, host = " << (r.host_tx ? "tx" : "rx") << " (" << r.host_port << ")\n"
      << r.text;
  return kExitOk;
}

std::optional<int> decode_line_capture(const std::string& file, std::ostream& out, std::ostream& err) {
  std::string bytes;
  try {
    const std::string head = read_text_head(file, 4);
    if (!pcap::looks_like_pcap(std::span(reinterpret_cast<const std::uint8_t*>(head.data()), head.size()))) {
      return std::nullopt;
    }
    bytes = read_text_file(file);
  } catch (const FileReadError&) {
    return std::nullopt;  // not looked at: the trace reader says why
  }
  const serial::LineCaptureReading r =
      serial::read_line_capture(std::span(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()));
  if (r.error) {
    err << "ibs decode: " << file << ": " << (r.error->packet > 0 ? "packet " + std::to_string(r.error->packet) + ": " : "")
        << r.error->what << "\n";
    return kExitBadInput;
  }
  const bool lustbus = r.protocol == serial::LineProtocol::lustbus;
  out << file << ": " << serial::to_string(r.protocol) << " capture (pcap, link type "
      << serial::linktype(r.protocol) << "), " << r.packets.size() << " packet(s)";
  if (!r.packets.empty()) out << " from " << utc(r.packets.front().at);
  out << "\n";
  const Time t0 = r.packets.empty() ? Time{0} : r.packets.front().at;
  if (lustbus) {
    std::vector<lb::LineBytes> chunks;
    chunks.reserve(r.packets.size());
    for (const auto& p : r.packets) chunks.push_back({seconds(p.at - t0), p.from == base::LineSide::host, p.bytes});
    out << lb::explain_line(chunks, devices::lustbus_parameter_lookup());
    return kExitOk;
  }
  devices::dfs1::FrameExplainer explainer;
  for (const auto& p : r.packets) {
    const bool host = p.from == base::LineSide::host;
    out << seconds(p.at - t0) << (host ? " host       " : " controller ") << explainer.explain(host, p.bytes) << "\n";
  }
  return kExitOk;
}

}  // namespace ibs::cli
