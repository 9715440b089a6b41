// The LUSTBUS line cut into telegrams for a capture (lustbus::CaptureFramer, docs/pcap.md "Serial
// lines"): the seed's exchanges, however the bytes come, a wrong BCC, an answer cut by EOT, the
// binary part of an MC6000 description (LB-D10), noise, and every byte kept.
#include <gtest/gtest.h>

#include <random>

#include "ibs/lustbus/capture_framer.hpp"
#include "../support/seed_telegrams.hpp"

namespace ibs::lustbus {
namespace {

using base::LineSide;
using base::LineTelegram;
using Bytes = std::vector<std::uint8_t>;

Bytes text(Bytes head, std::string_view s, Bytes tail) {
  head.insert(head.end(), s.begin(), s.end());
  head.insert(head.end(), tail.begin(), tail.end());
  return head;
}

// Each seed telegram fed as one chunk, 1 ms apart; then the end of the recording.
std::vector<LineTelegram> frame_seed(std::size_t chunk) {
  CaptureFramer f;
  std::vector<LineTelegram> out;
  Time t{0};
  for (const auto& s : test::lustbus_seed_exchanges()) {
    for (std::size_t i = 0; i < s.bytes.size(); i += chunk) {
      const std::size_t n = std::min(chunk, s.bytes.size() - i);
      f.feed(s.from, std::span<const std::uint8_t>(s.bytes).subspan(i, n), t, out);
      t += 1ms;
    }
  }
  f.finish(out);
  return out;
}

TEST(LustbusCaptureFramer, SeedExchangesAreOneTelegramEachWhateverTheChunks) {
  const auto seed = test::lustbus_seed_exchanges();
  for (const std::size_t chunk : {std::size_t{1}, std::size_t{3}, std::size_t{200}}) {
    const auto got = frame_seed(chunk);
    ASSERT_EQ(got.size(), seed.size()) << "chunks of " << chunk;
    for (std::size_t i = 0; i < seed.size(); ++i) {
      SCOPED_TRACE("telegram " + std::to_string(i) + ", chunks of " + std::to_string(chunk));
      EXPECT_EQ(got[i].from, seed[i].from);
      EXPECT_EQ(got[i].bytes, seed[i].bytes);
      EXPECT_EQ(got[i].flags, 0) << "BCCs of 2.2, nothing cut";
      // Every telegram but the closing EOT carries ADR '@': address 0.
      EXPECT_EQ(got[i].address, seed[i].bytes.size() == 1 ? std::nullopt : std::optional<std::uint8_t>(0));
      EXPECT_LE(got[i].first, got[i].last);
    }
  }
}

TEST(LustbusCaptureFramer, TheFirstAndLastBytesTimesAreKept) {
  CaptureFramer f;
  std::vector<LineTelegram> out;
  const Bytes enquiry = text({0x04, 0x41}, "00112", {0x05});
  f.feed(LineSide::host, std::span<const std::uint8_t>(enquiry).first(3), Time{10ms}, out);
  f.feed(LineSide::host, std::span<const std::uint8_t>(enquiry).subspan(3), Time{12ms}, out);
  ASSERT_EQ(out.size(), 1U);
  EXPECT_EQ(out[0].first, Time{10ms});
  EXPECT_EQ(out[0].last, Time{12ms});
  EXPECT_EQ(out[0].address, 1);
}

TEST(LustbusCaptureFramer, AWrongBccIsFlaggedOnEitherSide) {
  CaptureFramer f;
  std::vector<LineTelegram> out;
  f.feed(LineSide::host, text({0x04, 0x40, 0x02}, "00105=03E8", {0x03, 0x75}), Time{0}, out);  // 74H is right
  f.feed(LineSide::device, Bytes{0x40, 0x15}, Time{1ms}, out);
  f.feed(LineSide::host, text({0x04, 0x04, 0x40}, "00112", {0x05}), Time{2ms}, out);
  f.feed(LineSide::device, text({0x40, 0x02}, "00112=03E8", {0x03, 0x04}), Time{3ms}, out);  // a BCC of EOT
  f.finish(out);
  ASSERT_EQ(out.size(), 5U);
  EXPECT_EQ(out[0].flags, base::kTelegramCheckBad);
  EXPECT_EQ(out[1].flags, 0);
  EXPECT_EQ(out[2].bytes, Bytes{0x04}) << "the closing EOT";
  EXPECT_EQ(out[4].flags, base::kTelegramCheckBad) << "the byte after ETX is the BCC, even EOT (2.2)";
  EXPECT_EQ(out[4].bytes.back(), 0x04);
}

TEST(LustbusCaptureFramer, AnAnswerTheHostCutsWithEotIsCut) {
  CaptureFramer f;
  std::vector<LineTelegram> out;
  f.feed(LineSide::host, text({0x04, 0x40}, "00112", {0x05}), Time{0}, out);
  f.feed(LineSide::device, text({0x40, 0x02}, "0011", {}), Time{1ms}, out);
  f.feed(LineSide::host, Bytes{0x04}, Time{2ms}, out);
  f.finish(out);
  ASSERT_EQ(out.size(), 3U);
  EXPECT_EQ(out[1].flags, base::kTelegramCut);
  EXPECT_EQ(out[1].from, LineSide::device);
  EXPECT_EQ(out[2].flags, 0) << "the lone EOT is whole";
  // A SELECT cut by the end of the recording, and one cut by an EOT.
  CaptureFramer g;
  std::vector<LineTelegram> cut;
  g.feed(LineSide::host, text({0x04, 0x40, 0x02}, "00105=03", {0x04, 0x40, 0x02}), Time{0}, cut);
  g.finish(cut);
  ASSERT_EQ(cut.size(), 2U);
  EXPECT_EQ(cut[0].flags, base::kTelegramCut);
  EXPECT_EQ(cut[1].flags, base::kTelegramCut);
  EXPECT_EQ(cut[1].bytes, (Bytes{0x04, 0x40, 0x02}));
}

// LB-D10: the first 42 VALUE characters of an MC6000 description (specifier 3) travel as bytes,
// frame characters among them; an ETX there does not end the answer.
TEST(LustbusCaptureFramer, TheBinaryPartOfAnMc6000DescriptionIsTakenByLength) {
  CaptureFramer f;
  std::vector<LineTelegram> out;
  f.feed(LineSide::host, text({0x04, 0x42}, "30428", {0x05}), Time{0}, out);
  Bytes value(42, 0x03);  // 42 bytes of ETX
  Bytes answer = text({0x42, 0x02}, "30428=", {});
  answer.insert(answer.end(), value.begin(), value.end());
  answer.push_back(0x03);
  std::uint8_t bcc = 0;
  for (std::size_t i = 2; i < answer.size(); ++i) bcc ^= answer[i];
  answer.push_back(bcc);
  f.feed(LineSide::device, answer, Time{1ms}, out);
  f.finish(out);
  ASSERT_EQ(out.size(), 2U);
  EXPECT_EQ(out[1].bytes, answer);
  EXPECT_EQ(out[1].flags, 0);
  EXPECT_EQ(out[1].address, 2);
}

TEST(LustbusCaptureFramer, BytesThatBeginNoTelegramAreNoise) {
  CaptureFramer f;
  std::vector<LineTelegram> out;
  f.feed(LineSide::host, text({}, "xy", {0x04, 0x40}), Time{0}, out);
  f.feed(LineSide::host, text({}, "00112", {0x05}), Time{1ms}, out);
  f.feed(LineSide::device, Bytes{0x01, 0x02}, Time{2ms}, out);
  f.feed(LineSide::host, Bytes{0x04, 0x07}, Time{3ms}, out);  // EOT then no ADR
  f.finish(out);
  ASSERT_EQ(out.size(), 4U);
  EXPECT_EQ(out[0].bytes, (Bytes{'x', 'y'}));
  EXPECT_EQ(out[0].flags, base::kTelegramNoise);
  EXPECT_EQ(out[1].flags, 0);
  EXPECT_EQ(out[2].flags, base::kTelegramNoise);
  EXPECT_EQ(out[2].from, LineSide::device);
  EXPECT_EQ(out[3].flags, base::kTelegramNoise);
}

// Whatever comes, each side's telegrams joined are every byte it sent, in order, and the times
// never go back.
TEST(LustbusCaptureFramer, EveryByteIsKeptWhateverComes) {
  std::mt19937 rng(36);
  const std::array<std::uint8_t, 12> alphabet = {0x02, 0x03, 0x04, 0x05, 0x06, 0x15, 0x40, 0x41, '0', '3', '=', 0xFF};
  for (int round = 0; round < 200; ++round) {
    CaptureFramer f;
    std::vector<LineTelegram> out;
    Bytes sent[2];
    Time t{0};
    for (int chunk = 0; chunk < 20; ++chunk) {
      const auto side = static_cast<LineSide>(rng() % 2);
      Bytes b(1 + rng() % 12);
      for (auto& x : b) x = alphabet[rng() % alphabet.size()];
      f.feed(side, b, t, out);
      auto& s = sent[static_cast<int>(side)];
      s.insert(s.end(), b.begin(), b.end());
      t += 1ms;
    }
    f.finish(out);
    Bytes got[2];
    Time last{0};
    for (const auto& tg : out) {
      EXPECT_FALSE(tg.bytes.empty());
      EXPECT_GE(tg.first, last);
      last = tg.first;
      auto& g = got[static_cast<int>(tg.from)];
      g.insert(g.end(), tg.bytes.begin(), tg.bytes.end());
    }
    EXPECT_EQ(got[0], sent[0]);
    EXPECT_EQ(got[1], sent[1]);
  }
}

}  // namespace
}  // namespace ibs::lustbus
