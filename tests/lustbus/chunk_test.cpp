// The chunked byte paths: Receiver::receive, Host::receive and AnswerDecoder::feed taking the
// characters a port read returned together. A transport hands over whatever one read gave, so
// each must do exactly what the characters one at a time do (LUSTBUS manual 3; 2.2; LB-D23), wherever
// the chunks are cut: every answer, counter, state and outcome is compared with the one-at-a-time
// path over every cut of each stream and over random cuts.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "ibs/lustbus/host.hpp"
#include "ibs/lustbus/receiver.hpp"
#include "test_support.hpp"

namespace ibs::lustbus {
namespace {

using namespace std::chrono_literals;
using test::Bytes;
using test::RecordingResponder;

using Stream = std::vector<std::uint8_t>;
using Cuts = std::vector<std::size_t>;  // chunk sizes, summing to the stream's size

// Every way of cutting the stream in two, empty reads among the chunks, and twenty random
// cuttings.
std::vector<Cuts> cuttings(std::size_t n) {
  std::vector<Cuts> all;
  for (std::size_t i = 0; i <= n; ++i) all.push_back(i == 0 || i == n ? Cuts{n} : Cuts{i, n - i});
  // An empty read (nothing arrived at that time) first, in the middle and last.
  all.push_back(Cuts{0, n / 2, 0, n - n / 2, 0});
  std::mt19937 rng(26);
  for (int k = 0; k < 20; ++k) {
    Cuts c;
    std::size_t left = n;
    while (left > 0) {
      const std::size_t take = std::uniform_int_distribution<std::size_t>(1, left)(rng);
      c.push_back(take);
      left -= take;
    }
    all.push_back(c);
  }
  return all;
}

Stream answer_text(Address a, unsigned code, const char* value) {
  const Frame f = encode_text_answer(a, make_code(code), make_value(value));
  return {f.bytes.begin(), f.bytes.begin() + f.size};
}

// ---- AnswerDecoder (6.1, 6.2, 2.2) ---------------------------------------------------------------

struct DecoderCase {
  const char* what;
  AnswerDecoder::Expect expect;
  std::size_t binary_prefix;
  Stream bytes;
};

std::vector<DecoderCase> decoder_cases() {
  Stream bad_bcc = answer_text(5, 112, "03E8");
  bad_bcc.back() ^= 0x01U;
  Stream long_value = Bytes{}(address_char(5))(kStx)("00112=").v;
  for (int i = 0; i < 101; ++i) long_value.push_back('A');
  long_value.push_back(kEtx);
  Stream binary = Bytes{}(address_char(5))(kStx)("00112=")(kStx)(kEtx)("AB")(kEtx).v;
  binary.push_back(static_cast<std::uint8_t>(text_bcc(make_code(112), make_value("AB")) ^ kStx ^ kEtx));
  return {
      {"a text answer and the host's trailing noise", AnswerDecoder::Expect::text_or_nak, 0,
       [] {
         Stream s = answer_text(5, 112, "03E8");
         s.push_back('Z');
         return s;
       }()},
      {"NAK", AnswerDecoder::Expect::text_or_nak, 0, Bytes{}(address_char(5))(kNak)(kEot).v},
      {"ACK to a SELECT", AnswerDecoder::Expect::ack_or_nak, 0, Bytes{}(address_char(5))(kAck).v},
      {"ACK where text is due", AnswerDecoder::Expect::text_or_nak, 0, Bytes{}(address_char(5))(kAck).v},
      {"a wrong BCC", AnswerDecoder::Expect::text_or_nak, 0, bad_bcc},
      {"a garbled character", AnswerDecoder::Expect::text_or_nak, 0,
       Bytes{}(address_char(5))(kStx)("001")(0x9F)("12=03E8")(kEtx).v},
      {"another device's address", AnswerDecoder::Expect::text_or_nak, 0, answer_text(6, 112, "03E8")},
      {"another CODE", AnswerDecoder::Expect::text_or_nak, 0, answer_text(5, 113, "03E8")},
      {"a VALUE longer than 100", AnswerDecoder::Expect::text_or_nak, 0, long_value},
      {"a binary prefix with frame characters (LB-D10)", AnswerDecoder::Expect::text_or_nak, 2, binary},
      {"cut short", AnswerDecoder::Expect::text_or_nak, 0, Bytes{}(address_char(5))(kStx)("0011").v},
  };
}

TEST(LustbusChunks, TheAnswerDecoderTakesChunksAsItTakesCharacters) {
  for (const auto& c : decoder_cases()) {
    SCOPED_TRACE(c.what);
    AnswerDecoder one;
    one.start(5, make_code(112), c.expect, c.binary_prefix);
    for (const auto b : c.bytes) one.feed(b);
    for (const auto& cuts : cuttings(c.bytes.size())) {
      AnswerDecoder chunked;
      chunked.start(5, make_code(112), c.expect, c.binary_prefix);
      std::size_t at = 0;
      for (const std::size_t n : cuts) {
        const std::size_t before = chunked.bytes();
        const bool needed_more = chunked.status() == AnswerDecoder::Status::need_more;
        const std::size_t took = chunked.feed(std::span<const std::uint8_t>(c.bytes).subspan(at, n));
        // It takes every character while it needs more, the one that ends it included, and then
        // none: the rest belongs to the caller.
        EXPECT_EQ(took, chunked.bytes() - before);
        if (!needed_more) {
          EXPECT_EQ(took, 0U);
        }
        if (chunked.status() == AnswerDecoder::Status::need_more) {
          EXPECT_EQ(took, n);
        }
        at += n;
      }
      EXPECT_EQ(chunked.status(), one.status());
      EXPECT_EQ(chunked.kind(), one.kind());
      EXPECT_EQ(chunked.error(), one.error());
      EXPECT_EQ(chunked.value().view(), one.value().view());
      EXPECT_EQ(chunked.bytes(), one.bytes());
    }
  }
}

// ---- Receiver (3, LB-D23) ------------------------------------------------------------------------

struct Seen {
  ReceiverState state;
  ReceiverEvent event;
  ReceiverCounters counters;
  Stream answer;
  int enquiries, selects, checksum_errors, telegrams;
};

void expect_same(const Seen& a, const Seen& b) {
  EXPECT_EQ(a.state, b.state);
  EXPECT_EQ(a.event, b.event);
  EXPECT_EQ(a.answer, b.answer) << test::hex(a.answer) << "against " << test::hex(b.answer);
  EXPECT_EQ(a.counters.enquiries, b.counters.enquiries);
  EXPECT_EQ(a.counters.selects, b.counters.selects);
  EXPECT_EQ(a.counters.broadcasts, b.counters.broadcasts);
  EXPECT_EQ(a.counters.checksum_errors, b.counters.checksum_errors);
  EXPECT_EQ(a.counters.dropped, b.counters.dropped);
  EXPECT_EQ(a.counters.answers, b.counters.answers);
  EXPECT_EQ(a.counters.fragments, b.counters.fragments);
  EXPECT_EQ(a.counters.cut_answers, b.counters.cut_answers);
  EXPECT_EQ(a.enquiries, b.enquiries);
  EXPECT_EQ(a.selects, b.selects);
  EXPECT_EQ(a.checksum_errors, b.checksum_errors);
  EXPECT_EQ(a.telegrams, b.telegrams);
}

// The stream in chunks; chunk k arrives at k * `spacing` (a spacing above the inter-character
// timeout makes every cut a silence that drops a fragment, LB-D23). `chunked` false: the same
// characters one call each, at their chunk's time.
Seen run_receiver(const Stream& s, const Cuts& cuts, Duration spacing, bool chunked) {
  RecordingResponder r;
  Receiver rx(r, 5);
  std::size_t at = 0;
  Time now{0};
  for (const std::size_t n : cuts) {
    const auto part = std::span<const std::uint8_t>(s).subspan(at, n);
    if (chunked) {
      rx.receive(part, now);
    } else {
      for (const auto b : part) rx.receive(b, now);
    }
    at += n;
    now += spacing;
  }
  Seen seen{rx.state(), rx.last_event(), {}, {}, 0, 0, 0, 0};
  seen.answer = test::to_vector(rx.take_answer(now + 10s));
  seen.counters = rx.counters();
  seen.enquiries = r.enquiries;
  seen.selects = r.selects;
  seen.checksum_errors = r.checksum_errors;
  seen.telegrams = r.telegrams;
  return seen;
}

TEST(LustbusChunks, TheReceiverTakesChunksAsItTakesCharacters) {
  Stream bad_bcc = [] {
    const Frame f = encode_select(5, make_code(105), make_value("03E8"));
    Stream s(f.bytes.begin(), f.bytes.begin() + f.size);
    s.back() ^= 0x01U;
    return s;
  }();
  const Frame sel = encode_select(5, make_code(105), make_value("03E8"));
  const Frame broadcast = encode_select(kAddressBroadcast, make_code(105), make_value("0001"));
  const std::vector<std::pair<const char*, Stream>> streams = {
      {"an ENQUIRY", Bytes{}(kEot)(address_char(5))("00112")(kEnq).v},
      {"a SELECT", Stream(sel.bytes.begin(), sel.bytes.begin() + sel.size)},
      {"a SELECT with a wrong BCC", bad_bcc},
      {"a broadcast", Stream(broadcast.bytes.begin(), broadcast.bytes.begin() + broadcast.size)},
      {"another device's ENQUIRY, then ours", Bytes{}(kEot)(address_char(6))("00112")(kEnq)(kEot)(address_char(5))("00112")(kEnq).v},
      {"an improper telegram, EOT, an ENQUIRY", Bytes{}(kEot)(address_char(5))("00x")(kEot)(address_char(5))("00112")(kEnq).v},
      {"an ENQUIRY cut by EOT", Bytes{}(kEot)(address_char(5))("00112")(kEnq)(kEot).v},
  };
  for (const auto& [what, s] : streams) {
    SCOPED_TRACE(what);
    for (const auto& cuts : cuttings(s.size())) {
      for (const Duration spacing : {Duration{0}, Duration{1ms}, Duration{1s}}) {
        expect_same(run_receiver(s, cuts, spacing, true), run_receiver(s, cuts, spacing, false));
      }
    }
  }
}

// ---- Host (6.1, 3) -------------------------------------------------------------------------------

struct HostRun {
  std::vector<std::pair<HostState, Time>> after_each;  // state and next deadline after each chunk
  HostState state;
  Outcome outcome;
  Stream eot;
};

// One ENQUIRY of 00112 at address 5; the answer stream comes back in the given chunks.
HostRun run_host(const Stream& answer, const Cuts& cuts, bool chunked) {
  Host host;
  const auto id = host.submit(enquiry(5, make_code(112))).id;
  Time now{0};
  host.step(now);
  (void)host.take_output();
  host.output_done(now);
  std::vector<std::pair<HostState, Time>> seen;
  std::size_t at = 0;
  for (const std::size_t n : cuts) {
    now += 1ms;
    const auto part = std::span<const std::uint8_t>(answer).subspan(at, n);
    if (chunked) {
      host.receive(part, now);
    } else {
      for (const auto b : part) host.receive(b, now);
    }
    at += n;
    seen.emplace_back(host.state(), host.next_deadline());
  }
  HostRun r{seen, host.state(), {}, test::to_vector(host.take_output())};
  host.output_done(now);
  for (int i = 0; i < 20 && host.outcome(id) == nullptr; ++i) {
    now += 100ms;
    host.step(now);
    (void)host.take_output();
    host.output_done(now);
  }
  EXPECT_NE(host.outcome(id), nullptr);
  if (const Outcome* o = host.outcome(id)) r.outcome = *o;
  return r;
}

TEST(LustbusChunks, TheHostTakesChunksAsItTakesCharacters) {
  Stream bad_bcc = answer_text(5, 112, "03E8");
  bad_bcc.back() ^= 0x01U;
  Stream noisy = answer_text(5, 112, "03E8");
  noisy.insert(noisy.end(), {'Z', kEot, '7'});
  const std::vector<std::pair<const char*, Stream>> answers = {
      {"the value", answer_text(5, 112, "03E8")},
      {"the value and noise after it", noisy},
      {"NAK", Bytes{}(address_char(5))(kNak).v},
      {"a wrong BCC", bad_bcc},
      {"a garbled character and more", Bytes{}(address_char(5))(kStx)("0")(0xC1)("0112=03E8")(kEtx)("x").v},
  };
  for (const auto& [what, s] : answers) {
    SCOPED_TRACE(what);
    for (const auto& cuts : cuttings(s.size())) {
      const HostRun a = run_host(s, cuts, true);
      const HostRun b = run_host(s, cuts, false);
      EXPECT_EQ(a.after_each, b.after_each);
      EXPECT_EQ(a.state, b.state);
      EXPECT_EQ(a.eot, b.eot);
      EXPECT_EQ(a.outcome.kind, b.outcome.kind);
      EXPECT_EQ(a.outcome.value.view(), b.outcome.value.view());
      EXPECT_EQ(a.outcome.answer_error, b.outcome.answer_error);
      EXPECT_EQ(a.outcome.attempts, b.outcome.attempts);
      EXPECT_EQ(a.outcome.finished, b.outcome.finished);
    }
  }
}

}  // namespace
}  // namespace ibs::lustbus
