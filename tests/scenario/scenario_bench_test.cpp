// The test bench's keys (docs/testbench.md): [lustbus] and [dfs1] with their controllers, a
// device's `lustbus` address; read in both formats, written back equal, each refusal with its
// FILE:LINE.
#include <gtest/gtest.h>

#include <string>

#include "ibs/sim/scenario.hpp"

namespace ibs::sim {
namespace {

// Line 1 is `name`; the servo's `lustbus` is on line 9, [lustbus] starts on line 11.
const std::string kToml = R"(name = "bench"
duration = "2 s"

[[device]]
name = "servo"
type = "mc6000"
supi = 11
ibcnf = 2
lustbus = 1

[lustbus]
pty = true

[dfs1]
port = "/dev/ttyUSB1"
baud = 19200

[[dfs1.controller]]
name = "press"
uid = 7

[[timeline]]
at = "1 s"
device = "press"
fault = "power-cycle"
)";

std::string error_of(const std::string& toml) {
  try {
    parse_scenario_toml(toml, "b.toml");
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "accepted";
}

std::string with(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(ScenarioBench, TheKeysAreReadAndWrittenBackEqualInBothFormats) {
  const Scenario s = parse_scenario_toml(kToml, "b.toml");
  ASSERT_TRUE(s.lustbus.has_value());
  EXPECT_TRUE(s.lustbus->pty);
  EXPECT_EQ(s.lustbus->baud, 9600U);
  ASSERT_TRUE(s.controller_line.has_value());
  EXPECT_EQ(s.controller_line->port, "/dev/ttyUSB1");
  EXPECT_EQ(s.controller_line->baud, 19200U);
  ASSERT_EQ(s.controllers.size(), 1U);
  EXPECT_EQ(s.controllers[0].name, "press");
  EXPECT_EQ(s.controllers[0].uid, 7);
  EXPECT_EQ(s.devices[0].lustbus, 1);
  EXPECT_TRUE(s.serves_lines());
  EXPECT_EQ(parse_scenario_toml(write_scenario_toml(s), "w.toml"), s);
  EXPECT_EQ(parse_scenario_json(write_scenario_json(s), "w.json"), s);
  // A changed address is a different scenario.
  Scenario t = s;
  t.devices[0].lustbus = 2;
  EXPECT_FALSE(t == s);
}

TEST(ScenarioBench, EachRefusalNamesItsLine) {
  EXPECT_EQ(error_of(with(kToml, "lustbus = 1", "lustbus = 31")),
            "b.toml:9: 'lustbus' = 31 is not a drive's LUSTBUS address (1..30, LUSTBUS manual 9.1)");
  EXPECT_EQ(error_of(with(kToml, "[lustbus]\npty = true\n", "")),
            "b.toml:9: device 'servo': 'lustbus' = 1 needs the line it answers on: a [lustbus] table with pty = true "
            "or port = \"PATH\"");
  EXPECT_EQ(error_of(with(kToml, "pty = true\n", "")),
            "b.toml:11: [lustbus] needs either pty = true (a new pseudo-terminal) or port = \"PATH\" (a serial port), "
            "not neither");
  EXPECT_EQ(error_of(with(kToml, "port = \"/dev/ttyUSB1\"", "pty = true\nport = \"/dev/ttyUSB1\"")),
            "b.toml:14: [dfs1] needs either pty = true (a new pseudo-terminal) or port = \"PATH\" (a serial port), "
            "not both");
  EXPECT_EQ(error_of(with(kToml, "lustbus = 1\n", "")),
            "b.toml:10: [lustbus] serves no device: give the devices that answer on it their address (lustbus = 1..30)");
  EXPECT_EQ(error_of(with(kToml, "pty = true\n", "colour = 1\n")),
            "b.toml:12: unknown key 'colour' in [lustbus] (known: pty, port, baud)");
  EXPECT_EQ(error_of(with(kToml, "uid = 7", "uid = 0")), "b.toml:20: 'uid' = 0 is out of range (1..255)");
  EXPECT_EQ(error_of(with(kToml, "name = \"press\"", "name = \"servo\"")),
            "b.toml:18: controller name 'servo' is already a device's (line 4)");
  EXPECT_EQ(error_of(kToml + "\n[[dfs1.controller]]\nname = \"saw\"\nuid = 7\n"),
            "b.toml:29: controller 'saw': uid 7 is already controller 'press''s (line 18): both would answer at once");
  EXPECT_EQ(error_of(with(kToml, "fault = \"power-cycle\"", "speed = 100")),
            "b.toml:25: 'press' is a DFS-1 controller of the bench, not on the INTERBUS ring: 'speed' is not for it "
            "(it takes fault = \"device\" or \"power-cycle\", mains, load, input)");
  const std::string two = with(kToml, "[lustbus]", "[[device]]\nname = \"fan\"\ntype = \"vf1000\"\nlustbus = 1\n\n[lustbus]");
  EXPECT_EQ(error_of(two), "b.toml:14: device 'fan': LUSTBUS address 1 is already device 'servo''s (line 4): both would "
                           "answer at once (LUSTBUS manual 9.1)");
}

// A control line of a running bench is checked against the whole running scenario: its devices
// keep their LUSTBUS addresses (with the line they need) and its DFS-1 controllers are named.
TEST(ScenarioBench, AControlLineOfABenchIsCheckedAgainstItsLinesAndControllers) {
  const Scenario s = parse_scenario_toml(kToml, "b.toml");
  const TimelineEntry servo =
      parse_control_line(R"({"device": "servo", "fault": "device", "cause": "E-OP1"})", 1, s);
  EXPECT_EQ(servo.device, "servo");
  const TimelineEntry press = parse_control_line(R"({"device": "press", "mains": "off"})", 2, s);
  EXPECT_EQ(press.action, Action::mains);
  EXPECT_EQ(press.value, "off");
  try {
    (void)parse_control_line(R"({"device": "press", "speed": 5})", 3, s);
    FAIL() << "a speed for a DFS-1 controller of the bench was taken";
  } catch (const ScenarioError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("control:3: 'press' is a DFS-1 controller of the bench", 0), 0U) << e.what();
  }
}

}  // namespace
}  // namespace ibs::sim
