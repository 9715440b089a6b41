// The one-pass shortcuts of the chunked byte paths, compared with the character-by-character path
// on random telegrams: AnswerDecoder::feed taking a whole text answer at once (6.1, 2.2, 2.3) and
// Receiver::receive taking a whole ENQUIRY at once (6.1, 4.2). Each must leave everything --
// status, kind, error, VALUE, count, state, event, counters, the Responder's calls, the answer --
// exactly as the characters one at a time do; most cases are well formed (the shortcut's), the
// rest broken in one character, cut short or followed by more.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "ibs/lustbus/receiver.hpp"
#include "test_support.hpp"

namespace ibs::lustbus {
namespace {

using namespace std::chrono_literals;
using Stream = std::vector<std::uint8_t>;

std::uint8_t random_value_char(std::mt19937& rng) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  if (std::uniform_int_distribution<int>(0, 3)(rng) != 0) {
    return static_cast<std::uint8_t>(kHex[std::uniform_int_distribution<int>(0, 15)(rng)]);
  }
  for (;;) {  // any character a VALUE may carry, NUL included (2.3, 11.2.1)
    const auto b = static_cast<std::uint8_t>(std::uniform_int_distribution<int>(0, 0x7F)(rng));
    if (is_value_char(b)) return b;
  }
}

// One character changed, the stream cut, or more characters after it.
void damage(Stream& s, std::mt19937& rng) {
  static constexpr std::uint8_t kInteresting[] = {kStx, kEtx, kEot, kEnq, kAck, kNak, kEquals, kGarbled,
                                                  '0',  '9',  '@',  'A',  '_',  '^',  0x80,   0x00};
  switch (std::uniform_int_distribution<int>(0, 5)(rng)) {
    case 0:
    case 1: {  // one character replaced
      if (s.empty()) return;
      const std::size_t at = std::uniform_int_distribution<std::size_t>(0, s.size() - 1)(rng);
      s[at] = std::uniform_int_distribution<int>(0, 1)(rng) == 0
                  ? kInteresting[std::uniform_int_distribution<std::size_t>(0, std::size(kInteresting) - 1)(rng)]
                  : static_cast<std::uint8_t>(std::uniform_int_distribution<int>(0, 255)(rng));
      return;
    }
    case 2:  // cut short
      if (!s.empty()) s.resize(std::uniform_int_distribution<std::size_t>(0, s.size() - 1)(rng));
      return;
    case 3:  // one character more or less in the middle
      if (s.size() > 2) {
        const std::size_t at = std::uniform_int_distribution<std::size_t>(1, s.size() - 1)(rng);
        if (std::uniform_int_distribution<int>(0, 1)(rng) == 0) {
          s.erase(s.begin() + static_cast<std::ptrdiff_t>(at));
        } else {
          s.insert(s.begin() + static_cast<std::ptrdiff_t>(at), random_value_char(rng));
        }
      }
      return;
    default: {  // trailing characters
      const int n = std::uniform_int_distribution<int>(1, 4)(rng);
      for (int i = 0; i < n; ++i) s.push_back(kInteresting[std::uniform_int_distribution<std::size_t>(0, std::size(kInteresting) - 1)(rng)]);
      return;
    }
  }
}

// ---- is_value_char: one mask test for the list of 2.2 / 2.3 ------------------------------------

TEST(LustbusShortcuts, AValueCharacterIsAny7BitCharacterButTheSixFrameCharacters) {
  for (int i = 0; i < 256; ++i) {
    const auto b = static_cast<std::uint8_t>(i);
    const bool listed = b < 0x80 && b != kStx && b != kEtx && b != kEot && b != kEnq && b != kAck && b != kNak;
    EXPECT_EQ(is_value_char(b), listed) << i;
  }
}

// ---- AnswerDecoder: a whole text answer in one chunk ---------------------------------------------

// ADR STX CODE = VALUE ETX BCC with `n` random VALUE characters (more than 100 allowed: the
// decoder must refuse those as it does character by character).
Stream text_answer(Address a, const Code& c, std::size_t n, std::mt19937& rng) {
  Stream s{address_char(a), kStx};
  std::uint8_t x = kEquals ^ kEtx;
  for (std::size_t i = 0; i < kCodeLength; ++i) {
    s.push_back(static_cast<std::uint8_t>(c.digit(i)));
    x ^= static_cast<std::uint8_t>(c.digit(i));
  }
  s.push_back(kEquals);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t b = random_value_char(rng);
    s.push_back(b);
    x ^= b;
  }
  s.push_back(kEtx);
  s.push_back(x);
  return s;
}

struct Decoded {
  AnswerDecoder::Status status;
  AnswerKind kind;
  AnswerError error;
  std::string value;
  std::size_t bytes;
  std::vector<std::size_t> took;
};

Decoded decode(const Stream& s, const std::vector<std::size_t>& cuts, Address a, const Code& c,
               AnswerDecoder::Expect e, std::size_t prefix) {
  AnswerDecoder d;
  d.start(a, c, e, prefix);
  Decoded r{};
  std::size_t at = 0;
  for (const std::size_t n : cuts) {
    r.took.push_back(d.feed(std::span<const std::uint8_t>(s).subspan(at, n)));
    at += n;
  }
  r.status = d.status();
  r.kind = d.kind();
  r.error = d.error();
  r.value = std::string(d.value().view());
  r.bytes = d.bytes();
  return r;
}

TEST(LustbusShortcuts, AWholeTextAnswerInOneChunkDecodesAsCharacterByCharacter) {
  std::mt19937 rng(2611);
  int whole_values = 0;
  for (int k = 0; k < 20000; ++k) {
    const auto a = static_cast<Address>(std::uniform_int_distribution<int>(0, 31)(rng));
    const Code c = make_code(std::uniform_int_distribution<std::uint32_t>(0, 99999)(rng));
    const std::size_t n = std::uniform_int_distribution<int>(0, 9)(rng) == 0
                              ? std::uniform_int_distribution<std::size_t>(95, 102)(rng)
                              : std::uniform_int_distribution<std::size_t>(0, 8)(rng);
    Stream s = text_answer(a, c, n, rng);
    if (std::uniform_int_distribution<int>(0, 2)(rng) == 0) damage(s, rng);
    // Asked of this device and CODE mostly; sometimes another one, another kind, a binary prefix.
    const Address asked_a = std::uniform_int_distribution<int>(0, 15)(rng) == 0
                                ? static_cast<Address>(std::uniform_int_distribution<int>(0, 31)(rng))
                                : a;
    const Code asked_c = std::uniform_int_distribution<int>(0, 15)(rng) == 0
                             ? make_code(std::uniform_int_distribution<std::uint32_t>(0, 99999)(rng))
                             : c;
    const auto expect = std::uniform_int_distribution<int>(0, 15)(rng) == 0 ? AnswerDecoder::Expect::ack_or_nak
                                                                         : AnswerDecoder::Expect::text_or_nak;
    const std::size_t prefix =
        std::uniform_int_distribution<int>(0, 15)(rng) == 0 ? std::uniform_int_distribution<std::size_t>(1, 3)(rng) : 0;
    std::vector<std::size_t> ones(s.size(), 1);
    const Decoded one = decode(s, ones, asked_a, asked_c, expect, prefix);
    const std::size_t first = std::uniform_int_distribution<std::size_t>(0, s.size())(rng);
    for (const auto& cuts : {std::vector<std::size_t>{s.size()}, std::vector<std::size_t>{first, s.size() - first}}) {
      const Decoded chunked = decode(s, cuts, asked_a, asked_c, expect, prefix);
      SCOPED_TRACE(test::hex(s));
      ASSERT_EQ(chunked.status, one.status);
      ASSERT_EQ(chunked.kind, one.kind);
      ASSERT_EQ(chunked.error, one.error);
      ASSERT_EQ(chunked.value, one.value);
      ASSERT_EQ(chunked.bytes, one.bytes);
      // It takes the characters up to the one that ends the answer, and no more.
      std::size_t took = 0;
      for (const auto t : chunked.took) took += t;
      ASSERT_EQ(took, one.bytes);
    }
    if (one.kind == AnswerKind::text) ++whole_values;
  }
  EXPECT_GT(whole_values, 10000);  // the shortcut's case is the common one
}

// ---- Receiver: a whole ENQUIRY in one chunk ----------------------------------------------------

class LoggingResponder : public Responder {
 public:
  std::vector<std::string> log;
  std::uint32_t n = 0;

  EnquiryAnswer enquiry(const Code& c, const Context& ctx) override {
    note("enquiry", c, ctx);
    // Text, NAK or deferred by the CODE's last digit, to reach every answer path.
    switch (c.digit(4) % 3) {
      case 0: return EnquiryAnswer::text(make_value(std::to_string(++n)), 1ms);
      case 1: return EnquiryAnswer::nak();
      default: return c.digit(3) == '0' ? EnquiryAnswer::deferred() : EnquiryAnswer::text(make_value("03E8"));
    }
  }
  SelectAnswer select(const Code& c, const Value& v, const Context& ctx) override {
    note("select", c, ctx);
    log.back() += std::string(v.view());
    return SelectAnswer::ack();
  }
  void checksum_error(const Context& ctx) override { note("bcc", Code{}, ctx); }
  void telegram_received(const Context& ctx) override { note("telegram", Code{}, ctx); }
  [[nodiscard]] bool listening(Time now) const override { return now.count() % 7 != 3; }

 private:
  void note(const char* what, const Code& c, const Context& ctx) {
    log.push_back(std::string(what) + " " + std::string(c.text()) + " @" + std::to_string(ctx.address) +
                  " t" + std::to_string(ctx.now.count()));
  }
};

struct Received {
  std::vector<std::string> log;
  std::vector<std::pair<ReceiverState, ReceiverEvent>> after_each;
  std::vector<Stream> answers;
  ReceiverCounters counters;
};

// The telegrams in order, telegram i at time i ns, each in the given chunks (or one call per
// character); the answer taken after each.
Received run(const std::vector<Stream>& telegrams, const std::vector<std::vector<std::size_t>>& cuts,
             Address own, bool chunked) {
  LoggingResponder r;
  Receiver rx(r, own);
  rx.set_inter_char_timeout(Duration{0});
  Received out;
  for (std::size_t i = 0; i < telegrams.size(); ++i) {
    const Time now{static_cast<Duration::rep>(i)};
    std::size_t at = 0;
    for (const std::size_t n : cuts[i]) {
      const auto part = std::span<const std::uint8_t>(telegrams[i]).subspan(at, n);
      if (chunked) {
        rx.receive(part, now);
      } else {
        for (const auto b : part) rx.receive(b, now);
      }
      at += n;
      out.after_each.emplace_back(rx.state(), rx.last_event());
    }
    if (i % 5 == 4) rx.deliver_enquiry(EnquiryAnswer::text(make_value("0001")), now);
    out.answers.push_back(test::to_vector(rx.take_answer(now + 1s)));
  }
  out.log = r.log;
  out.counters = rx.counters();
  return out;
}

TEST(LustbusShortcuts, AWholeEnquiryInOneChunkIsReceivedAsCharacterByCharacter) {
  std::mt19937 rng(2612);
  for (int k = 0; k < 300; ++k) {
    const auto own = static_cast<Address>(std::uniform_int_distribution<int>(0, 30)(rng));
    std::vector<Stream> telegrams;
    std::vector<std::vector<std::size_t>> cuts;
    for (int t = 0; t < 40; ++t) {
      // Mostly ENQUIRYs at the own address, 0, 31 or another device; some SELECTs; some broken.
      const int pick = std::uniform_int_distribution<int>(0, 9)(rng);
      const Address a = pick < 5 ? own
                        : pick < 6 ? kAddressAny
                        : pick < 7 ? kAddressBroadcast
                                   : static_cast<Address>(std::uniform_int_distribution<int>(0, 31)(rng));
      const Code c = make_code(std::uniform_int_distribution<std::uint32_t>(0, 99999)(rng));
      Stream s;
      if (std::uniform_int_distribution<int>(0, 5)(rng) == 0) {
        const Frame f = encode_select(a, c, make_value("1A2B"));
        s.assign(f.bytes.begin(), f.bytes.begin() + f.size);
      } else {
        const Frame f = encode_enquiry(a, c);
        s.assign(f.bytes.begin(), f.bytes.begin() + f.size);
      }
      // Sometimes no EOT first (the receiver still waits for one), sometimes two telegrams at once.
      if (std::uniform_int_distribution<int>(0, 7)(rng) == 0) s.erase(s.begin());
      if (std::uniform_int_distribution<int>(0, 3)(rng) == 0) damage(s, rng);
      if (std::uniform_int_distribution<int>(0, 7)(rng) == 0) {
        const Frame f = encode_enquiry(own, c);
        s.insert(s.end(), f.bytes.begin(), f.bytes.begin() + f.size);
      }
      std::vector<std::size_t> cut{s.size()};
      if (!s.empty() && std::uniform_int_distribution<int>(0, 3)(rng) == 0) {
        const std::size_t first = std::uniform_int_distribution<std::size_t>(0, s.size())(rng);
        cut = {first, s.size() - first};
      }
      telegrams.push_back(std::move(s));
      cuts.push_back(std::move(cut));
    }
    const Received chunked = run(telegrams, cuts, own, true);
    const Received one = run(telegrams, cuts, own, false);
    ASSERT_EQ(chunked.log, one.log);
    ASSERT_EQ(chunked.after_each, one.after_each);
    ASSERT_EQ(chunked.answers, one.answers);
    ASSERT_EQ(chunked.counters.enquiries, one.counters.enquiries);
    ASSERT_EQ(chunked.counters.selects, one.counters.selects);
    ASSERT_EQ(chunked.counters.broadcasts, one.counters.broadcasts);
    ASSERT_EQ(chunked.counters.checksum_errors, one.counters.checksum_errors);
    ASSERT_EQ(chunked.counters.dropped, one.counters.dropped);
    ASSERT_EQ(chunked.counters.answers, one.counters.answers);
    ASSERT_EQ(chunked.counters.fragments, one.counters.fragments);
    ASSERT_EQ(chunked.counters.cut_answers, one.counters.cut_answers);
    ASSERT_GT(one.counters.enquiries, 5U);
  }
}

}  // namespace
}  // namespace ibs::lustbus
