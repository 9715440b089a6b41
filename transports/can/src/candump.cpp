#include "ibs/can/candump.hpp"

#include <charconv>
#include <cstdio>

namespace ibs::can {

namespace {

bool is_integer(std::string_view s) {
  long long v = 0;
  const char* last = s.data() + s.size();
  const auto r = std::from_chars(s.data(), last, v);
  return !s.empty() && r.ec == std::errc{} && r.ptr == last;
}

std::string_view trimmed(std::string_view line) {
  while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.remove_suffix(1);
  return line;
}

bool blank(const std::string& l) { return l.find_first_not_of(" \t\r") == std::string::npos; }

CandumpParsed refused(std::string_view why) { return {std::nullopt, why}; }

}  // namespace

std::string candump_line(const canlust::CanFrame& f, std::chrono::system_clock::time_point at,
                         std::string_view interface_name) {
  const auto us = std::chrono::duration_cast<std::chrono::microseconds>(at.time_since_epoch()).count();
  char head[64];
  std::snprintf(head, sizeof head, "(%lld.%06lld) ", static_cast<long long>(us / 1000000),
                static_cast<long long>(us % 1000000));
  char id[8];
  std::snprintf(id, sizeof id, "%03X#", static_cast<unsigned>(f.id));
  std::string s = head + std::string(interface_name) + " " + id;
  if (f.rtr) {
    s += "R";
    if (f.dlc > 0) s += std::to_string(f.dlc);
    return s;
  }
  for (const auto b : f.payload()) {
    char h[4];
    std::snprintf(h, sizeof h, "%02X", static_cast<unsigned>(b));
    s += h;
  }
  return s;
}

CandumpParsed read_candump_line(std::string_view line) {
  line = trimmed(line);
  if (line.size() < 4 || line[0] != '(') return refused("it does not begin with '(' and the time");
  const auto close = line.find(')');
  if (close == std::string_view::npos) return refused("no ')' after the time");
  CandumpRecord r;
  r.time = std::string(line.substr(1, close - 1));
  const auto dot = r.time.find('.');
  if (dot == std::string::npos || !is_integer(std::string_view(r.time).substr(0, dot)) ||
      !is_integer(std::string_view(r.time).substr(dot + 1))) {
    return refused("the time is not SECONDS.MICROS");
  }
  std::string_view rest = line.substr(close + 1);
  if (rest.empty() || rest[0] != ' ') return refused("no blank after the time");
  rest.remove_prefix(1);
  const auto sp = rest.find(' ');
  if (sp == std::string_view::npos || sp == 0) return refused("no interface name and frame after the time");
  r.interface_name = std::string(rest.substr(0, sp));
  const std::string_view frame = rest.substr(sp + 1);
  const auto hash = frame.find('#');
  if (hash == std::string_view::npos || hash == 0) return refused("the frame is not ID#DATA");
  const std::string_view id = frame.substr(0, hash);
  const std::string_view data = frame.substr(hash + 1);
  unsigned idv = 0;
  const auto rid = std::from_chars(id.data(), id.data() + id.size(), idv, 16);
  if (rid.ec != std::errc{} || rid.ptr != id.data() + id.size()) return refused("the identifier is not hex");
  if (id.size() > 3 || (!data.empty() && data[0] == '#')) {
    r.classic = false;  // an extended identifier or a CAN FD frame
    return {std::move(r), {}};
  }
  if (idv > canlust::kMaxStandardId) return refused("a three-digit identifier above 7FF");
  r.frame.id = static_cast<std::uint16_t>(idv);
  if (!data.empty() && (data[0] == 'R' || data[0] == 'r')) {
    r.frame.rtr = true;
    if (data.size() == 2 && data[1] >= '0' && data[1] <= '8') {
      r.frame.dlc = static_cast<std::uint8_t>(data[1] - '0');
    } else if (data.size() != 1) {
      return refused("a remote frame's length is not one digit 0..8");
    }
    return {std::move(r), {}};
  }
  constexpr std::string_view kBadData = "the data is not 0..8 bytes of two hex digits each";
  if (data.size() % 2 != 0 || data.size() > 2 * canlust::kMaxDlc) return refused(kBadData);
  for (std::size_t i = 0; i < data.size(); i += 2) {
    unsigned b = 0;
    const auto rb = std::from_chars(data.data() + i, data.data() + i + 2, b, 16);
    if (rb.ec != std::errc{} || rb.ptr != data.data() + i + 2) return refused(kBadData);
    r.frame.data[i / 2] = static_cast<std::uint8_t>(b);
  }
  r.frame.dlc = static_cast<std::uint8_t>(data.size() / 2);
  return {std::move(r), {}};
}

std::optional<CandumpRecord> parse_candump_line(std::string_view line) {
  return read_candump_line(line).record;
}

CandumpLog read_candump_log(std::span<const std::string> lines) {
  CandumpLog log;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string& l = lines[i];
    if (blank(l)) continue;
    CandumpParsed p = read_candump_line(l);
    if (!p.record) {
      log.error = CandumpError{i + 1, l, std::string(p.error)};
      return log;
    }
    log.entries.push_back({i + 1, std::string(trimmed(l)), std::move(*p.record)});
  }
  return log;
}

bool is_candump_log(std::span<const std::string> lines) {
  for (const std::string& l : lines) {
    if (!blank(l)) return read_candump_line(l).record.has_value();
  }
  return false;
}

}  // namespace ibs::can
