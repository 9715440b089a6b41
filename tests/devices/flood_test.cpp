// Floods (issue 23, "keep it from coming back"): every emulated drive on a serial bus, as the
// registry lists it, is fed minutes of line traffic that is no valid request for it -- random
// bytes, telegrams with a wrong check character, valid telegrams for another address, telegrams cut
// by a silence -- at the line's rate. Afterwards every value a host can write reads as before, and
// the drive answers the next well-formed request.
#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <optional>
#include <random>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "ibs/devices/dfs1/bus_face.hpp"
#include "ibs/devices/dfs1/controller.hpp"
#include "ibs/devices/drives.hpp"
#include "ibs/dfs1/frame.hpp"
#include "ibs/dfs1/host.hpp"
#include "ibs/lustbus/chars.hpp"
#include "ibs/lustbus/host.hpp"
#include "ibs/lustbus/receiver.hpp"
#include "ibs/lustbus/telegram.hpp"

namespace ibs::devices {
namespace {

using namespace std::chrono_literals;
using Bytes = std::vector<std::uint8_t>;

constexpr std::uint32_t kBaud = 9600;
constexpr Duration kChar = Duration{1'041'667};  // one 10-bit character at 9600 Bd
constexpr std::size_t kFloodBytes = 200'000;     // about 3.5 minutes of line at 9600 Bd

Bytes bytes_of(const lustbus::Frame& f) { return {f.bytes.begin(), f.bytes.begin() + f.size}; }

// --- LUSTBUS -----------------------------------------------------------------------------------

struct LustbusRig {
  explicit LustbusRig(const LustbusFace& f) : face(f), e(f.make(LustbusFaceOptions{})), rx(*e.responder, kOwn) {}

  static constexpr lustbus::Address kOwn = 1;

  void send(const Bytes& bytes) {
    for (const std::uint8_t b : bytes) {
      rx.receive(b, now);
      now += kChar;
      e.advance(now);
      if (const auto due = rx.answer_due(); due && *due <= now) (void)rx.take_answer(now);
    }
  }
  // The drive's answer to an ENQUIRY of `code` after a pause: its value, "NAK", or nullopt for no
  // answer within 20 s.
  std::optional<std::string> enquire(const lustbus::Code& code) {
    now += 100ms;  // a pause longer than the inter-character timeout: whatever was begun is dropped
    e.advance(now);
    for (const std::uint8_t b : bytes_of(lustbus::encode_enquiry(kOwn, code))) {
      rx.receive(b, now);
      now += kChar;
    }
    for (int i = 0; i < 20'000 && !rx.answer_due(); ++i) {
      now += 1ms;
      e.advance(now);
    }
    const auto due = rx.answer_due();
    if (!due) return std::nullopt;
    if (*due > now) now = *due;
    lustbus::AnswerDecoder d;
    d.start(kOwn, code, lustbus::AnswerDecoder::Expect::text_or_nak);
    for (const std::uint8_t b : rx.take_answer(now)) d.feed(b);
    if (d.status() != lustbus::AnswerDecoder::Status::done) return "undecodable";
    return d.kind() == lustbus::AnswerKind::text ? std::string(d.value().view()) : std::string("NAK");
  }

  const LustbusFace& face;
  LustbusEmulated e;
  lustbus::Receiver rx;
  Time now{0};
};

// Every parameter the face lets a host write, by its CODE.
std::vector<std::pair<unsigned, lustbus::Code>> writable_codes(const LustbusFace& face) {
  std::vector<std::pair<unsigned, lustbus::Code>> out;
  for (unsigned n = 0; n <= 999; ++n) {
    const auto p = face.find_parameter(std::to_string(n));
    if (!p || !p->writable) continue;
    if (const auto c = lustbus::parameter_code(face.family, n)) out.emplace_back(n, *c);
  }
  return out;
}

// A piece of traffic, and whether the line then falls silent (a sender that died).
struct Chunk {
  Bytes bytes;
  bool silence_after = false;
};

// Traffic that is no valid request for the drive at kOwn.
std::vector<Chunk> lustbus_flood(const std::vector<std::pair<unsigned, lustbus::Code>>& codes, std::mt19937& rng) {
  std::vector<Chunk> chunks;
  std::size_t total = 0;
  const auto value = [&] { return lustbus::make_value(std::to_string(rng() % 10000)); };
  while (total < kFloodBytes) {
    Chunk chunk;
    Bytes& out = chunk.bytes;
    const auto& code = codes[rng() % codes.size()].second;
    switch (rng() % 4) {
      case 0: {  // random bytes
        for (int i = 0; i < 64; ++i) out.push_back(static_cast<std::uint8_t>(rng()));
        break;
      }
      case 1: {  // a SELECT for us with a wrong BCC
        Bytes t = bytes_of(lustbus::encode_select(LustbusRig::kOwn, code, value()));
        t.back() = static_cast<std::uint8_t>(t.back() ^ (1U + rng() % 255U));
        out.insert(out.end(), t.begin(), t.end());
        break;
      }
      case 2: {  // a valid SELECT for another drive on the line
        const auto other = static_cast<lustbus::Address>(2 + rng() % 29);
        const Bytes t = bytes_of(lustbus::encode_select(other, code, value()));
        out.insert(out.end(), t.begin(), t.end());
        break;
      }
      default: {  // a SELECT for us cut before its BCC, then silence
        Bytes t = bytes_of(lustbus::encode_select(LustbusRig::kOwn, code, value()));
        t.resize(2 + rng() % (t.size() - 2));
        out.insert(out.end(), t.begin(), t.end());
        chunk.silence_after = true;
        break;
      }
    }
    total += out.size();
    chunks.push_back(std::move(chunk));
  }
  return chunks;
}

TEST(Flood, EveryLustbusDriveKeepsItsValuesAndAnswersAfterwards) {
  for (const Drive* d : drives_on(Bus::lustbus)) {
    SCOPED_TRACE(std::string(d->name));
    LustbusRig rig(*d->lustbus);
    const auto codes = writable_codes(*d->lustbus);
    ASSERT_FALSE(codes.empty());
    std::map<unsigned, std::optional<std::string>> before;
    std::size_t values = 0;
    for (const auto& [n, c] : codes) {
      before[n] = rig.enquire(c);
      if (before[n] && *before[n] != "NAK" && *before[n] != "undecodable") ++values;
    }
    EXPECT_GT(values, codes.size() / 2) << "the drive answers its writable parameters' values";

    std::mt19937 rng(23);
    for (const Chunk& c : lustbus_flood(codes, rng)) {
      rig.send(c.bytes);
      if (c.silence_after) rig.now += 100ms;
    }
    const auto& k = rig.rx.counters();
    EXPECT_EQ(k.selects, 0U) << "no SELECT of the flood reached the drive";
    EXPECT_EQ(k.broadcasts, 0U);
    EXPECT_GT(k.checksum_errors, 100U) << "the wrong BCCs were seen as such";
    EXPECT_GT(k.fragments, 100U) << "the cut telegrams were dropped after their silence";

    for (const auto& [n, c] : codes) EXPECT_EQ(rig.enquire(c), before[n]) << "parameter " << n;
  }
}

// --- DFS-1 -------------------------------------------------------------------------------------

struct Dfs1Rig {
  Dfs1Rig() : c(dfs1::bus_face().make(kUid, kBaud)) {}
  static constexpr std::uint8_t kUid = 1;

  void send(std::span<const std::uint8_t> bytes) {
    for (const std::uint8_t b : bytes) {
      c->receive(b, now);
      now += kChar;
      c->step(now);
      if (const auto due = c->next_deadline(); due && *due <= now) c->consume(c->pending(now).size());
    }
  }
  // The controller's reply to a read of parameter `p` after a pause, as bytes; empty for none.
  Bytes read(std::uint8_t p) {
    now += 100ms;
    const auto e = ::ibs::dfs1::encode(::ibs::dfs1::request::read_parameter(kUid, p));
    for (const std::uint8_t b : e.span()) c->receive(b, now);
    const auto due = c->next_deadline();
    if (!due) return {};
    now = *due;
    const auto reply = c->pending(now);
    Bytes out(reply.begin(), reply.end());
    c->consume(reply.size());
    return out;
  }

  std::unique_ptr<dfs1::Controller> c;
  Time now{0};
};

TEST(Flood, TheDfs1ControllerKeepsItsParametersAndAnswersAfterwards) {
  Dfs1Rig rig;
  std::map<int, Bytes> before;
  int answered = 0;
  for (int p = 0; p < 256; ++p) {
    before[p] = rig.read(static_cast<std::uint8_t>(p));
    if (!before[p].empty()) ++answered;
  }
  EXPECT_EQ(answered, 256) << "every read is answered, with a value or a NAK";

  std::mt19937 rng(23);
  std::uint64_t silences = 0;
  for (std::size_t sent = 0; sent < kFloodBytes;) {
    const auto p = static_cast<std::uint8_t>(rng() % 256);
    const auto write = ::ibs::dfs1::encode(::ibs::dfs1::request::write_parameter(Dfs1Rig::kUid, p, static_cast<std::uint32_t>(rng())));
    Bytes t(write.span().begin(), write.span().end());
    bool cut = false;
    switch (rng() % 4) {
      case 0:  // random bytes
        t.assign(64, 0);
        for (auto& b : t) b = static_cast<std::uint8_t>(rng());
        break;
      case 1:  // a write for us with a wrong checksum (the last byte; a doubled 10H loses its pair)
        t.back() = static_cast<std::uint8_t>(t.back() ^ (1U + rng() % 255U));
        break;
      case 2: {  // a valid write for another controller on the line
        const auto other = static_cast<std::uint8_t>(2 + rng() % 250);
        const auto w = ::ibs::dfs1::encode(::ibs::dfs1::request::write_parameter(other, p, static_cast<std::uint32_t>(rng())));
        t.assign(w.span().begin(), w.span().end());
        break;
      }
      default:  // a write for us cut before its end, then silence
        t.resize(2 + rng() % (t.size() - 3));
        cut = true;
        break;
    }
    rig.send(t);
    sent += t.size();
    if (cut) {
      rig.now += 100ms;
      ++silences;
    }
  }
  const auto& k = rig.c->counters();
  EXPECT_GT(k.decode_errors, 100U) << "the wrong checksums were seen as such";
  EXPECT_GT(k.foreign, 100U) << "the other controllers' writes were seen as theirs";
  EXPECT_GT(k.fragments, 100U) << "the cut writes were dropped after their silence";
  EXPECT_GT(silences, 100U);

  for (int p = 0; p < 256; ++p) EXPECT_EQ(rig.read(static_cast<std::uint8_t>(p)), before[p]) << "parameter " << p;
}

}  // namespace
}  // namespace ibs::devices
