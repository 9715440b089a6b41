// `ibs run` with a CANLust bus (docs/scenarios.md, "A CANLust bus"): the example scenario's
// logon, System Start executed by all drives together, references, parameter traffic, the
// watchdog tripping when the master falls silent, the bus load; and the reader's errors with
// file:line.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include <nlohmann/json.hpp>

#include "ibs/sim/canlust_scenario.hpp"
#include "ibs/sim/scenario.hpp"
#include "ibs/sim/scenario_file.hpp"

namespace ibs::sim::canlust {
namespace {

using namespace std::chrono_literals;

const std::string kExample = std::string(IBS_SOURCE_DIR) + "/examples/canlust/conveyors.toml";

void expect_error(const std::string& text, std::size_t line, const std::string& what) {
  try {
    parse_scenario(text, "bad.toml", false);
    ADD_FAILURE() << "accepted: " << text;
  } catch (const ScenarioError& e) {
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind("bad.toml:" + std::to_string(line) + ": ", 0), 0U) << e.what();
  }
}

const DriveResult& drive(const Report& r, const std::string& name) {
  for (const auto& d : r.drives) {
    if (d.name == name) return d;
  }
  throw std::runtime_error("no drive " + name);
}
std::optional<Time> first_state(const DriveResult& d, const std::string& state, Time from = Time{0}) {
  for (const auto& c : d.states) {
    if (c.state == state && c.at >= from) return c.at;
  }
  return std::nullopt;
}

TEST(CanlustRun, ExampleScenario) {
  // The one entry point sees the bus: CANLust here, INTERBUS in the other examples.
  const AnyScenario any = load_any_scenario(kExample);
  ASSERT_TRUE(std::holds_alternative<Scenario>(any));
  EXPECT_TRUE(std::holds_alternative<sim::Scenario>(load_any_scenario(std::string(IBS_SOURCE_DIR) + "/examples/faults.toml")));
  const Scenario s = std::get<Scenario>(any);
  EXPECT_EQ(s.name, "conveyors");
  EXPECT_EQ(s.timeline.size(), load_scenario(kExample).timeline.size());
  ASSERT_EQ(s.drives.size(), 2U);
  const Report r = run(s);
  const auto& left = drive(r, "left");
  const auto& right = drive(r, "right");
  // 5.2: logon every 100 ms from power-on; the right drive is switched on at 50 ms.
  ASSERT_TRUE(left.logon && right.logon);
  EXPECT_EQ(*left.logon, Time{0});
  EXPECT_GE(*right.logon, Time{50ms});
  EXPECT_LT(*right.logon, Time{51ms});
  // System Start at 300 ms: both execute what they stored, within 1 ms of each other.
  ASSERT_TRUE(left.started && right.started);
  ASSERT_TRUE(r.start_spread);
  EXPECT_LE(*r.start_spread, 1ms);
  EXPECT_GE(*left.started, Time{300ms});
  EXPECT_LT(*left.started, Time{301ms});
  // Both were asked for ENABLED while stopped: nothing moves before the Start, then both enable.
  const auto left_enabled = first_state(left, "ENABLED");
  const auto right_enabled = first_state(right, "ENABLED");
  ASSERT_TRUE(left_enabled && right_enabled);
  EXPECT_GT(*left_enabled, Time{300ms});
  EXPECT_LT(*left_enabled, Time{400ms});
  // The master falls silent at 2 s: 574-CAWDG (100 ms) trips within one status period (20 ms).
  const auto left_fault = first_state(left, "FAULT", Time{2s});
  ASSERT_TRUE(left_fault);
  EXPECT_GT(*left_fault, Time{2s});
  EXPECT_LE(*left_fault, Time{2s + 100ms + 20ms});
  EXPECT_EQ(left.watchdog_trips, 1U);
  EXPECT_EQ(right.watchdog_trips, 1U);
  EXPECT_EQ(right.state, "FAULT");  // the master never resets a fault by itself
  // The mains reset at 3 s: the left drive logs on again, is started again (D31), and stays in
  // START-UP INHIBIT: nobody asked for it anew.
  EXPECT_EQ(left.system_state, "System Start");
  EXPECT_EQ(left.state, "START-UP INHIBIT");
  // Parameter traffic.
  ASSERT_EQ(r.entries.size(), s.timeline.size());
  bool read_cascy = false;
  bool wrote_cascy = false;
  bool read_reff = false;
  for (const auto& e : r.entries) {
    EXPECT_TRUE(e.ok) << e.what << ": " << e.outcome;
    read_cascy = read_cascy || (e.what == "left: read 575-CASCY" && e.outcome.rfind("20 ms", 0) == 0);
    wrote_cascy = wrote_cascy || (e.what == "right: write 575-CASCY := 40" && e.outcome.rfind("ok, 40 ms", 0) == 0);
    read_reff = read_reff || (e.what == "right: read 406-REFF" && e.outcome.rfind("-12.25 Hz", 0) == 0);
  }
  EXPECT_TRUE(read_cascy && wrote_cascy && read_reff) << format_text(r);
  // The bus: every frame counted, the load a fraction of the time.
  EXPECT_GT(r.frames, 300U);
  EXPECT_GT(r.load, 0.01);
  EXPECT_LT(r.load, 0.10);
  EXPECT_GE(r.peak_load, r.load);
  EXPECT_EQ(r.overflows, 0U);
  // The JSON says the same.
  const auto j = nlohmann::json::parse(format_json(r));
  EXPECT_EQ(j["version"], 1);
  EXPECT_EQ(j["protocol"], "canlust");
  EXPECT_EQ(j["bus"]["frames"], r.frames);
  EXPECT_EQ(j["devices"][1]["state"], "FAULT");
  EXPECT_EQ(j["devices"][1]["watchdog_trips"], right.watchdog_trips);
  EXPECT_EQ(j["events"].size(), r.entries.size());
  EXPECT_DOUBLE_EQ(j["bus"]["load"].get<double>(), r.load);
}

// References reach the plant; a higher bit rate carries the same traffic at a lower load.
TEST(CanlustRun, ReferenceAndLoadScaleWithTheBitRate) {
  auto text = [](int bitrate) {
    return "name = \"x\"\nduration = \"2 s\"\n[bus]\nprotocol = \"canlust\"\nbitrate = " + std::to_string(bitrate) +
           "\n[[device]]\nname = \"a\"\ntype = \"cda3000\"\naddress = 3\n"
           "[[timeline]]\nat = \"100 ms\"\nsystem = \"start\"\n"
           "[[timeline]]\nat = \"100 ms\"\ndevice = \"a\"\nstate = \"enabled\"\n"
           "[[timeline]]\nat = \"100 ms\"\ndevice = \"a\"\nreference_hz = 50\n";
  };
  const Report fast = run(parse_scenario(text(500000), "fast.toml", false));
  const Report slow = run(parse_scenario(text(125000), "slow.toml", false));
  EXPECT_NEAR(fast.drives[0].actual_hz, 50.0, 0.5);  // 1.9 s of a 200 ms lag
  EXPECT_EQ(fast.drives[0].state, "ENABLED");
  EXPECT_NEAR(slow.load / fast.load, 4.0, 0.2);
}

// EasyDrive (cacnf = 4): STR runs the drive; the master falling silent trips 574-CAWDG into the
// ERROR bit, which stays until the scenario sends the error reset bit's edge; then STR again.
TEST(CanlustRun, EasyDriveWatchdogAndErrorReset) {
  const std::string text =
      "name = \"easy\"\nduration = \"5 s\"\n[bus]\nprotocol = \"canlust\"\n"
      "[[device]]\nname = \"e\"\ntype = \"cda3000\"\naddress = 1\ncacnf = 4\nwatchdog_ms = 80\nstatus_ms = 10\n"
      "[[timeline]]\nat = \"100 ms\"\nsystem = \"start\"\n"
      "[[timeline]]\nat = \"100 ms\"\ndevice = \"e\"\nreference_hz = 10\n"
      "[[timeline]]\nat = \"200 ms\"\ndevice = \"e\"\neasydrive = 1\n"       // STR
      "[[timeline]]\nat = \"1500 ms\"\nfault = \"master_silent\"\nduration = \"200 ms\"\n"
      "[[timeline]]\nat = \"2500 ms\"\ndevice = \"e\"\neasydrive = 0\n"
      "[[timeline]]\nat = \"2600 ms\"\ndevice = \"e\"\neasydrive = 128\n"    // error reset
      "[[timeline]]\nat = \"2700 ms\"\ndevice = \"e\"\neasydrive = 1\n";
  const Report r = run(parse_scenario(text, "easy.toml", false));
  const auto& e = r.drives[0];
  const auto fault = first_state(e, "FAULT", Time{1500ms});
  ASSERT_TRUE(fault);
  EXPECT_LE(*fault, Time{1500ms + 80ms + 10ms});  // 574-CAWDG plus one status period
  const auto reset = first_state(e, "READY", *fault);
  ASSERT_TRUE(reset);
  EXPECT_GE(*reset, Time{2600ms});  // not before the reset bit: never by the master itself
  EXPECT_EQ(e.state, "ENABLED");
  EXPECT_NEAR(e.actual_hz, 10.0, 0.5);
  EXPECT_NE(e.status.find("EasyDrive"), std::string::npos) << e.status;
  EXPECT_NE(e.status.find("ACTIV"), std::string::npos) << e.status;
  EXPECT_EQ(e.watchdog_trips, 1U);
  // The new [[timeline]] starts on the line after the scenario's last.
  const auto next_line = static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')) + 1;
  expect_error(text + "[[timeline]]\nat = \"1 s\"\ndevice = \"e\"\nstate = \"enabled\"\n", next_line,
               "runs EasyDrive (cacnf = 4)");
}


// The one entry point reads the file once and keeps each schema's errors with file:line, for a
// file of either bus, in TOML and JSON.
TEST(CanlustRun, OneEntryPointKeepsFileAndLine) {
  const auto error_of = [](const std::string& name, const std::string& text) -> std::string {
    const std::string path = ::testing::TempDir() + name;
    std::ofstream(path) << text;
    try {
      load_any_scenario(path);
    } catch (const ScenarioError& e) {
      return e.what();
    }
    return "accepted";
  };
  const std::string dir = ::testing::TempDir();
  // CANLust: the schema's own message at its line.
  EXPECT_EQ(error_of("one_entry.toml", "[bus]\nprotocol = \"canlust\"\nbitrate = 7\n"),
            dir + "one_entry.toml:3: bitrate = 7 is outside 25000..500000");
  EXPECT_EQ(error_of("one_entry.json", "{\"bus\": {\"protocol\": \"canlust\"},\n \"device\": [{\"name\": \"a\"}]}"),
            dir + "one_entry.json:2: device 'a': type must be \"cda3000\" on a CANLust bus");
  // INTERBUS: its schema, as load_scenario says it.
  const std::string interbus = "[bus]\ncycle_tme = \"1 ms\"\n";
  std::string direct;
  try {
    parse_scenario_toml(interbus, dir + "one_entry_ib.toml");
  } catch (const ScenarioError& e) {
    direct = e.what();
  }
  EXPECT_NE(direct.find("one_entry_ib.toml:2: "), std::string::npos) << direct;
  EXPECT_EQ(error_of("one_entry_ib.toml", interbus), direct);
  // A syntax error, and a file that is neither format.
  EXPECT_EQ(error_of("one_entry_syntax.toml", "[bus]\nprotocol = \"canlust\n").rfind(dir + "one_entry_syntax.toml:2: ", 0), 0U);
  EXPECT_EQ(error_of("one_entry.txt", "[bus]\nprotocol = \"canlust\"\n"),
            dir + "one_entry.txt:0: unknown scenario format: the file name must end in .toml or .json");
}

TEST(CanlustRun, ErrorsNameFileAndLine) {
  expect_error("name = \"x\"\n[bus]\nprotocol = \"canlust\"\n[[device]]\nname = \"a\"\ntype = \"cda3000\"\n"
               "address = 1\n[[timeline]]\nat = \"0 s\"\ndevice = \"a\"\neasydrive = 1\n",
               8, "easydrive needs cacnf = 4");
  const std::string head = "name = \"x\"\nduration = \"1 s\"\n[bus]\nprotocol = \"canlust\"\n";
  const std::string dev = "[[device]]\nname = \"a\"\ntype = \"cda3000\"\naddress = 1\n";  // lines 5-8
  expect_error(head + "bitrat = 1\n" + dev, 5, "unknown key 'bitrat' in [bus] (did you mean 'bitrate'?)");
  expect_error(head + "bitrate = 1000000\n" + dev, 5, "bitrate = 1000000 is outside 25000..500000");
  expect_error(head, 1, "no [[device]]");
  expect_error(head + dev + "[[device]]\nname = \"b\"\ntype = \"cda3000\"\naddress = 1\n", 12,
               "address 1 is given twice");
  expect_error(head + dev + "watchdog_ms = 300\n", 9, "watchdog_ms = 300 is outside 0..255");
  expect_error(head + dev + "[[device]]\nname = \"b\"\ntype = \"vf1000\"\naddress = 2\n", 11,
               "type must be \"cda3000\"");
  expect_error(head + dev + "[[timeline]]\nat = \"2 s\"\nsystem = \"start\"\n", 10, "is not inside the duration");
  expect_error(head + dev + "[[timeline]]\nat = \"0 s\"\ndevice = \"b\"\nstate = \"enabled\"\n", 11,
               "device 'b' is not among");
  expect_error(head + dev + "[[timeline]]\nat = \"0 s\"\ndevice = \"a\"\nstate = \"running\"\n", 12,
               "state = \"running\"");
  expect_error(head + dev + "[[timeline]]\nat = \"0 s\"\ndevice = \"a\"\nwrite = 574\nvalue = 300\n", 13,
               "574-CAWDG: 300 ms is above the maximum 255 ms");
  expect_error(head + dev + "[[timeline]]\nat = \"0 s\"\ndevice = \"a\"\nwrite = 574\n", 9, "write needs a value");
  expect_error(head + dev + "[[timeline]]\nat = \"0 s\"\nfault = \"master_silent\"\n", 9,
               "master_silent needs a duration");
  expect_error(head + dev + "[[timeline]]\nat = \"0 s\"\ndevice = \"a\"\nsystem = \"start\"\n", 11,
               "concerns the whole bus");
  expect_error(head + dev + "[[timeline]]\nat = \"0 s\"\ndevice = \"a\"\nread = 9999\n", 12,
               "the CDA3000 has no such parameter");
  expect_error(head + dev + "[[timeline]]\nat = \"0 s\"\ndevice = \"a\"\nread = 575\nstate = \"ready\"\n", 9,
               "exactly one of");
}

}  // namespace
}  // namespace ibs::sim::canlust
