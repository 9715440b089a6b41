// The telegrams of the LUSTBUS manual 6.1 and 6.2, byte for byte, and the host's decoder of the device's
// answers. Encoding and decoding allocate nothing and throw nothing.
//
//   ENQUIRY   host:   EOT ADR CODE ENQ                         (6.1)
//             device: ADR STX CODE = VALUE ETX BCC  |  ADR NAK
//   SELECT    host:   EOT ADR STX CODE = VALUE ETX BCC         (6.2)
//             device: ADR ACK  |  ADR NAK  (none at address 31, 4.2)
//   then      host:   EOT
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "ibs/lustbus/chars.hpp"
#include "ibs/lustbus/code.hpp"
#include "ibs/lustbus/value.hpp"

namespace ibs::lustbus {

// EOT ADR STX CODE(5) = VALUE(100) ETX BCC
inline constexpr std::size_t kMaxTelegramLength = 3 + kCodeLength + 1 + kMaxValueLength + 2;

// One telegram's bytes in a fixed buffer.
struct Frame {
  std::array<std::uint8_t, kMaxTelegramLength> bytes{};
  std::uint8_t size = 0;

  [[nodiscard]] std::span<const std::uint8_t> span() const { return {bytes.data(), size}; }
  [[nodiscard]] std::string_view text() const {
    return {reinterpret_cast<const char*>(bytes.data()), size};
  }
  void push(std::uint8_t b) { bytes[size++] = b; }
};

// 6.1, host: EOT ADR CODE ENQ (8 bytes).
Frame encode_enquiry(Address a, const Code& c);
// 6.2, host: EOT ADR STX CODE = VALUE ETX BCC.
Frame encode_select(Address a, const Code& c, const Value& v);
// 6.1, device: ADR STX CODE = VALUE ETX BCC.
Frame encode_text_answer(Address a, const Code& c, const Value& v);
// The same three written into `f` in place: its bytes from `size` on are left as they were (a
// Frame's readers look at [0, size) only), so a receiver or host that keeps its frame as a member
// neither clears 112 bytes nor copies them per telegram.
void encode_enquiry(Frame& f, Address a, const Code& c);
void encode_select(Frame& f, Address a, const Code& c, const Value& v);
void encode_text_answer(Frame& f, Address a, const Code& c, const Value& v);
// 6.1 / 6.2, device: ADR ACK, ADR NAK.
Frame encode_ack(Address a);
Frame encode_nak(Address a);
// The BCC of CODE = VALUE ETX (2.2).
std::uint8_t text_bcc(const Code& c, const Value& v);

// What the device answered, as the host reads it.
enum class AnswerKind : std::uint8_t { none, text, ack, nak };
std::string_view to_string(AnswerKind k);

// Why an answer was not taken (the host "tests the telegram syntax, the slave-address, and the
// text portion", 3).
enum class AnswerError : std::uint8_t {
  none,
  garbled,         // a character with a parity/framing error (two devices at once, 9.1)
  wrong_address,   // ADR is not the one addressed
  unexpected,      // a character the syntax does not allow here
  wrong_kind,      // ACK to an ENQUIRY, text to a SELECT
  wrong_code,      // the text's CODE is not the one asked for
  value_too_long,  // more than 100 VALUE characters
  bad_bcc,         // BCC does not match
  incomplete,      // the answer stopped (inter-character timeout)
  no_answer,       // nothing within the response timeout
  line_busy,       // characters kept coming until the exchange's overall deadline
};
std::string_view to_string(AnswerError e);

// The host's decoder of one answer, fed byte by byte.
class AnswerDecoder {
 public:
  enum class Status : std::uint8_t { need_more, done, error };
  enum class Expect : std::uint8_t { text_or_nak, ack_or_nak };

  // Starts a new answer: the device at `a` (as addressed, 0 included) answering `c`. The first
  // `binary_prefix` VALUE characters are taken as they come, frame characters included: the
  // binary elements of an 11.2 description, whose length is known (LB-D10).
  void start(Address a, const Code& c, Expect e, std::size_t binary_prefix = 0);
  Status feed(std::uint8_t b);
  // The characters in order until the answer is complete or wrong (status() says which); returns
  // how many it took: all of them while it needs more, none once it needs no more.
  std::size_t feed(std::span<const std::uint8_t> bytes);

  [[nodiscard]] Status status() const { return status_; }
  [[nodiscard]] AnswerKind kind() const { return kind_; }
  [[nodiscard]] AnswerError error() const { return error_; }
  [[nodiscard]] const Value& value() const { return value_; }
  [[nodiscard]] std::size_t bytes() const { return cursor_.count; }

 private:
  enum class Step : std::uint8_t { address, after_address, code, equals, value, bcc, finished };
  struct Cursor {
    Step step = Step::address;
    std::uint8_t code_pos = 0;
    std::uint8_t bcc = 0;
    std::size_t count = 0;
  };
  Status feed_one(Cursor& c, std::uint8_t b);
  std::size_t whole_text(std::span<const std::uint8_t> bytes);
  Status fail(Cursor& c, AnswerError e);
  Status done(Cursor& c, AnswerKind k);

  Address address_ = 0;
  Code code_{};
  Expect expect_ = Expect::text_or_nak;
  Status status_ = Status::need_more;
  AnswerKind kind_ = AnswerKind::none;
  AnswerError error_ = AnswerError::none;
  Value value_{};
  std::size_t binary_prefix_ = 0;
  Cursor cursor_{};
};

}  // namespace ibs::lustbus
