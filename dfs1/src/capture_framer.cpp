#include "ibs/dfs1/capture_framer.hpp"

#include <algorithm>

namespace ibs::dfs1 {

namespace {

using base::LineSide;
using base::LineTelegram;

// Noise is cut into packets of at most this many bytes.
constexpr std::size_t kMaxNoise = 256;

// The UID of a frame as sent: the byte after DLE STX (10H doubled).
std::optional<std::uint8_t> uid_of(const std::vector<std::uint8_t>& b) {
  if (b.size() < 3 || b[0] != kDle || b[1] != kStx) return std::nullopt;
  if (b[2] != kDle) return b[2];
  if (b.size() >= 4 && b[3] == kDle) return kDle;
  return std::nullopt;
}

}  // namespace

void CaptureFramer::emit(Side& s, std::uint8_t flags, std::vector<LineTelegram>& out) {
  if (s.t.bytes.empty()) return;
  s.t.flags |= flags;
  if ((s.t.flags & base::kTelegramNoise) == 0) s.t.address = uid_of(s.t.bytes);
  out.push_back(std::move(s.t));
  s.t = LineTelegram{};
}

void CaptureFramer::flush(Side& s, std::vector<LineTelegram>& out) {
  if (s.decoder.in_frame()) {
    emit(s, base::kTelegramCut, out);
  } else {
    emit(s, base::kTelegramNoise, out);  // noise, or a DLE that began nothing yet
  }
  s.decoder.reset();
}

void CaptureFramer::byte(Side& s, LineSide from, std::uint8_t b, Time at, std::vector<LineTelegram>& out) {
  const auto add = [&](std::uint8_t x) {
    if (s.t.bytes.empty()) {
      s.t.from = from;
      s.t.first = at;
    }
    s.t.bytes.push_back(x);
    s.t.last = at;
  };
  const bool was_in_frame = s.decoder.in_frame();
  const DecodeResult r = s.decoder.push(b);
  if (r.status == DecodeStatus::need_more) {
    if (!was_in_frame && s.decoder.in_frame() && s.t.bytes.size() > 1) {
      // DLE STX: a frame begins; what came before its DLE was noise.
      s.t.bytes.pop_back();
      emit(s, base::kTelegramNoise, out);
      add(kDle);
    }
    add(b);
    if (!s.decoder.in_frame() && s.decoder.at_rest() && s.t.bytes.size() >= kMaxNoise) {
      emit(s, base::kTelegramNoise, out);
    }
    return;
  }
  if (r.status == DecodeStatus::frame) {
    add(b);
    emit(s, 0, out);
    return;
  }
  switch (r.error) {
    case DecodeError::bad_checksum:
      add(b);
      emit(s, base::kTelegramCheckBad, out);
      return;
    case DecodeError::interrupted:
      // DLE STX inside a frame: the frame so far is cut, the DLE STX begins the next one.
      s.t.bytes.pop_back();
      emit(s, base::kTelegramCut, out);
      add(kDle);
      add(b);
      return;
    case DecodeError::checksum_not_doubled:
      // A CSM of 10H not doubled (D1): the frame ends at that CSM; this byte starts anew.
      emit(s, base::kTelegramCut, out);
      s.decoder.reset();
      byte(s, from, b, at, out);
      return;
    case DecodeError::too_short:
    case DecodeError::too_long:
    case DecodeError::lone_dle:
      add(b);
      emit(s, base::kTelegramCut, out);
      return;
  }
}

void CaptureFramer::feed(LineSide side, std::span<const std::uint8_t> bytes, Time at, std::vector<LineTelegram>& out) {
  if (bytes.empty()) return;
  Side& s = side == LineSide::host ? host_ : device_;
  // Half duplex: when one side speaks, what the other left pending has ended.
  flush(side == LineSide::host ? device_ : host_, out);
  for (const std::uint8_t b : bytes) byte(s, side, b, at, out);
}

void CaptureFramer::finish(std::vector<LineTelegram>& out) {
  Side* first = &host_;
  Side* second = &device_;
  if (!device_.t.bytes.empty() && (host_.t.bytes.empty() || device_.t.first < host_.t.first)) std::swap(first, second);
  flush(*first, out);
  flush(*second, out);
}

}  // namespace ibs::dfs1
