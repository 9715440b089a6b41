// The drives' descriptors without exceptions (docs/embedding.md, "An embedded build"):
// try_configure, validate_watchdog and try_ring_entry refuse with the code, the message and the
// named setting that configure, check_watchdog and ring_entry throw as SettingsError, and what they
// accept is what the throwing forms give.
#include <gtest/gtest.h>

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ibs/devices/descriptor.hpp"
#include "ibs/devices/mc6000/descriptor.hpp"
#include "ibs/devices/vf1000/descriptor.hpp"
#include "ibs/base/error.hpp"

namespace ibs::devices {
namespace {

using namespace std::chrono_literals;

struct Thrown {
  std::string what;
  std::string setting;
  std::string fallback;
};

// The SettingsError `f` throws, nullopt when it throws none.
std::optional<Thrown> thrown(const std::function<void()>& f) {
  try {
    f();
  } catch (const SettingsError& e) {
    return Thrown{e.what(), std::string(e.setting()), std::string(e.fallback())};
  }
  return std::nullopt;
}

void expect_same(const SettingsRefusal& r, const std::optional<Thrown>& t) {
  ASSERT_TRUE(t.has_value()) << "the throwing form accepted: " << r.message;
  EXPECT_EQ(r.message, t->what);
  EXPECT_EQ(r.setting, t->setting);
  EXPECT_EQ(r.fallback, t->fallback);
}

void expect_same(const Configuration& a, const Configuration& b) {
  EXPECT_EQ(a.settings, b.settings);
  EXPECT_EQ(a.id_code, b.id_code);
  EXPECT_EQ(a.bus, b.bus);
  EXPECT_EQ(a.exchanges_data, b.exchanges_data);
  EXPECT_EQ(a.pd_words, b.pd_words);
  EXPECT_EQ(a.pcp_words, b.pcp_words);
}

DeviceSettings mc(int supi, int ibcnf, interbus::BusKind bus = interbus::BusKind::remote) {
  DeviceSettings s;
  s.drive.set_integer("supi", supi);
  s.drive.set_integer("ibcnf", ibcnf);
  s.bus = bus;
  return s;
}

TEST(DescriptorError, Mc6000ConfigureRefusesTheLayoutNamingTheSetting) {
  const DriveDescriptor& k = mc6000::descriptor();
  struct Case {
    DeviceSettings settings;
    ErrorCode code;
    std::string_view setting;
    std::string_view fallback;
    const char* message;
  };
  const std::vector<Case> cases{
      {mc(13, 2), ErrorCode::layout_setting_out_of_range, "supi", "ibcnf",
       "405-SUPI = 13 is out of range (0..12, INTERBUS manual 3.2.2)"},
      {mc(-1, 2), ErrorCode::layout_setting_out_of_range, "supi", "ibcnf",
       "405-SUPI = -1 is out of range (0..12, INTERBUS manual 3.2.2)"},
      {mc(11, 5), ErrorCode::layout_setting_out_of_range, "ibcnf", "supi",
       "406-IBCNF = 5 is out of range (0..4, INTERBUS manual 3.2.3)"},
      {mc(9, 4), ErrorCode::layout_setting_unsupported, "ibcnf", "supi",
       "406-IBCNF = 4 (modified LISIM software) is not supported"},
      {mc(7, 2, interbus::BusKind::local), ErrorCode::layout_settings_conflict, "ibcnf", "supi",
       "406-IBCNF = 2 needs 405-SUPI 10..12, not 7 (INTERBUS manual 3.2.3)"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.message);
    const Expected<Configuration, SettingsRefusal> r = k.try_configure(c.settings);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().code, c.code);
    EXPECT_EQ(r.error().message, c.message);
    EXPECT_EQ(r.error().setting, c.setting);
    EXPECT_EQ(r.error().fallback, c.fallback);
    expect_same(r.error(), thrown([&] { (void)k.configure(c.settings); }));
    // A configuration of other settings is not one try_configure gave: the driver refuses it too.
    Configuration forged = k.configure(DeviceSettings{});
    forged.settings = c.settings;
    expect_same(r.error(), thrown([&] { (void)k.make_driver(forged); }));
  }
}

TEST(DescriptorError, Mc6000ConfigureAcceptsWhatConfigureAccepts) {
  const DriveDescriptor& k = mc6000::descriptor();
  int accepted = 0;
  for (int supi = 0; supi <= 12; ++supi) {
    for (int ibcnf = 0; ibcnf <= 3; ++ibcnf) {
      for (const auto bus : {interbus::BusKind::local, interbus::BusKind::remote}) {
        const DeviceSettings s = mc(supi, ibcnf, bus);
        const Expected<Configuration, SettingsRefusal> r = k.try_configure(s);
        const std::optional<Thrown> t = thrown([&] { (void)k.configure(s); });
        EXPECT_EQ(r.ok(), !t.has_value()) << supi << "/" << ibcnf;
        if (!r.ok()) {
          expect_same(r.error(), t);
          continue;
        }
        ++accepted;
        expect_same(r.value(), k.configure(s));
        EXPECT_NE(k.make_driver(r.value()), nullptr);
      }
    }
  }
  EXPECT_GT(accepted, 20);
}

TEST(DescriptorError, Vf1000ConfigureRefusesTheLocalBus) {
  const DriveDescriptor& k = vf1000::descriptor();
  DeviceSettings s;
  s.bus = interbus::BusKind::local;
  const Expected<Configuration, SettingsRefusal> r = k.try_configure(s);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::setting_bus_refused);
  EXPECT_EQ(r.error().message, "a VF1000 is always a remote bus device (INTERBUS manual 1.3)");
  EXPECT_EQ(r.error().setting, "bus");
  expect_same(r.error(), thrown([&] { (void)k.configure(s); }));

  s.bus = interbus::BusKind::remote;
  const Expected<Configuration, SettingsRefusal> ok = k.try_configure(s);
  ASSERT_TRUE(ok.ok());
  expect_same(ok.value(), k.configure(s));
  EXPECT_EQ(ok->id_code, interbus::IdCode{0x33B});
}

TEST(DescriptorError, WatchdogSettingsOfBothDrives) {
  struct Case {
    const DriveDescriptor* kind;
    DeviceSettings settings;
    ErrorCode code;  // none: accepted
    std::string_view setting;
  };
  const auto with = [](void (*change)(DeviceSettings&)) {
    DeviceSettings s;
    change(s);
    return s;
  };
  const DriveDescriptor* vf = &vf1000::descriptor();
  const DriveDescriptor* mc = &mc6000::descriptor();
  const std::vector<Case> cases{
      {vf, {}, ErrorCode::none, ""},
      {vf, with([](DeviceSettings& s) { s.watchdog_ms = 7; }), ErrorCode::setting_out_of_range,
       "watchdog_ms"},
      {vf, with([](DeviceSettings& s) { s.watchdog_ms = 65536; }), ErrorCode::setting_out_of_range,
       "watchdog_ms"},
      {vf, with([](DeviceSettings& s) { s.watchdog_ms = 8; }), ErrorCode::none, ""},
      {vf, with([](DeviceSettings& s) { s.watchdog_reaction = 4; }),
       ErrorCode::setting_out_of_range, "watchdog_reaction"},
      {vf, with([](DeviceSettings& s) { s.drive.set_duration("reset_time", 0s); }), ErrorCode::setting_out_of_range,
       "reset_time"},
      {vf, with([](DeviceSettings& s) { s.drive.set_duration("reset_time", 61s); }), ErrorCode::setting_out_of_range,
       "reset_time"},
      {vf, with([](DeviceSettings& s) { s.drive.set_boolean("keypad", true); }), ErrorCode::none, ""},
      {mc, {}, ErrorCode::none, ""},
      {mc, with([](DeviceSettings& s) { s.watchdog_ms = 0; }), ErrorCode::none, ""},
      {mc, with([](DeviceSettings& s) { s.watchdog_ms = -1; }), ErrorCode::setting_out_of_range,
       "watchdog_ms"},
      {mc, with([](DeviceSettings& s) { s.watchdog_reaction = 1; }),
       ErrorCode::setting_of_another_drive, "watchdog_reaction"},
      // The VF1000's own settings given an MC6000: check_settings' (settings_test.cpp).
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(std::string(c.kind->name()) + " " + std::string(c.setting));
    const SettingsRefusal r = c.kind->validate_watchdog(c.settings);
    const std::optional<Thrown> t = thrown([&] { c.kind->check_watchdog(c.settings); });
    EXPECT_EQ(r.code, c.code);
    if (c.code == ErrorCode::none) {
      EXPECT_FALSE(r);
      EXPECT_FALSE(t.has_value());
      continue;
    }
    EXPECT_TRUE(r);
    EXPECT_EQ(r.setting, c.setting);
    EXPECT_FALSE(r.message.empty());
    expect_same(r, t);
  }
}

TEST(DescriptorError, RingEntriesOfBothDrives) {
  struct Case {
    const DriveDescriptor* kind;
    std::vector<std::string_view> fields;
    ErrorCode code;
    std::string_view setting;
    const char* message;
  };
  const DriveDescriptor* vf = &vf1000::descriptor();
  const DriveDescriptor* mc = &mc6000::descriptor();
  const std::vector<Case> cases{
      {mc,
       {},
       ErrorCode::setting_missing,
       "supi",
       "the 405-SUPI is missing, expected mc6000:SUPI[:local|remote]"},
      {mc,
       {""},
       ErrorCode::setting_missing,
       "supi",
       "the 405-SUPI is missing, expected mc6000:SUPI[:local|remote]"},
      {mc,
       {"11", "local", "x"},
       ErrorCode::setting_too_many_fields,
       "",
       "too many fields, expected mc6000:SUPI[:local|remote]"},
      {mc, {"11x"}, ErrorCode::setting_invalid, "supi", "405-SUPI '11x' is not a number"},
      {mc,
       {"13"},
       ErrorCode::layout_setting_out_of_range,
       "supi",
       "405-SUPI 13 is out of range (0..12, INTERBUS manual 3.2.2)"},
      {mc,
       {"11", "upper"},
       ErrorCode::setting_invalid,
       "bus",
       "bus 'upper' is neither local nor remote"},
      {vf,
       {"11"},
       ErrorCode::setting_too_many_fields,
       "",
       "the VF1000 takes no settings (it always reports 33BH, 3 words on the remote bus, INTERBUS manual "
       "3.1.2)"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.message);
    const Expected<RingEntry, SettingsRefusal> r = c.kind->try_ring_entry(c.fields);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().code, c.code);
    EXPECT_EQ(r.error().setting, c.setting);
    EXPECT_EQ(r.error().message, c.message);
    expect_same(r.error(), thrown([&] { (void)c.kind->ring_entry(c.fields); }));
  }

  const std::vector<std::string_view> local{"0", "local"};
  const Expected<RingEntry, SettingsRefusal> e = mc->try_ring_entry(local);
  ASSERT_TRUE(e.ok());
  const RingEntry thrown_form = mc->ring_entry(local);
  EXPECT_EQ(e->id_code, thrown_form.id_code);
  EXPECT_EQ(e->id_code, interbus::IdCode{0x193});
  EXPECT_EQ(e->bus, interbus::BusKind::local);
  EXPECT_EQ(e->note, thrown_form.note);
  ASSERT_EQ(e->settings.size(), 1U);
  EXPECT_EQ(e->settings[0].key, "supi");
  EXPECT_EQ(e->settings[0].number, 0);
  const Expected<RingEntry, SettingsRefusal> v = vf->try_ring_entry({});
  ASSERT_TRUE(v.ok());
  EXPECT_EQ(v->id_code, vf->ring_entry({}).id_code);
}

}  // namespace
}  // namespace ibs::devices
