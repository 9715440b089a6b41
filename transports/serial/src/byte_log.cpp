#include "ibs/serial/byte_log.hpp"

#include <array>
#include <cstdio>
#include <stdexcept>

namespace ibs::serial {

std::string format_bytes(std::span<const std::uint8_t> bytes) {
  static constexpr std::array<char, 16> kHex = {'0', '1', '2', '3', '4', '5', '6', '7',
                                                '8', '9', 'A', 'B', 'C', 'D', 'E', 'F'};
  std::string s;
  s.reserve(bytes.size() * 3);
  for (std::uint8_t b : bytes) {
    if (!s.empty()) s += ' ';
    s += kHex[b >> 4];
    s += kHex[b & 0x0F];
  }
  return s;
}

ByteLog::ByteLog(const std::string& path) : file_(path), out_(&file_), start_(std::chrono::steady_clock::now()) {
  if (!file_) throw std::runtime_error("log " + path + ": cannot open for writing");
  *out_ << "ibs-serial-log 1\n" << std::flush;
}

ByteLog::ByteLog(std::ostream& out) : out_(&out), start_(std::chrono::steady_clock::now()) {
  *out_ << "ibs-serial-log 1\n" << std::flush;
}

void ByteLog::record(Direction d, std::string_view port, std::span<const std::uint8_t> bytes) {
  const auto us = std::chrono::duration_cast<std::chrono::microseconds>(
                      std::chrono::steady_clock::now() - start_)
                      .count();
  std::array<char, 32> t{};
  std::snprintf(t.data(), t.size(), "%lld.%06lld", static_cast<long long>(us / 1000000),
                static_cast<long long>(us % 1000000));
  *out_ << t.data() << (d == Direction::tx ? " tx " : " rx ") << port << ' ' << format_bytes(bytes)
       << '\n'
       << std::flush;
}

}  // namespace ibs::serial
