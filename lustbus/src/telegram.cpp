#include "ibs/lustbus/telegram.hpp"

namespace ibs::lustbus {

namespace {

void push_code(Frame& f, const Code& c) {
  for (std::size_t i = 0; i < kCodeLength; ++i) f.push(static_cast<std::uint8_t>(c.digit(i)));
}

// CODE = VALUE ETX BCC, the BCC over CODE..ETX (2.2).
void push_text(Frame& f, const Code& c, const Value& v) {
  const std::size_t from = f.size;
  push_code(f, c);
  f.push(kEquals);
  for (const char ch : v.view()) f.push(static_cast<std::uint8_t>(ch));
  f.push(kEtx);
  f.push(bcc({f.bytes.data() + from, f.size - from}));
}

}  // namespace

std::uint8_t text_bcc(const Code& c, const Value& v) {
  std::uint8_t x = kEquals ^ kEtx;
  for (std::size_t i = 0; i < kCodeLength; ++i) x ^= static_cast<std::uint8_t>(c.digit(i));
  for (const char ch : v.view()) x ^= static_cast<std::uint8_t>(ch);
  return x;
}

Frame encode_enquiry(Address a, const Code& c) {
  Frame f;
  f.push(kEot);
  f.push(address_char(a));
  push_code(f, c);
  f.push(kEnq);
  return f;
}

Frame encode_select(Address a, const Code& c, const Value& v) {
  Frame f;
  f.push(kEot);
  f.push(address_char(a));
  f.push(kStx);
  push_text(f, c, v);
  return f;
}

Frame encode_text_answer(Address a, const Code& c, const Value& v) {
  Frame f;
  f.push(address_char(a));
  f.push(kStx);
  push_text(f, c, v);
  return f;
}

Frame encode_ack(Address a) {
  Frame f;
  f.push(address_char(a));
  f.push(kAck);
  return f;
}

Frame encode_nak(Address a) {
  Frame f;
  f.push(address_char(a));
  f.push(kNak);
  return f;
}

std::string_view to_string(AnswerKind k) {
  switch (k) {
    case AnswerKind::none:
      return "none";
    case AnswerKind::text:
      return "text";
    case AnswerKind::ack:
      return "ACK";
    case AnswerKind::nak:
      return "NAK";
  }
  return "?";
}

std::string_view to_string(AnswerError e) {
  switch (e) {
    case AnswerError::none:
      return "none";
    case AnswerError::garbled:
      return "garbled character";
    case AnswerError::wrong_address:
      return "wrong address";
    case AnswerError::unexpected:
      return "unexpected character";
    case AnswerError::wrong_kind:
      return "wrong kind of answer";
    case AnswerError::wrong_code:
      return "wrong CODE";
    case AnswerError::value_too_long:
      return "VALUE longer than 100 characters";
    case AnswerError::bad_bcc:
      return "wrong BCC";
    case AnswerError::incomplete:
      return "incomplete answer";
    case AnswerError::no_answer:
      return "no answer";
    case AnswerError::line_busy:
      return "the line never fell quiet";
  }
  return "?";
}

void AnswerDecoder::start(Address a, const Code& c, Expect e, std::size_t binary_prefix) {
  binary_prefix_ = binary_prefix;
  address_ = a;
  code_ = c;
  expect_ = e;
  step_ = Step::address;
  status_ = Status::need_more;
  kind_ = AnswerKind::none;
  error_ = AnswerError::none;
  value_.clear();
  code_pos_ = 0;
  bcc_ = 0;
  count_ = 0;
}

AnswerDecoder::Status AnswerDecoder::fail(AnswerError e) {
  error_ = e;
  step_ = Step::finished;
  status_ = Status::error;
  return status_;
}

AnswerDecoder::Status AnswerDecoder::feed(std::uint8_t b) {
  if (status_ != Status::need_more) return status_;
  ++count_;
  // The BCC may be any byte, a garbled one included (then it cannot match).
  if (step_ == Step::bcc) {
    if (b != bcc_) return fail(AnswerError::bad_bcc);
    kind_ = AnswerKind::text;
    step_ = Step::finished;
    status_ = Status::done;
    return status_;
  }
  if (is_garbled(b)) return fail(AnswerError::garbled);
  switch (step_) {
    case Step::address:
      // 6.1.1: the device answers with the ADR it was addressed with ('@' at address 0).
      if (!address_from_char(b)) return fail(AnswerError::unexpected);
      if (b != address_char(address_)) return fail(AnswerError::wrong_address);
      step_ = Step::after_address;
      return status_;
    case Step::after_address:
      if (b == kNak) {
        kind_ = AnswerKind::nak;
        step_ = Step::finished;
        status_ = Status::done;
        return status_;
      }
      if (b == kAck) {
        if (expect_ != Expect::ack_or_nak) return fail(AnswerError::wrong_kind);
        kind_ = AnswerKind::ack;
        step_ = Step::finished;
        status_ = Status::done;
        return status_;
      }
      if (b == kStx) {
        if (expect_ != Expect::text_or_nak) return fail(AnswerError::wrong_kind);
        step_ = Step::code;
        return status_;
      }
      return fail(AnswerError::unexpected);
    case Step::code:
      if (b < '0' || b > '9') return fail(AnswerError::unexpected);
      bcc_ ^= b;
      if (static_cast<char>(b) != code_.digit(code_pos_)) return fail(AnswerError::wrong_code);
      if (++code_pos_ == kCodeLength) step_ = Step::equals;
      return status_;
    case Step::equals:
      if (b != kEquals) return fail(AnswerError::unexpected);
      bcc_ ^= b;
      step_ = Step::value;
      return status_;
    case Step::value:
      if (value_.size() < binary_prefix_) {  // LB-D10: a known number of binary bytes first
        if (!value_.push_binary(b)) return fail(AnswerError::value_too_long);
        bcc_ ^= b;
        return status_;
      }
      if (b == kEtx) {
        bcc_ ^= b;
        step_ = Step::bcc;
        return status_;
      }
      if (!is_value_char(b)) return fail(AnswerError::unexpected);
      if (!value_.push_back(b)) return fail(AnswerError::value_too_long);
      bcc_ ^= b;
      return status_;
    case Step::bcc:
    case Step::finished:
      break;
  }
  return fail(AnswerError::unexpected);
}

}  // namespace ibs::lustbus
