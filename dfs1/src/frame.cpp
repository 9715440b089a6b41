#include "ibs/dfs1/frame.hpp"

#include <algorithm>

namespace ibs::dfs1 {

std::uint32_t Frame::value_at(std::size_t offset) const {
  if (offset + 4 > size) return 0;
  return get_u32(std::span<const std::uint8_t, 4>(data.data() + offset, 4));
}

bool operator==(const Frame& a, const Frame& b) {
  return a.uid == b.uid && a.code == b.code && a.size == b.size &&
         std::equal(a.data.begin(), a.data.begin() + a.size, b.data.begin());
}

Frame make_frame(std::uint8_t uid, std::uint8_t code, std::span<const std::uint8_t> data) {
  Frame f;
  f.uid = uid;
  f.code = code;
  const std::size_t n = std::min(data.size(), kMaxData);
  std::copy_n(data.begin(), n, f.data.begin());
  f.size = static_cast<std::uint8_t>(n);
  return f;
}

Frame make_ack(std::uint8_t uid, std::span<const std::uint8_t> data) {
  return make_frame(uid, kAck, data);
}

Frame make_nak(std::uint8_t uid, ErrorCode error) {
  const std::array<std::uint8_t, 1> err = {static_cast<std::uint8_t>(error)};
  return make_frame(uid, kNak, err);
}

std::uint8_t checksum(const Frame& f) {
  // DFS-1 manual, note 2: 01 + 82 + 00 + 00 + 10 + 00 = 93, 2's complement = 6D.
  unsigned sum = f.uid + f.code;
  for (std::uint8_t b : f.payload()) sum += b;
  return static_cast<std::uint8_t>(0x100U - (sum & 0xFFU));
}

namespace {

void put_stuffed(EncodedFrame& out, std::uint8_t b) {
  out.bytes[out.size++] = b;
  if (b == kDle) out.bytes[out.size++] = kDle;  // "put the datum in twice" (DFS-1 manual, note 2)
}

}  // namespace

EncodedFrame encode(const Frame& f) {
  EncodedFrame out;
  out.bytes[out.size++] = kDle;
  out.bytes[out.size++] = kStx;
  put_stuffed(out, f.uid);
  put_stuffed(out, f.code);
  for (std::uint8_t b : f.payload()) put_stuffed(out, b);
  out.bytes[out.size++] = kDle;
  out.bytes[out.size++] = kEtx;
  put_stuffed(out, checksum(f));  // decision D1: a CSM of 10H is doubled too
  return out;
}

std::string_view to_string(DecodeError e) {
  switch (e) {
    case DecodeError::bad_checksum:
      return "bad checksum";
    case DecodeError::too_short:
      return "frame too short";
    case DecodeError::too_long:
      return "frame too long";
    case DecodeError::lone_dle:
      return "lone DLE in frame";
    case DecodeError::checksum_not_doubled:
      return "checksum 10H not doubled";
    case DecodeError::interrupted:
      return "frame interrupted by DLE STX";
  }
  return "unknown decode error";
}

void FrameDecoder::reset() {
  state_ = State::hunt;
  body_size_ = 0;
  sum_ = 0;
}

void FrameDecoder::start() {
  state_ = State::body;
  body_size_ = 0;
  sum_ = 0;
  frame_ = Frame{};
}

DecodeResult FrameDecoder::finish(std::uint8_t csm) {
  state_ = State::hunt;
  if (static_cast<std::uint8_t>(sum_ + csm) != 0) {
    return {DecodeStatus::error, DecodeError::bad_checksum};
  }
  return {DecodeStatus::frame, DecodeError::bad_checksum};
}

DecodeResult FrameDecoder::push(std::uint8_t byte) {
  constexpr DecodeResult kNeedMore{};
  switch (state_) {
    case State::hunt:
      if (byte == kDle) {
        state_ = State::hunt_dle;
      } else {
        ++garbage_;
      }
      return kNeedMore;
    case State::hunt_dle:
      if (byte == kStx) {
        start();
      } else {
        // DLE DLE is a stuffed datum of a frame we joined late; DLE x is noise.
        garbage_ += 2;
        state_ = State::hunt;
      }
      return kNeedMore;
    case State::body:
      if (byte == kDle) {
        state_ = State::body_dle;
        return kNeedMore;
      }
      break;
    case State::body_dle:
      if (byte == kStx) {
        start();
        return {DecodeStatus::error, DecodeError::interrupted};
      }
      if (byte == kEtx) {
        if (body_size_ < 2) {
          state_ = State::hunt;
          return {DecodeStatus::error, DecodeError::too_short};
        }
        state_ = State::checksum;
        return kNeedMore;
      }
      if (byte != kDle) {
        // "a single 10h is the DLE" (DFS-1 manual, note 2): DLE then data is a broken frame.
        state_ = State::hunt;
        ++garbage_;
        return {DecodeStatus::error, DecodeError::lone_dle};
      }
      state_ = State::body;
      break;  // a doubled DLE: one 10H datum
    case State::checksum:
      if (byte == kDle) {
        state_ = State::checksum_dle;
        return kNeedMore;
      }
      return finish(byte);
    case State::checksum_dle:
      if (byte == kDle) return finish(kDle);
      state_ = State::hunt;
      ++garbage_;
      return {DecodeStatus::error, DecodeError::checksum_not_doubled};
  }
  // A body byte (unstuffed).
  if (body_size_ >= 2 + kMaxData) {
    state_ = State::hunt;
    return {DecodeStatus::error, DecodeError::too_long};
  }
  if (body_size_ == 0) {
    frame_.uid = byte;
  } else if (body_size_ == 1) {
    frame_.code = byte;
  } else {
    frame_.data[body_size_ - 2] = byte;
    frame_.size = static_cast<std::uint8_t>(body_size_ - 1);
  }
  ++body_size_;
  sum_ = static_cast<std::uint8_t>(sum_ + byte);
  return kNeedMore;
}

}  // namespace ibs::dfs1
