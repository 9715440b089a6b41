#include "ibs/can/cannelloni.hpp"

namespace ibs::can::cannelloni {

std::string_view to_string(DecodeStatus s) {
  switch (s) {
    case DecodeStatus::ok: return "ok";
    case DecodeStatus::truncated: return "truncated";
    case DecodeStatus::bad_version: return "bad version";
    case DecodeStatus::bad_op_code: return "bad op code";
    case DecodeStatus::out_full: return "output full";
    case DecodeStatus::trailing: return "trailing bytes";
  }
  return "?";
}

namespace {
std::size_t frame_size(const CanFrame& f) { return 4U + 1U + (f.rtr ? 0U : f.dlc); }
}  // namespace

std::size_t encoded_size(std::span<const CanFrame> frames) {
  std::size_t n = kHeaderSize;
  for (const auto& f : frames) n += frame_size(f);
  return n;
}

std::optional<std::size_t> encode(std::span<const CanFrame> frames, std::uint8_t sequence,
                                  std::span<std::uint8_t> out) {
  if (frames.size() > 0xFFFFU) return std::nullopt;
  const std::size_t size = encoded_size(frames);
  if (size > out.size()) return std::nullopt;
  out[0] = kVersion;
  out[1] = kOpData;
  out[2] = sequence;
  out[3] = static_cast<std::uint8_t>(frames.size() >> 8U);
  out[4] = static_cast<std::uint8_t>(frames.size() & 0xFFU);
  std::size_t p = kHeaderSize;
  for (const auto& f : frames) {
    if (!f.valid()) return std::nullopt;
    const std::uint32_t id = (f.id & 0x7FFU) | (f.rtr ? kRtrFlag : 0U);
    for (unsigned i = 0; i < 4; ++i) out[p++] = static_cast<std::uint8_t>(id >> (24U - 8U * i));
    out[p++] = f.dlc;
    if (!f.rtr) {
      for (std::size_t i = 0; i < f.dlc; ++i) out[p++] = f.data[i];
    }
  }
  return p;
}

DecodeResult decode(std::span<const std::uint8_t> d, std::span<CanFrame> out) {
  DecodeResult r;
  if (d.size() < kHeaderSize) {
    r.status = DecodeStatus::truncated;
    return r;
  }
  if (d[0] != kVersion) {
    r.status = DecodeStatus::bad_version;
    return r;
  }
  if (d[1] != kOpData) {
    r.status = DecodeStatus::bad_op_code;
    return r;
  }
  r.sequence = d[2];
  r.count = static_cast<std::uint16_t>((d[3] << 8U) | d[4]);
  std::size_t p = kHeaderSize;
  for (unsigned k = 0; k < r.count; ++k) {
    if (d.size() - p < 5) {
      r.status = DecodeStatus::truncated;
      return r;
    }
    const std::uint32_t id = (static_cast<std::uint32_t>(d[p]) << 24U) |
                             (static_cast<std::uint32_t>(d[p + 1]) << 16U) |
                             (static_cast<std::uint32_t>(d[p + 2]) << 8U) | d[p + 3];
    std::uint8_t len = d[p + 4];
    p += 5;
    bool fd = false;
    if ((len & kCanFdFrame) != 0) {
      fd = true;
      if (d.size() - p < 1) {
        r.status = DecodeStatus::truncated;
        return r;
      }
      ++p;  // the CAN FD flags byte
      len = static_cast<std::uint8_t>(len & ~kCanFdFrame);
    }
    const bool rtr = (id & kRtrFlag) != 0;
    const std::size_t data = rtr ? 0U : len;  // RTR frames have no data section
    if (d.size() - p < data) {
      r.status = DecodeStatus::truncated;
      return r;
    }
    const bool foreign = fd || (id & (kEffFlag | kErrFlag)) != 0 || len > canlust::kMaxDlc ||
                         (id & 0x1FFFF800U) != 0;
    if (foreign) {
      ++r.skipped;
    } else if (r.frames == out.size()) {
      r.status = DecodeStatus::out_full;
      return r;
    } else {
      CanFrame& f = out[r.frames++];
      f = CanFrame{};
      f.id = static_cast<std::uint16_t>(id & 0x7FFU);
      f.rtr = rtr;
      f.dlc = len;
      for (std::size_t i = 0; i < data; ++i) f.data[i] = d[p + i];
    }
    p += data;
  }
  if (p != d.size()) r.status = DecodeStatus::trailing;
  return r;
}

}  // namespace ibs::can::cannelloni
