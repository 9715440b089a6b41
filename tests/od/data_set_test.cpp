// The data set's text (CANLust manual "Downloading parameter data sets", D39; LUSTBUS manual 11.4): the line
// reader ported from tests/canlust/data_set_test.cpp, and the dictionary's resolution that the
// CANLust download and the LUSTBUS download of tools/ibs each did their own way.
#include "ibs/od/data_set.hpp"

#include <gtest/gtest.h>

#include <string>

#include "sample.hpp"

namespace ibs::od {
namespace {

// A table of two parameters: 574 (0..255) and 575 (1..32000), by number only.
ResolvedRecord resolve(std::string_view param, std::string_view value) {
  const std::string p(param);
  const std::string v(value);
  if (p != "574" && p != "575") return {0, 0, "'" + p + "' is not a parameter of the table"};
  for (const char c : v) {
    if (c < '0' || c > '9') return {0, 0, p + ": '" + v + "' is not a number"};
  }
  return {static_cast<std::uint16_t>(std::stoi(p)), static_cast<Raw>(std::stoul(v)), {}};
}

struct ParseRow {
  const char* name;
  const char* text;
  std::size_t records;     // when it parses
  std::size_t error_line;  // else
  const char* error;
};

const ParseRow kRows[] = {
    {"TwoRecordsCommentsAndBlanks", "# a data set\n574 100   # the watchdog\n\n  575\t40\r\n", 2, 0,
     ""},
    {"NoNewlineAtTheEnd", "574 100", 1, 0, ""},
    {"OneWord", "574 100\n575\n", 0, 2, "expected `PARAM VALUE`"},
    {"ThreeWords", "574 1 2\n", 0, 1, "expected `PARAM VALUE`"},
    {"ManyWords", "574 1 2 3 4 5 6\n", 0, 1, "expected `PARAM VALUE`"},
    {"UnknownParameter", "\n\n999 1\n", 0, 3, "'999' is not a parameter of the table"},
    {"BadValue", "574 x\n", 0, 1, "574: 'x' is not a number"},
    {"Twice", "574 1\n575 2\n574 3\n", 0, 3, "parameter 574 is given twice (first on line 1)"},
    {"Empty", "# nothing\n\n", 0, 0, "no `PARAM VALUE` line: the data set is empty"},
    {"NothingAtAll", "", 0, 0, "no `PARAM VALUE` line: the data set is empty"},
};

class OdDataSetText : public ::testing::TestWithParam<ParseRow> {};

TEST_P(OdDataSetText, RecordsOrTheLineThatIsWrong) {
  const ParseRow row = GetParam();
  const DataSet p = parse_data_set(row.text, resolve);
  if (row.records > 0) {
    ASSERT_TRUE(p) << p.error;
    EXPECT_EQ(p.records.size(), row.records);
    return;
  }
  EXPECT_FALSE(p);
  EXPECT_TRUE(p.records.empty());
  EXPECT_EQ(p.error_line, row.error_line);
  EXPECT_EQ(p.error, row.error);
}

INSTANTIATE_TEST_SUITE_P(Rows, OdDataSetText, ::testing::ValuesIn(kRows),
                         [](const ::testing::TestParamInfo<ParseRow>& p) {
                           return std::string(p.param.name);
                         });

TEST(OdDataSet, RecordsKeepTheirLinesAndValues) {
  const DataSet p = parse_data_set("\n575 40\n574 100 # w\n", resolve);
  ASSERT_TRUE(p);
  ASSERT_EQ(p.records.size(), 2U);
  EXPECT_EQ(p.records[0].number, 575);
  EXPECT_EQ(p.records[0].raw, 40U);
  EXPECT_EQ(p.records[0].line, 2U);
  EXPECT_EQ(p.records[1].number, 574);
  EXPECT_EQ(p.records[1].line, 3U);
}

TEST(OdDataSet, BinaryOverlongAndTooManyLinesAreRefused) {
  EXPECT_EQ(parse_data_set(std::string_view("574 1\n575\0 2\n", 12), resolve).error_line, 2U);
  const std::string long_line = "574 " + std::string(kMaxDataSetLine, '1') + "\n";
  const DataSet p = parse_data_set(long_line, resolve);
  EXPECT_EQ(p.error_line, 1U);
  EXPECT_NE(p.error.find("at most 200"), std::string::npos) << p.error;
  std::string many;
  for (std::size_t i = 0; i <= kMaxDataSetRecords; ++i) many += std::to_string(i) + " 1\n";
  const auto count = [](std::string_view param, std::string_view) {
    return ResolvedRecord{static_cast<std::uint16_t>(std::stoi(std::string(param))), 1, {}};
  };
  const DataSet q = parse_data_set(many, count);
  EXPECT_EQ(q.error_line, kMaxDataSetRecords + 1);
  EXPECT_EQ(q.error, "more than 1000 records");
}

// The CDA3000's data set (CANLust manual D39): names, numbers, substitution texts and Hz; only Card
// Writeable parameters; each value against its entry.
TEST(OdDataSet, ByTheDictionaryWithLimits) {
  const DataSetOptions cda{.check_limits = true, .style = {2, nullptr}, .title = "CDA3000"};
  DataSet p = parse_data_set("CAWDG 100\n575 40\n260-CLSEL OPTN2\nrssl1 fmax\n", test::kCda, cda);
  ASSERT_TRUE(p) << p.error;
  ASSERT_EQ(p.records.size(), 4U);
  EXPECT_EQ(p.records[2].number, 260);
  EXPECT_EQ(p.records[2].raw, 6U);
  EXPECT_EQ(p.records[3].raw, 11U);
  p = parse_data_set("999 1\n", test::kCda, cda);
  EXPECT_EQ(p.error, "'999' is not a CDA3000 parameter");
  p = parse_data_set("CAWDG 1\n04-PROG 1\n", test::kCda, cda);
  EXPECT_EQ(p.error_line, 2U);
  EXPECT_EQ(p.error, "04-PROG cannot be part of a data set (it is not Card Writeable)");
  p = parse_data_set("CAWDG 300\n", test::kCda, cda);
  EXPECT_EQ(p.error, "574-CAWDG: 300 ms is above the maximum 255 ms");
  p = parse_data_set("CAWDG 1\n574 2\n", test::kCda, cda);
  EXPECT_EQ(p.error, "parameter 574 is given twice (first on line 1)");
}

// The MC6000's data set over LUSTBUS (LUSTBUS manual 11.4, tests/lustbus_cli DownloadADatasetFile): the
// values are checked for their type only -- the servo tests the whole set -- and a parameter
// without the CardWriteable attribute is refused with its line.
TEST(OdDataSet, ByTheDictionaryTypeOnly) {
  const DataSetOptions mc{.check_limits = false};
  DataSet p = parse_data_set("# speed control\nRSSL1 3   # RSIO\n419 9\n", test::kMc, mc);
  ASSERT_TRUE(p) << p.error;
  EXPECT_EQ(p.records[1].raw, 9U);
  p = parse_data_set("RSSL1 RSIO\n", test::kMc, mc);
  EXPECT_EQ(p.records[0].raw, 3U);
  p = parse_data_set("RSSL1 3\nSPEED 1\n", test::kMc, mc);
  EXPECT_EQ(p.error_line, 2U);
  EXPECT_EQ(p.error, "77-SPEED cannot be part of a data set (it is not Card Writeable)");
  p = parse_data_set("RSSL1 0x1FF\n", test::kMc, mc);
  EXPECT_EQ(p.error, "417-RSSL1: raw value '0x1FF' is not a 8-bit hex number");
  p = parse_data_set("FOO 1\n", test::kMc, mc);
  EXPECT_EQ(p.error, "'FOO' is not a parameter");
}

}  // namespace
}  // namespace ibs::od
