// Issue 26's shortcuts on the CANLust frame path, each compared with the general path it stands
// for on random maps, identifiers and telegrams: KindMatcher and IdentifierMap::own_id against
// IdentifierMap::classify (what the client and the node use instead of classifying every frame),
// and the parameter telegram's 64-bit coding against the bytes of 4.5 written one by one; the
// client's inline submit for numeric requests against its general path.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "fake_drive.hpp"
#include "ibs/canlust/identifiers.hpp"
#include "ibs/canlust/master.hpp"
#include "ibs/canlust/parameter_channel.hpp"
#include "ibs/canlust/parameter_client.hpp"
#include "ibs/canlust/telegrams.hpp"

namespace ibs::canlust {
namespace {

constexpr std::array<TelegramKind, 7> kAllKinds = {
    TelegramKind::error,  TelegramKind::logon,   TelegramKind::control,
    TelegramKind::status, TelegramKind::parameter_request, TelegramKind::parameter_reply,
    TelegramKind::system};

// The default map, the text's step 1, overlapping blocks (step 3 with 100 addresses reaches into
// the next block, 220 further), step 0, and random ones.
std::vector<IdentifierMap> maps(std::mt19937& rng, int random_ones) {
  std::vector<IdentifierMap> m = {IdentifierMap{}, IdentifierMap{1, 99}, IdentifierMap{3, 99},
                                  IdentifierMap{0, 99}, IdentifierMap{255, 255}, IdentifierMap{2, 0}};
  std::uniform_int_distribution<int> step(0, 255);
  std::uniform_int_distribution<int> small(1, 4);
  std::uniform_int_distribution<int> address(0, 255);
  for (int i = 0; i < random_ones; ++i) {
    const int s = i % 2 == 0 ? small(rng) : step(rng);
    m.push_back({static_cast<std::uint8_t>(s), static_cast<Address>(address(rng))});
  }
  return m;
}

TEST(CanlustShortcuts, KindMatcherIsClassifyOfItsKindForEveryIdentifier) {
  std::mt19937 rng(26);
  for (const IdentifierMap& ids : maps(rng, 24)) {
    std::vector<KindMatcher> matchers;
    for (const auto k : kAllKinds) matchers.emplace_back(ids, k);
    for (unsigned id = 0; id <= 0xFFFFU; ++id) {
      const auto c = ids.classify(static_cast<std::uint16_t>(id));
      for (std::size_t i = 0; i < kAllKinds.size(); ++i) {
        const std::optional<Address> want =
            c && c->kind == kAllKinds[i] ? std::optional<Address>(c->address) : std::nullopt;
        ASSERT_EQ(matchers[i].match(static_cast<std::uint16_t>(id)), want)
            << "step " << int{ids.step} << " max " << int{ids.max_address} << " kind "
            << to_string(kAllKinds[i]) << " id " << id;
      }
    }
  }
}

TEST(CanlustShortcuts, OwnIdIsTheOneIdentifierClassifyTakesForTheKindAndAddress) {
  std::mt19937 rng(27);
  for (const IdentifierMap& ids : maps(rng, 24)) {
    std::map<std::pair<TelegramKind, unsigned>, std::uint16_t> seen;
    for (unsigned id = 0; id <= 0xFFFFU; ++id) {
      if (const auto c = ids.classify(static_cast<std::uint16_t>(id))) {
        // classify is a function of the identifier and id(k, a) unique: one per pair at most.
        ASSERT_TRUE(seen.emplace(std::pair{c->kind, unsigned{c->address}},
                                 static_cast<std::uint16_t>(id)).second ||
                    c->kind == TelegramKind::system);
      }
    }
    for (const auto k : kAllKinds) {
      if (k == TelegramKind::system) {
        EXPECT_EQ(ids.own_id(k, 0), std::nullopt);
        continue;
      }
      for (unsigned a = 0; a <= 255; ++a) {
        const auto it = seen.find({k, a});
        const std::optional<std::uint16_t> want =
            it == seen.end() ? std::nullopt : std::optional<std::uint16_t>(it->second);
        ASSERT_EQ(ids.own_id(k, static_cast<Address>(a)), want)
            << "step " << int{ids.step} << " max " << int{ids.max_address} << " kind "
            << to_string(k) << " address " << a;
      }
    }
  }
}

// 4.5: bytes 0-1 the parameter number (low, high), 2 the mode / status, 3-6 the data (Intel
// order), 7 the block; written and read one byte at a time.
CanFrame reference_encode(std::uint16_t id, const ParameterTelegram& t) {
  CanFrame f;
  f.id = id;
  f.dlc = 8;
  f.data[0] = static_cast<std::uint8_t>(t.parameter & 0xFFU);
  f.data[1] = static_cast<std::uint8_t>(t.parameter >> 8U);
  f.data[2] = t.code;
  for (unsigned i = 0; i < 4; ++i) f.data[3 + i] = static_cast<std::uint8_t>((t.data >> (8U * i)) & 0xFFU);
  f.data[7] = t.block;
  return f;
}

Decoded<ParameterTelegram> reference_decode(const CanFrame& f) {
  if (f.rtr) return {{}, DecodeError::remote};
  if (f.dlc < 8) return {{}, DecodeError::too_short};
  ParameterTelegram t;
  t.parameter = static_cast<std::uint16_t>(f.data[0] | (f.data[1] << 8U));
  t.code = f.data[2];
  for (unsigned i = 0; i < 4; ++i) t.data |= static_cast<std::uint32_t>(f.data[3 + i]) << (8U * i);
  t.block = f.data[7];
  return {t, DecodeError::none};
}

TEST(CanlustShortcuts, ParameterTelegramCodingIsTheBytesOf45) {
  std::mt19937 rng(28);
  std::uniform_int_distribution<unsigned> byte(0, 255);
  std::uniform_int_distribution<std::uint32_t> word(0, 0xFFFF'FFFFU);
  std::uniform_int_distribution<int> address(0, 120);
  const IdentifierMap ids;
  for (int i = 0; i < 200'000; ++i) {
    const ParameterTelegram t{static_cast<std::uint16_t>(word(rng) & 0xFFFFU),
                              static_cast<std::uint8_t>(byte(rng)), word(rng),
                              static_cast<std::uint8_t>(byte(rng))};
    const auto a = static_cast<Address>(address(rng));
    const auto req = encode_parameter_request(ids, a, t);
    const auto rep = encode_parameter_reply(ids, a, t);
    const auto req_id = ids.id(TelegramKind::parameter_request, a);
    const auto rep_id = ids.id(TelegramKind::parameter_reply, a);
    ASSERT_EQ(req.has_value(), req_id.has_value());
    ASSERT_EQ(rep.has_value(), rep_id.has_value());
    if (req) {
      const CanFrame want = reference_encode(*req_id, t);
      ASSERT_EQ(req->id, want.id);
      ASSERT_EQ(req->dlc, want.dlc);
      ASSERT_EQ(req->rtr, want.rtr);
      ASSERT_EQ(req->data, want.data);
      ASSERT_EQ(decode_parameter(*req).value, t);
    }
    if (rep) {
      ASSERT_EQ(rep->data, reference_encode(*rep_id, t).data);
    }
    // Arbitrary frames: every byte, DLC and RTR flag.
    CanFrame f;
    f.id = static_cast<std::uint16_t>(word(rng) & 0x7FFU);
    f.dlc = static_cast<std::uint8_t>(byte(rng) % 16);
    f.rtr = byte(rng) < 16;
    for (auto& b : f.data) b = static_cast<std::uint8_t>(byte(rng));
    const auto got = decode_parameter(f);
    const auto want = reference_decode(f);
    ASSERT_EQ(got.error, want.error);
    ASSERT_EQ(got.value, want.value);
  }
}


// ---- The client's inline submit (issue 26) --------------------------------------------------

}  // namespace

// The comparison's access to the general path (friend of ParameterClient).
struct ParameterServerProbe {
  static void general(ParameterServer& s, const ParameterTelegram& r, Time now) {
    s.receive_general(r, now);
  }
};

struct ParameterClientProbe {
  static Submitted general(ParameterClient& c, const Request& r) { return c.submit_general(r); }
  static Poll poll_general(const ParameterClient& c, RequestId id) { return c.poll_general(id); }
};

namespace {

bool same_outcome(const Poll& a, const Poll& b) {
  if (a.state != b.state || (a.outcome == nullptr) != (b.outcome == nullptr)) return false;
  if (a.outcome == nullptr) return true;
  const Outcome& x = *a.outcome;
  const Outcome& y = *b.outcome;
  return x.kind == y.kind && x.status == y.status && x.value == y.value && x.text == y.text &&
         x.telegrams == y.telegrams && x.started == y.started && x.finished == y.finished;
}

// Two clients with one random configuration, fed the same random requests of every kind (bad
// addresses, texts of 0..120 characters on every kind, timeouts <= 0, full queues), one through
// submit() (numeric requests inline), the other through the general path for all of them; both
// get the same steps and the same replies (random status and data, sometimes none, sometimes
// stray). Every Submitted, frame, poll, outcome, counter and deadline must agree, and poll's
// inline look at the newest outcome must give what its general walk gives.
TEST(CanlustShortcuts, InlineSubmitIsTheGeneralSubmitForRandomRequests) {
  std::mt19937 rng(2611);
  std::uniform_int_distribution<int> pct(0, 99);
  const auto pick = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  for (int round = 0; round < 60; ++round) {
    ClientConfig cfg;
    cfg.ids = IdentifierMap{static_cast<std::uint8_t>(pick(1, 3)), static_cast<Address>(pick(0, 6))};
    cfg.queue_capacity = static_cast<std::size_t>(pick(1, 8));
    cfg.completed_capacity = static_cast<std::size_t>(pick(1, 16));
    cfg.outbox_capacity = static_cast<std::size_t>(pick(1, 8));
    cfg.timeout = std::chrono::milliseconds(pick(1, 30));
    cfg.string_timeout = std::chrono::milliseconds(pick(1, 80));
    ParameterClient a(cfg);
    ParameterClient b(cfg);
    std::vector<RequestId> ids;
    Time now{0};
    for (int action = 0; action < 400; ++action) {
      if (pct(rng) < 45) {
        Request r;
        r.kind = static_cast<RequestKind>(pick(0, 4));
        r.address = static_cast<Address>(pick(0, cfg.ids.max_address + 2));
        r.parameter = static_cast<std::uint16_t>(pick(0, 3));
        r.index = static_cast<std::uint8_t>(pick(0, 255));
        r.value = static_cast<std::uint32_t>(rng());
        const int n = pick(0, 120);
        std::string text;
        for (int i = 0; i < n; ++i) text.push_back(static_cast<char>(pick(1, 127)));
        r.text = FixedString::from(text);
        r.text_too_long = pct(rng) < 20;
        if (pct(rng) < 40) r.timeout = std::chrono::milliseconds(pick(-5, 60));
        const Submitted sa = a.submit(r);
        const Submitted sb = ParameterClientProbe::general(b, r);
        ASSERT_EQ(sa.id, sb.id);
        ASSERT_EQ(sa.error, sb.error);
        if (sa) ids.push_back(sa.id);
        continue;
      }
      now += std::chrono::milliseconds(pick(0, 12));
      a.step(now);
      b.step(now);
      CanFrame fa;
      CanFrame fb;
      for (;;) {
        const bool ha = a.take_frame(fa);
        const auto hb = b.take_frame();  // the optional form on one side
        ASSERT_EQ(ha, hb.has_value());
        if (!ha) break;
        fb = *hb;
        ASSERT_EQ(fa, fb);
        if (pct(rng) < 15) continue;  // no reply
        const auto req = decode_parameter(fa);
        ASSERT_TRUE(req);
        const auto c = cfg.ids.classify(fa.id);
        ASSERT_TRUE(c);
        ParameterTelegram t = req.value;
        t.code = pct(rng) < 75 ? kStatusOk : static_cast<std::uint8_t>(1U << pick(0, 7));
        if (pct(rng) < 50) t.data = static_cast<std::uint32_t>(rng());
        if (pct(rng) < 5) t.block = static_cast<std::uint8_t>(t.block + 1);  // stray
        const auto reply = encode_parameter_reply(cfg.ids, c->address, t);
        ASSERT_TRUE(reply);
        const Time at = now + std::chrono::milliseconds(pick(0, 3));
        a.receive(*reply, at);
        b.receive(*reply, at);
      }
      if (pct(rng) < 3) {
        a.abort_all(now);
        b.abort_all(now);
      }
      ASSERT_EQ(a.next_deadline(), b.next_deadline());
      ASSERT_EQ(a.idle(), b.idle());
      ASSERT_EQ(a.counters().stray_replies, b.counters().stray_replies);
      ASSERT_EQ(a.counters().timeouts, b.counters().timeouts);
      ASSERT_EQ(a.counters().dropped_frames, b.counters().dropped_frames);
      for (const RequestId id : ids) ASSERT_TRUE(same_outcome(a.poll(id), b.poll(id))) << id;
      // poll's inline newest-first look against its general walk, for every id submitted, 0,
      // and ids never handed out.
      for (RequestId id = 0; id <= static_cast<RequestId>(ids.size()) + 2; ++id) {
        const Poll p = a.poll(id);
        const Poll g = ParameterClientProbe::poll_general(a, id);
        ASSERT_EQ(p.state, g.state) << id;
        ASSERT_EQ(p.outcome, g.outcome) << id;  // the same entry of the ring
      }
    }
  }
}


// The server's inline read (mode 05 with no reply pending) against its general path: two fake
// drives, the same random request telegrams of every mode (string transfers with right and
// wrong blocks, reads of slow, unknown and string parameters, unknown modes), the same random
// moments to take replies. Every reply, counter, state and deadline must agree, and what the
// drives were asked.
TEST(CanlustShortcuts, InlineServerReadIsTheGeneralReceive) {
  std::mt19937 rng(2612);
  std::uniform_int_distribution<int> pct(0, 99);
  const auto pick = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  constexpr std::array<std::uint16_t, 9> kNumbers = {test::kParamDisp,  test::kParamText,
                                                     test::kParamName,  test::kParamFixed,
                                                     test::kParamSlow,  test::kParamQ16,
                                                     test::kParamSigned, 0, 4711};
  constexpr std::array<std::uint8_t, 8> kModes = {kModeRead,        kModeRead,       kModeWrite,
                                                  kModeDescribe,    kModeStringRead, kModeStringWrite,
                                                  kModeListEnd,     0x33};
  for (int round = 0; round < 200; ++round) {
    test::FakeDrive da;
    test::FakeDrive db;
    ParameterServer a(da);
    ParameterServer b(db);
    Time now{0};
    for (int i = 0; i < 300; ++i) {
      ParameterTelegram r;
      r.parameter = kNumbers[static_cast<std::size_t>(pick(0, static_cast<int>(kNumbers.size()) - 1))];
      r.code = kModes[static_cast<std::size_t>(pick(0, static_cast<int>(kModes.size()) - 1))];
      r.block = static_cast<std::uint8_t>(pct(rng) < 70 ? pick(0, 3) : pick(0, 255));
      r.data = pct(rng) < 30 ? 0U : static_cast<std::uint32_t>(rng());
      a.receive(r, now);
      ParameterServerProbe::general(b, r, now);
      if (pct(rng) < 80) {
        for (;;) {
          ParameterTelegram ta;
          const bool ha = a.take_reply(now, ta);
          const auto tb = b.take_reply(now);
          ASSERT_EQ(ha, tb.has_value());
          if (!ha) break;
          ASSERT_EQ(ta, *tb);
        }
      }
      ASSERT_EQ(a.state(), b.state());
      ASSERT_EQ(a.next_deadline(), b.next_deadline());
      ASSERT_EQ(a.counters().requests, b.counters().requests);
      ASSERT_EQ(a.counters().replies, b.counters().replies);
      ASSERT_EQ(a.counters().busy, b.counters().busy);
      ASSERT_EQ(a.counters().block_errors, b.counters().block_errors);
      ASSERT_EQ(a.counters().checksum_errors, b.counters().checksum_errors);
      ASSERT_EQ(a.counters().overlong_strings, b.counters().overlong_strings);
      ASSERT_EQ(da.text_view(), db.text_view());
      ASSERT_EQ(da.disp, db.disp);
      now += std::chrono::milliseconds(pick(0, 200));
    }
  }
}

}  // namespace
}  // namespace ibs::canlust

namespace ibs::canlust {
namespace {

// Master::take_frame(CanFrame&) against the optional form: two masters with a small outbox get
// the same random broadcasts, control telegrams and parameter reads (so both their own outbox and
// the client's fill, overflow and drain); one takes its frames by reference, the other as
// optionals. The same frames in the same order, the same "none", the same counters.
TEST(CanlustShortcuts, MasterTakeFrameIntoTheCallersFrameIsTheOptionalForm) {
  std::mt19937 rng(2711);
  const auto pick = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  std::size_t frames = 0;
  for (int round = 0; round < 40; ++round) {
    MasterConfig mc;
    mc.outbox_capacity = static_cast<std::size_t>(pick(1, 6));
    mc.client.outbox_capacity = static_cast<std::size_t>(pick(1, 6));
    Master a(mc);
    Master b(mc);
    Time now{0};
    for (int i = 0; i < 300; ++i) {
      switch (pick(0, 5)) {
        case 0:
          a.system_start();
          b.system_start();
          break;
        case 1:
          a.system_stop();
          b.system_stop();
          break;
        case 2: {
          const auto addr = static_cast<Address>(pick(0, 4));
          const ControlTelegram t{static_cast<std::uint16_t>(pick(0, 0xFFFF)), pick(-1000, 1000)};
          ASSERT_EQ(a.send_control(addr, t), b.send_control(addr, t));
          break;
        }
        case 3: {
          const Request r = read(static_cast<Address>(pick(1, 4)), static_cast<std::uint16_t>(pick(1, 999)));
          const Submitted x = a.parameters().submit(r);
          const Submitted y = b.parameters().submit(r);
          ASSERT_EQ(x.id, y.id);
          ASSERT_EQ(x.error, y.error);
          break;
        }
        case 4:
          now += std::chrono::milliseconds(pick(0, 30));
          a.step(now);
          b.step(now);
          break;
        default:
          for (int k = pick(1, 8); k > 0; --k) {
            CanFrame f{};
            const bool got = a.take_frame(f);
            const std::optional<CanFrame> g = b.take_frame();
            ASSERT_EQ(got, g.has_value()) << "round " << round << " action " << i;
            if (!got) break;
            ASSERT_EQ(f, *g) << "round " << round << " action " << i;
            ++frames;
          }
      }
      ASSERT_EQ(a.next_deadline(), b.next_deadline());
      ASSERT_EQ(a.counters().dropped_frames, b.counters().dropped_frames);
      ASSERT_EQ(a.parameters().counters().dropped_frames, b.parameters().counters().dropped_frames);
    }
  }
  EXPECT_GT(frames, 2000U);  // both outboxes were really drained, not only found empty
}

}  // namespace
}  // namespace ibs::canlust
