// drive::ParameterTable::validate (docs/embedding.md, "An embedded build"): each malformed table
// comes back as its error code with the very message the constructor throws, and a table it
// accepts is the table the constructor builds.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "ibs/drive/parameters.hpp"
#include "ibs/base/error.hpp"

namespace ibs::drive {
namespace {

// What the constructor throws for the table ("" when it accepts it).
std::string thrown(std::span<const ParameterInfo> params) {
  try {
    const ParameterTable t(params);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

const ParameterInfo kOk{7, "ABC", "", Category::ram_control, DataType::usign8, 0, 10, 5, 1.0, ""};

struct Refused {
  const char* name;
  std::vector<ParameterInfo> table;
  ErrorCode code;
  const char* message;
};

ParameterInfo with(void (*change)(ParameterInfo&)) {
  ParameterInfo p = kOk;
  change(p);
  return p;
}

std::vector<ParameterInfo> numbered(std::size_t n) {
  std::vector<ParameterInfo> v(n, kOk);
  for (std::size_t i = 0; i < n; ++i) v[i].number = static_cast<std::uint16_t>(i);
  return v;
}

TEST(ParameterTableValidate, EveryRefusalHasItsCodeAndTheConstructorsMessage) {
  const std::vector<Refused> cases{
      {"too large", numbered(0x401), ErrorCode::table_too_large,
       "parameter table: 1025 entries, but numbers only run from 0 to 3FFH"},
      {"number above 3FFH",
       {with([](ParameterInfo& p) { p.number = 0x400; })},
       ErrorCode::table_number_out_of_range,
       "parameter table entry 0 (parameter 1024-ABC): number above 3FFH (INTERBUS manual 4.1.3)"},
      {"number used twice",
       {kOk, kOk},
       ErrorCode::table_number_repeated,
       "parameter table entry 1 (parameter 7-ABC): number used twice"},
      {"empty name",
       {with([](ParameterInfo& p) { p.name = ""; })},
       ErrorCode::table_bad_name,
       "parameter table entry 0 (parameter 7-): name must be 1 to 5 printable characters "
       "(4.1.3.3)"},
      {"long name",
       {with([](ParameterInfo& p) { p.name = "TOOLONG"; })},
       ErrorCode::table_bad_name,
       "parameter table entry 0 (parameter 7-TOOLONG): name must be 1 to 5 printable characters "
       "(4.1.3.3)"},
      {"unprintable unit",
       {with([](ParameterInfo& p) { p.unit = "x\x01"; })},
       ErrorCode::table_bad_unit,
       "parameter table entry 0 (parameter 7-ABC): unit must be at most 5 printable characters "
       "(4.1.3.3)"},
      {"max outside the type",
       {with([](ParameterInfo& p) { p.max = 0x100; })},
       ErrorCode::table_limits_outside_type,
       "parameter table entry 0 (parameter 7-ABC): min/max outside the range of PT_USIGN8"},
      {"min above max",
       {with([](ParameterInfo& p) { p.min = 11; })},
       ErrorCode::table_min_above_max,
       "parameter table entry 0 (parameter 7-ABC): min above max"},
      {"default outside",
       {with([](ParameterInfo& p) { p.default_value = 11; })},
       ErrorCode::table_default_outside_limits,
       "parameter table entry 0 (parameter 7-ABC): default outside min/max"},
      {"zero scale",
       {with([](ParameterInfo& p) { p.scale = 0.0; })},
       ErrorCode::table_scale_not_positive,
       "parameter table entry 0 (parameter 7-ABC): scale must be positive"},
      {"NaN scale",
       {with([](ParameterInfo& p) { p.scale = std::numeric_limits<double>::quiet_NaN(); })},
       ErrorCode::table_scale_not_positive,
       "parameter table entry 0 (parameter 7-ABC): scale must be positive"},
  };
  for (const Refused& c : cases) {
    SCOPED_TRACE(c.name);
    const Error e = ParameterTable::validate(c.table);
    EXPECT_TRUE(e);
    EXPECT_EQ(e.code, c.code);
    EXPECT_EQ(e.message, c.message);
    EXPECT_EQ(e.message, thrown(c.table));
  }
}

TEST(ParameterTableValidate, TheFirstBadEntryIsTheOneNamed) {
  ParameterInfo second = kOk;
  second.number = 9;
  second.min = 11;
  ParameterInfo third = kOk;
  third.number = 9;
  const std::vector<ParameterInfo> table{kOk, second, third};
  EXPECT_EQ(ParameterTable::validate(table).code, ErrorCode::table_min_above_max);
  EXPECT_EQ(ParameterTable::validate(table).message, thrown(table));
}

TEST(ParameterTableValidate, AnAcceptedTableIsTheOneTheConstructorBuilds) {
  std::vector<ParameterInfo> table = numbered(0x400);  // every number 0..3FFH
  table[5].name = "FIVE";
  EXPECT_FALSE(ParameterTable::validate(table));
  EXPECT_EQ(thrown(table), "");
  const ParameterTable t(table);
  EXPECT_EQ(t.size(), 0x400U);
  EXPECT_EQ(t.find(5)->name, "FIVE");
  EXPECT_EQ(t.slot(0x3FF), 0x3FF);
  EXPECT_FALSE(ParameterTable::validate({}));
  EXPECT_EQ(ParameterTable(std::span<const ParameterInfo>{}).find(0), nullptr);
}

}  // namespace
}  // namespace ibs::drive
