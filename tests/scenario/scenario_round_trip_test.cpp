// Writers and parsers agree: every valid scenario written as TOML or JSON reads back equal, and
// equality is equality of meaning (scenario.hpp, operator==).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "ibs/devices/registry.hpp"
#include "ibs/sim/scenario.hpp"

namespace ibs::sim {
namespace {

// A device's own setting as its drive reads it: the value given, or its kind's default.
std::int64_t setting_of(const ibs::sim::DeviceConfig& d, std::string_view name) {
  return d.settings.value(*(*ibs::devices::find_drive_kind(d.kind))->setting(name));
}

const std::string kExamples = std::string(IBS_SOURCE_DIR) + "/examples";

Scenario via_toml(const Scenario& s) {
  return parse_scenario_toml(write_scenario_toml(s), "rt.toml");
}
Scenario via_json(const Scenario& s) {
  return parse_scenario_json(write_scenario_json(s), "rt.json");
}

TimelineEntry entry(Time at, std::string device, Action a) {
  TimelineEntry e;
  e.at = at;
  e.device = std::move(device);
  e.action = a;
  return e;
}

// Every key the schema has, with values off the defaults.
Scenario everything() {
  Scenario s;
  s.name = "every \"key\" \\ once: ÄÖÜ";
  s.duration = 90s + 1ns;
  s.bus.cycle_time = 1234567ns;
  s.bus.baud_2mbit = true;
  s.bus.software_time = 0ns;
  s.bus.recovery_cycles = 0;
  DeviceConfig a;
  a.name = "axis_1";
  a.kind = "mc6000";
  a.settings.set_integer("supi", 9);
  a.settings.set_integer("ibcnf", 1);
  a.bus = interbus::BusKind::local;
  a.phase = 999999ns;
  a.jitter = 499999ns;
  a.initialised = false;
  a.watchdog_ms = 0;
  DeviceConfig b;
  b.name = "Conveyor-2";
  b.kind = "vf1000";
  b.phase = 8199999ns;
  b.jitter = 4099999ns;
  b.watchdog_ms = 65535;
  b.watchdog_reaction = 3;
  b.settings.set_boolean("keypad", true);
  b.settings.set_duration("reset_time", 2500ms);
  DeviceConfig c;
  c.name = "pcp-only";
  c.kind = "mc6000";
  c.settings.set_integer("supi", 3);
  c.settings.set_integer("ibcnf", 0);
  s.devices = {a, b, c};

  auto state = entry(0s, "axis_1", Action::state);
  state.value = "start-up-inhibit";
  auto wait = entry(0s, "axis_1", Action::wait_state);
  wait.value = "emergency-stop-active";
  wait.duration = 1500ms;
  auto wait_forever = entry(1s, "Conveyor-2", Action::wait_state);
  wait_forever.value = "fault-response-active";
  auto speed = entry(1s, "axis_1", Action::speed);
  speed.number = -32768.0;
  auto frequency = entry(1s, "Conveyor-2", Action::frequency);
  frequency.number = -0.05;
  auto read = entry(2s, "pcp-only", Action::read);
  read.parameter = 999;
  auto describe = entry(2s, "Conveyor-2", Action::describe);
  describe.parameter = 0x3FF;
  auto write_vf = entry(2s, "Conveyor-2", Action::write);
  write_vf.parameter = 0;
  write_vf.number = -32768;
  auto write_mc = entry(2s, "axis_1", Action::write);
  write_mc.parameter = 409;
  write_mc.number = 4294967295.0;
  auto corrupt = entry(3s, "", Action::fault_corrupt);
  corrupt.count = 10000;
  auto corrupt_once = entry(3s, "", Action::fault_corrupt);
  auto device_fault = entry(4s, "axis_1", Action::fault_device);
  device_fault.duration = 1ns;
  auto device_fault_short = entry(4s, "axis_1", Action::fault_device);
  auto lost = entry(5s, "Conveyor-2", Action::fault_lost);
  lost.duration = 24h;
  // Issue 24's plant events: a cause by name and by number, mains, load, an input.
  auto device_fault_cause = entry(4s, "axis_1", Action::fault_device);
  device_fault_cause.cause = "E-OP1";
  auto device_fault_number = entry(4s, "Conveyor-2", Action::fault_device);
  device_fault_number.cause = "14";
  auto mains_off = entry(5s, "axis_1", Action::mains);
  mains_off.value = "off";
  auto mains_on = entry(5s, "axis_1", Action::mains);
  mains_on.value = "on";
  auto load = entry(5s, "axis_1", Action::load);
  load.number = -0.125;
  auto input = entry(5s, "axis_1", Action::input);
  input.value = "IS01";
  input.level = true;
  s.timeline = {state,
                wait,
                entry(0s, "axis_1", Action::emergency_stop),
                entry(0s, "Conveyor-2", Action::block_power),
                wait_forever,
                speed,
                frequency,
                read,
                describe,
                write_vf,
                write_mc,
                corrupt,
                corrupt_once,
                device_fault,
                device_fault_short,
                entry(4s, "Conveyor-2", Action::fault_power_cycle),
                device_fault_cause,
                device_fault_number,
                lost,
                mains_off,
                mains_on,
                load,
                input,
                entry(90s + 1ns, "", Action::master_restart)};
  s.random.seed = 9223372036854775807ULL;
  s.random.corrupt_per_s = 1000.0;
  s.random.power_cycle_per_s = 0.1;
  s.random.device_fault_per_s = 1e-9;
  s.random.lost_per_s = 0.3333333333333333;
  s.random.master_restart_per_s = 0.0;
  return s;
}

TEST(ScenarioRoundTrip, DefaultScenarioIsValid) {
  EXPECT_NO_THROW(validate_scenario(default_scenario()));
}

TEST(ScenarioRoundTrip, DefaultScenarioMatchesTheBrief) {
  const Scenario s = default_scenario();
  EXPECT_EQ(s.name, "default");
  EXPECT_EQ(s.duration, 8s);
  ASSERT_EQ(s.devices.size(), 2U);
  EXPECT_EQ(s.devices[0].name, "mc6000");
  EXPECT_EQ(setting_of(s.devices[0], "supi"), 11);
  EXPECT_EQ(setting_of(s.devices[0], "ibcnf"), 2);
  EXPECT_EQ(s.devices[1].kind, "vf1000");
  ASSERT_EQ(s.timeline.size(), 16U);
  EXPECT_EQ(s.timeline[10].action, Action::speed);
  EXPECT_EQ(s.timeline[10].number, 2500.25);
  EXPECT_EQ(s.timeline[3].action, Action::write);
  EXPECT_EQ(s.timeline[3].parameter, 22);
  EXPECT_EQ(s.timeline[3].number, 1000.0);
  EXPECT_EQ(s.timeline[15].at, 7600ms);
  EXPECT_EQ(s.timeline[15].value, "ready");
}

TEST(ScenarioRoundTrip, DefaultScenarioThroughBothFormats) {
  const Scenario s = default_scenario();
  EXPECT_EQ(via_toml(s), s);
  EXPECT_EQ(via_json(s), s);
}

TEST(ScenarioRoundTrip, EveryKeyThroughBothFormats) {
  const Scenario s = everything();
  ASSERT_NO_THROW(validate_scenario(s));
  EXPECT_EQ(via_toml(s), s) << write_scenario_toml(s);
  EXPECT_EQ(via_json(s), s) << write_scenario_json(s);
  EXPECT_EQ(via_json(via_toml(s)), s);
}

TEST(ScenarioRoundTrip, ExamplesThroughBothFormats) {
  int files = 0;
  for (const auto& f : std::filesystem::directory_iterator(kExamples)) {
    const std::string ext = f.path().extension().string();
    if (ext != ".toml" && ext != ".json") continue;
    const Scenario s = load_scenario(f.path().string());
    EXPECT_EQ(via_toml(s), s) << f.path();
    EXPECT_EQ(via_json(s), s) << f.path();
    ++files;
  }
  EXPECT_GE(files, 3);
}

TEST(ScenarioRoundTrip, WrittenTextIsStable) {
  // Writing what was read gives the same text again.
  const std::string toml = write_scenario_toml(everything());
  EXPECT_EQ(write_scenario_toml(parse_scenario_toml(toml, "a.toml")), toml);
  const std::string json = write_scenario_json(everything());
  EXPECT_EQ(write_scenario_json(parse_scenario_json(json, "a.json")), json);
}

TEST(ScenarioRoundTrip, EmptyTimelineAndDefaultRandomFaults) {
  Scenario s = default_scenario();
  s.timeline.clear();
  EXPECT_EQ(write_scenario_toml(s).find("random_faults"), std::string::npos);
  EXPECT_EQ(via_toml(s), s);
  EXPECT_EQ(via_json(s), s);
}

TEST(ScenarioEquality, ComparesMeaningNotUnusedFields) {
  DeviceConfig vf;
  vf.name = "v";
  vf.kind = "vf1000";
  DeviceConfig vf2 = vf;
  vf2.settings.set_integer("supi", 3);  // a VF1000 has no SUPI: not compared
  vf2.settings.set_integer("ibcnf", 0);
  EXPECT_EQ(vf, vf2);
  DeviceConfig mc;
  mc.name = "m";
  mc.kind = "mc6000";
  DeviceConfig mc2 = mc;
  mc2.settings.set_integer("supi", 12);
  EXPECT_NE(mc, mc2);
  mc2 = mc;
  mc2.watchdog_ms = 0;  // set to 0 is not the same as not set
  EXPECT_NE(mc, mc2);

  TimelineEntry r = entry(1s, "v", Action::read);
  r.parameter = 85;
  TimelineEntry r2 = r;
  r2.number = 7.0;  // a read has no value
  r2.count = 3;
  r2.source_line = 42;
  EXPECT_EQ(r, r2);
  r2.parameter = 86;
  EXPECT_NE(r, r2);
  TimelineEntry w = entry(1s, "v", Action::write);
  TimelineEntry w2 = w;
  w2.number = 1.0;
  EXPECT_NE(w, w2);
  TimelineEntry c = entry(1s, "", Action::fault_corrupt);
  TimelineEntry c2 = c;
  c2.count = 2;
  EXPECT_NE(c, c2);
  c2 = c;
  c2.at = 2s;
  EXPECT_NE(c, c2);

  Scenario a = default_scenario();
  Scenario b = a;
  EXPECT_EQ(a, b);
  b.random.seed = 2;
  EXPECT_NE(a, b);
  b = a;
  b.bus.cycle_time = 1ms;
  EXPECT_NE(a, b);
  b = a;
  b.timeline.pop_back();
  EXPECT_NE(a, b);
}

TEST(ScenarioRoundTrip, NameDefaultsToTheFileStem) {
  const std::string body = "duration = \"1 s\"\n[[device]]\nname = \"m\"\ntype = \"mc6000\"\n";
  EXPECT_EQ(parse_scenario_toml(body, "dir/night_shift.toml").name, "night_shift");
  EXPECT_EQ(
      parse_scenario_json(R"({"duration": "1 s", "device": [{"name": "m", "type": "mc6000"}]})",
                          "x/y/estop2.json")
          .name,
      "estop2");
}

TEST(ScenarioRoundTrip, DefaultsOfOmittedKeys) {
  const Scenario s = parse_scenario_toml(
      "duration = \"1 s\"\n[[device]]\nname = \"m\"\ntype = \"mc6000\"\n"
      "[[device]]\nname = \"v\"\ntype = \"vf1000\"\n"
      "[[timeline]]\nat = \"0 s\"\nfault = \"corrupt\"\n"
      "[[timeline]]\nat = \"0 s\"\ndevice = \"v\"\nwait_state = \"on\"\n"
      "[[timeline]]\nat = \"0 s\"\ndevice = \"m\"\nfault = \"device\"\n",
      "d.toml");
  EXPECT_EQ(s.bus, BusSettings{});
  EXPECT_EQ(s.random, RandomFaults{});
  const DeviceConfig& m = s.devices[0];
  EXPECT_EQ(setting_of(m, "supi"), 11);
  EXPECT_EQ(setting_of(m, "ibcnf"), 2);
  EXPECT_EQ(m.bus, interbus::BusKind::remote);
  EXPECT_EQ(m.phase, 0ns);
  EXPECT_EQ(m.jitter, 0ns);
  EXPECT_TRUE(m.initialised);
  EXPECT_FALSE(m.watchdog_ms.has_value());
  EXPECT_FALSE(m.watchdog_reaction.has_value());
  EXPECT_TRUE(m.settings.empty());
  EXPECT_EQ(s.devices[1].bus, interbus::BusKind::remote);
  EXPECT_EQ(s.timeline[0].count, 1);
  EXPECT_EQ(s.timeline[1].duration, 0ns);  // wait up to the end of the run
  EXPECT_EQ(s.timeline[2].duration, 0ns);  // the cause clears at once
  EXPECT_EQ(s.timeline[1].source_line, 11U);
}

TEST(ScenarioRoundTrip, TimelineAsAnArrayOfInlineTables) {
  // The same data as [[timeline]] tables, written compactly; TOML wants it before any [table].
  const Scenario s = parse_scenario_toml(R"(duration = "1 s"
timeline = [
  { at = "0 s", device = "m", state = "enabled" },
  { at = "10 ms", device = "m", write = { parameter = 409, value = 100 } },
]
[[device]]
name = "m"
type = "mc6000"
)",
                                         "inline.toml");
  ASSERT_EQ(s.timeline.size(), 2U);
  EXPECT_EQ(s.timeline[1].parameter, 409);
  EXPECT_EQ(s.timeline[1].number, 100.0);
  EXPECT_EQ(s.timeline[1].source_line, 4U);
}

TEST(ScenarioRoundTrip, TomlHexIntegersAreIntegers) {
  const Scenario s = parse_scenario_toml(
      "duration = \"1 s\"\n[[device]]\nname = \"v\"\ntype = \"vf1000\"\n"
      "[[timeline]]\nat = \"0 s\"\ndevice = \"v\"\nread = 0x55\n",
      "hex.toml");
  EXPECT_EQ(s.timeline[0].parameter, 85);
}

TEST(ScenarioRoundTrip, ValidateScenarioNamesTheEntrysSourceLine) {
  Scenario s = default_scenario();
  s.timeline[2].parameter = 1000;  // MC6000 parameter numbers end at 999
  s.timeline[2].source_line = 17;
  try {
    validate_scenario(s, "built-in");
    FAIL() << "accepted";
  } catch (const ScenarioError& e) {
    EXPECT_EQ(e.file(), "built-in");
    EXPECT_EQ(e.line(), 17U);
    EXPECT_STREQ(e.what(),
                 "built-in:17: parameter 1000 is out of range for the MC6000 device "
                 "'mc6000' (0..999, LUSTBUS manual 2.4.2)");
  }
  s = default_scenario();
  // A VF1000 has no 405-SUPI: built in code, the validator refuses it as the reader does.
  s.devices[1].settings.set_integer("supi", 0);
  try {
    validate_scenario(s, "built-in");
    FAIL() << "accepted";
  } catch (const ScenarioError& e) {
    EXPECT_STREQ(e.what(), "built-in:0: device 'vf1000': 'supi' is an MC6000 setting; a VF1000 has no 405-SUPI");
  }
  s.devices[1].settings = {};
  EXPECT_NO_THROW(validate_scenario(s));
  s.devices[0].name = "mc 6000";
  EXPECT_THROW(validate_scenario(s), ScenarioError);
}

// A scenario built in code may name any kind; the validator asks the drive registry.
TEST(ScenarioRoundTrip, ValidateScenarioNamesAnUnknownDriveKind) {
  Scenario s = default_scenario();
  s.devices[1].kind = "vf2000";
  try {
    validate_scenario(s, "built-in");
    FAIL() << "accepted";
  } catch (const ScenarioError& e) {
    EXPECT_STREQ(e.what(), "built-in:0: device 'vf1000': unknown type 'vf2000' (\"mc6000\" or \"vf1000\")");
  }
}

}  // namespace
}  // namespace ibs::sim
