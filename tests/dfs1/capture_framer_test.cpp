// The DFS-1 line cut into frames for a capture (dfs1::CaptureFramer, docs/pcap.md "Serial lines"):
// the seed's example with its doubled 10H, a wrong checksum, noise, a frame cut by DLE STX or by
// the other side, and every byte kept.
#include <gtest/gtest.h>

#include <random>

#include "ibs/dfs1/capture_framer.hpp"
#include "../support/seed_telegrams.hpp"

namespace ibs::dfs1 {
namespace {

using base::LineSide;
using base::LineTelegram;
using Bytes = std::vector<std::uint8_t>;

Bytes bytes_of(const Frame& f) {
  const auto e = encode(f);
  return Bytes(e.span().begin(), e.span().end());
}

TEST(Dfs1CaptureFramer, TheSeedExampleIsOneFrameEachWayWhateverTheChunks) {
  const auto seed = test::dfs1_seed_exchange();
  EXPECT_EQ(seed[1].bytes, bytes_of(make_ack(1)));
  for (const std::size_t chunk : {std::size_t{1}, std::size_t{2}, std::size_t{64}}) {
    CaptureFramer f;
    std::vector<LineTelegram> out;
    Time t{0};
    for (const auto& s : seed) {
      for (std::size_t i = 0; i < s.bytes.size(); i += chunk) {
        f.feed(s.from, std::span<const std::uint8_t>(s.bytes).subspan(i, std::min(chunk, s.bytes.size() - i)), t, out);
        t += 1ms;
      }
    }
    f.finish(out);
    ASSERT_EQ(out.size(), 2U) << "chunks of " << chunk;
    for (std::size_t i = 0; i < 2; ++i) {
      EXPECT_EQ(out[i].from, seed[i].from);
      EXPECT_EQ(out[i].bytes, seed[i].bytes);
      EXPECT_EQ(out[i].flags, 0);
      EXPECT_EQ(out[i].address, 1);
    }
  }
}

TEST(Dfs1CaptureFramer, AUidOf10HIsReadThroughItsDoubling) {
  CaptureFramer f;
  std::vector<LineTelegram> out;
  f.feed(LineSide::host, bytes_of(make_frame(0x10, 0x81)), Time{0}, out);
  ASSERT_EQ(out.size(), 1U);
  EXPECT_EQ(out[0].address, 0x10);
  EXPECT_EQ(out[0].flags, 0);
}

TEST(Dfs1CaptureFramer, AWrongChecksumIsFlagged) {
  CaptureFramer f;
  std::vector<LineTelegram> out;
  Bytes b = test::dfs1_seed_exchange()[0].bytes;
  b.back() = 0x6E;
  f.feed(LineSide::host, b, Time{0}, out);
  ASSERT_EQ(out.size(), 1U);
  EXPECT_EQ(out[0].flags, base::kTelegramCheckBad);
  EXPECT_EQ(out[0].bytes, b);
}

TEST(Dfs1CaptureFramer, NoiseBeforeAFrameAndAFrameCutByTheNextOrByTheOtherSide) {
  CaptureFramer f;
  std::vector<LineTelegram> out;
  Bytes b = {0x55, 0x10, 0x10, 0x10, 0x02, 0x01, 0x81};  // noise (a DLE DLE among it), then a frame begins
  const Bytes status = bytes_of(make_frame(1, 0x81));
  b.insert(b.end(), status.begin(), status.end());  // DLE STX inside the first: it is cut
  f.feed(LineSide::host, b, Time{0}, out);
  f.feed(LineSide::device, Bytes{0x10, 0x02, 0x01, 0x06, 0x00}, Time{1ms}, out);
  f.feed(LineSide::host, bytes_of(make_frame(2, 0x81)), Time{2ms}, out);
  f.finish(out);
  ASSERT_EQ(out.size(), 5U);
  EXPECT_EQ(out[0].bytes, (Bytes{0x55, 0x10, 0x10}));
  EXPECT_EQ(out[0].flags, base::kTelegramNoise);
  EXPECT_FALSE(out[0].address);
  EXPECT_EQ(out[1].bytes, (Bytes{0x10, 0x02, 0x01, 0x81}));
  EXPECT_EQ(out[1].flags, base::kTelegramCut);
  EXPECT_EQ(out[1].address, 1);
  EXPECT_EQ(out[2].bytes, status);
  EXPECT_EQ(out[2].flags, 0);
  EXPECT_EQ(out[3].from, LineSide::device);
  EXPECT_EQ(out[3].flags, base::kTelegramCut) << "the host spoke before the reply ended";
  EXPECT_EQ(out[4].address, 2);
}

TEST(Dfs1CaptureFramer, EveryByteIsKeptWhateverComes) {
  std::mt19937 rng(36);
  const std::array<std::uint8_t, 8> alphabet = {0x10, 0x02, 0x03, 0x01, 0x81, 0x06, 0x15, 0x6D};
  for (int round = 0; round < 300; ++round) {
    CaptureFramer f;
    std::vector<LineTelegram> out;
    Bytes sent[2];
    Time t{0};
    for (int chunk = 0; chunk < 20; ++chunk) {
      const auto side = static_cast<LineSide>(rng() % 2);
      Bytes b(1 + rng() % 16);
      for (auto& x : b) x = alphabet[rng() % alphabet.size()];
      f.feed(side, b, t, out);
      auto& s = sent[static_cast<int>(side)];
      s.insert(s.end(), b.begin(), b.end());
      t += 1ms;
    }
    f.finish(out);
    Bytes got[2];
    for (const auto& tg : out) {
      EXPECT_FALSE(tg.bytes.empty());
      auto& g = got[static_cast<int>(tg.from)];
      g.insert(g.end(), tg.bytes.begin(), tg.bytes.end());
    }
    EXPECT_EQ(got[0], sent[0]);
    EXPECT_EQ(got[1], sent[1]);
  }
}

}  // namespace
}  // namespace ibs::dfs1
