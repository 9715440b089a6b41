// ID code decoding and encoding against public-facts.md ("ID code", "PCP width") and the ID code
// tables of the INTERBUS manual (3.1.2 VF1000, 3.2.2 MC6000 SUPI).
#include "ibs/interbus/id_code.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>


namespace ibs::interbus {
namespace {

using ::testing::HasSubstr;

// The length-code table written out again by hand from public-facts.md, so the test does not
// check kLengthCodes against itself.
const std::map<int, unsigned> kExpectedLengthCodes{
    {0, 0x00}, {1, 0x01}, {2, 0x02},  {3, 0x03},  {4, 0x04},  {5, 0x05},  {6, 0x0E},  {7, 0x0F},
    {8, 0x06}, {9, 0x07}, {10, 0x15}, {12, 0x16}, {14, 0x17}, {16, 0x12}, {24, 0x13}, {26, 0x11},
};

TEST(IdCode, LengthCodeTableEncodesEveryListedWordCount) {
  for (const auto& [words, code] : kExpectedLengthCodes) {
    ASSERT_TRUE(length_code_from_words(words).has_value()) << words;
    EXPECT_EQ(*length_code_from_words(words), code) << words;
    ASSERT_TRUE(words_from_length_code(code).has_value()) << code;
    EXPECT_EQ(*words_from_length_code(code), words) << code;
  }
}

TEST(IdCode, UnlistedWordCountsHaveNoLengthCode) {
  for (int words = -1; words <= 40; ++words) {
    EXPECT_EQ(length_code_from_words(words).has_value(), kExpectedLengthCodes.contains(words))
        << words;
  }
}

TEST(IdCode, EveryFiveBitLengthCodeIsEitherKnownOrReportedUnknown) {
  int known = 0;
  for (unsigned code = 0; code < 32; ++code) {
    const IdCode id{static_cast<Word>((code << 8U) | 0x03U)};
    EXPECT_EQ(id.length_code(), code);
    if (id.ring_words()) {
      ++known;
      EXPECT_EQ(kExpectedLengthCodes.at(*id.ring_words()), code);
    } else {
      EXPECT_FALSE(id.decodable());
      EXPECT_THAT(describe(id), HasSubstr("unknown length code"));
    }
  }
  EXPECT_EQ(known, 16);
}

TEST(IdCode, UnknownLengthCodeIsNamedInTheDescription) {
  EXPECT_EQ(describe(IdCode{0x0803}),
            "803H: remote bus device, class 0H, type 0, in/out, unknown length code 08H");
}

TEST(IdCode, Vf1000RemoteBusThreeWordsWithoutPcp) {
  // INTERBUS manual 3.1.2: "33BH Remote bus user, conforming to profile, 3 words, without PCP".
  constexpr IdCode vf{0x33B};
  static_assert(vf.ring_words() == 3);
  EXPECT_EQ(vf.bus(), BusKind::remote);
  EXPECT_FALSE(vf.has_pcp());
  EXPECT_EQ(vf.pcp_words(), 0);
  EXPECT_EQ(vf.pd_words(), 3);
  EXPECT_EQ(vf.direction(), Direction::in_out);
  EXPECT_EQ(vf.device_class(), 0x3U);
  EXPECT_EQ(vf.type_bits(), 2U);
  EXPECT_EQ(vf.group(), 0x3B);
  EXPECT_EQ(describe(vf),
            "33BH: remote bus device, class 3H, type 2, in/out, 3 words process data, no PCP");
}

TEST(IdCode, PcpWidthFromTheTwoLowBits) {
  EXPECT_EQ(IdCode{0x1D3}.pcp_words(), 1);             // 11b
  EXPECT_EQ(IdCode{0x2D0}.pcp_words(), 2);             // 00b
  EXPECT_EQ(IdCode{0x4D1}.pcp_words(), 4);             // 01b
  EXPECT_EQ(IdCode{0x2DA}.pcp_words(), std::nullopt);  // 10b is not assigned
  EXPECT_FALSE(IdCode{0x2DA}.decodable());
  EXPECT_THAT(describe(IdCode{0x2DA}), HasSubstr("unassigned PCP width"));
  EXPECT_EQ(pcp_bits_from_words(1), 0b11U);
  EXPECT_EQ(pcp_bits_from_words(2), 0b00U);
  EXPECT_EQ(pcp_bits_from_words(4), 0b01U);
  EXPECT_EQ(pcp_bits_from_words(3), std::nullopt);
}

TEST(IdCode, PcpWiderThanTheDeviceDoesNotDecode) {
  const IdCode id{0x1D0};  // 1 word on the bus, 2-word PCP channel
  EXPECT_EQ(id.ring_words(), 1);
  EXPECT_EQ(id.pcp_words(), 2);
  EXPECT_EQ(id.pd_words(), std::nullopt);
  EXPECT_THAT(describe(id), HasSubstr("PCP channel of 2 words wider than the 1 word"));
}

TEST(IdCode, PcpDeviceIsDescribedWithBothChannels) {
  EXPECT_EQ(describe(IdCode{0x4DB}),
            "4DBH: remote bus device, class DH, type 2, PCP device, 3 words process data + 1 word "
            "PCP");
  EXPECT_EQ(describe(IdCode{0x2D0}),
            "2D0H: local bus device, class DH, type 0, PCP device, 0 words process data + 2 words "
            "PCP");
}

TEST(IdCode, DirectionBitsOfDevicesWithoutPcp) {
  EXPECT_EQ(IdCode{0x0101}.direction(), Direction::out);
  EXPECT_EQ(IdCode{0x0102}.direction(), Direction::in);
  EXPECT_EQ(IdCode{0x0103}.direction(), Direction::in_out);
  EXPECT_EQ(IdCode{0x0008}.direction(), Direction::none);
  EXPECT_EQ(IdCode{0x0008}.ring_words(), 0);
}

TEST(IdCode, PublicRemoteBusAndPcpCodesFollowTheModelledRules) {
  // WAGO 750-344 remote-bus coupler codes and KUKA's 0/1/2/4-word PCP remote interface codes.
  for (const int raw : {0x01, 0x02, 0x03, 0x31, 0x32, 0x33, 0x3C, 0xEB, 0xE8, 0xE9}) {
    EXPECT_EQ(IdCode{static_cast<Word>(raw)}.bus(), BusKind::remote) << raw;
  }
  EXPECT_FALSE(IdCode{0x03}.has_pcp());
  EXPECT_EQ(IdCode{0x1EB}.pcp_words(), 1);
  EXPECT_EQ(IdCode{0x2E8}.pcp_words(), 2);
  EXPECT_EQ(IdCode{0x4E9}.pcp_words(), 4);
}

TEST(IdCode, ErrorBitsAreSeparateFromTheConfiguredCode) {
  const IdCode id{0xA33B};
  EXPECT_EQ(id.error_bits(), 5U);
  EXPECT_EQ(id.without_errors(), IdCode{0x33B});
  EXPECT_EQ(id.ring_words(), 3);
  EXPECT_EQ(id.length_code(), 3U);
  EXPECT_THAT(describe(id), HasSubstr("error message bits 5"));
}

TEST(IdCode, MakeRefusesWhatCannotBeEncoded) {
  EXPECT_EQ(make_id_code(0x03, 11), std::nullopt);
  EXPECT_EQ(make_id_code(0x03, 16), IdCode{0x1203});
  EXPECT_EQ(make_pcp_id_code(0x9, 0, 3, 1), std::nullopt);   // class 9H is not a PCP class
  EXPECT_EQ(make_pcp_id_code(0xD, 0, 3, 3), std::nullopt);   // no 3-word PCP width
  EXPECT_EQ(make_pcp_id_code(0xD, 0, 10, 1), std::nullopt);  // 11 words: no length code
  EXPECT_EQ(make_pcp_id_code(0xE, 2, 0, 1), IdCode{0x1EB});
}

TEST(IdCode, HexNotationOfTheManual) {
  EXPECT_EQ(to_hex(IdCode{0x33B}), "33BH");
  EXPECT_EQ(to_hex(IdCode{0x0DB}), "0DBH");
  EXPECT_EQ(to_hex(IdCode{0x08}), "08H");
  EXPECT_EQ(to_hex(IdCode{0x1203}), "1203H");
}

}  // namespace
}  // namespace ibs::interbus
