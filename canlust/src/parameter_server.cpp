#include <algorithm>
#include <cstring>

#include "ibs/canlust/parameter_channel.hpp"

namespace ibs::canlust {

std::string_view mode_name(std::uint8_t mode) {
  switch (mode) {
    case kModeWrite: return "SEL (write)";
    case kModeDescribe: return "ENQUIRY_List (describe)";
    case kModeRead: return "ENQ (read)";
    case kModeStringWrite: return "SELECT_String";
    case kModeStringRead: return "ENQUIRY_String";
    case kModeListEnd: return "List_End";
    default: return "unknown mode";
  }
}

std::string describe_status(std::uint8_t status) {
  if (status == kStatusOk) return "ok";
  static constexpr std::array<std::string_view, 8> kBits = {
      "bit 0", "watchdog", "unknown mode", "read not permitted",
      "repeat", "unknown parameter", "change not permitted", "impermissible value"};
  std::string s;
  for (unsigned b = 0; b < 8; ++b) {
    if ((status & (1U << b)) == 0) continue;
    if (!s.empty()) s += ", ";
    s += kBits[b];
  }
  return s;
}

FixedString FixedString::from(std::string_view s) {
  FixedString f;
  const std::size_t n = std::min(s.size(), kMaxStringChars);
  std::copy_n(s.data(), n, f.chars.data());
  f.length = static_cast<std::uint8_t>(n);
  return f;
}

std::string_view to_string(ServerState s) {
  switch (s) {
    case ServerState::idle: return "idle";
    case ServerState::string_read: return "string read";
    case ServerState::string_write: return "string write";
  }
  return "?";
}

void ParameterServer::reset() {
  state_ = ServerState::idle;
  pending_.reset();
  busy_reply_.reset();
}

void ParameterServer::block_error(const ParameterTelegram& r, Time now) {
  // public-facts "String transfer": a wrong block counter resets the drive's string machine;
  // the status it answers is not public: 80H (decision D11).
  ++counters_.block_errors;
  state_ = ServerState::idle;
  reply(r, kStatusImpermissibleValue, r.data, now);
}

// receive()'s general path: every mode (the header's inline part serves a read with no reply
// pending the same way).
void ParameterServer::receive_general(const ParameterTelegram& r, Time now) {
  ++counters_.requests;
  if (pending_) {
    // One request at a time per drive (CAL): a second one while the first is unanswered gets
    // "repeat" at once (decision D12); the first reply still follows.
    ++counters_.busy;
    busy_reply_ = ParameterTelegram{r.parameter, kStatusRepeat, r.data, r.block};
    return;
  }
  switch (r.code) {
    case kModeStringRead: string_read(r, now); return;
    case kModeStringWrite: string_write(r, now); return;
    case kModeListEnd: list_end(r, now); return;
    default: break;
  }
  state_ = ServerState::idle;  // any other request abandons an open string transfer
  switch (r.code) {
    case kModeRead: {
      const auto v = drive_->read(r.parameter, r.block, now);
      reply(r, v.status, v.status == kStatusOk ? v.value : 0U, now + v.delay);
      return;
    }
    case kModeWrite: {
      const auto a = drive_->write(r.parameter, r.block, r.data, now);
      reply(r, a.status, r.data, now + a.delay);
      return;
    }
    case kModeDescribe: {
      const auto v = drive_->describe(r.parameter, r.block, now);
      reply(r, v.status, v.status == kStatusOk ? v.value : 0U, now + v.delay);
      return;
    }
    default:
      reply(r, kStatusUnknownMode, r.data, now);
      return;
  }
}

void ParameterServer::string_read(const ParameterTelegram& r, Time now) {
  if (r.block == 0) {
    // 4.5.x reading: block 0 starts (or restarts) the transfer and fetches the string.
    buffer_.fill(0);
    const auto s = drive_->read_string(r.parameter, std::span(buffer_.data(), kMaxStringChars), now);
    if (s.status != kStatusOk) {
      state_ = ServerState::idle;
      reply(r, s.status, 0, now + s.delay);
      return;
    }
    const std::size_t len = std::min<std::size_t>(s.length, kMaxStringChars);
    std::fill(buffer_.begin() + static_cast<std::ptrdiff_t>(len), buffer_.end(), '\0');
    buffer_bytes_ = len + 1;  // with the terminator
    string_parameter_ = r.parameter;
    state_ = ServerState::string_read;
    next_block_ = 1;
    const auto d = get_le32(std::span(reinterpret_cast<const std::uint8_t*>(buffer_.data()), 4));
    checksum_ = d;
    reply(r, kStatusOk, d, now + s.delay);
    return;
  }
  if (state_ != ServerState::string_read || r.parameter != string_parameter_ ||
      r.block != next_block_) {
    block_error(r, now);
    return;
  }
  const std::size_t blocks = (buffer_bytes_ + 3) / 4;
  if (r.block < blocks) {
    const auto* p = reinterpret_cast<const std::uint8_t*>(buffer_.data()) + 4U * r.block;
    const auto d = get_le32(std::span(p, 4));
    checksum_ = string_checksum_step(checksum_, d);
    ++next_block_;
    reply(r, kStatusOk, d, now);
    return;
  }
  // The block after the one with the terminator: List_End and the checksum (decision D8: XOR of
  // the data words of every block before it, as for writing).
  state_ = ServerState::idle;
  reply(r, kStatusListEnd, checksum_, now);
}

void ParameterServer::string_write(const ParameterTelegram& r, Time now) {
  if (r.block == 0) {
    // 4.5.x writing: block 0 is a handshake only; its data bytes are not relevant.
    const auto a = drive_->begin_string_write(r.parameter, now);
    if (a.status != kStatusOk) {
      state_ = ServerState::idle;
      reply(r, a.status, r.data, now + a.delay);
      return;
    }
    state_ = ServerState::string_write;
    string_parameter_ = r.parameter;
    next_block_ = 1;
    buffer_.fill(0);
    buffer_bytes_ = 0;
    checksum_ = 0;
    overflow_ = false;
    reply(r, kStatusOk, r.data, now + a.delay);
    return;
  }
  if (state_ != ServerState::string_write || r.parameter != string_parameter_ ||
      r.block != next_block_) {
    block_error(r, now);
    return;
  }
  if (buffer_bytes_ + 4 > kMaxStringBytes) {
    overflow_ = true;  // p. 47: more than 100 characters: not saved, error at the end
  } else {
    put_le32(std::span(reinterpret_cast<std::uint8_t*>(buffer_.data()) + buffer_bytes_, 4), r.data);
    buffer_bytes_ += 4;
  }
  checksum_ = string_checksum_step(checksum_, r.data);
  ++next_block_;
  reply(r, kStatusOk, r.data, now);  // every block is echoed
}

void ParameterServer::list_end(const ParameterTelegram& r, Time now) {
  if (state_ != ServerState::string_write || r.parameter != string_parameter_ ||
      r.block != next_block_) {
    block_error(r, now);
    return;
  }
  state_ = ServerState::idle;
  if (overflow_) {
    ++counters_.overlong_strings;
    reply(r, kStatusImpermissibleValue, r.data, now);
    return;
  }
  if (r.data != checksum_) {
    // The checksum status is not public: 80H "impermissible value" (decision D11).
    ++counters_.checksum_errors;
    reply(r, kStatusImpermissibleValue, r.data, now);
    return;
  }
  const auto* end = std::find(buffer_.data(), buffer_.data() + buffer_bytes_, '\0');
  const std::string_view text(buffer_.data(), static_cast<std::size_t>(end - buffer_.data()));
  const auto a = drive_->write_string(r.parameter, text, now);
  reply(r, a.status, r.data, now + a.delay);
}

Time ParameterServer::next_deadline() const {
  if (busy_reply_) return Time::min();
  if (pending_) return pending_at_;
  return Time::max();
}

}  // namespace ibs::canlust
