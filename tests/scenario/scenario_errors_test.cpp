// Every refusal of the scenario reader and validator, in both formats, with its exact
// FILE:LINE: message (docs/scenarios.md, "Errors"). Documents come from scenario_errors.hpp,
// which says on which line each part starts.
#include "scenario_errors.hpp"

#include <gtest/gtest.h>

#include <string>

#include "ibs/sim/scenario.hpp"

namespace ibs::sim::test {
namespace {

const std::string kTimeForm = "a number and a unit (ns, us, ms, s), e.g. \"250 ms\" or \"8.2 ms\"";

// ---- top level ------------------------------------------------------------------------------

TEST(ScenarioErrors, UnknownTopLevelKeys) {
  EXPECT_TRUE(refused(tdoc::top("nmae = \"x\"\nduration = \"1 s\"\n"), 1,
                      jdoc::top(" \"nmae\": \"x\",\n \"duration\": \"1 s\",\n"), 2,
                      "unknown key 'nmae' at the top level (did you mean 'name'?)"));
  EXPECT_TRUE(refused(tdoc::top("duration = \"1 s\"\ncolour = \"red\"\n"), 2,
                      jdoc::top(" \"duration\": \"1 s\",\n \"colour\": \"red\",\n"), 3,
                      "unknown key 'colour' at the top level (known: name, duration, bus, "
                      "device, timeline, random_faults, lustbus, dfs1)"));
  EXPECT_TRUE(refused(tdoc::top("duration = \"1 s\"\ndevices = []\n"), 2,
                      jdoc::top(" \"duration\": \"1 s\",\n \"devices\": [],\n"), 3,
                      "unknown key 'devices' at the top level (did you mean 'device'?)"));
}

TEST(ScenarioErrors, Name) {
  EXPECT_TRUE(refused(tdoc::top("name = 5\nduration = \"1 s\"\n"), 1,
                      jdoc::top(" \"name\": 5,\n \"duration\": \"1 s\",\n"), 2,
                      "'name' must be a string, not an integer"));
  EXPECT_TRUE(refused(tdoc::top("duration = \"1 s\"\nname = \"\"\n"), 2,
                      jdoc::top(" \"duration\": \"1 s\",\n \"name\": \"\",\n"), 3,
                      "'name' must not be empty"));
  EXPECT_TRUE(refused(tdoc::top("duration = \"1 s\"\nname = \"a\\u0007b\"\n"), 2,
                      jdoc::top(" \"duration\": \"1 s\",\n \"name\": \"a\\u0007b\",\n"), 3,
                      "'name' must not hold control characters"));
}

TEST(ScenarioErrors, Duration) {
  EXPECT_TRUE(refused(tdoc::top("name = \"x\"\n"), 1, jdoc::top(" \"name\": \"x\",\n"), 1,
                      "a scenario needs 'duration' (the simulated time to run, e.g. \"6 s\")"));
  const auto refused_duration = [](const std::string& toml_value, const std::string& json_value,
                                   const std::string& what, const std::string& json_what = {}) {
    return refused(tdoc::top("name = \"x\"\nduration = " + toml_value + "\n"), 2,
                   jdoc::top(" \"name\": \"x\",\n \"duration\": " + json_value + ",\n"), 3, what,
                   json_what);
  };
  EXPECT_TRUE(refused_duration(
      "6", "6", "'duration' must be a time string with a unit, e.g. \"250 ms\", not an integer"));
  EXPECT_TRUE(refused_duration(
      "6.5", "6.5",
      "'duration' must be a time string with a unit, e.g. \"250 ms\", not a fractional number"));
  EXPECT_TRUE(refused_duration(
      "1979-05-27", "null",
      "'duration' must be a time string with a unit, e.g. \"250 ms\", not a date/time",
      "'duration' must be a time string with a unit, e.g. \"250 ms\", not null"));
  EXPECT_TRUE(refused_duration("true", "true",
                               "'duration' must be a time string with a unit, e.g. \"250 ms\", "
                               "not true"));
  EXPECT_TRUE(refused_duration("\"6\"", "\"6\"",
                               "'duration': \"6\" has no unit: write \"6 s\" (or ms, us, ns)"));
  EXPECT_TRUE(refused_duration("\"6 h\"", "\"6 h\"",
                               "'duration': \"6 h\" has the unknown unit 'h' (ns, us, ms, s)"));
  EXPECT_TRUE(refused_duration("\"-1 s\"", "\"-1 s\"",
                               "'duration': \"-1 s\" is negative: times here are never negative"));
  EXPECT_TRUE(refused_duration("\"soon\"", "\"soon\"",
                               "'duration': \"soon\" is not a time: write " + kTimeForm));
  EXPECT_TRUE(refused_duration("\"1.5 ns\"", "\"1.5 ns\"",
                               "'duration': \"1.5 ns\" is not a whole number of nanoseconds"));
  EXPECT_TRUE(refused_duration("\"86401 s\"", "\"86401 s\"",
                               "'duration': \"86401 s\" is longer than 24 h"));
  EXPECT_TRUE(refused_duration("\"0 s\"", "\"0 s\"", "'duration' must be longer than 0 s"));
}

TEST(ScenarioErrors, SectionsOfTheWrongType) {
  EXPECT_TRUE(refused(tdoc::top("duration = \"1 s\"\nbus = \"fast\"\n"), 2,
                      jdoc::top(" \"duration\": \"1 s\",\n \"bus\": \"fast\",\n"), 3,
                      "'bus' must be a table, not a string",
                      "'bus' must be an object, not a string"));
  EXPECT_TRUE(refused(tdoc::top("duration = \"1 s\"\nrandom_faults = [1]\n"), 2,
                      jdoc::top(" \"duration\": \"1 s\",\n \"random_faults\": [1],\n"), 3,
                      "'random_faults' must be a table, not an array",
                      "'random_faults' must be an object, not an array"));
  EXPECT_TRUE(refused("duration = \"1 s\"\ndevice = \"m\"\n", 2,
                      "{\"duration\": \"1 s\",\n \"device\": \"m\"}", 2,
                      "'device' must be an array ([[device]] in TOML, [ ... ] in JSON), not a "
                      "string"));
  EXPECT_TRUE(refused("duration = \"1 s\"\n[device]\nname = \"m\"\n", 2,
                      "{\"duration\": \"1 s\",\n \"device\": {\"name\": \"m\"}}", 2,
                      "'device' must be an array ([[device]] in TOML, [ ... ] in JSON), not a "
                      "table",
                      "'device' must be an array ([[device]] in TOML, [ ... ] in JSON), not an "
                      "object"));
  EXPECT_TRUE(refused("duration = \"1 s\"\ndevice = [1]\n", 2,
                      "{\"duration\": \"1 s\",\n \"device\": [1]}", 2,
                      "each 'device' must be a table, not an integer",
                      "each 'device' must be an object, not an integer"));
  EXPECT_TRUE(refused(tdoc::top("duration = \"1 s\"\ntimeline = 3\n"), 2,
                      jdoc::top(" \"duration\": \"1 s\",\n \"timeline\": 3,\n"), 3,
                      "'timeline' must be an array ([[timeline]] in TOML, [ ... ] in JSON), not "
                      "an integer"));
  EXPECT_TRUE(refused(tdoc::top("duration = \"1 s\"\ntimeline = [\n\"x\"]\n"), 3,
                      jdoc::top(" \"duration\": \"1 s\",\n \"timeline\": [\n\"x\"],\n"), 4,
                      "each 'timeline' entry must be a table, not a string",
                      "each 'timeline' entry must be an object, not a string"));
}

TEST(ScenarioErrors, AtLeastOneDevice) {
  const std::string what =
      "a scenario needs at least one device ([[device]] in TOML, \"device\": [...] in JSON)";
  EXPECT_TRUE(refused("duration = \"1 s\"\ndevice = []\n", 2,
                      "{\"duration\": \"1 s\",\n \"device\": []}", 2, what));
  EXPECT_TRUE(refused("\nduration = \"1 s\"\n", 1, "\n{\"duration\": \"1 s\"}", 2, what));
}

TEST(ScenarioErrors, JsonTopLevelMustBeAnObject) {
  EXPECT_EQ(json_error("[1]"), at_json(1, "a scenario must be an object at the top, not an array"));
  EXPECT_EQ(json_error("\n\n\"x\""),
            at_json(3, "a scenario must be an object at the top, not a string"));
}

// ---- bus ------------------------------------------------------------------------------------

TEST(ScenarioErrors, Bus) {
  const auto refused_bus = [](const std::string& toml_body, int toml_line,
                              const std::string& json_members, int json_line,
                              const std::string& what) {
    return refused(tdoc::bus(toml_body), toml_line, jdoc::bus(json_members), json_line, what);
  };
  EXPECT_TRUE(refused_bus("cycletime = \"1 ms\"\n", 9, "\"cycletime\": \"1 ms\"", 4,
                          "unknown key 'cycletime' in bus (did you mean 'cycle_time'?)"));
  EXPECT_TRUE(refused_bus("baud = \"1M\"\n", 9, "\"baud\": \"1M\"", 4,
                          "'baud' must be \"500k\" or \"2M\", not \"1M\""));
  EXPECT_TRUE(refused_bus("baud = 500000\n", 9, "\"baud\": 500000", 4,
                          "'baud' must be a string, not an integer"));
  EXPECT_TRUE(refused_bus("cycle_time = \"0 s\"\n", 9, "\"cycle_time\": \"0 s\"", 4,
                          "'cycle_time' must be longer than 0 s"));
  EXPECT_TRUE(refused_bus("cycle_time = \"2 s\"\n", 9, "\"cycle_time\": \"2 s\"", 4,
                          "'cycle_time' 2 s is longer than 1 s (INTERBUS cycles take "
                          "milliseconds)"));
  EXPECT_TRUE(refused_bus("cycle_time = 0.002\n", 9, "\"cycle_time\": 0.002", 4,
                          "'cycle_time' must be a time string with a unit, e.g. \"250 ms\", not "
                          "a fractional number"));
  EXPECT_TRUE(refused_bus("baud = \"2M\"\nsoftware_time = \"1.5 s\"\n", 10,
                          "\"baud\": \"2M\",\n\"software_time\": \"1.5 s\"", 5,
                          "'software_time' 1.5 s is longer than 1 s"));
  EXPECT_TRUE(refused_bus("baud = \"2M\"\nsoftware_time = \"100 us\"\nrecovery_cycles = -1\n", 11,
                          "\"baud\": \"2M\",\n\"software_time\": \"100 us\",\n"
                          "\"recovery_cycles\": -1",
                          6, "'recovery_cycles' = -1 is out of range (0..100)"));
  EXPECT_TRUE(refused_bus("recovery_cycles = 101\n", 9, "\"recovery_cycles\": 101", 4,
                          "'recovery_cycles' = 101 is out of range (0..100)"));
  EXPECT_TRUE(refused_bus("recovery_cycles = 1.5\n", 9, "\"recovery_cycles\": 1.5", 4,
                          "'recovery_cycles' must be an integer, not a fractional number"));
}

// ---- devices --------------------------------------------------------------------------------

// TOML: body from line 9 (header on 8); JSON: the object from line 4, one member per line when
// `json_members` holds newlines.
::testing::AssertionResult refused_device(const std::string& toml_body, int toml_line,
                                          const std::string& json_object, int json_line,
                                          const std::string& what,
                                          const std::string& json_what = {}) {
  return refused(tdoc::device(toml_body), toml_line, jdoc::device(json_object), json_line, what,
                 json_what);
}

TEST(ScenarioErrors, DeviceNameAndType) {
  EXPECT_TRUE(refused_device("type = \"mc6000\"\n", 8, "{\"type\": \"mc6000\"}", 4,
                             "a device needs a 'name'"));
  EXPECT_TRUE(refused_device("name = \"x\"\n", 8, "{\"name\": \"x\"}", 4,
                             "device 'x' needs a 'type' (\"mc6000\" or \"vf1000\")"));
  EXPECT_TRUE(refused_device("name = \"x\"\ntype = \"mc7000\"\n", 10,
                             "{\"name\": \"x\",\n \"type\": \"mc7000\"}", 5,
                             "'type' must be \"mc6000\" or \"vf1000\", not \"mc7000\""));
  EXPECT_TRUE(refused_device("name = \"my drive\"\ntype = \"mc6000\"\n", 9,
                             "{\"name\": \"my drive\", \"type\": \"mc6000\"}", 4,
                             "device name 'my drive' must be 1..32 letters, digits, '_' or '-'"));
  const std::string long_name(33, 'a');
  EXPECT_TRUE(
      refused_device("type = \"mc6000\"\nname = \"" + long_name + "\"\n", 10,
                     "{\"type\": \"mc6000\",\n \"name\": \"" + long_name + "\"}", 5,
                     "device name '" + long_name + "' must be 1..32 letters, digits, '_' or '-'"));
  EXPECT_TRUE(refused_device("name = \"\"\ntype = \"mc6000\"\n", 9,
                             "{\"name\": \"\", \"type\": \"mc6000\"}", 4,
                             "a device name must not be empty"));
  EXPECT_TRUE(refused_device("name = \"m\"\ntype = \"vf1000\"\n", 9,
                             "{\"name\": \"m\", \"type\": \"vf1000\"}", 4,
                             "device name 'm' is already used (line 2)"));
  EXPECT_TRUE(refused_device("name = 7\n", 9, "{\"name\": 7}", 4,
                             "'name' must be a string, not an integer"));
  EXPECT_TRUE(refused_device("name = \"x\"\ntype = \"vf1000\"\nsup = 11\n", 11,
                             "{\"name\": \"x\", \"type\": \"vf1000\",\n \"sup\": 11}", 5,
                             "unknown key 'sup' in a device (did you mean 'supi'?)"));
}

TEST(ScenarioErrors, VfHasNoSupiIbcnfOrLocalBus) {
  EXPECT_TRUE(refused_device("name = \"x\"\ntype = \"vf1000\"\nsupi = 11\n", 11,
                             "{\"name\": \"x\", \"type\": \"vf1000\",\n \"supi\": 11}", 5,
                             "'supi' is an MC6000 setting; a VF1000 has no 405-SUPI"));
  // The type may come after the key.
  EXPECT_TRUE(refused_device("name = \"x\"\nibcnf = 2\ntype = \"vf1000\"\n", 10,
                             "{\"name\": \"x\",\n \"ibcnf\": 2,\n \"type\": \"vf1000\"}", 5,
                             "'ibcnf' is an MC6000 setting; a VF1000 has no 406-IBCNF"));
  EXPECT_TRUE(refused_device("name = \"x\"\ntype = \"vf1000\"\nbus = \"local\"\n", 11,
                             "{\"name\": \"x\", \"type\": \"vf1000\",\n \"bus\": \"local\"}", 5,
                             "device 'x': a VF1000 is always a remote bus device (INTERBUS manual 1.3)"));
  EXPECT_TRUE(refused_device("name = \"x\"\ntype = \"mc6000\"\nbus = \"ring\"\n", 11,
                             "{\"name\": \"x\", \"type\": \"mc6000\",\n \"bus\": \"ring\"}", 5,
                             "'bus' must be \"local\" or \"remote\", not \"ring\""));
}

TEST(ScenarioErrors, Mc6000LayoutsOf322And323) {
  EXPECT_TRUE(refused_device("name = \"x\"\ntype = \"mc6000\"\nsupi = 13\n", 11,
                             "{\"name\": \"x\", \"type\": \"mc6000\",\n \"supi\": 13}", 5,
                             "device 'x': 405-SUPI = 13 is out of range (0..12, INTERBUS manual 3.2.2)"));
  EXPECT_TRUE(
      refused_device("name = \"x\"\ntype = \"mc6000\"\nibcnf = 1\nsupi = -1\n", 12,
                     "{\"name\": \"x\", \"type\": \"mc6000\",\n \"ibcnf\": 1,\n \"supi\": -1}", 6,
                     "device 'x': 405-SUPI = -1 is out of range (0..12, INTERBUS manual 3.2.2)"));
  // A refused pair is reported on the IBCNF line when the file gives one.
  EXPECT_TRUE(
      refused_device("name = \"x\"\ntype = \"mc6000\"\nsupi = 7\nibcnf = 2\n", 12,
                     "{\"name\": \"x\", \"type\": \"mc6000\",\n \"supi\": 7,\n \"ibcnf\": 2}", 6,
                     "device 'x': 406-IBCNF = 2 needs 405-SUPI 10..12, not 7 (INTERBUS manual "
                     "3.2.3)"));
  // ... and on the SUPI line when the IBCNF is the default 2.
  EXPECT_TRUE(refused_device("name = \"x\"\ntype = \"mc6000\"\nsupi = 7\n", 11,
                             "{\"name\": \"x\", \"type\": \"mc6000\",\n \"supi\": 7}", 5,
                             "device 'x': 406-IBCNF = 2 needs 405-SUPI 10..12, not 7 (INTERBUS manual "
                             "3.2.3)"));
  EXPECT_TRUE(
      refused_device("name = \"x\"\ntype = \"mc6000\"\nibcnf = 1\nsupi = 6\n", 11,
                     "{\"name\": \"x\", \"type\": \"mc6000\",\n \"ibcnf\": 1,\n \"supi\": 6}", 5,
                     "device 'x': 406-IBCNF = 1 needs 405-SUPI 7..12, not 6 (INTERBUS manual "
                     "3.2.3)"));
  EXPECT_TRUE(
      refused_device("name = \"x\"\ntype = \"mc6000\"\nibcnf = 4\n", 11,
                     "{\"name\": \"x\", \"type\": \"mc6000\",\n \"ibcnf\": 4}", 5,
                     "device 'x': 406-IBCNF = 4 (modified LISIM software) is not supported"));
  EXPECT_TRUE(refused_device("name = \"x\"\ntype = \"mc6000\"\nibcnf = 5\n", 11,
                             "{\"name\": \"x\", \"type\": \"mc6000\",\n \"ibcnf\": 5}", 5,
                             "device 'x': 406-IBCNF = 5 is out of range (0..4, INTERBUS manual 3.2.3)"));
  EXPECT_TRUE(refused_device("name = \"x\"\ntype = \"mc6000\"\nsupi = 3000000000\n", 11,
                             "{\"name\": \"x\", \"type\": \"mc6000\",\n \"supi\": 3000000000}", 5,
                             "'supi' = 3000000000 is out of range (0..12)"));
  EXPECT_TRUE(refused_device("name = \"x\"\ntype = \"mc6000\"\nsupi = \"11\"\n", 11,
                             "{\"name\": \"x\", \"type\": \"mc6000\",\n \"supi\": \"11\"}", 5,
                             "'supi' must be an integer, not a string"));
}

TEST(ScenarioErrors, PhaseAndJitterWithinTheSamplePeriod) {
  EXPECT_TRUE(refused_device("name = \"x\"\ntype = \"mc6000\"\nphase = \"1 ms\"\n", 11,
                             "{\"name\": \"x\", \"type\": \"mc6000\",\n \"phase\": \"1 ms\"}", 5,
                             "device 'x': 'phase' 1 ms must be at least 0 s and shorter than the "
                             "MC6000's sample period 1 ms"));
  EXPECT_TRUE(refused_device("name = \"x\"\ntype = \"vf1000\"\nphase = \"8.2 ms\"\n", 11,
                             "{\"name\": \"x\", \"type\": \"vf1000\",\n \"phase\": \"8.2 ms\"}", 5,
                             "device 'x': 'phase' 8.2 ms must be at least 0 s and shorter than "
                             "the VF1000's sample period 8.2 ms"));
  EXPECT_TRUE(refused_device("name = \"x\"\ntype = \"mc6000\"\njitter = \"500 us\"\n", 11,
                             "{\"name\": \"x\", \"type\": \"mc6000\",\n \"jitter\": \"500 us\"}", 5,
                             "device 'x': 'jitter' 500 us must be at least 0 s and shorter than "
                             "half the MC6000's sample period (500 us)"));
  EXPECT_TRUE(refused_device("name = \"x\"\ntype = \"vf1000\"\njitter = \"4.1 ms\"\n", 11,
                             "{\"name\": \"x\", \"type\": \"vf1000\",\n \"jitter\": \"4.1 ms\"}", 5,
                             "device 'x': 'jitter' 4.1 ms must be at least 0 s and shorter than "
                             "half the VF1000's sample period (4.1 ms)"));
  EXPECT_TRUE(refused_device("name = \"x\"\ntype = \"vf1000\"\nphase = 0\n", 11,
                             "{\"name\": \"x\", \"type\": \"vf1000\",\n \"phase\": 0}", 5,
                             "'phase' must be a time string with a unit, e.g. \"250 ms\", not an "
                             "integer"));
}

TEST(ScenarioErrors, Watchdogs) {
  EXPECT_TRUE(refused_device("name = \"x\"\ntype = \"vf1000\"\nwatchdog_ms = 7\n", 11,
                             "{\"name\": \"x\", \"type\": \"vf1000\",\n \"watchdog_ms\": 7}", 5,
                             "device 'x': 'watchdog_ms' = 7 is out of range (8..65535, "
                             "906-IB-WD)"));
  EXPECT_TRUE(refused_device("name = \"x\"\ntype = \"mc6000\"\nwatchdog_ms = 65536\n", 11,
                             "{\"name\": \"x\", \"type\": \"mc6000\",\n \"watchdog_ms\": 65536}", 5,
                             "device 'x': 'watchdog_ms' = 65536 is out of range (0..65535, "
                             "409-BUTWD, 0 = off)"));
  EXPECT_TRUE(refused_device("name = \"x\"\ntype = \"mc6000\"\nwatchdog_reaction = 1\n", 11,
                             "{\"name\": \"x\", \"type\": \"mc6000\",\n \"watchdog_reaction\": 1}",
                             5,
                             "device 'x': 'watchdog_reaction' is a VF1000 setting (907-IBCOD); "
                             "the MC6000 always reports E-OP1 (INTERBUS manual 3.2.4)"));
  EXPECT_TRUE(refused_device("name = \"x\"\ntype = \"mc6000\"\nkeypad = true\n", 11,
                             "{\"name\": \"x\", \"type\": \"mc6000\",\n \"keypad\": true}", 5,
                             "'keypad' is a VF1000 setting (INTERBUS manual 7.1); the MC6000's PCP times "
                             "have no KEYPAD row"));
  EXPECT_TRUE(refused_device("name = \"x\"\ntype = \"vf1000\"\nreset_time = \"0 s\"\n", 11,
                             "{\"name\": \"x\", \"type\": \"vf1000\",\n \"reset_time\": \"0 s\"}", 5,
                             "device 'x': 'reset_time' must be above 0 s and at most 60 s (the self-test after "
                             "RESET FAULT)"));
  EXPECT_TRUE(
      refused_device("name = \"x\"\ntype = \"vf1000\"\nwatchdog_reaction = 4\n", 11,
                     "{\"name\": \"x\", \"type\": \"vf1000\",\n \"watchdog_reaction\": 4}", 5,
                     "device 'x': 'watchdog_reaction' = 4 is out of range (0..3, 907-IBCOD)"));
  EXPECT_TRUE(refused_device("name = \"x\"\ntype = \"vf1000\"\ninitialised = \"yes\"\n", 11,
                             "{\"name\": \"x\", \"type\": \"vf1000\",\n \"initialised\": \"yes\"}",
                             5, "'initialised' must be true or false, not a string"));
}

// ---- timeline -------------------------------------------------------------------------------

// TOML: entry body from line 9 (header on 8); JSON: entries from line 5.
::testing::AssertionResult refused_entry(const std::string& toml_body, int toml_line,
                                         const std::string& json_entries, int json_line,
                                         const std::string& what,
                                         const std::string& json_what = {}) {
  return refused(tdoc::entry(toml_body), toml_line, jdoc::entries(json_entries), json_line, what,
                 json_what);
}

TEST(ScenarioErrors, EntryShape) {
  EXPECT_TRUE(refused_entry("device = \"m\"\nstate = \"on\"\n", 8,
                            "{\"device\": \"m\", \"state\": \"on\"}", 5,
                            "a timeline entry needs 'at' (its time, e.g. at = \"250 ms\")"));
  EXPECT_TRUE(refused_entry("at = \"0 s\"\ndevice = \"m\"\n", 8,
                            "{\"at\": \"0 s\", \"device\": \"m\"}", 5,
                            "a timeline entry needs an action (one of: state, emergency_stop, "
                            "block_power, speed, frequency, read, write, describe, wait_state, "
                            "fault, master_restart, mains, load, input, smartcard, option_card)"));
  EXPECT_TRUE(refused_entry(
      "at = \"0 s\"\ndevice = \"m\"\nstate = \"on\"\nspeed = 1.0\n", 12,
      "{\"at\": \"0 s\", \"device\": \"m\",\n \"state\": \"on\",\n \"speed\": 1.0}", 7,
      "a timeline entry holds one action: this one already has 'state' "
      "(line 11), so 'speed' needs an entry of its own",
      "a timeline entry holds one action: this one already has 'state' "
      "(line 6), so 'speed' needs an entry of its own"));
  EXPECT_TRUE(refused_entry("at = \"0 s\"\ndevice = \"m\"\nstat = \"on\"\n", 11,
                            "{\"at\": \"0 s\", \"device\": \"m\",\n \"stat\": \"on\"}", 6,
                            "unknown key 'stat' in a timeline entry (did you mean 'state'?)"));
  EXPECT_TRUE(
      refused_entry("at = \"0 s\"\ndevice = \"m\"\nwait_state = \"on\"\ntmeout = \"1 s\"\n", 12,
                    "{\"at\": \"0 s\", \"device\": \"m\", \"wait_state\": \"on\",\n "
                    "\"tmeout\": \"1 s\"}",
                    6, "unknown key 'tmeout' in a timeline entry (did you mean 'timeout'?)"));
}

TEST(ScenarioErrors, EntryTimes) {
  EXPECT_TRUE(refused_entry("at = \"1.5 s\"\ndevice = \"m\"\nstate = \"on\"\n", 9,
                            "{\"at\": \"1.5 s\", \"device\": \"m\", \"state\": \"on\"}", 5,
                            "'at' = 1.5 s is after the end of the run ('duration' 1 s)"));
  EXPECT_TRUE(refused_entry("at = 0\ndevice = \"m\"\nstate = \"on\"\n", 9,
                            "{\"at\": 0, \"device\": \"m\", \"state\": \"on\"}", 5,
                            "'at' must be a time string with a unit, e.g. \"250 ms\", not an "
                            "integer"));
  EXPECT_TRUE(
      refused_entry("at = \"200 ms\"\ndevice = \"m\"\nstate = \"on\"\n[[timeline]]\n"
                    "at = \"100 ms\"\ndevice = \"m\"\nstate = \"ready\"\n",
                    13,
                    "{\"at\": \"200 ms\", \"device\": \"m\", \"state\": \"on\"},\n"
                    "{\"at\": \"100 ms\", \"device\": \"m\", \"state\": \"ready\"}",
                    6,
                    "'at' = 100 ms is earlier than the entry before it (200 ms, line 8): "
                    "the timeline is written in time order",
                    "'at' = 100 ms is earlier than the entry before it (200 ms, line 5): "
                    "the timeline is written in time order"));
  EXPECT_TRUE(
      refused_entry("at = \"0 s\"\ndevice = \"m\"\nwait_state = \"on\"\ntimeout = \"soon\"\n", 12,
                    "{\"at\": \"0 s\", \"device\": \"m\", \"wait_state\": \"on\",\n "
                    "\"timeout\": \"soon\"}",
                    6, "'timeout': \"soon\" is not a time: write " + kTimeForm));
}

TEST(ScenarioErrors, EntryDevices) {
  EXPECT_TRUE(refused_entry("at = \"0 s\"\ndevice = \"q\"\nstate = \"on\"\n", 10,
                            "{\"at\": \"0 s\",\n \"device\": \"q\", \"state\": \"on\"}", 6,
                            "unknown device 'q' (devices: m, v)"));
  EXPECT_TRUE(refused_entry("at = \"0 s\"\nstate = \"on\"\n", 8,
                            "{\"at\": \"0 s\", \"state\": \"on\"}", 5, "'state' needs a 'device'"));
  EXPECT_TRUE(refused_entry("at = \"0 s\"\nfault = \"lost\"\nduration = \"1 ms\"\n", 8,
                            "{\"at\": \"0 s\", \"fault\": \"lost\", \"duration\": \"1 ms\"}", 5,
                            "fault = \"lost\" needs a 'device'"));
  EXPECT_TRUE(refused_entry("at = \"0 s\"\ndevice = \"m\"\nfault = \"corrupt\"\n", 10,
                            "{\"at\": \"0 s\",\n \"device\": \"m\", \"fault\": \"corrupt\"}", 6,
                            "fault = \"corrupt\" is bus-wide: it takes no 'device'"));
  EXPECT_TRUE(refused_entry("at = \"0 s\"\nmaster_restart = true\ndevice = \"v\"\n", 11,
                            "{\"at\": \"0 s\", \"master_restart\": true,\n \"device\": \"v\"}", 6,
                            "'master_restart' is bus-wide: it takes no 'device'"));
  EXPECT_TRUE(refused_entry("at = \"0 s\"\ndevice = 1\nstate = \"on\"\n", 10,
                            "{\"at\": \"0 s\",\n \"device\": 1, \"state\": \"on\"}", 6,
                            "'device' must be a string, not an integer"));
}

TEST(ScenarioErrors, ActionsForTheOtherDeviceType) {
  EXPECT_TRUE(refused_entry("at = \"0 s\"\ndevice = \"v\"\nspeed = 100.0\n", 11,
                            "{\"at\": \"0 s\", \"device\": \"v\",\n \"speed\": 100.0}", 6,
                            "'speed' is an MC6000 action, but device 'v' is a VF1000 (use "
                            "'frequency')"));
  EXPECT_TRUE(refused_entry("at = \"0 s\"\ndevice = \"m\"\nfrequency = 50\n", 11,
                            "{\"at\": \"0 s\", \"device\": \"m\",\n \"frequency\": 50}", 6,
                            "'frequency' is a VF1000 action, but device 'm' is an MC6000 (use "
                            "'speed')"));
}

TEST(ScenarioErrors, States) {
  EXPECT_TRUE(refused_entry("at = \"0 s\"\ndevice = \"m\"\nstate = \"enabeld\"\n", 11,
                            "{\"at\": \"0 s\", \"device\": \"m\",\n \"state\": \"enabeld\"}", 6,
                            "'state' = \"enabeld\" is not a target state (start-up-inhibit, "
                            "ready, on, enabled)"));
  EXPECT_TRUE(refused_entry("at = \"0 s\"\ndevice = \"m\"\nstate = \"fault\"\n", 11,
                            "{\"at\": \"0 s\", \"device\": \"m\",\n \"state\": \"fault\"}", 6,
                            "'state' = \"fault\" is not a target state (start-up-inhibit, ready, "
                            "on, enabled)"));
  EXPECT_TRUE(refused_entry("at = \"0 s\"\ndevice = \"v\"\nwait_state = \"running\"\n", 11,
                            "{\"at\": \"0 s\", \"device\": \"v\",\n \"wait_state\": \"running\"}",
                            6,
                            "'wait_state' = \"running\" is not a DRIVECOM state (not-ready, "
                            "start-up-inhibit, ready, on, enabled, fault, fault-response-active, "
                            "emergency-stop-active)"));
  EXPECT_TRUE(refused_entry("at = \"0 s\"\ndevice = \"v\"\nstate = 3\n", 11,
                            "{\"at\": \"0 s\", \"device\": \"v\",\n \"state\": 3}", 6,
                            "'state' must be a string, not an integer"));
}

TEST(ScenarioErrors, Flags) {
  EXPECT_TRUE(refused_entry("at = \"0 s\"\ndevice = \"v\"\nemergency_stop = false\n", 11,
                            "{\"at\": \"0 s\", \"device\": \"v\",\n \"emergency_stop\": false}", 6,
                            "'emergency_stop' can only be true (leave the entry out instead)"));
  EXPECT_TRUE(refused_entry("at = \"0 s\"\ndevice = \"v\"\nblock_power = 1\n", 11,
                            "{\"at\": \"0 s\", \"device\": \"v\",\n \"block_power\": 1}", 6,
                            "'block_power' must be true or false, not an integer"));
  EXPECT_TRUE(refused_entry("at = \"0 s\"\nmaster_restart = false\n", 10,
                            "{\"at\": \"0 s\",\n \"master_restart\": false}", 6,
                            "'master_restart' can only be true (leave the entry out instead)"));
}

TEST(ScenarioErrors, References) {
  EXPECT_TRUE(refused_entry("at = \"0 s\"\ndevice = \"m\"\nspeed = \"fast\"\n", 11,
                            "{\"at\": \"0 s\", \"device\": \"m\",\n \"speed\": \"fast\"}", 6,
                            "'speed' must be a number, not a string"));
  EXPECT_TRUE(refused_entry("at = \"0 s\"\ndevice = \"m\"\nspeed = 40000\n", 11,
                            "{\"at\": \"0 s\", \"device\": \"m\",\n \"speed\": 40000}", 6,
                            "'speed' = 40000 rpm is out of range (-32768..32767 rpm)"));
  EXPECT_TRUE(refused_entry("at = \"0 s\"\ndevice = \"m\"\nspeed = -32768.5\n", 11,
                            "{\"at\": \"0 s\", \"device\": \"m\",\n \"speed\": -32768.5}", 6,
                            "'speed' = -32768.5 rpm is out of range (-32768..32767 rpm)"));
  EXPECT_TRUE(refused_entry("at = \"0 s\"\ndevice = \"v\"\nfrequency = 3276.8\n", 11,
                            "{\"at\": \"0 s\", \"device\": \"v\",\n \"frequency\": 3276.8}", 6,
                            "'frequency' = 3276.8 Hz is out of range (-3276.75..3276.75 Hz, "
                            "0.05 Hz per bit)"));
}

TEST(ScenarioErrors, NotANumberOnlyInToml) {
  EXPECT_EQ(toml_error(tdoc::entry("at = \"0 s\"\ndevice = \"m\"\nspeed = nan\n")),
            at_toml(11, "'speed' needs a finite number"));
  EXPECT_EQ(toml_error(tdoc::entry("at = \"0 s\"\ndevice = \"v\"\nfrequency = -inf\n")),
            at_toml(11, "'frequency' needs a finite number"));
  EXPECT_EQ(toml_error(tdoc::random("master_restart_per_s = inf\n")),
            at_toml(9, "'master_restart_per_s' = inf is out of range (0..1000 per second)"));
}

TEST(ScenarioErrors, ParameterNumbers) {
  EXPECT_TRUE(refused_entry("at = \"0 s\"\ndevice = \"v\"\nread = 1024\n", 11,
                            "{\"at\": \"0 s\", \"device\": \"v\",\n \"read\": 1024}", 6,
                            "parameter 1024 is out of range for the VF1000 device 'v' (0..1023, "
                            "10-bit PNR, INTERBUS manual 4.1.2.1)"));
  EXPECT_TRUE(refused_entry("at = \"0 s\"\ndevice = \"m\"\ndescribe = 1000\n", 11,
                            "{\"at\": \"0 s\", \"device\": \"m\",\n \"describe\": 1000}", 6,
                            "parameter 1000 is out of range for the MC6000 device 'm' (0..999, "
                            "LUSTBUS manual 2.4.2)"));
  EXPECT_TRUE(refused_entry("at = \"0 s\"\ndevice = \"m\"\ndescribe = 70000\n", 11,
                            "{\"at\": \"0 s\", \"device\": \"m\",\n \"describe\": 70000}", 6,
                            "'describe' = 70000 is out of range (0..65535)"));
  EXPECT_TRUE(refused_entry("at = \"0 s\"\ndevice = \"m\"\nread = -1\n", 11,
                            "{\"at\": \"0 s\", \"device\": \"m\",\n \"read\": -1}", 6,
                            "'read' = -1 is out of range (0..65535)"));
  EXPECT_TRUE(refused_entry("at = \"0 s\"\ndevice = \"m\"\nread = \"0x16\"\n", 11,
                            "{\"at\": \"0 s\", \"device\": \"m\",\n \"read\": \"0x16\"}", 6,
                            "'read' must be an integer, not a string"));
}

TEST(ScenarioErrors, Writes) {
  EXPECT_TRUE(
      refused_entry("at = \"0 s\"\ndevice = \"v\"\nwrite = { parameter = 22 }\n", 11,
                    "{\"at\": \"0 s\", \"device\": \"v\",\n \"write\": {\"parameter\": 22}}", 6,
                    "'write' needs a 'value' (the raw value)"));
  EXPECT_TRUE(refused_entry("at = \"0 s\"\ndevice = \"v\"\nwrite = { value = 22 }\n", 11,
                            "{\"at\": \"0 s\", \"device\": \"v\",\n \"write\": {\"value\": 22}}", 6,
                            "'write' needs a 'parameter' (its number)"));
  EXPECT_TRUE(refused_entry("at = \"0 s\"\ndevice = \"v\"\nwrite = 22\n", 11,
                            "{\"at\": \"0 s\", \"device\": \"v\",\n \"write\": 22}", 6,
                            "'write' must be a table, not an integer",
                            "'write' must be an object, not an integer"));
  EXPECT_TRUE(refused_entry("at = \"0 s\"\ndevice = \"v\"\nwrite = { parameter = 22, valeu = 1 }\n",
                            11,
                            "{\"at\": \"0 s\", \"device\": \"v\", \"write\": {\"parameter\": 22,\n "
                            "\"valeu\": 1}}",
                            6, "unknown key 'valeu' in write (did you mean 'value'?)"));
  EXPECT_TRUE(
      refused_entry("at = \"0 s\"\ndevice = \"v\"\nwrite = { parameter = 22, value = 1.5 }\n", 11,
                    "{\"at\": \"0 s\", \"device\": \"v\", \"write\": {\"parameter\": 22,\n "
                    "\"value\": 1.5}}",
                    6, "write's 'value' = 1.5 must be an integer (the raw value)"));
  EXPECT_TRUE(
      refused_entry("at = \"0 s\"\ndevice = \"v\"\nwrite = { parameter = 22, value = 65536 }\n", 11,
                    "{\"at\": \"0 s\", \"device\": \"v\", \"write\": {\"parameter\": 22,\n "
                    "\"value\": 65536}}",
                    6,
                    "write's 'value' = 65536 is out of range for the VF1000 "
                    "(-32768..65535, 16 bits)"));
  EXPECT_TRUE(
      refused_entry("at = \"0 s\"\ndevice = \"m\"\n"
                    "write = { parameter = 409, value = -2147483649 }\n",
                    11,
                    "{\"at\": \"0 s\", \"device\": \"m\", \"write\": {\"parameter\": 409,\n "
                    "\"value\": -2147483649}}",
                    6,
                    "write's 'value' = -2147483649 is out of range for the MC6000 "
                    "(-2^31..2^32-1, 32 bits)"));
  EXPECT_TRUE(
      refused_entry("at = \"0 s\"\ndevice = \"v\"\nwrite = { parameter = 1024, value = 1 }\n", 11,
                    "{\"at\": \"0 s\", \"device\": \"v\", \"write\": {\"value\": 1,\n "
                    "\"parameter\": 1024}}",
                    6,
                    "parameter 1024 is out of range for the VF1000 device 'v' (0..1023, "
                    "10-bit PNR, INTERBUS manual 4.1.2.1)"));
}

TEST(ScenarioErrors, Faults) {
  EXPECT_TRUE(refused_entry("at = \"0 s\"\nfault = \"melt\"\n", 10,
                            "{\"at\": \"0 s\",\n \"fault\": \"melt\"}", 6,
                            "'fault' must be \"corrupt\", \"power-cycle\", \"device\" or \"lost\", "
                            "not \"melt\""));
  EXPECT_TRUE(refused_entry("at = \"0 s\"\nfault = \"corrupt\"\ncount = 0\n", 11,
                            "{\"at\": \"0 s\", \"fault\": \"corrupt\",\n \"count\": 0}", 6,
                            "'count' = 0 is out of range (1..10000)"));
  EXPECT_TRUE(refused_entry("at = \"0 s\"\nfault = \"corrupt\"\ncount = 10001\n", 11,
                            "{\"at\": \"0 s\", \"fault\": \"corrupt\",\n \"count\": 10001}", 6,
                            "'count' = 10001 is out of range (1..10000)"));
  EXPECT_TRUE(refused_entry("at = \"0 s\"\ndevice = \"v\"\nfault = \"lost\"\n", 11,
                            "{\"at\": \"0 s\", \"device\": \"v\",\n \"fault\": \"lost\"}", 6,
                            "fault = \"lost\" needs 'duration': how long the device stays off the "
                            "bus"));
  EXPECT_TRUE(
      refused_entry("at = \"0 s\"\ndevice = \"v\"\nfault = \"lost\"\nduration = \"0 s\"\n", 12,
                    "{\"at\": \"0 s\", \"device\": \"v\", \"fault\": \"lost\",\n \"duration\": "
                    "\"0 s\"}",
                    6, "fault = \"lost\" needs a 'duration' longer than 0 s"));
}

TEST(ScenarioErrors, ModifiersBelongToTheirAction) {
  EXPECT_TRUE(
      refused_entry("at = \"0 s\"\ndevice = \"m\"\nstate = \"on\"\ncount = 2\n", 12,
                    "{\"at\": \"0 s\", \"device\": \"m\", \"state\": \"on\",\n \"count\": 2}", 6,
                    "'count' does not go with 'state'"));
  EXPECT_TRUE(
      refused_entry("at = \"0 s\"\ndevice = \"m\"\nfault = \"device\"\ntimeout = \"1 s\"\n", 12,
                    "{\"at\": \"0 s\", \"device\": \"m\", \"fault\": \"device\",\n "
                    "\"timeout\": \"1 s\"}",
                    6, "'timeout' does not go with fault = \"device\" (it takes 'duration')"));
  EXPECT_TRUE(
      refused_entry("at = \"0 s\"\ndevice = \"m\"\nwait_state = \"on\"\nduration = \"1 s\"\n", 12,
                    "{\"at\": \"0 s\", \"device\": \"m\", \"wait_state\": \"on\",\n "
                    "\"duration\": \"1 s\"}",
                    6, "'duration' does not go with 'wait_state' (it takes 'timeout')"));
  EXPECT_TRUE(
      refused_entry("at = \"0 s\"\ndevice = \"m\"\nfault = \"power-cycle\"\n"
                    "duration = \"1 s\"\n",
                    12,
                    "{\"at\": \"0 s\", \"device\": \"m\", \"fault\": \"power-cycle\",\n "
                    "\"duration\": \"1 s\"}",
                    6, "'duration' does not go with fault = \"power-cycle\""));
  EXPECT_TRUE(refused_entry("at = \"0 s\"\nfault = \"corrupt\"\ncount = 2\nduration = \"1 ms\"\n",
                            12,
                            "{\"at\": \"0 s\", \"fault\": \"corrupt\",\n \"count\": 2,\n "
                            "\"duration\": \"1 ms\"}",
                            7, "'duration' and 'count' (line 11) do not go together in one entry",
                            "'duration' and 'count' (line 6) do not go together in one entry"));
}

// An MC6000 "p" with the given SUPI/IBCNF and one entry for it, whose action is given in both
// formats; the action is on line 10 (TOML) and 3 (JSON).
::testing::AssertionResult refused_for_layout(int supi, int ibcnf, const std::string& toml_action,
                                              const std::string& json_action,
                                              const std::string& what) {
  const std::string s = std::to_string(supi);
  const std::string c = std::to_string(ibcnf);
  const std::string toml =
      "duration = \"1 s\"\n[[device]]\nname = \"p\"\ntype = \"mc6000\"\nsupi = " + s +
      "\nibcnf = " + c + "\n[[timeline]]\nat = \"0 s\"\ndevice = \"p\"\n" + toml_action + "\n";
  const std::string json =
      "{\"duration\": \"1 s\",\n \"device\": [{\"name\": \"p\", \"type\": \"mc6000\", \"supi\": " +
      s + ", \"ibcnf\": " + c + "}],\n \"timeline\": [{\"at\": \"0 s\", \"device\": \"p\", " +
      json_action + "}]}";
  return refused(toml, 10, json, 3, what);
}

TEST(ScenarioErrors, ActionsTheLayoutCannotCarry) {
  EXPECT_TRUE(refused_for_layout(12, 0, "read = 406", "\"read\": 406",
                                 "device 'p' has no PCP channel (405-SUPI 12), so 'read' cannot "
                                 "reach it"));
  EXPECT_TRUE(refused_for_layout(7, 1, "write = { parameter = 409, value = 100 }",
                                 "\"write\": {\"parameter\": 409, \"value\": 100}",
                                 "device 'p' has no PCP channel (405-SUPI 7), so 'write' cannot "
                                 "reach it"));
  EXPECT_TRUE(refused_for_layout(3, 0, "state = \"on\"", "\"state\": \"on\"",
                                 "device 'p' has no control word (405-SUPI 3: PCP only), so "
                                 "'state' cannot reach it"));
  EXPECT_TRUE(refused_for_layout(0, 0, "emergency_stop = true", "\"emergency_stop\": true",
                                 "device 'p' has no control word (405-SUPI 0: no data exchange), "
                                 "so 'emergency_stop' cannot reach it"));
  EXPECT_TRUE(refused_for_layout(0, 2, "describe = 406", "\"describe\": 406",
                                 "device 'p' has no PCP channel (405-SUPI 0), so 'describe' cannot "
                                 "reach it"));
  EXPECT_TRUE(refused_for_layout(11, 0, "speed = 100.0", "\"speed\": 100.0",
                                 "device 'p' carries no speed reference (406-IBCNF 0, 405-SUPI "
                                 "11)"));
  EXPECT_TRUE(
      refused_for_layout(4, 0, "speed = 100.0", "\"speed\": 100.0",
                         "device 'p' carries no speed reference (406-IBCNF 0, 405-SUPI 4)"));
  EXPECT_TRUE(refused_for_layout(3, 0, "wait_state = \"on\"", "\"wait_state\": \"on\"",
                                 "device 'p' has no control word (405-SUPI 3: PCP only), so "
                                 "'wait_state' cannot reach it"));
}

// ---- random faults --------------------------------------------------------------------------

TEST(ScenarioErrors, RandomFaults) {
  const auto refused_random = [](const std::string& toml_body, int toml_line,
                                 const std::string& json_members, int json_line,
                                 const std::string& what) {
    return refused(tdoc::random(toml_body), toml_line, jdoc::random(json_members), json_line, what);
  };
  EXPECT_TRUE(refused_random("seed = -1\n", 9, "\"seed\": -1", 4,
                             "'seed' = -1 is out of range (0..9223372036854775807)"));
  EXPECT_TRUE(refused_random("seed = 1.5\n", 9, "\"seed\": 1.5", 4,
                             "'seed' must be an integer, not a fractional number"));
  EXPECT_TRUE(refused_random("seed = 3\ncorrupt_per_s = -1\n", 10,
                             "\"seed\": 3,\n\"corrupt_per_s\": -1", 5,
                             "'corrupt_per_s' = -1 is out of range (0..1000 per second)"));
  EXPECT_TRUE(refused_random("lost_per_s = 1000.5\n", 9, "\"lost_per_s\": 1000.5", 4,
                             "'lost_per_s' = 1000.5 is out of range (0..1000 per second)"));
  EXPECT_TRUE(refused_random("power_cycle_per_s = \"often\"\n", 9,
                             "\"power_cycle_per_s\": \"often\"", 4,
                             "'power_cycle_per_s' must be a number, not a string"));
  EXPECT_TRUE(refused_random("corrupt = 1.0\n", 9, "\"corrupt\": 1.0", 4,
                             "unknown key 'corrupt' in random_faults (known: seed, corrupt_per_s, "
                             "power_cycle_per_s, device_fault_per_s, lost_per_s, "
                             "master_restart_per_s)"));
}

// ---- the first problem wins ------------------------------------------------------------------

TEST(ScenarioErrors, FormatProblemsComeBeforeMeaningAndInFileOrder) {
  // Line 2 holds an unknown key, line 3 a bad SUPI; the format problem is reported.
  EXPECT_EQ(toml_error("duration = \"0 s\"\ncolour = 1\n[[device]]\nname = \"m\"\n"
                       "type = \"mc6000\"\nsupi = 99\n"),
            at_toml(2,
                    "unknown key 'colour' at the top level (known: name, duration, bus, "
                    "device, timeline, random_faults, lustbus, dfs1)"));
  // Two type errors: the earlier line is reported although toml++ sorts keys by name.
  EXPECT_EQ(toml_error("name = 1\nbus = 2\nduration = \"1 s\"\n"),
            at_toml(1, "'name' must be a string, not an integer"));
  EXPECT_EQ(toml_error("duration = 3\nname = 1\n"),
            at_toml(1,
                    "'duration' must be a time string with a unit, e.g. \"250 ms\", not an "
                    "integer"));
}

}  // namespace
}  // namespace ibs::sim::test
