// Value text from the dictionary entry (ibs_od_text): what the CDA3000's parameters.cpp and the
// LUSTBUS command line's value checks do today, ported (tests/cda3000/parameters_test.cpp,
// tests/lustbus_cli/cli_test.cpp "BadInputExitsTwoWithAClearMessage") -- numbers, substitution
// texts, Hz of an INT32Q16, raw 0x patterns, and every refusal naming parameter, value and limit.
#include "ibs/od/value_text.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <random>
#include <string>

#include "sample.hpp"

namespace ibs::od {
namespace {

using test::kCda;
using test::kMc;
using test::kVf;

const Entry& cda(std::uint16_t n) {
  return *kCda.find(n);
}
const Entry& vf(std::uint16_t n) {
  return *kVf.find(n);
}
const Entry& mc(std::uint16_t n) {
  return *kMc.find(n);
}
constexpr TextStyle kCdaStyle{2, test::cda_error_name};

TEST(OdValueText, DisplayNames) {
  EXPECT_EQ(display_name(cda(574)), "574-CAWDG");
  EXPECT_EQ(display_name(cda(4), kCdaStyle), "04-PROG");  // CANLust manual: "parameter 04 PROG"
  EXPECT_EQ(display_name(vf(4)), "4-FSSEL");              // LUSTBUS manual: "4-FSSEL"
  EXPECT_EQ(display_name(vf(906)), "906-IB-WD");
}

// From tests/cda3000/parameters_test.cpp, ChecksSayWhichLimit and ParseValueNumbersNamesAndHz.
TEST(OdValueText, CdaChecksSayWhichLimit) {
  EXPECT_EQ(fit(cda(574), 255), Fit::ok);
  EXPECT_EQ(fit(cda(574), 256), Fit::too_high);
  EXPECT_EQ(fit(cda(406), 0x00148000U), Fit::ok);
  EXPECT_EQ(fit(cda(575), 0), Fit::too_low);
  EXPECT_EQ(fit(cda(575), 32001), Fit::too_high);
  EXPECT_EQ(refusal_text(cda(575), 32001, Refusal::too_high),
            "575-CASCY: 32001 ms is above the maximum 32000 ms");
  EXPECT_EQ(fit_text(cda(575), 32001), "575-CASCY: 32001 ms is above the maximum 32000 ms");
  EXPECT_EQ(fit_text(cda(575), 80), "");
  EXPECT_EQ(fit(cda(280), 3), Fit::not_a_choice);
  EXPECT_EQ(format_value(cda(280), 6), "6 (OPTN2)");
}

TEST(OdValueText, CdaParseNumbersNamesAndHz) {
  EXPECT_EQ(parse_value(cda(574), "100").raw, 100U);
  EXPECT_EQ(parse_value(cda(574), "+100").raw, 100U);
  EXPECT_EQ(parse_value(cda(260), "OPTN2").raw, 6U);
  EXPECT_EQ(parse_value(cda(260), "optn2").raw, 6U);
  EXPECT_EQ(parse_value(cda(575), "0").error, "575-CASCY: 0 ms is below the minimum 1 ms");
  EXPECT_EQ(parse_value(cda(574), "300").error, "574-CAWDG: 300 ms is above the maximum 255 ms");
  EXPECT_EQ(parse_value(cda(260), "SIO").error,
            "260-CLSEL: 'SIO' is not a number or one of TERM, OPTN2");
  EXPECT_EQ(parse_value(cda(260), "3").error,
            "260-CLSEL: 3 is not one of its values (0 TERM, 6 OPTN2)");
  EXPECT_FALSE(parse_value(cda(90), "x"));
  EXPECT_EQ(parse_value(cda(90), "x").error,
            "90-NAME: a STRING parameter takes text, not a number (string write)");
  EXPECT_EQ(parse_value(cda(574), "").error, "574-CAWDG: no value given");
  // INT32Q16 in its unit: 20.5 Hz = 00 80 14 00 (CANLust manual 5.5.5).
  EXPECT_EQ(parse_value(cda(406), "20.5").raw, 0x00148000U);
  EXPECT_EQ(format_value(cda(406), 0x00148000U), "20.5 Hz");
  EXPECT_EQ(parse_value(cda(406), "-20.5").raw, static_cast<Raw>(-0x00148000));
  EXPECT_EQ(parse_value(cda(406), "fast").error, "406-REFF: 'fast' is not a number of Hz");
  EXPECT_EQ(parse_value(cda(406), "40000").error,
            "406-REFF: 40000 Hz is above the maximum 32767.99998 Hz");
  EXPECT_EQ(parse_value(cda(406), "nan").error, "406-REFF: 'nan' is not a number of Hz");
  EXPECT_EQ(parse_value(cda(574), "5.5").error, "574-CAWDG: '5.5' is not a whole number");
  EXPECT_EQ(parse_value(cda(574), "99999999999999999999").error,
            "574-CAWDG: 99999999999999999999 ms is above the maximum 255 ms");
  EXPECT_EQ(parse_value(cda(574), "1e3").error, "574-CAWDG: 1000 ms is above the maximum 255 ms");
  EXPECT_EQ(parse_value(cda(574), "2e1").raw, 20U);
}

// From tests/lustbus_cli/cli_test.cpp: the LUSTBUS command line's value checks.
TEST(OdValueText, LustbusValues) {
  EXPECT_EQ(parse_value(vf(4), "26").error, "4-FSSEL: 26 is above the maximum 25");
  EXPECT_EQ(parse_value(vf(5), "-1").error, "5-FSSIO: -1 Hz is below the minimum 0.00 Hz");
  EXPECT_EQ(parse_value(vf(5), "-1", {.check_limits = false}).error,
            "5-FSSIO: -1 Hz does not fit its data type FIXPOINT16 (value too low)");
  EXPECT_EQ(parse_value(mc(417), "0x1FF").error,
            "417-RSSL1: raw value '0x1FF' is not a 8-bit hex number");
  EXPECT_EQ(parse_value(mc(417), "0x").error,
            "417-RSSL1: raw value '0x' is not a 8-bit hex number");
  EXPECT_EQ(parse_value(mc(417), "0x-1").error,
            "417-RSSL1: raw value '0x-1' is not a 8-bit hex number");
  EXPECT_EQ(refusal_text(vf(91), 1, Refusal::read_only), "91-TYPE is read-only");
  // FIXPOINT16 in its unit: 23.15 Hz = 463 (LUSTBUS manual 7.1), 50.00 Hz = 03E8H (6.2.2).
  EXPECT_EQ(parse_value(vf(5), "23.15").raw, 463U);
  EXPECT_EQ(parse_value(vf(5), "0x3E8").raw, 0x3E8U);
  EXPECT_EQ(format_value(vf(5), 463), "23.15 Hz");
  EXPECT_EQ(parse_value(vf(5), "1000").error, "5-FSSIO: 1000.00 Hz is above the maximum 999.95 Hz");
  // An INTEGER16 in 0.05 Hz (911-FDRIV): the raw pattern is the two's complement.
  EXPECT_EQ(parse_value(vf(911), "-10").raw, raw(Type::int16, -200));
  EXPECT_EQ(parse_value(vf(911), "0xFFFF").raw, raw(Type::int16, -1));
  EXPECT_EQ(format_value(vf(911), raw(Type::int16, -200)), "-10 Hz");
  // A data set the drive tests as a whole: only the type is checked (LUSTBUS manual 11.4).
  EXPECT_EQ(parse_value(mc(419), "9", {.check_limits = false}).raw, 9U);
  EXPECT_EQ(parse_value(mc(419), "256", {.check_limits = false}).error,
            "419-RSSL3: 256 does not fit its data type USIGN8");
  EXPECT_EQ(parse_value(mc(419), "9").error, "419-RSSL3: 9 is above the maximum 7");
  // A substitution text of the enhanced family (LUSTBUS manual 11.3).
  EXPECT_EQ(parse_value(mc(417), "RSIO").raw, 3U);
  EXPECT_EQ(format_value(mc(417), 3), "3 (RSIO)");
  EXPECT_EQ(format_value(mc(77), from_engineering(Type::int32q16, 2500.25).raw), "2500.25 rpm");
  EXPECT_EQ(number_text(mc(77), 0x7FFFFFFF), "32767.99998");
  EXPECT_EQ(number_text(mc(77), 1), "1.52588e-05");
}

TEST(OdValueText, FloatsErrorsAndTheirTexts) {
  EXPECT_EQ(parse_value(mc(600), "1.5").raw, std::bit_cast<Raw>(1.5F));
  EXPECT_EQ(format_value(mc(600), std::bit_cast<Raw>(1.5F)), "1.5");
  EXPECT_EQ(parse_value(mc(600), "101").error, "600-GAIN: 101 is above the maximum 100");
  EXPECT_EQ(parse_value(mc(600), "-0.5").error, "600-GAIN: -0.5 is below the minimum 0");
  // CANLust manual p. 32: E-OP2 at location 172 after 85 h; the name is the wing's.
  EXPECT_EQ(format_value(cda(95), 0x0055AC10U, kCdaStyle), "16 E-OP2 at location 172, 85 h");
  EXPECT_EQ(format_value(cda(95), 0x0055AC10U), "16 at location 172, 85 h");
  EXPECT_EQ(format_value(cda(95), 0), "0 (no error)");
  EXPECT_EQ(parse_value(cda(95), "0x0055AC10").raw, 0x0055AC10U);
  const Entry vf_error{
      .number = 97, .name = "ERR", .type = Type::error16, .max = 0xFFFF, .default_value = 0x0F0F};
  EXPECT_EQ(format_value(vf_error, 0x0304), "error 3, 24 min after power-on");
  EXPECT_EQ(format_value(vf_error, 0x030F), "error 3");
  EXPECT_EQ(format_value(vf_error, 0x0F0F), "no error");
}

// Whatever a value is, its text parses back to it exactly (the number, or the substitution text):
// six significant digits where they are enough, more where not (the top of an INT32Q16).
TEST(OdValueText, EveryFormattedValueParsesBack) {
  for (const Dictionary* d : {&kVf, &kMc, &kCda}) {
    for (const Entry& e : d->entries()) {
      if (e.is_text() || e.type == Type::error16 || e.type == Type::error32) continue;
      SCOPED_TRACE(display_name(e));
      std::mt19937 gen(e.number);
      for (int i = 0; i < 2000; ++i) {
        const std::int64_t span = e.max - e.min;
        const std::int64_t n =
            e.min + static_cast<std::int64_t>(gen() % static_cast<std::uint64_t>(span + 1));
        const Raw r = raw(e.type, n);
        if (fit(e, r) != Fit::ok) continue;
        std::string text =
            e.choice(r) != nullptr ? std::string(e.choice(r)->name) : number_text(e, r);
        const ParsedValue p = parse_value(e, text);
        ASSERT_TRUE(p) << text << ": " << p.error;
        ASSERT_EQ(*p.raw, r) << text;
      }
    }
  }
}

}  // namespace
}  // namespace ibs::od
