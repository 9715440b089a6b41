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

// Issue 24: the drive events of the timeline, each in the scenario's own style, checked at load.
TEST(CanlustEvents, KeysAndTheirErrors) {
  const std::string head = "name = \"x\"\nduration = \"1 s\"\n[bus]\nprotocol = \"canlust\"\n";
  const std::string dev = "[[device]]\nname = \"a\"\ntype = \"cda3000\"\naddress = 1\n";  // lines 5-8
  const std::string tl = "[[timeline]]\nat = \"0.5 s\"\ndevice = \"a\"\n";               // lines 9-11
  const Scenario s = parse_scenario(head + dev + tl + "fault = \"device\"\ncause = \"E-OTI\"\n" + tl +
                                        "mains = \"off\"\n" + tl + "mains = \"on\"\n" + tl + "load = 80\n" + tl +
                                        "input = \"ENPO\"\nlevel = \"low\"\n" + tl + "fault = \"device\"\ncause = 12\n",
                                    "ok.toml", false);
  ASSERT_EQ(s.timeline.size(), 6U);
  EXPECT_EQ(s.timeline[0].action, Action::device_fault);
  EXPECT_EQ(s.timeline[0].cause, "E-OTI");
  EXPECT_EQ(s.timeline[1].action, Action::mains_off);
  EXPECT_EQ(s.timeline[2].action, Action::mains_on);
  EXPECT_EQ(s.timeline[3].action, Action::load);
  EXPECT_DOUBLE_EQ(s.timeline[3].load, 80.0);
  EXPECT_EQ(s.timeline[4].action, Action::input);
  EXPECT_EQ(s.timeline[4].input, "ENPO");
  EXPECT_FALSE(s.timeline[4].level);
  EXPECT_EQ(s.timeline[5].cause, "12");

  expect_error(head + dev + tl + "fault = \"device\"\n", 9, "fault = \"device\" needs a cause");
  expect_error(head + dev + tl + "fault = \"device\"\ncause = \"E-XYZ\"\n", 9,
               "cause 'E-XYZ': the CDA3000's errors (CANLust manual, table 5.9) are 8 E-OTI");
  expect_error(head + dev + tl + "mains = \"down\"\n", 12, "mains = \"down\": expected \"off\" or \"on\"");
  expect_error(head + dev + tl + "load = 400\n", 9, "the CDA3000 takes -300 .. 300 %");
  expect_error(head + dev + tl + "input = \"X1\"\nlevel = \"high\"\n", 9, "input 'X1'");
  expect_error(head + dev + tl + "input = \"ENPO\"\n", 9, "input needs a level");
  expect_error(head + dev + tl + "input = \"ENPO\"\nlevel = \"1\"\n", 13, "level = \"1\"");
  expect_error(head + dev + tl + "load = 10\ncause = \"E-OTI\"\n", 13, "cause belongs to fault = \"device\"");
  expect_error(head + dev + tl + "load = 10\nmains = \"off\"\n", 9, "exactly one of");
}

// The events in a run: the fault shows in the master's view of the drive (FAULT in its status
// telegram, an error telegram), the load lowers the actual value, the summary lists each entry.
TEST(CanlustEvents, FaultAndLoadInARun) {
  const Scenario s = parse_scenario(R"(name = "ev"
duration = "3 s"
[bus]
protocol = "canlust"
[[device]]
name = "a"
type = "cda3000"
address = 1
[[timeline]]
at = "0.1 s"
system = "start"
[[timeline]]
at = "0.1 s"
device = "a"
state = "enabled"
[[timeline]]
at = "0.1 s"
device = "a"
reference_hz = 20
[[timeline]]
at = "1.2 s"
device = "a"
load = 100
[[timeline]]
at = "2.5 s"
device = "a"
read = "ERR1"
[[timeline]]
at = "2.4 s"
device = "a"
fault = "device"
cause = "E-OTI"
)",
                                    "ev.toml", false);
  const Report r = run(s);
  const DriveResult& a = drive(r, "a");
  EXPECT_EQ(a.state, "FAULT");
  EXPECT_EQ(a.errors, 1U);
  EXPECT_NE(a.status.find("FAULT"), std::string::npos) << a.status;
  ASSERT_EQ(r.entries.size(), 6U);
  EXPECT_EQ(r.entries[3].what, "a: load 100.0 %");
  EXPECT_EQ(r.entries[3].outcome, "set: the motor slips 3.00 Hz below the output frequency");
  EXPECT_EQ(r.entries[4].what, "a: device fault E-OTI");
  EXPECT_EQ(r.entries[4].type, "fault");
  EXPECT_EQ(r.entries[4].outcome, "8 E-OTI (drive unit overheating), FAULT, error telegram sent");
  EXPECT_EQ(r.entries[5].outcome.rfind("8 E-OTI at location 0, 0 h (", 0), 0U) << r.entries[5].outcome;
  // 100 % load: 3 Hz of slip (D35) before the fault at 2.4 s.
  const auto at_fault = first_state(a, "FAULT");
  ASSERT_TRUE(at_fault);
  EXPECT_EQ(*at_fault, Time{0} + 2400ms);
}

// With bus = ..., the user's master drives: master commands are refused at load, with why.
TEST(CanlustServed, BusKeyAndMasterCommandsRefused) {
  const std::string head = "name = \"x\"\nduration = \"1 s\"\n[bus]\nprotocol = \"canlust\"\n";
  const std::string dev = "[[device]]\nname = \"a\"\ntype = \"cda3000\"\naddress = 1\n";  // lines 6-9
  const Scenario s = parse_scenario(head + "bus = \"udp:0:127.0.0.1:0\"\n" + dev, "ok.toml", false);
  EXPECT_EQ(s.bus, "udp:0:127.0.0.1:0");
  EXPECT_EQ(s.bus_line, 5U);
  EXPECT_EQ(parse_scenario(head + "bus = \"socketcan:vcan0\"\n" + dev, "ok.toml", false).bus, "socketcan:vcan0");
  expect_error(head + "bus = \"tcp:1\"\n" + dev, 5, "expected \"udp:LOCALPORT:HOST:PORT\" or \"socketcan:IFACE\"");
  expect_error(head + "bus = \"udp:1:2\"\n" + dev, 5, "expected \"udp:LOCALPORT:HOST:PORT\"");
  for (const std::string entry : {"system = \"start\"\n", "device = \"a\"\nstate = \"enabled\"\n",
                                  "device = \"a\"\nread = 575\n", "fault = \"master_silent\"\nduration = \"1 ms\"\n"}) {
    expect_error(head + "bus = \"udp:0:127.0.0.1:0\"\n" + dev + "[[timeline]]\nat = \"0 s\"\n" + entry, 10,
                 "with bus = \"udp:0:127.0.0.1:0\", your own master drives the bus; the timeline holds drive events "
                 "only");
  }
  EXPECT_NO_THROW(parse_scenario(head + "bus = \"udp:0:127.0.0.1:0\"\n" + dev +
                                     "[[timeline]]\nat = \"0 s\"\ndevice = \"a\"\nfault = \"device\"\ncause = 9\n",
                                 "ok.toml", false));
}

// A control line is a timeline entry without `at`, read by the same reader; errors name the line.
TEST(CanlustControl, LinesAreEntriesWithoutAt) {
  const Scenario s = parse_scenario(
      "name = \"x\"\nduration = \"1 s\"\n[bus]\nprotocol = \"canlust\"\n[[device]]\nname = \"a\"\ntype = "
      "\"cda3000\"\naddress = 1\n",
      "ok.toml", false);
  const Entry e = parse_control_entry(s, R"({"device": "a", "fault": "device", "cause": "E-PAR"})", 3);
  EXPECT_EQ(e.action, Action::device_fault);
  EXPECT_EQ(e.cause, "E-PAR");
  EXPECT_EQ(parse_control_entry(s, R"({"system": "start"})", 1).action, Action::start);
  const auto expect_bad = [&](const std::string& line, const std::string& what) {
    try {
      parse_control_entry(s, line, 7);
      ADD_FAILURE() << "accepted: " << line;
    } catch (const ScenarioError& err) {
      EXPECT_EQ(std::string(err.what()).rfind("control:7: ", 0), 0U) << err.what();
      EXPECT_NE(std::string(err.what()).find(what), std::string::npos) << err.what();
    }
  };
  expect_bad(R"({"at": "1 s", "system": "start"})", "control entries apply at once: no 'at'");
  expect_bad(R"({"device": "b", "load": 1})", "device 'b' is not among");
  expect_bad(R"({"device": "a", "fault": "device", "cause": "E-XYZ"})", "cause 'E-XYZ'");
  expect_bad(R"({"device": "a", "lod": 1})", "unknown key 'lod' in a control entry (did you mean 'load'?)");
  expect_bad(R"({"device": )", "");
  expect_bad(R"([1, 2])", "a control line is a JSON object");
}

// run_realtime on the simulated bus: paced at 1 ms steps, control entries applied at the step
// they arrive and listed with their time; the summary has the real-time counts.
TEST(CanlustControl, RealtimeRunAppliesControlEntries) {
  const Scenario s = parse_scenario(R"(name = "rt"
duration = "300 ms"
[bus]
protocol = "canlust"
[[device]]
name = "a"
type = "cda3000"
address = 1
[[timeline]]
at = "10 ms"
system = "start"
)",
                                    "rt.toml", false);
  RealtimeOptions o;
  bool sent = false;
  o.each_step = [&](Time now, std::vector<Entry>& out) {
    if (!sent && now >= Time{0} + 100ms) {
      out.push_back(parse_control_entry(s, R"({"device": "a", "fault": "device", "cause": "E-FLT"})", 1));
      sent = true;
    }
  };
  const auto t0 = std::chrono::steady_clock::now();
  const Report r = run_realtime(s, o);
  EXPECT_GE(std::chrono::steady_clock::now() - t0, 300ms);  // paced in real time
  ASSERT_TRUE(r.realtime);
  EXPECT_EQ(r.realtime->cycles, 301U);
  EXPECT_TRUE(r.realtime->served.empty());
  ASSERT_EQ(r.entries.size(), 2U);
  EXPECT_EQ(r.entries[1].at, Time{0} + 100ms);
  EXPECT_EQ(r.entries[1].what, "a: device fault E-FLT");
  EXPECT_TRUE(r.entries[1].ok) << r.entries[1].outcome;
  EXPECT_EQ(drive(r, "a").state, "FAULT");
  EXPECT_EQ(drive(r, "a").errors, 1U);
  const std::string text = format_text(r);
  EXPECT_NE(text.find("real time: 301 steps of 1 ms, "), std::string::npos) << text;
  EXPECT_NE(text.find("0.100 s  a: device fault E-FLT: 11 E-FLT (floating point error), FAULT"), std::string::npos) << text;
  const auto j = nlohmann::json::parse(format_json(r));
  EXPECT_EQ(j["bus"]["realtime"]["cycles"], 301);
  EXPECT_TRUE(j["bus"]["realtime"].contains("overruns"));
}

}  // namespace
}  // namespace ibs::sim::canlust
