// DFS-1 frames (DFS-1 manual 6.0): the seed's example byte-exact both ways, DLE stuffing at every
// position a 10H can take, the checksum, and the decoder's errors and resynchronisation.
#include "ibs/dfs1/frame.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace ibs::dfs1 {
namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes encoded(const Frame& f) {
  const EncodedFrame e = encode(f);
  return {e.span().begin(), e.span().end()};
}

struct Decoded {
  std::vector<Frame> frames;
  std::vector<DecodeError> errors;
};

Decoded decode_all(const Bytes& bytes, FrameDecoder& d) {
  Decoded out;
  for (std::uint8_t b : bytes) {
    const DecodeResult r = d.push(b);
    if (r.status == DecodeStatus::frame) out.frames.push_back(d.frame());
    if (r.status == DecodeStatus::error) out.errors.push_back(r.error);
  }
  return out;
}

Decoded decode_all(const Bytes& bytes) {
  FrameDecoder d;
  return decode_all(bytes, d);
}

// DFS-1 manual, note 2: [10][02] [01] [82] [00][00][10][10][00] [10] [03] [6D].
const Bytes kSeedExample = {0x10, 0x02, 0x01, 0x82, 0x00, 0x00, 0x10, 0x10, 0x00, 0x10, 0x03, 0x6D};

TEST(Dfs1Frame, SeedExampleEncodesByteExact) {
  const Frame f = make_frame(0x01, 0x82, Bytes{0x00, 0x00, 0x10, 0x00});
  EXPECT_EQ(checksum(f), 0x6D);  // 01 + 82 + 00 + 00 + 10 + 00 = 93, 2's complement 6D
  EXPECT_EQ(encoded(f), kSeedExample);
}

TEST(Dfs1Frame, SeedExampleDecodesByteExact) {
  const Decoded d = decode_all(kSeedExample);
  ASSERT_EQ(d.frames.size(), 1U);
  EXPECT_TRUE(d.errors.empty());
  const Frame& f = d.frames[0];
  EXPECT_EQ(f.uid, 0x01);
  EXPECT_EQ(f.code, 0x82);
  EXPECT_EQ(Bytes(f.payload().begin(), f.payload().end()), (Bytes{0x00, 0x00, 0x10, 0x00}));
  EXPECT_EQ(f.value_at(0), 0x1000U);  // 4096, most significant byte first (DFS-1 manual, note 3)
}

TEST(Dfs1Frame, UidOf10HIsDoubled) {
  const Frame f = make_frame(0x10, 0x81);
  const Bytes want = {0x10, 0x02, 0x10, 0x10, 0x81, 0x10, 0x03, 0x6F};
  EXPECT_EQ(encoded(f), want);
  const Decoded d = decode_all(want);
  ASSERT_EQ(d.frames.size(), 1U);
  EXPECT_EQ(d.frames[0], f);
}

TEST(Dfs1Frame, CommandOf10HIsDoubled) {
  const Frame f = make_frame(0x01, 0x10);
  const Bytes want = {0x10, 0x02, 0x01, 0x10, 0x10, 0x10, 0x03, 0xEF};
  EXPECT_EQ(encoded(f), want);
  const Decoded d = decode_all(want);
  ASSERT_EQ(d.frames.size(), 1U);
  EXPECT_EQ(d.frames[0], f);
}

TEST(Dfs1Frame, EveryDataPositionOf10HIsDoubled) {
  for (std::size_t pos = 0; pos < 4; ++pos) {
    Bytes data = {0x00, 0x00, 0x00, 0x00};
    data[pos] = 0x10;
    const Frame f = make_frame(0x05, 0x82, data);
    Bytes want = {0x10, 0x02, 0x05, 0x82};
    for (std::uint8_t b : data) {
      want.push_back(b);
      if (b == 0x10) want.push_back(0x10);
    }
    want.insert(want.end(), {0x10, 0x03, static_cast<std::uint8_t>(0x100 - 0x05 - 0x82 - 0x10)});
    EXPECT_EQ(encoded(f), want) << "position " << pos;
    const Decoded d = decode_all(want);
    ASSERT_EQ(d.frames.size(), 1U);
    EXPECT_EQ(d.frames[0], f);
  }
}

TEST(Dfs1Frame, DecisionD1AChecksumOf10HIsDoubled) {
  // 01 + 82 + 00 00 00 6D = F0: the checksum is 10H.
  const Frame f = make_frame(0x01, 0x82, Bytes{0x00, 0x00, 0x00, 0x6D});
  ASSERT_EQ(checksum(f), 0x10);
  const Bytes want = {0x10, 0x02, 0x01, 0x82, 0x00, 0x00, 0x00, 0x6D, 0x10, 0x03, 0x10, 0x10};
  EXPECT_EQ(encoded(f), want);
  const Decoded d = decode_all(want);
  ASSERT_EQ(d.frames.size(), 1U);
  EXPECT_EQ(d.frames[0], f);
}

TEST(Dfs1Frame, DecisionD1AChecksumOf10HSentOnceIsAnError) {
  const Bytes single = {0x10, 0x02, 0x01, 0x82, 0x00, 0x00, 0x00, 0x6D, 0x10, 0x03, 0x10, 0x55};
  const Decoded d = decode_all(single);
  EXPECT_TRUE(d.frames.empty());
  ASSERT_EQ(d.errors.size(), 1U);
  EXPECT_EQ(d.errors[0], DecodeError::checksum_not_doubled);
}

TEST(Dfs1Frame, AllTenHFrameRoundTrips) {
  const Frame f = make_frame(0x10, 0x10, Bytes{0x10, 0x10, 0x10, 0x10, 0x10});
  const Bytes e = encoded(f);
  EXPECT_EQ(e.size(), 2U + 14U + 2U + 1U);  // 7 doubled bytes; CSM = -(7 * 10H) = 90H
  const Decoded d = decode_all(e);
  ASSERT_EQ(d.frames.size(), 1U);
  EXPECT_EQ(d.frames[0], f);
}

TEST(Dfs1Frame, BadChecksumIsRejected) {
  Bytes b = kSeedExample;
  b.back() = 0x6E;
  const Decoded d = decode_all(b);
  EXPECT_TRUE(d.frames.empty());
  ASSERT_EQ(d.errors.size(), 1U);
  EXPECT_EQ(d.errors[0], DecodeError::bad_checksum);
}

TEST(Dfs1Frame, FrameWithoutUidAndCommandIsTooShort) {
  const Decoded d = decode_all({0x10, 0x02, 0x01, 0x10, 0x03, 0xFF});
  EXPECT_TRUE(d.frames.empty());
  ASSERT_FALSE(d.errors.empty());
  EXPECT_EQ(d.errors[0], DecodeError::too_short);
}

TEST(Dfs1Frame, MoreThanSixteenDataBytesIsTooLong) {
  Bytes b = {0x10, 0x02, 0x01, 0x06};
  for (int i = 0; i < 17; ++i) b.push_back(0x00);
  b.insert(b.end(), {0x10, 0x03, 0xF9});
  const Decoded d = decode_all(b);
  EXPECT_TRUE(d.frames.empty());
  ASSERT_FALSE(d.errors.empty());
  EXPECT_EQ(d.errors[0], DecodeError::too_long);
  // Sixteen data bytes (the status response) are fine.
  const Frame ok = make_ack(0x01, Bytes(16, 0x00));
  const Decoded d16 = decode_all(encoded(ok));
  ASSERT_EQ(d16.frames.size(), 1U);
  EXPECT_EQ(d16.frames[0], ok);
}

TEST(Dfs1Frame, UnstuffedLoneDleIsRejected) {
  // The seed's example with its datum 10H sent once: "a single 10h is the DLE".
  const Bytes b = {0x10, 0x02, 0x01, 0x82, 0x00, 0x00, 0x10, 0x00, 0x10, 0x03, 0x6D};
  const Decoded d = decode_all(b);
  EXPECT_TRUE(d.frames.empty());
  ASSERT_FALSE(d.errors.empty());
  EXPECT_EQ(d.errors[0], DecodeError::lone_dle);
}

TEST(Dfs1Frame, ResynchronisesOnDleStxAfterGarbage) {
  Bytes b = {0x00, 0xFF, 0x03, 0x10, 0x03, 0x55, 0x10, 0x10, 0x02};  // noise, a stuffed pair
  b.insert(b.end(), kSeedExample.begin(), kSeedExample.end());
  FrameDecoder dec;
  const Decoded d = decode_all(b, dec);
  ASSERT_EQ(d.frames.size(), 1U);
  EXPECT_EQ(d.frames[0].value_at(0), 0x1000U);
  EXPECT_GT(dec.garbage(), 0U);
}

TEST(Dfs1Frame, DleStxInsideAFrameStartsANewOne) {
  Bytes b = {0x10, 0x02, 0x01, 0x82, 0x00};  // cut short
  b.insert(b.end(), kSeedExample.begin(), kSeedExample.end());
  const Decoded d = decode_all(b);
  ASSERT_EQ(d.errors.size(), 1U);
  EXPECT_EQ(d.errors[0], DecodeError::interrupted);
  ASSERT_EQ(d.frames.size(), 1U);
  EXPECT_EQ(d.frames[0].value_at(0), 0x1000U);
}

TEST(Dfs1Frame, BackToBackFramesAllDecode) {
  Bytes b;
  for (int i = 0; i < 3; ++i) b.insert(b.end(), kSeedExample.begin(), kSeedExample.end());
  const Frame with_10h_csm = make_frame(0x01, 0x82, Bytes{0x00, 0x00, 0x00, 0x6D});
  const Bytes e = encoded(with_10h_csm);
  b.insert(b.end(), e.begin(), e.end());
  b.insert(b.end(), kSeedExample.begin(), kSeedExample.end());
  const Decoded d = decode_all(b);
  EXPECT_TRUE(d.errors.empty());
  EXPECT_EQ(d.frames.size(), 5U);
}

TEST(Dfs1Frame, NakCarriesItsErrorCode) {
  for (ErrorCode e : kAllErrorCodes) {
    const Frame f = make_nak(0x07, e);
    const Decoded d = decode_all(encoded(f));
    ASSERT_EQ(d.frames.size(), 1U);
    EXPECT_TRUE(d.frames[0].is_nak());
    EXPECT_EQ(d.frames[0].size, 1U);
    EXPECT_EQ(d.frames[0].data[0], static_cast<std::uint8_t>(e));
    EXPECT_NE(error_name(static_cast<std::uint8_t>(e)), "unknown error");
  }
}

TEST(Dfs1Protocol, FourByteValuesAreBigEndian) {
  std::array<std::uint8_t, 4> b{};
  put_u32(b, 0x12345678U);
  EXPECT_EQ(b, (std::array<std::uint8_t, 4>{0x12, 0x34, 0x56, 0x78}));
  EXPECT_EQ(get_u32(b), 0x12345678U);
  put_u32(b, to_unsigned(-1500));
  EXPECT_EQ(to_signed(get_u32(b)), -1500);
  // DFS-1 manual, note 3: parameter 48's MOP is [00][00][00][01].
  put_u32(b, 1);
  EXPECT_EQ(b, (std::array<std::uint8_t, 4>{0, 0, 0, 1}));
}

TEST(Dfs1Protocol, CommandTableCoversEightyOneToEightyF) {
  for (unsigned code = 0; code < 256; ++code) {
    const bool known = code >= 0x81 && code <= 0x8F;
    EXPECT_EQ(find_command(static_cast<std::uint8_t>(code)) != nullptr, known) << code;
  }
  for (Command c : kAllCommands) EXPECT_NE(to_string(c), "unknown command");
}

}  // namespace
}  // namespace ibs::dfs1
