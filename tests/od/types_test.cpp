// The one data-type family (od/types.hpp): raw <-> number both ways for every pattern of every
// type up to 16 bits and a sample of the 32-bit ones, the engineering conversions with the
// manuals' examples, and -- so that nothing is lost when the four families of today go -- every
// type of drive::, pcp::, lustbus:: and canlust:: against its od::Type.
#include "ibs/od/types.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <random>

#include "ibs/canlust/data_types.hpp"
#include "ibs/drive/data_types.hpp"
#include "ibs/lustbus/value.hpp"
#include "ibs/pcp/data_types.hpp"

namespace ibs::od {
namespace {

constexpr std::array kAll{Type::binary8,  Type::usign8,     Type::int8,     Type::usign16,
                          Type::int16,    Type::usign32,    Type::int32,    Type::fixpoint16,
                          Type::int32q16, Type::float_ieee, Type::password, Type::error16,
                          Type::error32,  Type::string};

TEST(OdTypes, TheTableIsInTheEnumsOrder) {
  ASSERT_EQ(kAll.size(), kTypeCount);
  for (std::size_t i = 0; i < kAll.size(); ++i) {
    EXPECT_EQ(kTypes[i].type, kAll[i]);
    EXPECT_EQ(static_cast<std::size_t>(kAll[i]), i);
  }
  EXPECT_EQ(to_string(Type::fixpoint16), "FIXPOINT16");
  EXPECT_EQ(bytes(Type::int32q16), 4U);
  EXPECT_EQ(bytes(Type::binary8), 1U);
}

// Every pattern of every type of at most 16 bits: its number is the pattern read as the type
// (two's complement for the signed ones), the number's Raw is the canonical image (sign-extended),
// and the number comes back from it -- from the zero-extended pattern too.
TEST(OdTypes, NumberAndRawRoundTripForEveryRawOfEveryType) {
  for (const Type t : kAll) {
    const unsigned b = bits(t);
    if (b == 0 || b > 16) continue;
    SCOPED_TRACE(std::string(to_string(t)));
    const std::uint32_t patterns = 1U << b;
    for (std::uint32_t p = 0; p < patterns; ++p) {
      const std::int64_t n = number(t, p);
      const std::int64_t expected = is_signed(t) && p >= patterns / 2
                                        ? static_cast<std::int64_t>(p) - patterns
                                        : static_cast<std::int64_t>(p);
      ASSERT_EQ(n, expected) << p;
      ASSERT_TRUE(fits(t, n));
      const Raw r = raw(t, n);
      ASSERT_EQ(number(t, r), n) << p;
      ASSERT_EQ(pattern(t, r), p) << p;
      ASSERT_EQ(canonical(t, p), r) << p;
      ASSERT_TRUE(is_canonical(t, r));
      ASSERT_EQ(is_canonical(t, p), !is_signed(t) || p < patterns / 2) << p;
      // Bits above the width are not the value's.
      ASSERT_EQ(number(t, p | (0xA5A5U << b)), n) << p;
    }
    EXPECT_EQ(min_number(t), is_signed(t) ? -static_cast<std::int64_t>(patterns / 2) : 0);
    EXPECT_EQ(max_number(t),
              is_signed(t) ? static_cast<std::int64_t>(patterns / 2) - 1 : patterns - 1);
    EXPECT_FALSE(fits(t, max_number(t) + 1));
    EXPECT_FALSE(fits(t, min_number(t) - 1));
  }
}

TEST(OdTypes, NumberAndRawRoundTripSampledAt32Bits) {
  std::mt19937 gen(38);
  std::uniform_int_distribution<std::uint32_t> any;
  const std::uint32_t edges[] = {0,          1,          0x7FFFFFFF, 0x80000000,
                                 0xFFFFFFFF, 0x0000FFFF, 0x00010000, 0xFFFF0000};
  for (const Type t : kAll) {
    if (bits(t) != 32) continue;
    SCOPED_TRACE(std::string(to_string(t)));
    for (int i = 0; i < 200000 + 8; ++i) {
      const std::uint32_t p = i < 8 ? edges[i] : any(gen);
      const std::int64_t n = number(t, p);
      ASSERT_EQ(n, is_signed(t) ? std::int64_t{static_cast<std::int32_t>(p)} : std::int64_t{p});
      ASSERT_TRUE(fits(t, n));
      ASSERT_EQ(raw(t, n), p);
      ASSERT_TRUE(is_canonical(t, p));
      ASSERT_EQ(pattern(t, p), p);
    }
    EXPECT_FALSE(fits(t, max_number(t) + 1));
    EXPECT_FALSE(fits(t, min_number(t) - 1));
  }
}

// LUSTBUS manual 2.3.1/2.3.2: FIXPOINT16 is "an unsigned 16-bit integer scaled to 0.05": 50.00 Hz =
// 03E8H (6.2.2), 23.15 Hz = 463 (7.1); its top is 3276.75 -- the table's 3276.80 is one step past
// 65535 (LB-E6, PCP errata). CANLust manual p. 32: 10.05 = 201 = C9 00 00 00.
TEST(OdTypes, Fixpoint16InFiveHundredths) {
  EXPECT_EQ(from_engineering(Type::fixpoint16, 50.0).raw, 0x03E8U);
  EXPECT_EQ(from_engineering(Type::fixpoint16, 23.15).raw, 463U);
  EXPECT_EQ(from_engineering(Type::fixpoint16, 10.05).raw, 201U);
  EXPECT_EQ(from_engineering(Type::fixpoint16, 3276.75).raw, 65535U);
  EXPECT_EQ(from_engineering(Type::fixpoint16, 3276.80).error, Conversion::too_high);
  EXPECT_EQ(from_engineering(Type::fixpoint16, -0.05).error, Conversion::too_low);
  EXPECT_DOUBLE_EQ(*engineering(Type::fixpoint16, 463), 23.15);
  EXPECT_DOUBLE_EQ(step(Type::fixpoint16), 0.05);
}

// CANLust manual p. 32: 10.5 in INT32Q16 = 00 80 0A 00 (Intel order: 000A8000H); LUSTBUS manual 2.3.2: the full
// signed 32 bits at 1/65536.
TEST(OdTypes, Int32q16InSixtyFiveThousandFiveHundredThirtySixths) {
  EXPECT_EQ(from_engineering(Type::int32q16, 10.5).raw, 0x000A8000U);
  EXPECT_EQ(from_engineering(Type::int32q16, -10.5).raw, static_cast<Raw>(-0x000A8000));
  EXPECT_DOUBLE_EQ(*engineering(Type::int32q16, 0x000A8000U), 10.5);
  EXPECT_DOUBLE_EQ(*engineering(Type::int32q16, 0x80000000U), -32768.0);
  EXPECT_EQ(from_engineering(Type::int32q16, 32768.0).error, Conversion::too_high);
  EXPECT_TRUE(from_engineering(Type::int32q16, 32767.99998).ok());
  EXPECT_EQ(from_engineering(Type::int32q16, -32768.0).raw, 0x80000000U);
}

TEST(OdTypes, ScaledIntegersFloatsAndTheOnesWithoutAnEngineeringValue) {
  // The VF1000's 911-FDRIV: INTEGER16 in 0.05 Hz (INTERBUS manual 4.1.1): -10 Hz = -200.
  EXPECT_EQ(from_engineering(Type::int16, -10.0, 0.05).raw, raw(Type::int16, -200));
  EXPECT_DOUBLE_EQ(*engineering(Type::int16, raw(Type::int16, -200), 0.05), -10.0);
  EXPECT_EQ(from_engineering(Type::float_ieee, 1.5).raw, std::bit_cast<Raw>(1.5F));
  EXPECT_DOUBLE_EQ(*engineering(Type::float_ieee, std::bit_cast<Raw>(-2.25F)), -2.25);
  EXPECT_EQ(from_engineering(Type::float_ieee, 1e39).error, Conversion::too_high);
  EXPECT_EQ(from_engineering(Type::usign8, 255.4).raw, 255U);
  EXPECT_EQ(from_engineering(Type::usign8, 255.5).error, Conversion::too_high);
  EXPECT_EQ(from_engineering(Type::int8, -128.4).raw, raw(Type::int8, -128));
  EXPECT_EQ(from_engineering(Type::usign16, std::nan("")).error, Conversion::not_a_number);
  EXPECT_EQ(from_engineering(Type::usign16, INFINITY).error, Conversion::too_high);
  EXPECT_EQ(from_engineering(Type::usign16, 1.0, 0.0).error, Conversion::not_a_number);
  for (const Type t : {Type::error16, Type::error32, Type::string}) {
    EXPECT_FALSE(engineering(t, 1).has_value());
    EXPECT_EQ(from_engineering(t, 1.0).error, Conversion::wrong_type);
  }
}

TEST(OdTypes, CompareOrdersAsTheTypesNumbers) {
  EXPECT_LT(compare(Type::int16, raw(Type::int16, -1), 1), 0);
  EXPECT_GT(compare(Type::usign16, 0xFFFF, 1), 0);
  EXPECT_EQ(compare(Type::int16, 0xFFFF, raw(Type::int16, -1)), 0);  // both images of -1
  const Raw nan = std::bit_cast<Raw>(std::numeric_limits<float>::quiet_NaN());
  EXPECT_GT(compare(Type::float_ieee, nan, std::bit_cast<Raw>(1e30F)), 0);
  EXPECT_LT(compare(Type::float_ieee, std::bit_cast<Raw>(-1.0F), std::bit_cast<Raw>(0.5F)), 0);
}

// INTERBUS manual 4.1.3.3 footnote: high byte's low nibble the code, low byte's the time in tenths of an
// hour; 0FH each: none. LUSTBUS manual 2.3.1: an erased EEPROM (FFH) reads as no error.
TEST(OdTypes, ErrorStructures) {
  EXPECT_EQ(vf_error(0x0304).code, 3);
  EXPECT_EQ(vf_error(0x0304).time_tenths, 4);
  EXPECT_EQ(vf_error(kVfErrorNone), VfError{});
  EXPECT_EQ(vf_error(0xFFFF), VfError{});
  EXPECT_EQ(vf_error_raw({3, 4}), 0x0304U);
  EXPECT_EQ(vf_error_raw({}), kVfErrorNone);
  EXPECT_FALSE(vf_error_raw({15, std::nullopt}));
  // CANLust manual p. 32: E-OP2 (16) at location 172 after 85 h = 10 AC 55 00.
  const ErrorRecord e{16, 172, 85};
  EXPECT_EQ(error_record_raw(e), 0x0055AC10U);
  EXPECT_EQ(error_record(0x0055AC10U), e);
}

// ---- nothing lost: the four families of today, type by type ------------------------------------

Type of(drive::DataType t) {
  switch (t) {
    case drive::DataType::binary8:
      return Type::binary8;
    case drive::DataType::fixpoint16:
      return Type::fixpoint16;
    case drive::DataType::usign16:
      return Type::usign16;
    case drive::DataType::usign8:
      return Type::usign8;
    case drive::DataType::vf_error:
      return Type::error16;
    case drive::DataType::password:
      return Type::password;
    case drive::DataType::integer16:
      return Type::int16;
  }
  return Type::string;
}
Type of(pcp::DataType t) {
  switch (t) {
    case pcp::DataType::usign8:
      return Type::usign8;
    case pcp::DataType::usign16:
      return Type::usign16;
    case pcp::DataType::fixpoint16:
      return Type::fixpoint16;
    case pcp::DataType::integer16:
      return Type::int16;
    case pcp::DataType::int32q16:
      return Type::int32q16;
    case pcp::DataType::float_ieee:
      return Type::float_ieee;
    case pcp::DataType::mc_error:
      return Type::error32;
    case pcp::DataType::password:
      return Type::password;
  }
  return Type::string;
}
Type of(lustbus::DataType t) {
  switch (t) {
    case lustbus::DataType::binary8:
      return Type::binary8;
    case lustbus::DataType::usign8:
      return Type::usign8;
    case lustbus::DataType::usign16:
      return Type::usign16;
    case lustbus::DataType::fixpoint16:
      return Type::fixpoint16;
    case lustbus::DataType::integer16:
      return Type::int16;
    case lustbus::DataType::int32q16:
      return Type::int32q16;
    case lustbus::DataType::float_ieee:
      return Type::float_ieee;
    case lustbus::DataType::vf_error:
      return Type::error16;
    case lustbus::DataType::mc_error:
      return Type::error32;
    case lustbus::DataType::password:
      return Type::password;
  }
  return Type::string;
}
Type of(canlust::DataType t) {
  switch (t) {
    case canlust::DataType::usign8:
      return Type::usign8;
    case canlust::DataType::int8:
      return Type::int8;
    case canlust::DataType::usign16:
      return Type::usign16;
    case canlust::DataType::int16:
      return Type::int16;
    case canlust::DataType::usign32:
      return Type::usign32;
    case canlust::DataType::int32:
      return Type::int32;
    case canlust::DataType::int32q16:
      return Type::int32q16;
    case canlust::DataType::fixpoint16:
      return Type::fixpoint16;
    case canlust::DataType::err_struc:
      return Type::error32;
    case canlust::DataType::string:
      return Type::string;
  }
  return Type::binary8;
}

// drive:: (the comm word's): the raw word as a number, its range and its engineering value.
TEST(OdTypesKeepTodays, DriveTypesEveryWord) {
  for (int c = 0; c < 7; ++c) {
    const auto d = static_cast<drive::DataType>(c);
    const Type t = of(d);
    SCOPED_TRACE(std::string(drive::to_string(d)));
    EXPECT_EQ(number(t, drive::type_min_raw(d)), min_number(t));
    EXPECT_EQ(number(t, drive::type_max_raw(d)), max_number(t));
    for (std::uint32_t w = 0; w <= 0xFFFF; ++w) {
      const auto word = static_cast<Word>(w);
      if (drive::is_single_byte(d) && w > 0xFF) break;
      ASSERT_EQ(number(t, word), drive::raw_as_number(d, word)) << w;
      const auto today = drive::to_engineering(d, word);
      const auto now = engineering(t, word);
      ASSERT_EQ(today.has_value(), now.has_value()) << w;
      if (today) {
        ASSERT_DOUBLE_EQ(*now, *today) << w;
      }
    }
  }
}

// pcp:: (PCP's): signed_raw, the value's width, and the engineering value both ways.
TEST(OdTypesKeepTodays, PcpTypes) {
  std::mt19937 gen(1);
  std::uniform_int_distribution<std::uint32_t> any;
  for (std::uint8_t code = 1; code <= 8; ++code) {
    const pcp::DataType p = *pcp::data_type_from_code(code);
    const Type t = of(p);
    SCOPED_TRACE(std::string(pcp::to_string(p)));
    EXPECT_EQ(pcp::size_of(p), bytes(t));
    EXPECT_EQ(pcp::is_signed(p), is_signed(t));
    for (int i = 0; i < 70000; ++i) {
      const std::uint32_t r = pcp::size_of(p) == 4 ? any(gen)
                                                   : static_cast<std::uint32_t>(i) &
                                                         ((1U << (8 * pcp::size_of(p))) - 1U);
      const pcp::Value v{p, r};
      if (p != pcp::DataType::float_ieee && p != pcp::DataType::mc_error) {
        ASSERT_EQ(number(t, r), pcp::signed_raw(v)) << r;
        ASSERT_DOUBLE_EQ(*engineering(t, r), pcp::to_engineering(v)) << r;
        ASSERT_EQ(pcp::value_from_signed_raw(p, number(t, r))->raw,
                  pattern(t, raw(t, number(t, r))));
      }
      if (p == pcp::DataType::float_ieee) {
        const double e = pcp::to_engineering(v);
        if (!std::isnan(e)) {
          ASSERT_DOUBLE_EQ(*engineering(t, r), e) << r;
        }
      }
      ASSERT_EQ(pcp::compare(p, r, r ^ 1U) < 0, compare(t, r, r ^ 1U) < 0) << r;
    }
    for (const double x :
         {0.0, 1.0, 23.15, 3276.75, 3276.8, -1.0, 255.0, 256.0, 32767.0, -32768.0, 12345.678}) {
      const pcp::Converted today = pcp::from_engineering(p, x);
      const Converted now = from_engineering(t, x);
      if (p == pcp::DataType::mc_error) {
        EXPECT_FALSE(now.ok());
        continue;
      }
      ASSERT_EQ(today.ok(), now.ok()) << x;
      if (today.ok()) {
        ASSERT_EQ(today.value.raw, pattern(t, now.raw)) << x;
      }
    }
  }
}

// lustbus:: (LUSTBUS's VALUEs): the width of the pattern and the engineering value.
TEST(OdTypesKeepTodays, LustbusTypes) {
  for (int c = 0; c < 10; ++c) {
    const auto l = static_cast<lustbus::DataType>(c);
    const Type t = of(l);
    SCOPED_TRACE(std::string(lustbus::to_string(l)));
    EXPECT_EQ(lustbus::width_bits(l), bits(t));
    for (std::uint32_t r : {0U, 1U, 0x7FU, 0x80U, 0xFFU, 0x1F4U, 0x7FFFU, 0x8000U, 0xFFFFU,
                            0x000A8000U, 0xFFFFFFFFU}) {
      r = pattern(t, r);
      const auto today = lustbus::to_engineering(l, r);
      const auto now = engineering(t, r);
      // A NaN pattern: LUSTBUS refuses its engineering value (not_finite), od gives the NaN and
      // leaves the refusal to the codec.
      if (now && std::isnan(*now)) {
        EXPECT_FALSE(today.ok());
        continue;
      }
      ASSERT_EQ(today.ok(), now.has_value()) << r;
      if (today.ok()) {
        ASSERT_DOUBLE_EQ(*now, today.value) << r;
      }
    }
    for (const double x : {0.0, 23.15, 50.0, 3276.75, 3276.8, -1.0, 255.0, 256.0, -32768.0, 10.5}) {
      const auto today = lustbus::from_engineering(l, x);
      const Converted now = from_engineering(t, x);
      ASSERT_EQ(today.ok(), now.ok()) << x;
      if (today.ok()) {
        ASSERT_EQ(today.value, pattern(t, now.raw)) << x;
      }
    }
  }
}

// canlust:: (CANLust's wire images): the wire image is the canonical Raw.
TEST(OdTypesKeepTodays, CanlustTypesAreTheirWireImages) {
  std::mt19937 gen(3);
  std::uniform_int_distribution<std::uint32_t> any;
  for (int c = 0; c < 10; ++c) {
    const auto k = static_cast<canlust::DataType>(c);
    const Type t = of(k);
    SCOPED_TRACE(std::string(canlust::to_string(k)));
    EXPECT_EQ(canlust::to_string(k) == "ERR_STRUC" ? "MC_ERROR" : canlust::to_string(k),
              to_string(t));
    for (int i = 0; i < 70000; ++i) {
      std::uint32_t w = any(gen);
      if (i < 0x200) w = static_cast<std::uint32_t>(i);
      if (i >= 0x200 && i < 0x400) w = 0xFFFFFF00U + static_cast<std::uint32_t>(i - 0x200);
      ASSERT_EQ(canlust::wire_fits(k, w), is_canonical(t, w)) << w;
    }
  }
  EXPECT_EQ(canlust::q16_from_double(10.5),
            static_cast<std::int32_t>(from_engineering(Type::int32q16, 10.5).raw));
  EXPECT_EQ(*canlust::fixpoint16_from_double(10.05), from_engineering(Type::fixpoint16, 10.05).raw);
  const canlust::ErrStruc e{16, 172, 85};
  EXPECT_EQ(canlust::wire_from_err_struc(e), error_record_raw({16, 172, 85}));
}

}  // namespace
}  // namespace ibs::od
