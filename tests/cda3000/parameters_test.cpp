// The CDA3000 parameter table against CANLust manual (CM-CAN1 manual): the rows whose range, factory
// setting, unit or type the manual prints are checked against its text, transcribed here first;
// then the value checks and conversions the drive and the master share.
#include <gtest/gtest.h>

#include <string>

#include "ibs/devices/cda3000/descriptor.hpp"
#include "ibs/devices/cda3000/parameters.hpp"

namespace ibs::devices::cda3000 {
namespace {

using canlust::DataType;

// What CANLust manual prints, row by row (number, name, min, max, factory, unit): 4.3.1 "489 CLBDR CAN
// bus baud rate 25 500 500", "574 CAWDG CAN bus watchdog time 0 255 0 ms", "575 CASCY Sampling
// time for status message 1 32000 80 ms"; 4.3.2 "_28RS 0 FCON 11 FMAX 11 FMAX USIGN8 FLASH".
struct ManualRow {
  std::uint16_t number;
  std::string_view name;
  std::int64_t min;
  std::int64_t max;
  std::int64_t factory;
  std::string_view unit;
};
constexpr ManualRow kManual[] = {
    {489, "CLBDR", 25, 500, 500, "kBaud"},
    {574, "CAWDG", 0, 255, 0, "ms"},
    {575, "CASCY", 1, 32000, 80, "ms"},
    {280, "RSSL1", 0, 11, 11, ""},
};

TEST(Cda3000Parameters, RowsTheManualPrintsAreTheManuals) {
  for (const auto& m : kManual) {
    const ParameterInfo* p = find_parameter(m.number);
    ASSERT_NE(p, nullptr) << m.number;
    EXPECT_EQ(p->name, m.name);
    EXPECT_EQ(p->min, m.min) << m.name;
    EXPECT_EQ(p->max, m.max) << m.name;
    EXPECT_EQ(p->factory, m.factory) << m.name;
    EXPECT_EQ(p->unit, m.unit) << m.name;
  }
  EXPECT_EQ(find_parameter(kRssl1)->type, DataType::usign8);
  EXPECT_EQ(find_parameter(kRssl1)->memory, Memory::flash);
  EXPECT_FALSE(find_parameter(kClbdr)->invented);
  EXPECT_FALSE(find_parameter(kCawdg)->invented);
  EXPECT_FALSE(find_parameter(kCascy)->invented);
}

// Every parameter the seed and the notes name is in the table.
TEST(Cda3000Parameters, EveryNamedParameterIsThere) {
  const std::pair<std::uint16_t, std::string_view> named[] = {
      {4, "PROG"},    {150, "SAVE"},  {151, "ASTPR"}, {152, "ASTER"}, {180, "FISA0"},
      {260, "CLSEL"}, {280, "RSSL1"}, {360, "DISP"},  {406, "REFF"},  {489, "CLBDR"},
      {492, "CACNF"}, {570, "CAMOD"}, {571, "CLADR"}, {574, "CAWDG"}, {575, "CASCY"},
      {578, "OPTN2"}, {651, "CDSSL"}};
  for (const auto& [n, name] : named) {
    const ParameterInfo* p = find_parameter(n);
    ASSERT_NE(p, nullptr) << n;
    EXPECT_EQ(p->name, name);
    EXPECT_FALSE(p->source.empty());
  }
  // Numbers are unique, every row's factory setting passes its own check.
  for (std::size_t i = 0; i < kParameters.size(); ++i) {
    for (std::size_t j = i + 1; j < kParameters.size(); ++j) EXPECT_NE(kParameters[i].number, kParameters[j].number);
    const auto& p = kParameters[i];
    if (!p.is_string() && p.number != kReff) {
      EXPECT_EQ(check_value(p, wire_of(p, p.factory)), ValueCheck::ok) << display_name(p);
    }
  }
}

// The substitution-text codes the seed prints: 280-RSSL1 "7 TBSEL" (5.4.1 footnote 1), FCON 0,
// FA0 1, FA1 2, FPOT 4, FMAX 11 (4.3.2); 651-CDSSL "6 OPTN2" (footnote 2). D22: OPTN2 = 6 in
// every selector.
TEST(Cda3000Parameters, SubstitutionTextCodesOfTheSeed) {
  const ParameterInfo& rssl1 = *find_parameter(kRssl1);
  EXPECT_EQ(find_choice(rssl1, "TBSEL")->code, 7U);
  EXPECT_EQ(find_choice(rssl1, "FCON")->code, 0U);
  EXPECT_EQ(find_choice(rssl1, "FA0")->code, 1U);
  EXPECT_EQ(find_choice(rssl1, "FA1")->code, 2U);
  EXPECT_EQ(find_choice(rssl1, "FPOT")->code, 4U);
  EXPECT_EQ(find_choice(rssl1, "FMAX")->code, 11U);
  EXPECT_EQ(find_choice(*find_parameter(kCdssl), "OPTN2")->code, 6U);
  for (const auto n : {kRssl1, kClsel, kFisa0, kCdssl}) {
    EXPECT_EQ(find_choice(*find_parameter(n), "optn2")->code, kOptn2Code) << n;
  }
}

TEST(Cda3000Parameters, FindByNumberNameOrBoth) {
  EXPECT_EQ(find_parameter("574")->number, 574);
  EXPECT_EQ(find_parameter("cawdg")->number, 574);
  EXPECT_EQ(find_parameter("574-CAWDG")->number, 574);
  EXPECT_EQ(find_parameter("04-PROG")->number, 4);
  EXPECT_EQ(find_parameter("574-CASCY"), nullptr);
  EXPECT_EQ(find_parameter("999"), nullptr);
  EXPECT_EQ(find_parameter("nonsense"), nullptr);
  EXPECT_EQ(display_name(*find_parameter(kProg)), "04-PROG");
  EXPECT_EQ(display_name(*find_parameter(kCawdg)), "574-CAWDG");
}

TEST(Cda3000Parameters, ChecksSayWhichLimit) {
  const ParameterInfo& cawdg = *find_parameter(kCawdg);
  EXPECT_EQ(check_value(cawdg, 255), ValueCheck::ok);
  EXPECT_EQ(check_value(cawdg, 256), ValueCheck::above_max);
  EXPECT_EQ(check_value(*find_parameter(kReff), 0x00148000U), ValueCheck::ok);
  const ParameterInfo& cascy = *find_parameter(kCascy);
  EXPECT_EQ(check_value(cascy, 0), ValueCheck::below_min);
  EXPECT_EQ(check_value(cascy, 32001), ValueCheck::above_max);
  EXPECT_EQ(describe_refusal(cascy, 32001, ValueCheck::above_max),
            "575-CASCY: 32001 ms is above the maximum 32000 ms");
  const ParameterInfo& rssl1 = *find_parameter(kRssl1);
  EXPECT_EQ(check_value(rssl1, 3), ValueCheck::not_a_choice);
  EXPECT_EQ(format_value(rssl1, 6), "6 (OPTN2)");
}

TEST(Cda3000Parameters, ParseValueNumbersNamesAndHz) {
  EXPECT_EQ(parse_value(*find_parameter(kCawdg), "100").wire, 100U);
  EXPECT_EQ(parse_value(*find_parameter(kClsel), "OPTN2").wire, 6U);
  EXPECT_EQ(parse_value(*find_parameter(kCascy), "0").error, "575-CASCY: 0 ms is below the minimum 1 ms");
  EXPECT_EQ(parse_value(*find_parameter(kCawdg), "300").error, "574-CAWDG: 300 ms is above the maximum 255 ms");
  EXPECT_EQ(parse_value(*find_parameter(kClsel), "SIO").error,
            "260-CLSEL: 'SIO' is not a number or one of TERM, OPTN2");
  EXPECT_EQ(parse_value(*find_parameter(kClsel), "3").error,
            "260-CLSEL: 3 is not one of its values (0 TERM, 6 OPTN2)");
  EXPECT_FALSE(parse_value(*find_parameter(kName), "x").wire);
  // INT32Q16 in its unit: 20.5 Hz = 00 80 14 00 (5.5.5).
  EXPECT_EQ(parse_value(*find_parameter(kReff), "20.5").wire, 0x00148000U);
  EXPECT_EQ(format_value(*find_parameter(kReff), 0x00148000U), "20.5 Hz");
}

// 5.5.5: 20.5 Hz = 00 80 14 00 in Q16; Int16Q0 (CACNF 1) carries whole Hz (D25).
TEST(Cda3000Scaling, ReferenceInHz) {
  EXPECT_EQ(wire_from_hz(canlust::ValueWidth::int32q16, 20.5), 0x00148000);
  EXPECT_EQ(wire_from_hz(canlust::ValueWidth::int16q0, 20.4), 20);
  EXPECT_EQ(wire_from_hz(canlust::ValueWidth::int16q0, -50.0), -50);
  EXPECT_FALSE(wire_from_hz(canlust::ValueWidth::int16q0, 40000.0));
  EXPECT_FALSE(wire_from_hz(canlust::ValueWidth::int32q16, 40000.0));
  EXPECT_DOUBLE_EQ(hz_from_wire(canlust::ValueWidth::int32q16, 0x00148000), 20.5);
}

// 7.1.2's status words explained; the ENABLE OPERATION row of 5.4.2 (CAN-E9) is 37H, bit 6 clear.
TEST(Cda3000Words, StatusAndControlInWords) {
  EXPECT_EQ(explain_status_word(0x0240), "0240 START-UP INHIBIT, block-power request, e-stop request, remote");
  EXPECT_EQ(explain_status_word(0x0231), "0231 READY, remote");
  EXPECT_EQ(explain_status_word(0x0637), "0637 ENABLED, remote, reference reached");
  EXPECT_EQ(explain_control_word(0x000F), "000F POWER-ON/ENABLE");
  EXPECT_EQ(explain_control_word(0x0080, 0x0000), "0080 BLOCK POWER, RESET FAULT edge");
}

}  // namespace
}  // namespace ibs::devices::cda3000
