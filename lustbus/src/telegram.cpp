#include "ibs/lustbus/telegram.hpp"

#include <cstring>

namespace ibs::lustbus {

std::uint8_t text_bcc(const Code& c, const Value& v) {
  std::uint8_t x = kEquals ^ kEtx;
  for (std::size_t i = 0; i < kCodeLength; ++i) x ^= static_cast<std::uint8_t>(c.digit(i));
  for (const char ch : v.view()) x ^= static_cast<std::uint8_t>(ch);
  return x;
}

namespace {

// Fills a frame with its size in a register: every byte stored through a uint8_t could change
// `Frame::size` as far as the compiler knows, so Frame::push reloads it each time.
class Writer {
 public:
  explicit Writer(Frame& f) : f_(f) {}
  ~Writer() { f_.size = static_cast<std::uint8_t>(n_); }
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  void push(std::uint8_t b) { f_.bytes[n_++] = b; }
  void code(const Code& c) {
    std::memcpy(f_.bytes.data() + n_, c.text().data(), kCodeLength);  // five digits at once
    n_ += kCodeLength;
  }
  // CODE = VALUE ETX BCC, the BCC over CODE..ETX (2.2).
  // The BCC is formed while the characters are written, in one pass: the XOR text_bcc() forms.
  void text(const Code& c, const Value& v) {
    std::uint8_t x = kEquals ^ kEtx;
    code(c);
    for (const char d : c.text()) x ^= static_cast<std::uint8_t>(d);
    push(kEquals);
    for (const char ch : v.view()) {
      push(static_cast<std::uint8_t>(ch));
      x ^= static_cast<std::uint8_t>(ch);
    }
    push(kEtx);
    push(x);
  }

 private:
  Frame& f_;
  std::size_t n_ = 0;
};

}  // namespace

void encode_enquiry(Frame& f, Address a, const Code& c) {
  Writer w(f);
  w.push(kEot);
  w.push(address_char(a));
  w.code(c);
  w.push(kEnq);
}

void encode_select(Frame& f, Address a, const Code& c, const Value& v) {
  Writer w(f);
  w.push(kEot);
  w.push(address_char(a));
  w.push(kStx);
  w.text(c, v);
}

void encode_text_answer(Frame& f, Address a, const Code& c, const Value& v) {
  Writer w(f);
  w.push(address_char(a));
  w.push(kStx);
  w.text(c, v);
}

Frame encode_enquiry(Address a, const Code& c) {
  Frame f;
  encode_enquiry(f, a, c);
  return f;
}

Frame encode_select(Address a, const Code& c, const Value& v) {
  Frame f;
  encode_select(f, a, c, v);
  return f;
}

Frame encode_text_answer(Address a, const Code& c, const Value& v) {
  Frame f;
  encode_text_answer(f, a, c, v);
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
  status_ = Status::need_more;
  kind_ = AnswerKind::none;
  error_ = AnswerError::none;
  value_.clear();
  cursor_ = Cursor{};
}

AnswerDecoder::Status AnswerDecoder::fail(Cursor& c, AnswerError e) {
  error_ = e;
  c.step = Step::finished;
  status_ = Status::error;
  return status_;
}

AnswerDecoder::Status AnswerDecoder::done(Cursor& c, AnswerKind k) {
  kind_ = k;
  c.step = Step::finished;
  status_ = Status::done;
  return status_;
}

// One character while the answer needs more. The cursor (step, BCC, code position, count) is the
// caller's local copy, kept in registers across a run of characters: each character stored into
// the VALUE is a char store the compiler must assume could change any member.
inline AnswerDecoder::Status AnswerDecoder::feed_one(Cursor& c, std::uint8_t b) {
  ++c.count;
  // The BCC may be any byte, a garbled one included (then it cannot match).
  if (c.step == Step::bcc) {
    if (b != c.bcc) return fail(c, AnswerError::bad_bcc);
    return done(c, AnswerKind::text);
  }
  if (is_garbled(b)) return fail(c, AnswerError::garbled);
  switch (c.step) {
    case Step::address:
      // 6.1.1: the device answers with the ADR it was addressed with ('@' at address 0).
      if (!address_from_char(b)) return fail(c, AnswerError::unexpected);
      if (b != address_char(address_)) return fail(c, AnswerError::wrong_address);
      c.step = Step::after_address;
      return Status::need_more;
    case Step::after_address:
      if (b == kNak) return done(c, AnswerKind::nak);
      if (b == kAck) {
        if (expect_ != Expect::ack_or_nak) return fail(c, AnswerError::wrong_kind);
        return done(c, AnswerKind::ack);
      }
      if (b == kStx) {
        if (expect_ != Expect::text_or_nak) return fail(c, AnswerError::wrong_kind);
        c.step = Step::code;
        return Status::need_more;
      }
      return fail(c, AnswerError::unexpected);
    case Step::code:
      if (b < '0' || b > '9') return fail(c, AnswerError::unexpected);
      c.bcc ^= b;
      if (static_cast<char>(b) != code_.digit(c.code_pos)) return fail(c, AnswerError::wrong_code);
      if (++c.code_pos == kCodeLength) c.step = Step::equals;
      return Status::need_more;
    case Step::equals:
      if (b != kEquals) return fail(c, AnswerError::unexpected);
      c.bcc ^= b;
      c.step = Step::value;
      return Status::need_more;
    case Step::value:
      if (value_.size() < binary_prefix_) {  // LB-D10: a known number of binary bytes first
        if (!value_.push_binary(b)) return fail(c, AnswerError::value_too_long);
        c.bcc ^= b;
        return Status::need_more;
      }
      if (b == kEtx) {
        c.bcc ^= b;
        c.step = Step::bcc;
        return Status::need_more;
      }
      if (!is_value_char(b)) return fail(c, AnswerError::unexpected);
      if (!value_.push_back(b)) return fail(c, AnswerError::value_too_long);
      c.bcc ^= b;
      return Status::need_more;
    case Step::bcc:
    case Step::finished:
      break;
  }
  return fail(c, AnswerError::unexpected);
}

AnswerDecoder::Status AnswerDecoder::feed(std::uint8_t b) {
  if (status_ != Status::need_more) return status_;
  Cursor c = cursor_;
  const Status st = feed_one(c, b);
  cursor_ = c;
  return st;
}

// A whole, valid text answer at the start of a chunk (6.1: ADR STX CODE = VALUE ETX BCC), taken in
// one pass: the characters checked as feed_one() checks them -- the ADR addressed (6.1.1), STX where
// text is due, the CODE asked for (whose digits are digits: a Code holds nothing else, 2.4), '=',
// VALUE characters up to ETX, at most 100 (2.3), the BCC over CODE..ETX (2.2) -- and the decoder
// left as feed_one() leaves it after the BCC. Anything else (a NAK, an error, an answer cut by the
// chunk, a binary prefix) returns 0 having changed nothing but the VALUE, which the caller
// empties: the character-by-character path then takes the chunk from its start.
std::size_t AnswerDecoder::whole_text(std::span<const std::uint8_t> bytes) {
  constexpr std::size_t kBeforeValue = 2 + kCodeLength + 1;  // ADR STX CODE =
  if (bytes.size() < kBeforeValue + 2) return 0;               // + ETX BCC
  const std::uint8_t* p = bytes.data();
  if (p[0] != address_char(address_) || p[1] != kStx) return 0;
  std::uint8_t x = kEquals ^ kEtx;
  for (std::size_t i = 0; i < kCodeLength; ++i) {
    if (static_cast<char>(p[2 + i]) != code_.digit(i)) return 0;
    x ^= p[2 + i];
  }
  if (p[kBeforeValue - 1] != kEquals) return 0;
  std::size_t i = kBeforeValue;
  const std::size_t n = bytes.size();
  for (;; ++i) {
    if (i + 1 >= n) return 0;  // no room for ETX BCC: cut by the chunk
    const std::uint8_t b = p[i];
    if (b == kEtx) break;
    if (!value_.push_back(b)) return 0;  // a frame or garbled character, or more than 100
    x ^= b;
  }
  if (p[i + 1] != x) return 0;
  cursor_.step = Step::finished;
  cursor_.code_pos = kCodeLength;
  cursor_.bcc = x;
  cursor_.count = i + 2;
  kind_ = AnswerKind::text;
  status_ = Status::done;
  return i + 2;
}

std::size_t AnswerDecoder::feed(std::span<const std::uint8_t> bytes) {
  if (status_ != Status::need_more) return 0;
  // Nothing taken yet (the ADR is the next character), text due, no binary prefix (LB-D10).
  if (cursor_.step == Step::address && expect_ == Expect::text_or_nak && binary_prefix_ == 0) {
    if (const std::size_t n = whole_text(bytes); n != 0) return n;
    value_.clear();
  }
  Cursor c = cursor_;
  std::size_t n = 0;
  while (n < bytes.size()) {
    if (feed_one(c, bytes[n++]) != Status::need_more) break;
  }
  cursor_ = c;
  return n;
}

}  // namespace ibs::lustbus
