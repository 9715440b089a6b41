// MC6000 data types (LUSTBUS manual 2.3.2) and the examples of seeds 000 and 001 that pin them.
#include "ibs/pcp/data_types.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace ibs::pcp {
namespace {

std::uint32_t raw(DataType t, double v) {
  const Converted c = from_engineering(t, v);
  EXPECT_TRUE(c.ok()) << to_string(t) << " " << v << ": " << to_string(c.error);
  return c.value.raw;
}

TEST(DataTypes, SizesOnTheChannel) {
  EXPECT_EQ(size_of(DataType::usign8), 1U);
  EXPECT_EQ(size_of(DataType::usign16), 2U);
  EXPECT_EQ(size_of(DataType::fixpoint16), 2U);
  EXPECT_EQ(size_of(DataType::integer16), 2U);
  EXPECT_EQ(size_of(DataType::password), 2U);
  EXPECT_EQ(size_of(DataType::int32q16), 4U);
  EXPECT_EQ(size_of(DataType::float_ieee), 4U);
  EXPECT_EQ(size_of(DataType::mc_error), 4U);
}

TEST(DataTypes, Fixpoint16ScalesByOneTwentieth) {
  EXPECT_EQ(raw(DataType::fixpoint16, 50.00), 0x03E8U);  // LUSTBUS manual 6.2.2: 50.00 * 20 = 03E8H
  EXPECT_DOUBLE_EQ(to_engineering({DataType::fixpoint16, 0x03E8}), 50.0);
  EXPECT_EQ(raw(DataType::fixpoint16, 0.026), 1U);  // nearest step
  EXPECT_EQ(raw(DataType::fixpoint16, 0.024), 0U);
}

TEST(DataTypes, Fixpoint16TopIs3276_75NotTheTables3276_80) {
  // Errata (docs/pcp.md): 65535 * 0.05 = 3276.75; the table's 3276.80 would be raw 65536.
  EXPECT_EQ(raw(DataType::fixpoint16, 3276.75), 0xFFFFU);
  EXPECT_EQ(from_engineering(DataType::fixpoint16, 3276.80).error, ConversionError::too_high);
  EXPECT_EQ(from_engineering(DataType::fixpoint16, -0.05).error, ConversionError::too_low);
}

TEST(DataTypes, Int32Q16MatchesTheSeedExamples) {
  EXPECT_EQ(raw(DataType::int32q16, 333.254), 0x014D4106U);  // LUSTBUS manual 6.2.3: 14D4106H
  EXPECT_EQ(raw(DataType::int32q16, 1274.25), 0x04FA4000U);  // LUSTBUS manual 6.1.1.2: 4FA4000H
  EXPECT_DOUBLE_EQ(to_engineering({DataType::int32q16, 0x04FA4000}), 1274.25);
  EXPECT_EQ(raw(DataType::int32q16, 132.15), 0x00842666U);   // LUSTBUS manual 7.2.1: VALUE 842666
  EXPECT_EQ(raw(DataType::int32q16, 2500.25), 0x09C44000U);  // INTERBUS manual 5.3.4
  EXPECT_DOUBLE_EQ(to_engineering({DataType::int32q16, 0xFFFF0000U}), -1.0);
}

TEST(DataTypes, Int32Q16SpansTheFullSigned32BitRange) {
  // Errata (docs/pcp.md): the table's -32767.99 .. 32766.99 is narrower than the type.
  EXPECT_EQ(raw(DataType::int32q16, -32768.0), 0x80000000U);
  EXPECT_EQ(raw(DataType::int32q16, 32767.0 + 65535.0 / 65536.0), 0x7FFFFFFFU);
  EXPECT_EQ(from_engineering(DataType::int32q16, 32768.0).error, ConversionError::too_high);
  EXPECT_EQ(from_engineering(DataType::int32q16, -32768.0001).error, ConversionError::too_low);
}

TEST(DataTypes, IntegerTypesAndPassword) {
  EXPECT_EQ(raw(DataType::integer16, -1.0), 0xFFFFU);
  EXPECT_DOUBLE_EQ(to_engineering({DataType::integer16, 0x8000}), -32768.0);
  EXPECT_EQ(from_engineering(DataType::integer16, 32768.0).error, ConversionError::too_high);
  EXPECT_EQ(raw(DataType::usign8, 255.0), 0xFFU);
  EXPECT_EQ(from_engineering(DataType::usign8, 256.0).error, ConversionError::too_high);
  EXPECT_EQ(from_engineering(DataType::usign16, -1.0).error, ConversionError::too_low);
  EXPECT_EQ(raw(DataType::password, 65535.0), 0xFFFFU);
  EXPECT_EQ(from_engineering(DataType::usign16, std::nan("")).error, ConversionError::not_a_number);
}

TEST(DataTypes, FloatIeeeIsTheBitPattern) {
  EXPECT_EQ(raw(DataType::float_ieee, 1.5), 0x3FC00000U);
  EXPECT_DOUBLE_EQ(to_engineering({DataType::float_ieee, 0xC0490FDB}),
                   static_cast<double>(-3.14159274f));
  EXPECT_EQ(from_engineering(DataType::float_ieee, 1e39).error, ConversionError::too_high);
  EXPECT_EQ(from_engineering(DataType::float_ieee, std::nan("")).error,
            ConversionError::not_a_number);
}

TEST(DataTypes, McErrorPacksNumberLocationTime) {
  // INTERBUS manual 3.2.4: the bus watchdog is error 16 ('E-OP1') at location 1. Errata (docs/pcp.md):
  // the manual's C union on a little-endian PC puts the number in the lowest byte.
  const McError e{16, 1, 0x0123};
  const Value v = to_value(e);
  EXPECT_EQ(v.raw, 0x01230110U);
  EXPECT_EQ(to_mc_error(v), e);
  EXPECT_EQ(size_of(DataType::mc_error), 4U) << "32 bits, not the table's 0..65535";
  EXPECT_EQ(from_engineering(DataType::mc_error, 1.0).error, ConversionError::wrong_type);
}

TEST(DataTypes, BytesAreBigEndianAndLengthChecked) {
  std::array<std::uint8_t, 4> b{};
  EXPECT_EQ(encode({DataType::int32q16, 0x014D4106}, b), 4U);
  EXPECT_EQ(b, (std::array<std::uint8_t, 4>{0x01, 0x4D, 0x41, 0x06}));
  EXPECT_EQ(encode({DataType::usign8, 0x7F}, b), 1U);
  EXPECT_EQ(b[0], 0x7F);
  EXPECT_EQ(decode(DataType::usign16, std::span<const std::uint8_t>(b.data(), 2)),
            (Value{DataType::usign16, 0x7F4D}));
  EXPECT_FALSE(decode(DataType::usign16, std::span<const std::uint8_t>(b.data(), 1)).has_value());
  EXPECT_FALSE(decode(DataType::usign16, std::span<const std::uint8_t>(b.data(), 4)).has_value());
  std::array<std::uint8_t, 1> small{};
  EXPECT_EQ(encode({DataType::usign16, 1}, small), 0U);
}

TEST(DataTypes, SignedRawAndCompare) {
  EXPECT_EQ(signed_raw({DataType::integer16, 0xFFFE}), -2);
  EXPECT_EQ(signed_raw({DataType::usign16, 0xFFFE}), 0xFFFE);
  EXPECT_EQ(value_from_signed_raw(DataType::integer16, -2)->raw, 0xFFFEU);
  EXPECT_FALSE(value_from_signed_raw(DataType::integer16, 40000).has_value());
  EXPECT_FALSE(value_from_signed_raw(DataType::usign8, -1).has_value());
  EXPECT_LT(compare(DataType::integer16, 0xFFFF, 0x0001), 0);
  EXPECT_GT(compare(DataType::usign16, 0xFFFF, 0x0001), 0);
  EXPECT_LT(compare(DataType::float_ieee, 0xBF800000, 0x3F800000), 0);  // -1 < 1
  EXPECT_GT(compare(DataType::float_ieee, 0x7FC00000, 0x7F7FFFFF), 0);  // NaN above all
}

}  // namespace
}  // namespace ibs::pcp
