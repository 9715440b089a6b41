// The dictionary: its index (made at compile time, one load a lookup), the lookups by number, name
// and "NNN-NAME", the roles, and every refusal of check()/validate() with the entry it names.
#include "ibs/od/dictionary.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "sample.hpp"

namespace ibs::od {
namespace {

using test::kCda;
using test::kMc;
using test::kVf;

// Made at compile time: the wings' tables are constexpr, and so are lookups in them.
static_assert(kVf.slot(22) == 5);
static_assert(kVf.slot(23) == kNoSlot);
static_assert(kVf.slot(0xFFFF) == kNoSlot);
static_assert(kVf.find("906-IB-WD")->number == 906);
static_assert(kCda.slot_of(Role::save) == 4);
static_assert(check(test::kMcEntries).ok());

TEST(OdDictionary, SlotIsOneLookup) {
  // For every 16-bit number the index says what a walk of the entries says.
  for (const Dictionary* d : {&kVf, &kMc, &kCda}) {
    for (std::uint32_t n = 0; n <= 0xFFFF; ++n) {
      Slot walk = kNoSlot;
      for (std::size_t i = 0; i < d->size(); ++i) {
        if (d->entries()[i].number == n) walk = static_cast<Slot>(i);
      }
      ASSERT_EQ(d->slot(static_cast<std::uint16_t>(n)), walk) << n;
      ASSERT_EQ(d->find(static_cast<std::uint16_t>(n)),
                walk == kNoSlot ? nullptr : &d->entries()[walk]);
    }
  }
  // (What it costs -- a compare and one load -- bench/od measures: BM_Slot, slot_once.)
}

TEST(OdDictionary, FindsByNumberNameOrBoth) {
  EXPECT_EQ(kCda.find("574")->name, "CAWDG");
  EXPECT_EQ(kCda.find("0574")->name, "CAWDG");
  EXPECT_EQ(kCda.find("cawdg")->number, 574);
  EXPECT_EQ(kCda.find("574-CAWDG")->number, 574);
  EXPECT_EQ(kCda.find("574-cawdg")->number, 574);
  EXPECT_EQ(kCda.find("04-PROG")->number, 4);
  EXPECT_EQ(kCda.find("574-CASCY"), nullptr);
  EXPECT_EQ(kCda.find("999"), nullptr);
  EXPECT_EQ(kCda.find("99999999999"), nullptr);
  EXPECT_EQ(kCda.find("nonsense"), nullptr);
  EXPECT_EQ(kCda.find(""), nullptr);
  EXPECT_EQ(kCda.find("574-"), nullptr);
  EXPECT_EQ(kCda.find("-574"), nullptr);
  // A name with a dash (INTERBUS manual 4.1.1: 906-IB-WD), by name and by both.
  EXPECT_EQ(kVf.find("IB-WD")->number, 906);
  EXPECT_EQ(kVf.find("906-ib-wd")->number, 906);
  EXPECT_EQ(kVf.find("IB"), nullptr);
  EXPECT_EQ(kVf.slot("VB2"), 5);
  EXPECT_EQ(kVf.slot("VB3"), kNoSlot);
}

TEST(OdDictionary, RolesAndProfile) {
  EXPECT_EQ(kVf[kVf.slot_of(Role::error_flags)].name, "SIOF");
  EXPECT_EQ(kVf[kVf.slot_of(Role::load_defaults)].number, 71);
  EXPECT_EQ(kVf.slot_of(Role::download), kNoSlot);
  EXPECT_EQ(kVf.slot_of(Role::value), kNoSlot);
  EXPECT_EQ(kMc[kMc.slot_of(Role::download)].name, "SLOAD");
  EXPECT_EQ(kCda.slot_of(Role::error_flags), kNoSlot);
  EXPECT_EQ(kVf.profile(), Profile::lust_standard);
  EXPECT_EQ(kCda.profile(), Profile::none);
}

// One valid entry, then one thing wrong with it per row.
Entry good() {
  return {.number = 574, .name = "CAWDG", .type = Type::usign8, .min = 0, .max = 255, .unit = "ms"};
}

constexpr std::array kTwoChoices{Choice{0, "OFF", ""}, Choice{6, "OPTN2", ""}};
constexpr std::array kRepeatedChoice{Choice{0, "OFF", ""}, Choice{1, "off", ""}};
constexpr std::array kWideChoice{Choice{0x100, "BIG", ""}};
constexpr Keypad kInDataSet{.activity = 5};

struct Refused {
  const char* name;
  Entry entry;
  ErrorCode code;
  const char* what;  // in the message
};

std::vector<Refused> refused_rows() {
  std::vector<Refused> rows;
  const auto row = [&rows](const char* name, auto change, ErrorCode code, const char* what) {
    Entry e = good();
    change(e);
    rows.push_back({name, e, code, what});
  };
  row(
      "NumberAbove3FFH", [](Entry& e) { e.number = 0x400; }, ErrorCode::table_number_out_of_range,
      "above 3FFH");
  row(
      "EmptyName", [](Entry& e) { e.name = ""; }, ErrorCode::table_bad_name,
      "name must be printable");
  row(
      "NameWithALeadingDigit", [](Entry& e) { e.name = "9AB"; }, ErrorCode::table_bad_name,
      "no digit");
  row(
      "NameEndingInADash", [](Entry& e) { e.name = "AB-"; }, ErrorCode::table_bad_name, "'-'");
  row(
      "NameWithATab", [](Entry& e) { e.name = "A\tB"; }, ErrorCode::table_bad_name, "printable");
  row(
      "UnitNotPrintable", [](Entry& e) { e.unit = "\x01"; }, ErrorCode::table_bad_unit, "unit");
  row(
      "ScaleZero", [](Entry& e) { e.scale = 0.0; }, ErrorCode::table_scale_not_positive, "scale");
  row(
      "ScaleNaN", [](Entry& e) { e.scale = std::nan(""); }, ErrorCode::table_scale_not_positive,
      "scale");
  row(
      "NoElements", [](Entry& e) { e.elements = 0; }, ErrorCode::table_bad_elements, "element");
  row(
      "MaxOutsideTheType", [](Entry& e) { e.max = 256; }, ErrorCode::table_limits_outside_type,
      "outside the data type");
  row(
      "MinOutsideTheType", [](Entry& e) { e.min = -1; }, ErrorCode::table_limits_outside_type,
      "outside the data type");
  row(
      "MinAboveMax", [](Entry& e) { e.min = 10, e.max = 9, e.default_value = 9; },
      ErrorCode::table_min_above_max, "min above max");
  row(
      "DefaultAboveMax", [](Entry& e) { e.max = 9, e.default_value = 10; },
      ErrorCode::table_default_outside_limits, "default");
  row(
      "DefaultTextOfANumber", [](Entry& e) { e.default_text = "x"; },
      ErrorCode::table_default_outside_limits, "text");
  row(
      "TextLongerThan255", [](Entry& e) { e.type = Type::string, e.max = 256; },
      ErrorCode::table_limits_outside_type, "0..255");
  row(
      "DefaultTextTooLong",
      [](Entry& e) { e.type = Type::string, e.max = 3, e.default_text = "LCAN"; },
      ErrorCode::table_default_outside_limits, "default text");
  row(
      "FloatMinAboveMax",
      [](Entry& e) {
        e.type = Type::float_ieee, e.min = 0x40000000, e.max = 0x3F800000,
        e.default_value = 0x3F800000;
      },
      ErrorCode::table_min_above_max, "min above max");
  row(
      "ShowTextWithoutChoices", [](Entry& e) { e.attributes = attr::kShowText; },
      ErrorCode::table_bad_choices, "ShowText");
  row(
      "ChoicesOnlyWithoutChoices", [](Entry& e) { e.choices_only = true; },
      ErrorCode::table_bad_choices, "choices_only");
  row(
      "ChoiceNameTwice", [](Entry& e) { e.choices = kRepeatedChoice; },
      ErrorCode::table_bad_choices, "used twice");
  row(
      "ChoiceNoValueOfTheType", [](Entry& e) { e.choices = kWideChoice; },
      ErrorCode::table_bad_choices, "no value of the type");
  row(
      "DefaultNoneOfTheChoices",
      [](Entry& e) { e.choices = kTwoChoices, e.choices_only = true, e.default_value = 3; },
      ErrorCode::table_bad_choices, "default is none");
  row(
      "SiofNotAt85", [](Entry& e) { e.role = Role::error_flags, e.storage = Storage::ram_actual; },
      ErrorCode::table_bad_role, "number 85");
  row(
      "SiofWritable", [](Entry& e) { e.number = 85, e.role = Role::error_flags; },
      ErrorCode::table_bad_role, "not writable");
  row(
      "SloadUnsigned", [](Entry& e) { e.role = Role::download; }, ErrorCode::table_bad_role,
      "signed");
  row(
      "ProgReadOnly", [](Entry& e) { e.role = Role::load_defaults, e.read_only = true; },
      ErrorCode::table_bad_role, "PROG");
  row(
      "SaveWithoutOne", [](Entry& e) { e.role = Role::save, e.max = 0; }, ErrorCode::table_bad_role,
      "take 1");
  row(
      "KeypadActivityOutsideTheDataSet", [](Entry& e) { e.keypad = &kInDataSet; },
      ErrorCode::table_bad_role, "activity area");
  row(
      "ReadOnlyInTheDataSet",
      [](Entry& e) { e.in_data_set = true, e.storage = Storage::ram_actual; },
      ErrorCode::table_bad_role, "only writable values");
  return rows;
}

TEST(OdDictionary, ValidateRefusesEveryBrokenRuleNamingTheEntry) {
  const Entry first{.number = 1, .name = "MODE", .type = Type::usign8, .max = 4};
  for (const Refused& r : refused_rows()) {
    SCOPED_TRACE(r.name);
    const std::array entries{first, r.entry};
    const Finding f = check(entries);
    EXPECT_EQ(f.code, r.code);
    EXPECT_EQ(f.entry, 1U);
    const Error e = Dictionary::validate(entries);
    EXPECT_EQ(e.code, r.code);
    EXPECT_EQ(e.message.rfind("dictionary entry 1 (" + std::to_string(r.entry.number) + "-", 0), 0U)
        << e.message;
    EXPECT_NE(e.message.find(r.what), std::string::npos) << e.message;
    // The constructor of the default build throws the same message.
    try {
      const Dictionary d(entries);
      ADD_FAILURE() << "made a dictionary of " << r.name;
    } catch (const std::invalid_argument& x) {
      EXPECT_EQ(x.what(), e.message);
    }
  }
}

TEST(OdDictionary, ValidateRefusesRepeatsAcrossEntries) {
  const Entry a{
      .number = 4, .name = "PROG", .type = Type::usign8, .max = 1, .role = Role::load_defaults};
  Entry b = a;
  b.name = "PROG2";
  EXPECT_EQ(check(std::array{a, b}).code, ErrorCode::table_number_repeated);
  b.number = 5;
  EXPECT_EQ(check(std::array{a, b}).code, ErrorCode::table_bad_role);
  b.role = Role::value;
  b.name = "prog";
  EXPECT_EQ(check(std::array{a, b}).code,
            ErrorCode::table_bad_name);  // names are found in any case
  b.name = "FOO";
  EXPECT_TRUE(check(std::array{a, b}).ok());
  EXPECT_TRUE(Dictionary::validate(std::array{a, b}).ok());
  EXPECT_EQ(Dictionary::validate(std::vector<Entry>(1025, a)).code, ErrorCode::table_too_large);
}

TEST(OdDictionary, TheDrivesOfTodayPass) {
  EXPECT_TRUE(Dictionary::validate(test::kVfEntries).ok());
  EXPECT_TRUE(Dictionary::validate(test::kMcEntries).ok());
  EXPECT_TRUE(Dictionary::validate(test::kCdaEntries).ok());
  // Made at run time too (a test's or a tool's table), with the same index.
  const Dictionary d(test::kVfEntries);
  for (std::uint16_t n = 0; n <= kMaxNumber; ++n) EXPECT_EQ(d.slot(n), kVf.slot(n));
}

}  // namespace
}  // namespace ibs::od
