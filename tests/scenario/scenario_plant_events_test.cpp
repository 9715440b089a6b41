// The plant and fault events of the timeline (issue 24: cause, mains, load, input/level) and the
// control channel's lines (parse_control_line): read, checked against the drive kind's own lists
// (DriveFacts::events), written and read back equal; each refusal on its line.
#include <gtest/gtest.h>

#include <string>

#include "ibs/sim/scenario.hpp"
#include "scenario_errors.hpp"

namespace ibs::sim::test {
namespace {

using namespace std::chrono_literals;

TEST(ScenarioPlantEvents, EveryNewKeyReadsAndRoundTrips) {
  const std::string text = tdoc::kBase +
                           "[[timeline]]\nat = \"10 ms\"\ndevice = \"v\"\nfault = \"device\"\ncause = \"E-IBS\"\n"
                           "duration = \"50 ms\"\n"
                           "[[timeline]]\nat = \"20 ms\"\ndevice = \"m\"\nfault = \"device\"\ncause = 16\n"
                           "[[timeline]]\nat = \"30 ms\"\ndevice = \"m\"\nmains = \"off\"\n"
                           "[[timeline]]\nat = \"40 ms\"\ndevice = \"m\"\nmains = \"on\"\n"
                           "[[timeline]]\nat = \"50 ms\"\ndevice = \"m\"\nload = 2.5\n"
                           "[[timeline]]\nat = \"60 ms\"\ndevice = \"m\"\ninput = \"IS01\"\nlevel = \"high\"\n";
  const Scenario s = parse_scenario_toml(text, "s.toml");
  ASSERT_EQ(s.timeline.size(), 6U);
  EXPECT_EQ(s.timeline[0].action, Action::fault_device);
  EXPECT_EQ(s.timeline[0].cause, "E-IBS");
  EXPECT_EQ(s.timeline[0].duration, 50ms);
  EXPECT_EQ(s.timeline[1].cause, "16");
  EXPECT_EQ(s.timeline[2].action, Action::mains);
  EXPECT_EQ(s.timeline[2].value, "off");
  EXPECT_EQ(s.timeline[4].action, Action::load);
  EXPECT_EQ(s.timeline[4].number, 2.5);
  EXPECT_EQ(s.timeline[5].action, Action::input);
  EXPECT_EQ(s.timeline[5].value, "IS01");
  EXPECT_TRUE(s.timeline[5].level);
  EXPECT_EQ(parse_scenario_toml(write_scenario_toml(s), "rt.toml"), s);
  EXPECT_EQ(parse_scenario_json(write_scenario_json(s), "rt.json"), s);
  // A different cause or level is a different scenario.
  Scenario other = s;
  other.timeline[0].cause = "12";
  EXPECT_FALSE(other == s);
  other = s;
  other.timeline[5].level = false;
  EXPECT_FALSE(other == s);
}

TEST(ScenarioPlantEvents, RefusalsNameTheDrivesOwnLists) {
  // INTERBUS manual 4.1.3.3: the VF1000's error codes are 00H..0EH.
  EXPECT_EQ(toml_error(tdoc::entry("at = \"0 s\"\ndevice = \"v\"\nfault = \"device\"\ncause = 15\n")),
            at_toml(12, "'cause' of device 'v': '15' is not an error of the VF1000 (0..14, E-IBS; INTERBUS manual "
                        "4.1.3.3: 00H..0EH)"));
  EXPECT_EQ(toml_error(tdoc::entry("at = \"0 s\"\ndevice = \"m\"\nfault = \"device\"\ncause = \"E-OV\"\n")),
            at_toml(12, "'cause' of device 'm': 'E-OV' is not an error of the MC6000 (0..255, E-OP1; LUSTBUS manual 3: "
                        "one byte)"));
  EXPECT_EQ(toml_error(tdoc::entry("at = \"0 s\"\ndevice = \"m\"\nfault = \"lost\"\nduration = \"1 ms\"\n"
                                   "cause = 16\n")),
            at_toml(13, "'cause' goes with fault = \"device\" only"));
  EXPECT_EQ(toml_error(tdoc::entry("at = \"0 s\"\ndevice = \"v\"\nload = 1\n")),
            at_toml(11, "'load' is not for device 'v', a VF1000: the VF1000 is an inverter without a motor "
                        "model here: its frequency follows the ramp, whatever the load (docs/errata.md VF-E17)"));
  EXPECT_EQ(toml_error(tdoc::entry("at = \"0 s\"\ndevice = \"m\"\ninput = \"ENPO\"\nlevel = \"high\"\n")),
            at_toml(11, "'input' = \"ENPO\" is not an input of the MC6000 device 'm' (\"IS00\" or \"IS01\")"));
  EXPECT_EQ(toml_error(tdoc::entry("at = \"0 s\"\ndevice = \"m\"\ninput = \"IS00\"\n")),
            at_toml(11, "'input' needs 'level' (\"high\" or \"low\")"));
  EXPECT_EQ(toml_error(tdoc::entry("at = \"0 s\"\ndevice = \"m\"\nmains = \"down\"\n")),
            at_toml(11, "'mains' must be \"off\" or \"on\", not \"down\""));
  EXPECT_EQ(toml_error(tdoc::entry("at = \"0 s\"\ndevice = \"m\"\nmains = \"off\"\nlevel = \"low\"\n")),
            at_toml(12, "'level' goes with 'input' only"));
  // INTERBUS manual 5.2.1 / 5.2.2: the VF1000's terminals (docs/errata.md VF-E22) are its list.
  EXPECT_EQ(toml_error(tdoc::entry("at = \"0 s\"\ndevice = \"v\"\ninput = \"IS00\"\nlevel = \"high\"\n")),
            at_toml(11, "'input' = \"IS00\" is not an input of the VF1000 device 'v' (\"S1IND\", \"S2IND\", "
                        "\"STR\", \"STL\", \"S1OUT\" or \"S2OUT\")"));
}

TEST(ScenarioPlantEvents, TheVf1000sTerminalsReadAndRoundTrip) {
  // INTERBUS manual 5.2.1 (inputs S1IND, S2IND, STR, STL) and 5.2.2 (outputs S1OUT, S2OUT, whose level the
  // scenario states: docs/errata.md VF-E22), in TOML and JSON, each written and read back equal.
  std::string text = tdoc::kBase;
  int ms = 10;
  for (const char* name : {"S1IND", "S2IND", "STR", "STL", "S1OUT", "S2OUT"}) {
    text += "[[timeline]]\nat = \"" + std::to_string(ms) + " ms\"\ndevice = \"v\"\ninput = \"" + name +
            "\"\nlevel = \"" + (ms % 20 == 0 ? "low" : "high") + "\"\n";
    ms += 10;
  }
  const Scenario s = parse_scenario_toml(text, "s.toml");
  ASSERT_EQ(s.timeline.size(), 6U);
  EXPECT_EQ(s.timeline[4].action, Action::input);
  EXPECT_EQ(s.timeline[4].value, "S1OUT");
  EXPECT_TRUE(s.timeline[4].level);
  EXPECT_FALSE(s.timeline[5].level);
  EXPECT_EQ(parse_scenario_toml(write_scenario_toml(s), "rt.toml"), s);
  EXPECT_EQ(parse_scenario_json(write_scenario_json(s), "rt.json"), s);
}

TEST(ScenarioPlantEvents, ASmartcardOperationReadsRoundTripsAndIsCheckedAgainstTheDrive) {
  // LUSTBUS manual 10 exception 2: a SMARTCARD read "can last up to 10 seconds, depending on the
  // device"; INTERBUS manual 6.1: read and written (docs/errata.md VF-E21). The VF1000 declares it
  // (EventFacts::card_max_s); a drive that does not is refused with the reason.
  const std::string text = tdoc::kBase +
                           "[[timeline]]\nat = \"10 ms\"\ndevice = \"v\"\nsmartcard = \"read\"\nduration = \"2 s\"\n"
                           "[[timeline]]\nat = \"500 ms\"\ndevice = \"v\"\nsmartcard = \"write\"\nduration = \"10 s\"\n";
  const Scenario s = parse_scenario_toml(text, "s.toml");
  ASSERT_EQ(s.timeline.size(), 2U);
  EXPECT_EQ(s.timeline[0].action, Action::smartcard);
  EXPECT_EQ(s.timeline[0].value, "read");
  EXPECT_EQ(s.timeline[0].duration, 2s);
  EXPECT_EQ(s.timeline[1].value, "write");
  EXPECT_EQ(parse_scenario_toml(write_scenario_toml(s), "rt.toml"), s);
  EXPECT_EQ(parse_scenario_json(write_scenario_json(s), "rt.json"), s);
  Scenario other = s;
  other.timeline[0].duration = 3s;
  EXPECT_FALSE(other == s);

  EXPECT_EQ(toml_error(tdoc::entry("at = \"0 s\"\ndevice = \"v\"\nsmartcard = \"read\"\n")),
            at_toml(11, "'smartcard' needs 'duration': how long the card is read or written"));
  EXPECT_EQ(toml_error(tdoc::entry("at = \"0 s\"\ndevice = \"v\"\nsmartcard = \"insert\"\nduration = \"1 s\"\n")),
            at_toml(11, "'smartcard' must be \"read\" or \"write\", not \"insert\""));
  EXPECT_EQ(toml_error(tdoc::entry("at = \"0 s\"\ndevice = \"v\"\nsmartcard = \"read\"\nduration = \"11 s\"\n")),
            at_toml(12, "'duration' of a SMARTCARD operation of device 'v' must be above 0 s and at most 10 s (LUSTBUS manual "
                        "10 exception 2, INTERBUS manual 6.1)"));
  EXPECT_EQ(toml_error(tdoc::entry("at = \"0 s\"\ndevice = \"v\"\nsmartcard = \"read\"\ncount = 2\n")),
            at_toml(12, "'count' does not go with 'smartcard' (it takes 'duration')"));
  // The MC6000 takes it too (LUSTBUS manual 10 exception 2, docs/errata.md MC-D9), with its own source.
  EXPECT_EQ(parse_scenario_toml(tdoc::entry("at = \"0 s\"\ndevice = \"m\"\nsmartcard = \"write\"\nduration = \"1 s\"\n"),
                                "s.toml")
                .timeline.size(),
            1U);
  EXPECT_EQ(toml_error(tdoc::entry("at = \"0 s\"\ndevice = \"m\"\nsmartcard = \"read\"\nduration = \"10.5 s\"\n")),
            at_toml(12, "'duration' of a SMARTCARD operation of device 'm' must be above 0 s and at most 10 s (LUSTBUS manual "
                        "10 exception 2)"));
}

TEST(ScenarioPlantEvents, AnOptionCardWithdrawnOrInsertedReadsRoundTripsAndIsCheckedAgainstTheDrive) {
  // INTERBUS manual 3.2.1: the MC6000 detects its INTERBUS card at power-on; withdrawn, 3.2.1's
  // parameters go back to their factory defaults at the next power-up (docs/errata.md MC-D10).
  const std::string text = tdoc::kBase +
                           "[[timeline]]\nat = \"10 ms\"\ndevice = \"m\"\noption_card = \"withdrawn\"\n"
                           "[[timeline]]\nat = \"500 ms\"\ndevice = \"m\"\noption_card = \"inserted\"\n";
  const Scenario s = parse_scenario_toml(text, "s.toml");
  ASSERT_EQ(s.timeline.size(), 2U);
  EXPECT_EQ(s.timeline[0].action, Action::option_card);
  EXPECT_EQ(s.timeline[0].value, "withdrawn");
  EXPECT_EQ(s.timeline[1].value, "inserted");
  EXPECT_EQ(parse_scenario_toml(write_scenario_toml(s), "rt.toml"), s);
  EXPECT_EQ(parse_scenario_json(write_scenario_json(s), "rt.json"), s);
  Scenario other = s;
  other.timeline[0].value = "inserted";
  EXPECT_FALSE(other == s);

  EXPECT_EQ(toml_error(tdoc::entry("at = \"0 s\"\ndevice = \"m\"\noption_card = \"out\"\n")),
            at_toml(11, "'option_card' must be \"withdrawn\" or \"inserted\", not \"out\""));
  EXPECT_EQ(toml_error(tdoc::entry("at = \"0 s\"\ndevice = \"m\"\noption_card = \"withdrawn\"\nduration = \"1 s\"\n")),
            at_toml(12, "'duration' does not go with 'option_card'"));
  EXPECT_EQ(toml_error(tdoc::entry("at = \"0 s\"\ndevice = \"v\"\noption_card = \"withdrawn\"\n")),
            at_toml(11, "'option_card' is not for device 'v', a VF1000: its INTERBUS operation is a modified software "
                        "package, not a card it detects (INTERBUS manual 3.1.1); no seed gives a withdrawal an effect"));
}

TEST(ControlLine, AGoodLineIsAnEntryWithoutAt) {
  const Scenario running = parse_scenario_toml(tdoc::kBase, "s.toml");
  const TimelineEntry e =
      parse_control_line(R"({"device": "m", "fault": "device", "cause": "E-OP1", "duration": "0.5 s"})", 3, running);
  EXPECT_EQ(e.action, Action::fault_device);
  EXPECT_EQ(e.device, "m");
  EXPECT_EQ(e.cause, "E-OP1");
  EXPECT_EQ(e.duration, 500ms);
  EXPECT_EQ(e.at, Time{0});
  EXPECT_EQ(e.source_line, 3U);
  EXPECT_EQ(parse_control_line(R"({"device": "m", "speed": 500})", 1, running).number, 500.0);
  // Written as a control line, it reads back equal.
  EXPECT_EQ(parse_control_line(write_control_line(e), 9, running), e);
  EXPECT_EQ(write_control_line(e), R"({"device": "m", "fault": "device", "duration": "500 ms", "cause": "E-OP1"})");
}

std::string control_error(const std::string& text, std::size_t line) {
  const Scenario running = parse_scenario_toml(tdoc::kBase, "s.toml");
  try {
    (void)parse_control_line(text, line, running);
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "no error";
}

TEST(ControlLine, BadLinesSayWhatIsWrongOnTheirLine) {
  EXPECT_EQ(control_error(R"({"at": "1 s", "device": "m", "speed": 5})", 3),
            "control:3: control entries apply at once: no 'at'");
  EXPECT_EQ(control_error(R"({"device": "x", "speed": 5})", 3), "control:3: unknown device 'x' (devices: m, v)");
  EXPECT_EQ(control_error(R"({"device": "m", "speed": )", 3).rfind("control:3: ", 0), 0U);
  EXPECT_EQ(control_error(R"([1, 2])", 4),
            "control:4: a control line must be a JSON object (a timeline entry without 'at'), not an array");
  EXPECT_EQ(control_error(R"({"device": "v", "speed": 5})", 7).rfind("control:7: 'speed' is an MC6000 action", 0), 0U);
  EXPECT_EQ(control_error(R"({"device": "m"})", 2).rfind("control:2: a control line needs an action", 0), 0U);
}

}  // namespace
}  // namespace ibs::sim::test
