#include "ibs/dfs1/controller.hpp"

#include <algorithm>

namespace ibs::dfs1 {

Reply Reply::ack(std::span<const std::uint8_t> d) {
  Reply r;
  r.kind = Kind::ack;
  const std::size_t n = std::min(d.size(), kMaxData);
  std::copy_n(d.begin(), n, r.data.begin());
  r.size = static_cast<std::uint8_t>(n);
  return r;
}

Reply Reply::ack_value(std::uint32_t v) {
  std::array<std::uint8_t, 4> d{};
  put_u32(d, v);
  return ack(d);
}

Reply Reply::nak(ErrorCode e) {
  Reply r;
  r.kind = Kind::nak;
  r.error = e;
  return r;
}

void ControllerReceiver::receive(std::uint8_t byte, Time now, RequestHandler& handler) {
  // D13: what a silent host left half-sent is dropped; this byte starts afresh.
  if (!decoder_.at_rest() && gap_ > Duration::zero() && now - last_byte_at_ > gap_) {
    decoder_.reset();
    ++counters_.fragments;
  }
  last_byte_at_ = now;
  const DecodeResult r = decoder_.push(byte);
  if (r.status == DecodeStatus::error) {
    ++counters_.decode_errors;
  } else if (r.status == DecodeStatus::frame) {
    on_frame(decoder_.frame(), now, handler);
  }
}

void ControllerReceiver::receive(std::span<const std::uint8_t> bytes, Time now,
                                 RequestHandler& handler) {
  for (std::uint8_t b : bytes) receive(b, now, handler);
}

void ControllerReceiver::restart() {
  decoder_.reset();
  reply_ = EncodedFrame{};
  sent_ = 0;
}

void ControllerReceiver::on_frame(const Frame& f, Time now, RequestHandler& handler) {
  const bool global = f.uid == kGlobalUid;
  const CommandInfo* row = find_command(f.code);
  if (global) {
    // Notes: UID 00 only with command 83, and no response. Anything else to UID 0 is ignored.
    if (row == nullptr || row->command != Command::execute_speed || f.size != 0) {
      ++counters_.foreign;
      return;
    }
    ++counters_.requests;
    ++counters_.globals;
    (void)handler.handle(f, true, now);
    return;
  }
  // Responses (ACK/NAK) of other controllers and requests for other UIDs: no answer.
  if (f.uid != uid_ || f.code == kAck || f.code == kNak) {
    ++counters_.foreign;
    return;
  }
  ++counters_.requests;
  if (replying()) ++counters_.dropped_replies;
  // The handler may change the UID (parameter 1) or the turnaround (56): they apply from the next
  // request on.
  const std::uint8_t uid = uid_;
  const Duration turnaround = turnaround_;
  Reply reply = (row == nullptr || f.size != row->request_size)
                    ? Reply::nak(ErrorCode::illegal_command)
                    : handler.handle(f, false, now);
  switch (reply.kind) {
    case Reply::Kind::ack:
      reply_ = encode(make_ack(uid, std::span<const std::uint8_t>(reply.data.data(), reply.size)));
      break;
    case Reply::Kind::nak:
      reply_ = encode(make_nak(uid, reply.error));
      break;
    case Reply::Kind::none:
      reply_ = EncodedFrame{};
      break;
  }
  sent_ = 0;
  due_ = now + turnaround;
}

std::span<const std::uint8_t> ControllerReceiver::pending(Time now) const {
  if (!replying() || now < due_) return {};
  return reply_.span().subspan(sent_);
}

void ControllerReceiver::consume(std::size_t n) {
  sent_ = std::min(reply_.size, sent_ + n);
}

std::optional<Time> ControllerReceiver::next_deadline() const {
  if (!replying()) return std::nullopt;
  return due_;
}

}  // namespace ibs::dfs1
