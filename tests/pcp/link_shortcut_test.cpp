// LinkShortcuts.*: Link::receive and Link::transmit take a shortcut for the ready link's IDLE and
// data frames (docs/pcp.md, "Go-back-N"); receive_general and transmit_general decide every frame
// the general way. Two links of one configuration, one through each, get the same frames, sends,
// aborts, releases and times, at random: real traffic of a peer with lost and repeated cycles,
// arbitrary words, frames with a changed administrative byte, short spans, ack timeouts. Every
// event, counter, state, message and output word must be the same.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <random>
#include <vector>

#include "ibs/pcp/link.hpp"

namespace ibs::pcp {
namespace {

using Frame = std::array<Word, kMaxChannelWords>;

TEST(LinkShortcuts, TheAdminTablesAreTheDocumentedBitRules) {
  // decode_admin and encode_admin read tables: every byte against docs/pcp.md's rules.
  for (unsigned b = 0; b < 256; ++b) {
    const bool odd = std::popcount(b) % 2 == 1;
    const bool invalid_control = ((b >> 5U) & 3U) == 0 && ((b >> 3U) & 3U) == 3;
    const auto d = decode_admin(static_cast<std::uint8_t>(b));
    ASSERT_EQ(d.has_value(), odd && !invalid_control) << b;
    if (d) {
      EXPECT_EQ(encode_admin(*d), b) << b;
    }
  }
}

unsigned below(std::mt19937& rng, unsigned n) {
  return static_cast<unsigned>(rng() % n);
}

std::vector<std::uint8_t> random_pdu(std::mt19937& rng) {
  const std::size_t count = 1 + below(rng, 65);  // 6..134 bytes
  std::vector<std::uint8_t> p(4 + 2 * count);
  for (auto& x : p) x = static_cast<std::uint8_t>(rng());
  p[2] = high_byte(static_cast<Word>(count));
  p[3] = low_byte(static_cast<Word>(count));
  return p;
}

void expect_same(const Link& fast, const Link& general, const char* what, int cycle) {
  ASSERT_EQ(fast.state(), general.state()) << what << " cycle " << cycle;
  ASSERT_EQ(fast.stats(), general.stats()) << what << " cycle " << cycle;
  ASSERT_EQ(fast.sending(), general.sending()) << what << " cycle " << cycle;
  ASSERT_EQ(fast.can_send(), general.can_send()) << what << " cycle " << cycle;
  ASSERT_EQ(fast.has_message(), general.has_message()) << what << " cycle " << cycle;
  const auto a = fast.message();
  const auto b = general.message();
  ASSERT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end())) << what << " cycle " << cycle;
}

// Frames of one message from a to_server peer: the PDU in fragments, the LAST one's padding zeros
// except the byte `dirty` bytes after the PDU's end (none when dirty < 0), set to `value`.
std::vector<Frame> message_frames(int words, const std::vector<std::uint8_t>& pdu, int dirty,
                                  std::uint8_t value) {
  const std::size_t data = frame_data_size(words);
  std::vector<Frame> frames;
  for (std::size_t offset = 0, k = 0; offset < pdu.size(); offset += data, ++k) {
    const bool last = pdu.size() - offset <= data;
    const FrameType type = last ? FrameType::last
                                : (offset == 0 ? FrameType::first : FrameType::middle);
    std::array<std::uint8_t, kMaxFrameBytes> b{};
    b[0] = encode_admin(AdminByte{Direction::to_server, type, static_cast<std::uint8_t>(k % 4), 3});
    for (std::size_t i = 0; i < data && offset + i < pdu.size(); ++i) b[1 + i] = pdu[offset + i];
    if (last && dirty >= 0) b[1 + pdu.size() - offset + static_cast<std::size_t>(dirty)] = value;
    Frame f{};
    for (std::size_t i = 0; i < static_cast<std::size_t>(words); ++i)
      f[i] = make_word(b[2 * i], b[2 * i + 1]);
    frames.push_back(f);
  }
  return frames;
}

TEST(LinkShortcuts, EveryPaddingByteOfTheLastFrameIsChecked) {
  // docs/pcp.md ("Link"): a message is delivered only when its length and its zero padding check.
  // Every width, every PDU size, every padding byte of its LAST frame set to a random non-zero
  // value: dropped by both ways; with zero padding: delivered.
  std::mt19937 rng(26);
  for (const int words : {1, 2, 4}) {
    const std::size_t data = frame_data_size(words);
    for (std::size_t count = 1; count <= (kMaxPduSize - 4) / 2; ++count) {
      std::vector<std::uint8_t> pdu(4 + 2 * count);
      for (auto& x : pdu) x = static_cast<std::uint8_t>(rng());
      pdu[2] = high_byte(static_cast<Word>(count));
      pdu[3] = low_byte(static_cast<Word>(count));
      if (words < 4 && pdu.size() <= data) continue;
      const int padding = static_cast<int>((data - pdu.size() % data) % data);
      for (int dirty = -1; dirty < padding; ++dirty) {
        const auto value = static_cast<std::uint8_t>(1 + below(rng, 255));
        const LinkConfig cfg{words, Direction::to_client, 100ms, true};
        Link fast(cfg);
        Link general(cfg);
        for (const Frame& f : message_frames(words, pdu, dirty, value)) {
          const auto in = std::span<const Word>(f.data(), static_cast<std::size_t>(words));
          ASSERT_EQ(fast.receive(Time{}, in), general.receive_general(Time{}, in));
        }
        expect_same(fast, general, "padding", dirty);
        ASSERT_EQ(fast.has_message(), dirty < 0) << words << " words, " << pdu.size() << " bytes";
        ASSERT_EQ(fast.stats().messages_dropped, dirty < 0 ? 0U : 1U);
        if (dirty < 0) {
          const auto m = fast.message();
          ASSERT_TRUE(std::equal(m.begin(), m.end(), pdu.begin(), pdu.end()));
        }
      }
    }
  }
}

// One random run: `words` wide, the pair on side `dir`, a general peer on the other side; `total`
// gets the fast link's counters.
void run(int words, Direction dir, std::uint32_t seed, int cycles, LinkStats& total) {
  std::mt19937 rng(seed);
  const auto chance = [&](unsigned percent) { return below(rng, 100) < percent; };
  const bool start_ready = chance(50);
  const LinkConfig cfg{words, dir, 10ms, start_ready};
  const Direction peer_dir =
      dir == Direction::to_server ? Direction::to_client : Direction::to_server;
  Link fast(cfg);
  Link general(cfg);
  Link peer(LinkConfig{words, peer_dir, 10ms, start_ready});
  const auto n = static_cast<std::size_t>(words);
  std::vector<Frame> from_peer{Frame{}};
  std::vector<Frame> from_pair{Frame{}};
  Time now{};
  for (int c = 0; c < cycles; ++c) {
    now += std::chrono::microseconds(below(rng, 3000));
    if (chance(1)) now += 15ms;  // beyond the ack timeout
    // What the pair sees: the peer's newest frame, or an older one (lost, repeated cycles),
    // arbitrary words, or a peer frame with another administrative byte.
    Frame in = from_peer.back();
    const unsigned how = below(rng, 100);
    if (how < 15) {
      in = from_peer[from_peer.size() - 1 -
                     std::min<std::size_t>(below(rng, 4), from_peer.size() - 1)];
    } else if (how < 20) {
      for (auto& w : in) w = static_cast<Word>(rng());
    } else if (how < 30) {
      AdminByte a{peer_dir, static_cast<FrameType>(below(rng, 4)),
                  static_cast<std::uint8_t>(below(rng, 4)),
                  static_cast<std::uint8_t>(below(rng, 4))};
      if (a.type == FrameType::control && a.seq == 3) a.seq = 0;
      in[0] = make_word(encode_admin(a), low_byte(in[0]));
      if (chance(30))
        in[0] = static_cast<Word>(in[0] ^ (1U << below(rng, 8)));  // parity, direction
    }
    const std::size_t in_size = chance(2) ? n - 1 : n;
    const LinkEvents ef = fast.receive(now, std::span<const Word>(in.data(), in_size));
    const LinkEvents eg = general.receive_general(now, std::span<const Word>(in.data(), in_size));
    EXPECT_EQ(ef, eg) << "cycle " << c;
    expect_same(fast, general, "receive", c);
    if (::testing::Test::HasFatalFailure()) return;

    if (chance(20)) {
      const auto p = random_pdu(rng);
      ASSERT_EQ(fast.send(p), general.send(p)) << "cycle " << c;
    }
    if (chance(1)) {
      fast.abort();
      general.abort();
    }
    if (fast.has_message() && chance(70)) {
      fast.release_message();
      general.release_message();
    }
    expect_same(fast, general, "user", c);
    if (::testing::Test::HasFatalFailure()) return;

    Frame of{};
    Frame og{};
    const std::size_t out_size = chance(2) ? n - 1 : n;
    fast.transmit(now, std::span<Word>(of.data(), out_size));
    general.transmit_general(now, std::span<Word>(og.data(), out_size));
    ASSERT_EQ(of, og) << "cycle " << c;
    expect_same(fast, general, "transmit", c);
    if (::testing::Test::HasFatalFailure()) return;
    from_pair.push_back(of);

    // The peer: the pair's newest frame or an older one, its own messages and releases.
    const Frame& seen = chance(85)
                            ? from_pair.back()
                            : from_pair[from_pair.size() - 1 -
                                        std::min<std::size_t>(below(rng, 3), from_pair.size() - 1)];
    peer.receive(now, std::span<const Word>(seen.data(), n));
    if (peer.can_send() && chance(30)) peer.send(random_pdu(rng));
    if (peer.has_message() && chance(70)) peer.release_message();
    if (chance(1)) peer.abort();
    Frame pf{};
    peer.transmit(now, std::span<Word>(pf.data(), n));
    from_peer.push_back(pf);
    if (from_peer.size() > 8) from_peer.erase(from_peer.begin());
    if (from_pair.size() > 8) from_pair.erase(from_pair.begin());
  }
  total = fast.stats();
}

TEST(LinkShortcuts, RandomTrafficGivesTheSameEventsCountersAndWordsBothWays) {
  LinkStats sum{};
  for (const int words : {1, 2, 4}) {
    for (const Direction dir : {Direction::to_server, Direction::to_client}) {
      for (std::uint32_t seed = 1; seed <= 12; ++seed) {
        LinkStats s{};
        run(words, dir, seed * 7919U + static_cast<std::uint32_t>(words), 4000, s);
        if (HasFatalFailure()) return;
        sum.frames_invalid += s.frames_invalid;
        sum.frames_repeated += s.frames_repeated;
        sum.frames_ahead += s.frames_ahead;
        sum.frames_refused += s.frames_refused;
        sum.fragments_orphaned += s.fragments_orphaned;
        sum.messages_sent += s.messages_sent;
        sum.messages_received += s.messages_received;
        sum.messages_dropped += s.messages_dropped;
        sum.sequence_errors += s.sequence_errors;
        sum.ack_timeouts += s.ack_timeouts;
        sum.aborts_local += s.aborts_local;
        sum.aborts_peer += s.aborts_peer;
      }
    }
  }
  // The runs reach every counter, so that both ways were compared on each kind of frame.
  EXPECT_GT(sum.frames_invalid, 0U);
  EXPECT_GT(sum.frames_repeated, 100U);
  EXPECT_GT(sum.frames_ahead, 0U);
  EXPECT_GT(sum.frames_refused, 0U);
  EXPECT_GT(sum.fragments_orphaned, 0U);
  EXPECT_GT(sum.messages_sent, 100U);
  EXPECT_GT(sum.messages_received, 100U);
  EXPECT_GT(sum.messages_dropped, 0U);
  EXPECT_GT(sum.sequence_errors, 0U);
  EXPECT_GT(sum.ack_timeouts, 0U);
  EXPECT_GT(sum.aborts_local, 0U);
  EXPECT_GT(sum.aborts_peer, 0U);
  std::printf(
      "compared: %u repeated, %u ahead, %u refused, %u sent, %u received, %u dropped, %u sequence "
      "errors, %u ack timeouts\n",
      sum.frames_repeated, sum.frames_ahead, sum.frames_refused, sum.messages_sent,
      sum.messages_received, sum.messages_dropped, sum.sequence_errors, sum.ack_timeouts);
}

}  // namespace
}  // namespace ibs::pcp
