// The drives' own settings as their wings declare them (devices/settings.hpp) and check_settings,
// which every reader (scenario, trace header, command line) uses besides the wing's own checks.
#include <gtest/gtest.h>

#include <chrono>
#include <set>
#include <string>

#include "ibs/devices/registry.hpp"

namespace ibs::devices {
namespace {

using namespace std::chrono_literals;

const DriveKind& kind(std::string_view name) { return *find_drive_kind(name); }

TEST(DriveSettings, EveryDeclarationIsWhole) {
  std::set<std::string_view> names;
  for (const DriveKind& k : drive_kinds()) {
    for (const SettingSpec& s : k->settings()) {
      SCOPED_TRACE(std::string(k->name()) + " " + std::string(s.name));
      // One name means one setting: no two kinds declare the same name (a reader would not know
      // which declaration's type to read it by before the device's type).
      EXPECT_TRUE(names.insert(s.name).second);
      EXPECT_EQ(k->setting(s.name), &s);
      EXPECT_LE(s.min, s.fallback);
      EXPECT_LE(s.fallback, s.max);
      EXPECT_FALSE(s.seed.empty());
      EXPECT_FALSE(s.range.empty());
      EXPECT_FALSE(s.meaning.empty());
      EXPECT_NE(s.faces, 0);
      EXPECT_NE(s.elsewhere.find("'" + std::string(s.name) + "'"), std::string_view::npos);
      if (s.kind == SettingKind::boolean) {
        EXPECT_EQ(s.min, 0);
        EXPECT_EQ(s.max, 1);
      }
      // The declared default is what the drive does when nothing is given.
      EXPECT_FALSE(check_settings(k, SettingValues{}));
      SettingValues at_default;
      at_default.set(s.name, s.kind, s.fallback);
      EXPECT_FALSE(check_settings(k, at_default));
    }
  }
  EXPECT_EQ(declared_setting_names().size(), names.size());
}

TEST(DriveSettings, TheDefaultsAreTheFactorySettings) {
  // MC6000: 405-SUPI 11 = 3 process-data words and 1 PCP word, ID code 4DBH (INTERBUS manual 3.2.2).
  const Configuration mc = kind("mc6000")->configure(DeviceSettings{});
  EXPECT_EQ(mc.pd_words, 3U);
  EXPECT_EQ(mc.pcp_words, 1U);
  EXPECT_EQ(mc.id_code, interbus::IdCode{0x04DB});
  // Given explicitly, the same.
  DeviceSettings given;
  given.drive.set_integer("supi", 11);
  given.drive.set_integer("ibcnf", 2);
  EXPECT_EQ(kind("mc6000")->configure(given).id_code, mc.id_code);
  given.drive.set_integer("supi", 12);
  EXPECT_EQ(kind("mc6000")->configure(given).pd_words, 4U);
}

TEST(DriveSettings, CheckSettingsNamesTheSettingTheValueAndTheLimit) {
  struct Case {
    std::string_view kind;
    SettingValues values;
    ErrorCode code;
    std::string_view setting;
    std::string message;
  };
  const auto with = [](std::string_view name, SettingKind k, std::int64_t v) {
    SettingValues s;
    s.set(name, k, v);
    return s;
  };
  const std::vector<Case> cases{
      {"vf1000", with("supi", SettingKind::integer, 11), ErrorCode::setting_of_another_drive, "supi",
       "'supi' is an MC6000 setting; a VF1000 has no 405-SUPI"},
      {"vf1000", with("ibcnf", SettingKind::integer, 2), ErrorCode::setting_of_another_drive, "ibcnf",
       "'ibcnf' is an MC6000 setting; a VF1000 has no 406-IBCNF"},
      {"mc6000", with("keypad", SettingKind::boolean, 1), ErrorCode::setting_of_another_drive, "keypad",
       "'keypad' is a VF1000 setting (INTERBUS manual 7.1); the MC6000's PCP times have no KEYPAD row"},
      {"mc6000", with("reset_time", SettingKind::duration, std::chrono::nanoseconds(1s).count()),
       ErrorCode::setting_of_another_drive, "reset_time",
       "'reset_time' is a VF1000 setting (5.2.1: its RESET FAULT is a software reset)"},
      {"mc6000", with("colour", SettingKind::integer, 1), ErrorCode::setting_invalid, "",
       "'colour' is not a setting of an MC6000"},
      {"mc6000", with("supi", SettingKind::boolean, 1), ErrorCode::setting_invalid, "supi",
       "'supi' must be an integer"},
      {"vf1000", with("keypad", SettingKind::integer, 1), ErrorCode::setting_invalid, "keypad",
       "'keypad' must be true or false"},
      {"mc6000", with("supi", SettingKind::integer, 13), ErrorCode::setting_out_of_range, "supi",
       "'supi' = 13 is out of range (0..12, 405-SUPI, INTERBUS manual 3.2.2)"},
      {"mc6000", with("ibcnf", SettingKind::integer, -1), ErrorCode::setting_out_of_range, "ibcnf",
       "'ibcnf' = -1 is out of range (0..4, 406-IBCNF, INTERBUS manual 3.2.3)"},
      {"vf1000", with("reset_time", SettingKind::duration, std::chrono::nanoseconds(61s).count()),
       ErrorCode::setting_out_of_range, "reset_time",
       "'reset_time' = 61000000000 ns is out of range (above 0 s and at most 60 s, INTERBUS manual 5.2.1)"},
      {"vf1000", with("reset_time", SettingKind::duration, std::chrono::nanoseconds(60s).count()), ErrorCode::none,
       "", ""},
      {"mc6000", with("supi", SettingKind::integer, 0), ErrorCode::none, "", ""},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(std::string(c.kind) + " " + c.message);
    const SettingsRefusal r = check_settings(kind(c.kind), c.values);
    EXPECT_EQ(r.code, c.code);
    EXPECT_EQ(r.setting, c.setting);
    EXPECT_EQ(r.message, c.message);
  }
}

TEST(DriveSettings, ValuesCompareByNameAndValueNotByOrder) {
  SettingValues a;
  a.set_integer("supi", 3);
  a.set_integer("ibcnf", 0);
  SettingValues b;
  b.set_integer("ibcnf", 0);
  b.set_integer("supi", 3);
  EXPECT_EQ(a, b);
  b.set_integer("supi", 4);
  EXPECT_NE(a, b);
  EXPECT_EQ(b.find("supi")->value, 4);
  b.erase("supi");
  EXPECT_FALSE(b.given("supi"));
  EXPECT_EQ(b.value(*kind("mc6000")->setting("supi")), 11);
}

}  // namespace
}  // namespace ibs::devices
