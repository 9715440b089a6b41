#include "ibs/lustbus/receiver.hpp"

namespace ibs::lustbus {

std::string_view to_string(ReceiverState s) {
  switch (s) {
    case ReceiverState::idle:
      return "idle";
    case ReceiverState::address:
      return "address";
    case ReceiverState::enquiry_code:
      return "enquiry_code";
    case ReceiverState::enquiry_end:
      return "enquiry_end";
    case ReceiverState::select_code:
      return "select_code";
    case ReceiverState::select_equals:
      return "select_equals";
    case ReceiverState::select_value:
      return "select_value";
    case ReceiverState::select_bcc:
      return "select_bcc";
    case ReceiverState::deferred:
      return "deferred";
    case ReceiverState::answering:
      return "answering";
    case ReceiverState::ignoring:
      return "ignoring";
  }
  return "?";
}

std::string_view to_string(ReceiverEvent e) {
  switch (e) {
    case ReceiverEvent::none:
      return "none";
    case ReceiverEvent::reset:
      return "reset";
    case ReceiverEvent::enquiry:
      return "enquiry";
    case ReceiverEvent::select:
      return "select";
    case ReceiverEvent::broadcast:
      return "broadcast";
    case ReceiverEvent::checksum_error:
      return "checksum_error";
    case ReceiverEvent::dropped:
      return "dropped";
  }
  return "?";
}

std::string_view to_string(Reply r) {
  switch (r) {
    case Reply::text:
      return "text";
    case Reply::ack:
      return "ACK";
    case Reply::nak:
      return "NAK";
    case Reply::deferred:
      return "deferred";
    case Reply::none:
      return "none";
    case Reply::cut:
      return "cut";
  }
  return "?";
}

Receiver::Receiver(Responder& responder, Address own) : responder_(&responder), own_(own) {}

void Receiver::power_on() {
  state_ = ReceiverState::idle;
  event_ = ReceiverEvent::none;
  answer_pending_ = false;
  answer_.size = 0;
}

// 3: "No answer: improper telegram construction; incorrect received control characters".
void Receiver::drop() {
  state_ = ReceiverState::ignoring;
  event_ = ReceiverEvent::dropped;
  ++counters_.dropped;
}

namespace {
// A telegram begun and not complete (not idle, not waiting for EOT after an answer or a drop).
bool in_fragment(ReceiverState s) {
  switch (s) {
    case ReceiverState::address:
    case ReceiverState::enquiry_code:
    case ReceiverState::enquiry_end:
    case ReceiverState::select_code:
    case ReceiverState::select_equals:
    case ReceiverState::select_value:
    case ReceiverState::select_bcc: return true;
    case ReceiverState::idle:
    case ReceiverState::deferred:
    case ReceiverState::answering:
    case ReceiverState::ignoring: return false;
  }
  return false;
}
}  // namespace

inline void Receiver::silence(Time now) {
  // LB-D23: a fragment followed by silence is dropped; this character starts afresh.
  if (in_fragment(state_) && gap_ > Duration::zero() && now - last_char_at_ > gap_) {
    state_ = ReceiverState::idle;
    ++counters_.fragments;
  }
  last_char_at_ = now;
}

// The per-character machine of section 3 on a cursor: the members a character changes are held in
// locals while a chunk runs (a character stored into received_code_ or value_ may alias any member,
// so the compiler would reload them all after each). Every step that calls out -- a finished
// telegram, a drop -- puts the cursor back first and takes it again after, so the members are
// the truth wherever anything else can see them.
inline void Receiver::drop(Cursor& c) {
  c.state = ReceiverState::ignoring;
  c.event = ReceiverEvent::dropped;
  ++counters_.dropped;
}

inline void Receiver::receive_one(Cursor& c, std::uint8_t b, Time now) {
  c.event = ReceiverEvent::none;
  // 2.2: the byte after ETX is the BCC whatever its value — even EOT.
  if (c.state == ReceiverState::select_bcc) {
    put(c);
    finish_select(b, now);
    c = cursor();
    return;
  }
  // 3: EOT sets the state machine back to its start; an answer not yet sent is dropped.
  if (b == kEot) {
    if (answer_pending_ || c.state == ReceiverState::deferred) ++counters_.cut_answers;
    c.state = ReceiverState::idle;
    c.event = ReceiverEvent::reset;
    answer_pending_ = false;
    return;
  }
  switch (c.state) {
    case ReceiverState::idle: {
      const auto a = address_from_char(b);
      if (!a) {
        drop(c);
        return;
      }
      // 4.2: 0 every device, 31 every device (broadcast), else only the own address.
      if (*a == kAddressAny || *a == kAddressBroadcast || (*a == own_ && own_ != kAddressAny)) {
        address_ = *a;
        c.state = ReceiverState::address;
      } else {
        c.state = ReceiverState::ignoring;
      }
      return;
    }
    case ReceiverState::address:
      if (b == kStx) {  // 6.2 SELECT
        c.state = ReceiverState::select_code;
        c.code_pos = 0;
        c.bcc = 0;
        value_.clear();
      } else if (received_code_.set_digit(0, b)) {  // 6.1 ENQUIRY: EOT ADR CODE ENQ
        c.code_pos = 1;
        c.state = ReceiverState::enquiry_code;
      } else {
        drop(c);
      }
      return;
    case ReceiverState::enquiry_code:
      if (!received_code_.set_digit(c.code_pos, b)) {
        drop(c);
        return;
      }
      if (++c.code_pos == kCodeLength) c.state = ReceiverState::enquiry_end;
      return;
    case ReceiverState::enquiry_end:
      if (b != kEnq) {
        drop(c);
        return;
      }
      put(c);
      finish_enquiry(now);
      c = cursor();
      return;
    case ReceiverState::select_code:
      if (!received_code_.set_digit(c.code_pos, b)) {
        drop(c);
        return;
      }
      c.bcc ^= b;
      if (++c.code_pos == kCodeLength) c.state = ReceiverState::select_equals;
      return;
    case ReceiverState::select_equals:
      if (b != kEquals) {
        drop(c);
        return;
      }
      c.bcc ^= b;
      c.state = ReceiverState::select_value;
      return;
    case ReceiverState::select_value:
      if (b == kEtx) {
        c.bcc ^= b;
        c.state = ReceiverState::select_bcc;
        return;
      }
      // A frame character or a garbled one breaks the telegram; more than 100 characters is an
      // improper construction (LB-D4).
      if (!value_.push_back(b)) {
        drop(c);
        return;
      }
      c.bcc ^= b;
      return;
    case ReceiverState::select_bcc:  // handled above
    case ReceiverState::deferred:
    case ReceiverState::answering:
    case ReceiverState::ignoring:
      return;
  }
}

void Receiver::receive(std::uint8_t b, Time now) {
  silence(now);
  Cursor c = cursor();
  receive_one(c, b, now);
  put(c);
}

// 6.1: a whole ENQUIRY, ADR CODE ENQ, at `p` (7 characters) while the receiver is idle: when the
// ADR is one this device takes (4.2: 0, 31 or its own), the five characters after it digits and the
// seventh ENQ, the characters take it where receive_one() would -- enquiry_end with the ADR and
// CODE kept, event none -- and the seventh finishes it as there. Otherwise false, having changed
// nothing receive_one() would not set again (digits of a CODE it rewrites from its first): the
// chunk goes character by character.
inline bool Receiver::whole_enquiry(Cursor& c, const std::uint8_t* p, Time now) {
  const auto a = address_from_char(p[0]);
  if (!a || !(*a == kAddressAny || *a == kAddressBroadcast || (*a == own_ && own_ != kAddressAny))) {
    return false;
  }
  if (p[1 + kCodeLength] != kEnq) return false;
  for (std::size_t i = 0; i < kCodeLength; ++i) {
    if (!received_code_.set_digit(i, p[1 + i])) return false;
  }
  address_ = *a;
  c.state = ReceiverState::enquiry_end;
  c.event = ReceiverEvent::none;
  c.code_pos = kCodeLength;
  put(c);
  finish_enquiry(now);
  c = cursor();
  return true;
}

void Receiver::receive(std::span<const std::uint8_t> bytes, Time now) {
  if (bytes.empty()) return;
  silence(now);  // the characters after the first follow it with no silence
  Cursor c = cursor();
  constexpr std::size_t kEnquiryRest = 2 + kCodeLength;  // ADR CODE ENQ
  const std::uint8_t* p = bytes.data();
  const std::uint8_t* const end = p + bytes.size();
  while (p != end) {
    if (c.state == ReceiverState::idle && static_cast<std::size_t>(end - p) >= kEnquiryRest &&
        whole_enquiry(c, p, now)) {
      p += kEnquiryRest;
      continue;
    }
    receive_one(c, *p++, now);
  }
  put(c);
}

void Receiver::finish_enquiry(Time now) {
  // 4.2 / 9.1: no answer at the broadcast address; an ENQUIRY there makes no sense.
  if (address_ == kAddressBroadcast) {
    drop();
    return;
  }
  if (!responder_->listening(now)) {  // 8.1: booting, deaf
    drop();
    return;
  }
  code_ = received_code_;  // five digits, each checked as it came (6.1)
  const Context ctx{address_, now};
  ++counters_.enquiries;
  event_ = ReceiverEvent::enquiry;
  responder_->telegram_received(ctx);
  const EnquiryAnswer a = responder_->enquiry(code_, ctx);
  if (a.reply == Reply::deferred) {
    state_ = ReceiverState::deferred;
    deferred_enquiry_ = true;
    return;
  }
  prepare(a, now);
}

void Receiver::finish_select(std::uint8_t bcc_received, Time now) {
  const Context ctx{address_, now};
  if (!responder_->listening(now)) {  // 8.1: booting, deaf
    drop();
    return;
  }
  if (bcc_received != bcc_) {
    // 3: "ADR NAK: occurs with wrong BCC"; 9.2 bit 3. None at 31 (4.2).
    ++counters_.checksum_errors;
    event_ = ReceiverEvent::checksum_error;
    responder_->checksum_error(ctx);
    if (ctx.broadcast()) {
      state_ = ReceiverState::ignoring;
      return;
    }
    prepare(SelectAnswer::nak(), now);
    return;
  }
  code_ = received_code_;  // five digits, each checked as it came (6.2)
  responder_->telegram_received(ctx);
  const SelectAnswer a = responder_->select(code_, value_, ctx);
  if (ctx.broadcast()) {
    // 4.2: "Every device reacts to the position command without giving a receipt".
    ++counters_.broadcasts;
    event_ = ReceiverEvent::broadcast;
    state_ = ReceiverState::ignoring;
    return;
  }
  ++counters_.selects;
  event_ = ReceiverEvent::select;
  if (a.reply == Reply::deferred) {
    state_ = ReceiverState::deferred;
    deferred_enquiry_ = false;
    return;
  }
  prepare(a, now);
}

void Receiver::prepare(const EnquiryAnswer& a, Time now) {
  state_ = ReceiverState::answering;
  answer_pending_ = true;
  answer_at_ = now + a.reaction;
  switch (a.reply) {
    case Reply::text:
      encode_text_answer(answer_, address_, code_, a.value);  // 6.1: ADR STX CODE = VALUE ETX BCC
      return;
    case Reply::nak:
      answer_ = encode_nak(address_);
      return;
    case Reply::ack:       // not an answer to an ENQUIRY: the drive is wrong; say nothing
    case Reply::cut:
    case Reply::deferred:  // deferring a deferred answer
    case Reply::none:
      answer_pending_ = false;
      return;
  }
}

void Receiver::prepare(const SelectAnswer& a, Time now) {
  state_ = ReceiverState::answering;
  answer_pending_ = true;
  answer_at_ = now + a.reaction;
  switch (a.reply) {
    case Reply::ack:
      answer_ = encode_ack(address_);
      return;
    case Reply::nak:
      answer_ = encode_nak(address_);
      return;
    case Reply::cut:  // 8.1: the ADR goes out, the ACK does not
      answer_ = encode_ack(address_);
      answer_.size = 1;
      return;
    case Reply::text:
    case Reply::deferred:
    case Reply::none:
      answer_pending_ = false;
      return;
  }
}

bool Receiver::deliver_enquiry(const EnquiryAnswer& a, Time now) {
  if (state_ != ReceiverState::deferred || !deferred_enquiry_ || a.reply == Reply::deferred) {
    return false;
  }
  prepare(a, now);
  return true;
}

bool Receiver::deliver_select(const SelectAnswer& a, Time now) {
  if (state_ != ReceiverState::deferred || deferred_enquiry_ || a.reply == Reply::deferred) {
    return false;
  }
  prepare(a, now);
  return true;
}

std::optional<Time> Receiver::answer_due() const {
  if (!answer_pending_) return std::nullopt;
  return answer_at_;
}

std::span<const std::uint8_t> Receiver::take_answer(Time now) {
  if (!answer_pending_ || now < answer_at_) return {};
  answer_pending_ = false;
  ++counters_.answers;
  return answer_.span();
}

}  // namespace ibs::lustbus
