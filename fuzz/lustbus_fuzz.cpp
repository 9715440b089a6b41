// LUSTBUS (docs/lustbus.md): the host's answer decoder, the device's receiver (LUSTBUS manual,
// section 3) and the host client, fed arbitrary bytes, faults and times.
//
// Byte 0 picks the part; the rest drives it.
// - decoder: arbitrary bytes as a device answer. Asserts: a completed text answer re-encodes to
//   exactly the bytes consumed (ADR STX CODE = VALUE ETX BCC with the rule's BCC); ACK / NAK only
//   as two bytes; an error never after done.
// - receiver: arbitrary bytes into a Receiver with a checking responder. Asserts: a SELECT reaches
//   the responder only when the bytes since the last EOT are exactly EOT? ADR STX CODE = VALUE ETX
//   BCC for that code and value with the right BCC (so no value is ever taken from a broken
//   telegram); an ENQUIRY only after ADR CODE ENQ; never at another address; broadcast never
//   answered; every answer is a well-formed answer (decodes) to the telegram just received; a
//   telegram begun and followed by a silence longer than the inter-character timeout is dropped
//   (LB-D23) and never completed by what follows, and nothing is dropped without such a silence.
// - host: requests and arbitrary answer bytes at arbitrary times into a Host. Asserts: every
//   request ends within a bound of simulated time; a value outcome holds only VALUE characters;
//   the host's output is always EOT-led telegrams or a lone EOT; nothing is sent while awaiting.
// - chunks: the same bytes one at a time and in chunks cut where the input says (a port read),
//   into two decoders, two receivers and two hosts. Asserts: everything observable is the same on
//   both paths (status, kind, error, value, count; state, event, counters, answers; outcomes).
#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "fuzz_support.hpp"
#include "ibs/lustbus/host.hpp"
#include "ibs/lustbus/receiver.hpp"

namespace {

using namespace ibs;
using namespace ibs::lustbus;
using ibs::fuzz::fail;
using In = ibs::fuzz::Input;

std::string random_string(In& in, std::size_t max) {
  const auto n = in.ConsumeIntegralInRange<std::size_t>(0, max);
  const auto bytes = in.ConsumeBytes<std::uint8_t>(n);
  return {bytes.begin(), bytes.end()};
}

void fuzz_decoder(In& in) {
  const auto a = static_cast<Address>(in.ConsumeIntegralInRange<int>(0, 30));
  const Code c = make_code(in.ConsumeIntegralInRange<std::uint32_t>(0, 99999));
  const bool enq = in.ConsumeBool();
  const auto bytes = in.ConsumeBytes<std::uint8_t>(in.remaining_bytes());
  AnswerDecoder d;
  d.start(a, c, enq ? AnswerDecoder::Expect::text_or_nak : AnswerDecoder::Expect::ack_or_nak);
  std::size_t used = 0;
  for (const auto b : bytes) {
    const auto before = d.status();
    const auto st = d.feed(b);
    if (before != AnswerDecoder::Status::need_more && st != before) fail("status changed after the end");
    if (before == AnswerDecoder::Status::need_more) ++used;
  }
  if (d.status() != AnswerDecoder::Status::done) return;
  const std::vector<std::uint8_t> got(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(used));
  Frame f;
  switch (d.kind()) {
    case AnswerKind::text:
      if (!enq) fail("text accepted for a SELECT");
      f = encode_text_answer(a, c, d.value());
      break;
    case AnswerKind::ack:
      if (enq) fail("ACK accepted for an ENQUIRY");
      f = encode_ack(a);
      break;
    case AnswerKind::nak:
      f = encode_nak(a);
      break;
    case AnswerKind::none:
      fail("done without a kind");
  }
  if (std::vector<std::uint8_t>(f.bytes.begin(), f.bytes.begin() + f.size) != got) {
    fail("accepted answer does not re-encode to its bytes");
  }
}

class Checking : public Responder {
 public:
  explicit Checking(In& in) : in_(in) {}
  std::vector<std::uint8_t> since_eot;  // the bytes since the last EOT, EOT included
  Address own = 1;
  bool last_was_select = false;
  Code code{};
  Value value{};
  Address addr = 0;

  EnquiryAnswer enquiry(const Code& c, const Context& ctx) override {
    check_address(ctx);
    if (ctx.broadcast()) fail("ENQUIRY at 31 reached the responder");
    const Frame f = encode_enquiry(ctx.address, c);
    if (!ends_with(f, 0)) fail("ENQUIRY taken from bytes that are not EOT ADR CODE ENQ");
    last_was_select = false;
    code = c;
    addr = ctx.address;
    if (in_.ConsumeBool()) return EnquiryAnswer::nak();
    const auto v = Value::from(random_string(in_, 100));
    return v ? EnquiryAnswer::text(*v, Duration{in_.ConsumeIntegral<std::uint8_t>()})
             : EnquiryAnswer::nak();
  }
  SelectAnswer select(const Code& c, const Value& v, const Context& ctx) override {
    check_address(ctx);
    const Frame f = encode_select(ctx.address, c, v);
    if (!ends_with(f, 1)) fail("SELECT taken from bytes that are not its telegram with its BCC");
    last_was_select = true;
    code = c;
    value = v;
    addr = ctx.address;
    return in_.ConsumeBool() ? SelectAnswer::ack() : SelectAnswer::nak();
  }
  void checksum_error(const Context& ctx) override {
    check_address(ctx);
    last_was_select = true;
    addr = ctx.address;
  }

 private:
  void check_address(const Context& ctx) const {
    if (ctx.address != 0 && ctx.address != 31 && ctx.address != own) fail("another device's telegram taken");
  }
  // The bytes since the last reset end with the frame's telegram (without its leading EOT), and
  // only EOTs precede it.
  bool ends_with(const Frame& f, int) const {
    const std::size_t body = f.size - 1;  // without the frame's leading EOT
    if (since_eot.size() < body) return false;
    const std::size_t off = since_eot.size() - body;
    for (std::size_t i = 0; i < body; ++i) {
      if (since_eot[off + i] != f.bytes[i + 1]) return false;
    }
    // Only EOTs may precede the telegram since the receiver was reset.
    for (std::size_t i = 0; i < off; ++i) {
      if (since_eot[i] != kEot) return false;
    }
    return true;
  }
  In& in_;
};

void fuzz_receiver(In& in) {
  Checking r(in);
  r.own = static_cast<Address>(in.ConsumeIntegralInRange<int>(0, 30));
  Receiver rx(r, r.own);
  Time now{0};
  Time last_at{0};
  while (in.remaining_bytes() > 0) {
    const auto b = in.ConsumeIntegral<std::uint8_t>();
    const bool bcc_position = rx.state() == ReceiverState::select_bcc;
    if (b == kEot && !bcc_position) {
      r.since_eot.assign(1, kEot);
    } else {
      r.since_eot.push_back(b);
    }
    const std::uint32_t fragments_before = rx.counters().fragments;
    rx.receive(b, now);
    if (rx.counters().fragments != fragments_before) {
      // LB-D23: the receiver dropped a fragment after a silence and took `b` afresh, as after EOT.
      if (now - last_at <= rx.inter_char_timeout()) fail("a fragment dropped within the inter-character timeout");
      r.since_eot.assign(1, kEot);
      if (b != kEot) r.since_eot.push_back(b);
    }
    last_at = now;
    // Mostly gaps of 0..60 us between characters; the top values are silences of 1..5535 ms, which
    // cut a telegram where they fall (a host that died there).
    const auto gap = in.ConsumeIntegral<std::uint16_t>();
    now += gap < 60000 ? Duration{gap} : Duration{std::chrono::milliseconds(gap - 60000)};
    const auto due = rx.answer_due();
    if (!due) continue;
    const auto answer = rx.take_answer(*due);
    if (answer.empty()) fail("a due answer was not given");
    if (r.addr == kAddressBroadcast) fail("a broadcast was answered");
    AnswerDecoder d;
    d.start(r.addr, r.code,
            r.last_was_select ? AnswerDecoder::Expect::ack_or_nak : AnswerDecoder::Expect::text_or_nak);
    for (const auto x : answer) d.feed(x);
    if (d.status() != AnswerDecoder::Status::done) fail("an answer that does not decode");
  }
}

void fuzz_host(In& in) {
  HostConfig cfg;
  cfg.response_timeout = Duration{in.ConsumeIntegralInRange<std::int64_t>(1, 300'000'000)};
  cfg.inter_char_timeout = Duration{in.ConsumeIntegralInRange<std::int64_t>(1, 50'000'000)};
  cfg.turnaround = Duration{in.ConsumeIntegralInRange<std::int64_t>(0, 5'000'000)};
  cfg.download_timeout = 1s;
  cfg.download_poll_interval = 50ms;
  cfg.scan_response_timeout = 10ms;
  cfg.queue_capacity = 4;
  Host host(cfg);
  static const Assignment kRecords[] = {{make_code(20300), make_value("2")}};
  // The procedures of the LUSTBUS manual 11 as a servo describes them (80-SLOAD, 108-STEXT, PosMOD1).
  static const DownloadProcedure kDownload{Family::enhanced, 80, -1, -2};
  static const IndexedTextProcedure kTexts{Family::enhanced, 108};
  static const BlockTransferProcedure kBlock = [] {
    BlockTransferProcedure b;
    b.code = kPosmodCode;
    b.max_user_data = 80;
    b.error_read = make_value("1%RDF");
    b.asks_answer = &posmod_asks_answer;
    return b;
  }();
  Time now{0};
  std::vector<RequestId> ids;
  while (in.remaining_bytes() > 0) {
    switch (in.ConsumeIntegralInRange<int>(0, 9)) {
      case 0: {
        const auto a = static_cast<Address>(in.ConsumeIntegralInRange<int>(0, 31));
        const Code c = make_code(in.ConsumeIntegralInRange<std::uint32_t>(0, 99999));
        const auto v = Value::from(random_string(in, 12)).value_or(Value{});
        Request r;
        switch (in.ConsumeIntegralInRange<int>(0, 6)) {
          case 6: r = block_transfer_request(kBlock, a, in.ConsumeBool() ? std::string_view{} : v.view()); break;  // 11.6
          case 0: r = enquiry(a, c); break;
          case 1: r = select(a, c, v); break;
          case 2: r = broadcast(c, v); break;
          case 3: r = network_scan(); break;
          case 4: r = download(kDownload, a, kRecords); break;
          default: r = indexed_text_request(kTexts, a, static_cast<std::uint16_t>(c.number() % 1000), 1); break;
        }
        const auto s = host.submit(r);
        if (s) ids.push_back(s.id);
        break;
      }
      case 1:
      case 2:
      case 3:
        host.receive(in.ConsumeIntegral<std::uint8_t>(), now);
        break;
      case 4:
        if (in.ConsumeBool()) host.restart(now);
        break;
      default:
        now += Duration{in.ConsumeIntegralInRange<std::int64_t>(0, 20'000'000)};
        break;
    }
    host.step(now);
    const auto out = host.take_output();
    if (!out.empty()) {
      if (out[0] != kEot) fail("host output does not start with EOT");
      host.output_done(now);
    }
  }
  // With no more answers, every request ends within a bound of simulated time.
  const Time limit = now + 600s;
  while (!host.idle() && now < limit) {
    const Time d = host.next_deadline();
    now = d == Time::max() ? now + 1ms : std::max(d, now);
    host.step(now);
    if (!host.take_output().empty()) host.output_done(now);
  }
  if (!host.idle()) fail("a request never ended");
  // The ring keeps the last completed_capacity outcomes.
  for (const RequestId id : ids) {
    if (id + cfg.completed_capacity <= ids.back()) continue;
    const Poll p = host.poll(id);
    if (p.state != RequestState::done) fail("request " + std::to_string(id) + " not done");
    if (p.outcome->kind == OutcomeKind::value) {
      for (const char ch : p.outcome->value.view()) {
        if (!is_value_char(static_cast<std::uint8_t>(ch))) fail("value outcome with a frame character");
      }
    }
  }
}

// Answers every ENQUIRY with one value and every SELECT with ACK, counting what reached it.
class Fixed : public Responder {
 public:
  int enquiries = 0;
  int selects = 0;
  int checksum_errors = 0;
  EnquiryAnswer enquiry(const Code&, const Context&) override {
    ++enquiries;
    return EnquiryAnswer::text(make_value("03E8"));
  }
  SelectAnswer select(const Code&, const Value&, const Context&) override {
    ++selects;
    return SelectAnswer::ack();
  }
  void checksum_error(const Context&) override { ++checksum_errors; }
};

void fuzz_chunks(In& in) {
  const auto a = static_cast<Address>(in.ConsumeIntegralInRange<int>(0, 30));
  const Code c = make_code(in.ConsumeIntegralInRange<std::uint32_t>(0, 99999));
  const bool enq = in.ConsumeBool();
  const auto prefix = in.ConsumeIntegralInRange<std::size_t>(0, 3);
  // Chunk k arrives k * gap after the first: 0, within or beyond the inter-character timeout.
  const Duration gap = Duration{in.ConsumeIntegralInRange<std::int64_t>(0, 10'000'000)};
  std::vector<std::size_t> cuts;
  const int n_cuts = in.ConsumeIntegralInRange<int>(1, 8);
  for (int i = 0; i < n_cuts; ++i) cuts.push_back(in.ConsumeIntegralInRange<std::size_t>(0, 32));
  const auto bytes = in.ConsumeBytes<std::uint8_t>(in.remaining_bytes());
  // The chunks: the cut sizes in turn, the last chunk whatever is left.
  std::vector<std::span<const std::uint8_t>> chunks;
  for (std::size_t at = 0, k = 0; at < bytes.size(); ++k) {
    const std::size_t n = std::min(cuts[k % cuts.size()], bytes.size() - at);
    chunks.emplace_back(bytes.data() + at, k + 1 >= 64 ? bytes.size() - at : n);
    at += chunks.back().size();
  }

  const auto expect = enq ? AnswerDecoder::Expect::text_or_nak : AnswerDecoder::Expect::ack_or_nak;
  AnswerDecoder d1, d2;
  d1.start(a, c, expect, prefix);
  d2.start(a, c, expect, prefix);
  for (const auto& ch : chunks) {
    for (const auto b : ch) d1.feed(b);
    const bool needed = d2.status() == AnswerDecoder::Status::need_more;
    const std::size_t before = d2.bytes();
    const std::size_t took = d2.feed(ch);
    if (took != d2.bytes() - before || (!needed && took != 0) ||
        (d2.status() == AnswerDecoder::Status::need_more && took != ch.size())) {
      fail("the chunked decoder took another count than it counted");
    }
  }
  if (d1.status() != d2.status() || d1.kind() != d2.kind() || d1.error() != d2.error() ||
      d1.value().view() != d2.value().view() || d1.bytes() != d2.bytes()) {
    fail("the decoder decided differently on chunks");
  }

  Fixed r1, r2;
  Receiver x1(r1, a), x2(r2, a);
  std::vector<std::uint8_t> ans1, ans2;
  Time now{0};
  for (const auto& ch : chunks) {
    for (const auto b : ch) x1.receive(b, now);
    x2.receive(ch, now);
    if (x1.state() != x2.state() || x1.last_event() != x2.last_event()) {
      fail("the receiver's state differs on chunks");
    }
    now += gap;
    for (const auto b : x1.take_answer(now)) ans1.push_back(b);
    for (const auto b : x2.take_answer(now)) ans2.push_back(b);
  }
  const auto& k1 = x1.counters();
  const auto& k2 = x2.counters();
  if (ans1 != ans2 || r1.enquiries != r2.enquiries || r1.selects != r2.selects ||
      r1.checksum_errors != r2.checksum_errors || k1.enquiries != k2.enquiries ||
      k1.selects != k2.selects || k1.broadcasts != k2.broadcasts ||
      k1.checksum_errors != k2.checksum_errors || k1.dropped != k2.dropped ||
      k1.answers != k2.answers || k1.fragments != k2.fragments || k1.cut_answers != k2.cut_answers) {
    fail("the receiver answered or counted differently on chunks");
  }

  Host h1, h2;
  const Request req = enq ? enquiry(a, c) : select(a, c, make_value("0001"));
  const RequestId id1 = h1.submit(req).id;
  const RequestId id2 = h2.submit(req).id;
  now = Time{0};
  for (Host* h : {&h1, &h2}) {
    h->step(now);
    (void)h->take_output();
    h->output_done(now);
  }
  for (const auto& ch : chunks) {
    now += gap;
    for (const auto b : ch) h1.receive(b, now);
    h2.receive(ch, now);
    if (h1.state() != h2.state() || h1.next_deadline() != h2.next_deadline()) {
      fail("the host's state differs on chunks");
    }
  }
  const Time limit = now + 600s;
  while ((!h1.idle() || !h2.idle()) && now < limit) {
    const Time d = std::min(h1.next_deadline(), h2.next_deadline());
    now = d == Time::max() ? now + 1ms : std::max(d, now);
    for (Host* h : {&h1, &h2}) {
      h->step(now);
      if (!h->take_output().empty()) h->output_done(now);
    }
  }
  const Outcome* o1 = h1.outcome(id1);
  const Outcome* o2 = h2.outcome(id2);
  if ((o1 == nullptr) != (o2 == nullptr)) fail("one host ended the request, the other did not");
  if (o1 != nullptr && (o1->kind != o2->kind || o1->value.view() != o2->value.view() ||
                        o1->answer_error != o2->answer_error || o1->attempts != o2->attempts ||
                        o1->finished != o2->finished)) {
    fail("the host's outcome differs on chunks");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  In in(data, size);
  switch (in.ConsumeIntegralInRange<int>(0, 3)) {
    case 0:
      fuzz_decoder(in);
      break;
    case 1:
      fuzz_receiver(in);
      break;
    case 3:
      fuzz_chunks(in);
      break;
    default:
      fuzz_host(in);
      break;
  }
  return 0;
}
