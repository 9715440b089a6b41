// The data set text of a download (CANLust manual, "Downloading parameter data sets"; docs/canlust.md
// D39): one `PARAM VALUE` a line, resolved by the drive's table; every refusal names its line.
#include <gtest/gtest.h>

#include <string>

#include "ibs/canlust/data_set.hpp"

namespace ibs::canlust {
namespace {

// A table of two parameters: 574 (0..255) and 575 (1..32000), by number only.
ResolvedRecord resolve(std::string_view param, std::string_view value) {
  const std::string p(param);
  const std::string v(value);
  if (p != "574" && p != "575") return {0, 0, "'" + p + "' is not a parameter of the table"};
  for (const char c : v) {
    if (c < '0' || c > '9') return {0, 0, p + ": '" + v + "' is not a number"};
  }
  return {static_cast<std::uint16_t>(std::stoi(p)), static_cast<std::uint32_t>(std::stoul(v)), {}};
}

struct ParseRow {
  const char* name;
  const char* text;
  std::size_t records;     // when it parses
  std::size_t error_line;  // else
  const char* error;
};

const ParseRow kRows[] = {
    {"TwoRecordsCommentsAndBlanks", "# a data set\n574 100   # the watchdog\n\n  575\t40\r\n", 2, 0, ""},
    {"NoNewlineAtTheEnd", "574 100", 1, 0, ""},
    {"OneWord", "574 100\n575\n", 0, 2, "expected `PARAM VALUE`"},
    {"ThreeWords", "574 1 2\n", 0, 1, "expected `PARAM VALUE`"},
    {"UnknownParameter", "\n\n999 1\n", 0, 3, "'999' is not a parameter of the table"},
    {"BadValue", "574 x\n", 0, 1, "574: 'x' is not a number"},
    {"Twice", "574 1\n575 2\n574 3\n", 0, 3, "parameter 574 is given twice (first on line 1)"},
    {"Empty", "# nothing\n\n", 0, 0, "no `PARAM VALUE` line: the data set is empty"},
};

class DataSetText : public ::testing::TestWithParam<ParseRow> {};

TEST_P(DataSetText, RecordsOrTheLineThatIsWrong) {
  const ParseRow row = GetParam();
  const DataSetParse p = parse_data_set(row.text, resolve);
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

INSTANTIATE_TEST_SUITE_P(Rows, DataSetText, ::testing::ValuesIn(kRows),
                         [](const ::testing::TestParamInfo<ParseRow>& p) { return std::string(p.param.name); });

TEST(DataSetText, RecordsKeepTheirLinesAndValues) {
  const DataSetParse p = parse_data_set("\n575 40\n574 100 # w\n", resolve);
  ASSERT_TRUE(p);
  ASSERT_EQ(p.records.size(), 2U);
  EXPECT_EQ(p.records[0].parameter, 575);
  EXPECT_EQ(p.records[0].value, 40U);
  EXPECT_EQ(p.records[0].line, 2U);
  EXPECT_EQ(p.records[1].parameter, 574);
  EXPECT_EQ(p.records[1].line, 3U);
}

TEST(DataSetText, BinaryAndOverlongLinesAreRefused) {
  EXPECT_EQ(parse_data_set(std::string_view("574 1\n575\0 2\n", 12), resolve).error_line, 2U);
  const std::string long_line = "574 " + std::string(kMaxDataSetLine, '1') + "\n";
  const DataSetParse p = parse_data_set(long_line, resolve);
  EXPECT_EQ(p.error_line, 1U);
  EXPECT_NE(p.error.find("at most 200"), std::string::npos) << p.error;
}

}  // namespace
}  // namespace ibs::canlust
