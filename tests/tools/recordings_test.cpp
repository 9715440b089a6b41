// Every INTERBUS scenario in examples/ recorded with `ibs run FILE --trace DIR` replays unchanged
// through the binary, whatever faults the run injected (corrupted cycles, lost devices, power
// cycles, device faults, random faults): the recordings carry the steps without data
// (`! no-data N`), the watchdog (`watchdog_ms`) and the step time (`step-time`) that
// ../shared/specs/trace-format.md gives them. And `ibs decode` judges a file as `ibs replay`
// does: one validation, the same FILE:LINE message and exit 2 (docs/replay.md, "Errors").
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "ibs/interbus/trace.hpp"

#include "../support/run_shell.hpp"

namespace {

namespace fs = std::filesystem;
using Result = ibs::test::ShellResult;
using ibs::test::run_shell;

Result run(const std::string& args) { return run_shell(std::string(IBS_CLI) + " " + args + " 2>&1"); }

std::string read(const fs::path& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A name of this test process's own under the temporary directory: two test runs on one machine
// (a developer's and CI's) must not write into each other's recordings.
fs::path scratch(const std::string& name) {
  return fs::path(::testing::TempDir()) / ("ibs" + std::to_string(::getpid()) + "_" + name);
}

std::string temp_file(const std::string& name, const std::string& text) {
  const std::string path = scratch(name).string();
  std::ofstream(path) << text;
  return path;
}

// The scenarios of examples/ (the top level: examples/canlust/ holds the CANLust bus, whose runs
// write no cycle traces -- checked below).
std::vector<fs::path> interbus_examples() {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(fs::path(IBS_SOURCE_DIR) / "examples")) {
    const auto ext = e.path().extension();
    if (e.is_regular_file() && (ext == ".toml" || ext == ".json")) out.push_back(e.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

TEST(RecordingsReplay, EveryExampleScenarioRecordsTracesThatReplayWithTheDeviceModel) {
  const auto examples = interbus_examples();
  ASSERT_GE(examples.size(), 4U);
  std::size_t traces = 0;
  std::size_t without_data = 0;
  for (const fs::path& scenario : examples) {
    SCOPED_TRACE(scenario.filename().string());
    const fs::path dir = scratch("recordings_" + scenario.stem().string());
    fs::remove_all(dir);
    const Result r = run("run " + scenario.string() + " --trace " + dir.string());
    ASSERT_EQ(r.exit_code, 0) << r.out;
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(dir)) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    ASSERT_FALSE(files.empty());
    for (const fs::path& file : files) {
      SCOPED_TRACE(file.filename().string());
      ++traces;
      const std::string text = read(file);
      // The step time is the device's sample period, always written.
      EXPECT_NE(text.find("\n# step-time: "), std::string::npos) << text.substr(0, 300);
      if (text.find("\n! no-data ") != std::string::npos) ++without_data;
      const Result device = run("replay --emulate device " + file.string());
      EXPECT_EQ(device.exit_code, 0) << device.out;
      EXPECT_TRUE(std::regex_match(device.out, std::regex("replay: [0-9]+ steps matched\n"))) << device.out;
      // A recording has no `request` (the run's master was asked through its timeline, not one
      // request per trace): --emulate master has nothing to do and refuses it, as docs/replay.md
      // says. A file that has one replays with the master too.
      const auto t = ibs::trace::parse(text, file.string());
      const Result master = run("replay --emulate master " + file.string());
      if (t.header.request) {
        EXPECT_EQ(master.exit_code, 0) << master.out;
      } else {
        EXPECT_EQ(master.exit_code, 2) << master.out;
        EXPECT_NE(master.out.find("no `request` header"), std::string::npos) << master.out;
      }
    }
    fs::remove_all(dir);
  }
  EXPECT_GE(traces, examples.size());
  // The faults of examples/faults.toml (and a 2 ms cycle slower than the MC6000's samples) give
  // steps without data: the test covers them.
  EXPECT_GT(without_data, 0U);
}

TEST(RecordingsReplay, ACanlustRunWritesNoCycleTraces) {
  const fs::path scenario = fs::path(IBS_SOURCE_DIR) / "examples" / "canlust" / "conveyors.toml";
  const fs::path dir = scratch("recordings_canlust");
  fs::remove_all(dir);
  const Result r = run("run " + scenario.string() + " --trace " + dir.string());
  // The cycle trace format is INTERBUS's: a CANLust run refuses --trace or writes none.
  if (r.exit_code == 0) {
    EXPECT_TRUE(!fs::exists(dir) || fs::is_empty(dir)) << r.out;
  } else {
    EXPECT_EQ(r.exit_code, 2) << r.out;
  }
  fs::remove_all(dir);
}

// A servo whose data stop for longer than its 409-BUTWD: the watchdog trips in the replay at the
// row the recording shows it (error 16 E-OP1 makes the drive FAULT), and without the no-data
// event the same file does not replay.
TEST(RecordingsReplay, AWatchdogThatTripsDuringStepsWithoutDataReplays) {
  const std::string scenario = temp_file("watchdog_trip.toml", R"(name = "watchdog-trip"
duration = "1500 ms"
[bus]
cycle_time = "1 ms"
[[device]]
name = "servo"
type = "mc6000"
watchdog_ms = 20
[[timeline]]
at = "0 s"
device = "servo"
state = "enabled"
[[timeline]]
at = "600 ms"
device = "servo"
fault = "lost"
duration = "100 ms"
)");
  const fs::path dir = scratch("recordings_watchdog_trip");
  fs::remove_all(dir);
  const Result r = run("run " + scenario + " --trace " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("watchdog"), std::string::npos) << r.out;
  const fs::path file = dir / "servo.trace";
  const std::string text = read(file);
  EXPECT_NE(text.find("# watchdog_ms: 20\n"), std::string::npos);
  EXPECT_NE(text.find("# step-time: 1 ms\n"), std::string::npos);
  EXPECT_NE(text.find("\n! no-data 100\n"), std::string::npos);
  const Result replay = run("replay --emulate device " + file.string());
  EXPECT_EQ(replay.exit_code, 0) << replay.out;
  // Without the event (its steps joined to the rows) the replayed servo's watchdog is fed on.
  auto t = ibs::trace::parse(text, file.string());
  std::uint64_t step = 0;
  for (auto& row : t.rows) {
    std::erase_if(row.events_before, [](const ibs::trace::Event& e) { return e.kind == ibs::trace::Event::Kind::no_data; });
    row.step = step++;
  }
  const Result fed = run("replay --emulate device " + temp_file("watchdog_fed.trace", ibs::trace::write(t)));
  EXPECT_EQ(fed.exit_code, 1) << fed.out;
  // A different watchdog setting is a different replay.
  std::string other = text;
  other.replace(other.find("# watchdog_ms: 20"), 17, "# watchdog_ms: 0");  // 409-BUTWD 0: off
  const Result off = run("replay --emulate device " + temp_file("watchdog_off.trace", other));
  EXPECT_EQ(off.exit_code, 1) << off.out;
  fs::remove_all(dir);
}

// Files that replay refuses (exit 2) are refused by decode with the same FILE:LINE message.
TEST(RecordingsReplay, DecodeRefusesWhatReplayRefusesWithTheSameMessage) {
  const std::string comm = "# format: ibs-trace 1\n# device: vf1000\n# words: comm\n";
  const std::string pcp = "# format: ibs-trace 1\n# device: mc6000\n# words: pcp\n# supi: 3\n# ibcnf: 0\n";
  const std::string vf_pd = "# format: ibs-trace 1\n# device: vf1000\n# words: pd\n";
  const std::string mc_pd = "# format: ibs-trace 1\n# device: mc6000\n# words: pd\n";
  const std::string comm_rows = "0, 0000, 8000\n1, 2416, 8000\n2, 2416, A003\n";
  const std::string pcp_rows = "0, 0E00 0000 0000 0000, 8F00 0000 0000 0000\n1, 0E00 0000 0000 0000, 9700 0000 0000 0000\n";
  const std::string vf_rows = "0, 0000 0000 0000, 0240 0000 8000\n1, 0006 0000 0000, 0231 0000 8000\n";
  struct Case {
    const char* name;
    std::string text;
    std::string message;  // after FILE:
  };
  const std::vector<Case> cases = {
      {"fault_in_comm", comm + "# request: read 0x16\n0, 0000, 8000\n! fault\n1, 2416, 8000\n",
       "6: event 'fault': the emulated vf1000 with words: comm is its parameter channel alone"},
      {"no_data_in_comm", comm + "# request: read 0x16\n0, 0000, 8000\n1, 2416, 8000\n! no-data 2\n4, 2416, A003\n",
       "7: event 'no-data': the emulated vf1000 with words: comm"},
      {"state_in_pcp", pcp + "# request: state enabled\n# outcome: ok\n" + pcp_rows,
       "6: a PCP channel trace cannot carry `request: state enabled`"},
      {"state_in_comm", comm + "# request: state enabled\n" + comm_rows, "4: vf1000 comm: `state enabled` is a DRIVECOM request"},
      {"comm_parameter_too_high", comm + "# request: read 2000\n" + comm_rows, "4: vf1000 comm: parameter 2000 above 3FFH"},
      {"parameter_request_in_pd", vf_pd + "# request: read 22\n" + vf_rows, "4: request: 'read 22' is a parameter request"},
      {"outcome_without_request", vf_pd + "# outcome: ok\n" + vf_rows, "4: header 'outcome' needs a 'request' to judge"},
      {"request_at_no_row", comm + "# request: read 0x16\n# request-at: 9\n" + comm_rows,
       "5: request-at: step 9 does not appear in the trace"},
      {"vf1000_watchdog_below_range", vf_pd + "# watchdog_ms: 5\n" + vf_rows, "4: 'watchdog_ms' = 5 is out of range (8..65535, 906-IB-WD)"},
      {"mc6000_watchdog_above_range", mc_pd + "# watchdog_ms: 70000\n0, 0000 0000 0000, 0240 0000 0000\n",
       "4: 'watchdog_ms' = 70000 is out of range"},
      {"watchdog_in_channel_trace", comm + "# watchdog_ms: 200\n# request: read 0x16\n" + comm_rows,
       "4: watchdog_ms: a words: comm trace emulates the parameter channel alone"},
      {"pcp_without_channel", "# format: ibs-trace 1\n# device: mc6000\n# words: pcp\n# supi: 12\n# request: read 1\n" + pcp_rows,
       "5: `supi: 12` gives the MC6000 no PCP channel"},
      {"step_time_without_unit", vf_pd + "# step-time: 5\n" + vf_rows, "4: step-time: \"5\" has no unit"},
      {"step_time_zero", vf_pd + "# step-time: 0 ms\n" + vf_rows, "4: step-time: '0 ms' must lie above 0 s and be at most 1 s"},
      {"step_time_too_long", vf_pd + "# step-time: 2 s\n" + vf_rows, "4: step-time: '2 s' must lie above 0 s"},
      {"no_data_zero", vf_pd + "0, 0000 0000 0000, 0240 0000 8000\n! no-data 0\n1, 0006 0000 0000, 0231 0000 8000\n",
       "5: no-data: '0' is not a number of steps"},
      {"no_data_step_not_counted", vf_pd + "0, 0000 0000 0000, 0240 0000 8000\n! no-data 3\n1, 0006 0000 0000, 0231 0000 8000\n",
       "6: step 1 should be 4"},
      {"no_data_before_first_row", vf_pd + "! no-data 3\n0, 0000 0000 0000, 0240 0000 8000\n", "4: an event must stand between two data rows"},
      {"short_row", vf_pd + "# request: state enabled\n0, 0000 0000, 0240 0000\n1, 0006 0000, 0231 0000\n", "5: this vf1000 with words: pd exchanges 3 m2s"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string path = temp_file(std::string("refused_") + c.name + ".trace", c.text);
    const std::string want = path + ":" + c.message;
    const Result device = run("replay --emulate device " + path);
    EXPECT_EQ(device.exit_code, 2) << device.out;
    EXPECT_EQ(device.out.rfind(want, 0), 0U) << device.out << "\nexpected: " << want;
    const Result decode = run("decode " + path);
    EXPECT_EQ(decode.exit_code, 2) << decode.out;
    EXPECT_EQ(decode.out, device.out);
    const Result json = run("decode --json " + path);
    EXPECT_EQ(json.exit_code, 2) << json.out;
    EXPECT_EQ(json.out, device.out);
    // The master refuses it too: with the same message, or, without a request, for the lack of one.
    const Result master = run("replay --emulate master " + path);
    EXPECT_EQ(master.exit_code, 2) << master.out;
    if (c.text.find("# request: ") != std::string::npos) {
      EXPECT_EQ(master.out, device.out);
    }
  }
}

// The new headers and events round-trip through decode, which shows them and does not act on
// them; --emulate master keeps them too.
TEST(RecordingsReplay, DecodeShowsTheWatchdogTheStepTimeAndTheStepsWithoutData) {
  const std::string path = std::string(IBS_TEST_DATA_DIR) + "/mc6000_pd_watchdog_no_data.trace";
  const Result d = run("decode " + path);
  ASSERT_EQ(d.exit_code, 0) << d.out;
  EXPECT_NE(d.out.find("# watchdog_ms: 20\n"), std::string::npos) << d.out;
  EXPECT_NE(d.out.find("# step-time: 1 ms\n"), std::string::npos) << d.out;
  EXPECT_NE(d.out.find("\n! no-data 25"), std::string::npos) << d.out;
  const Result j = run("decode --json " + path);
  ASSERT_EQ(j.exit_code, 0) << j.out;
  EXPECT_NE(j.out.find("\"watchdog_ms\":20"), std::string::npos) << j.out;
  EXPECT_NE(j.out.find("\"step_time\":\"1 ms\""), std::string::npos) << j.out;
  EXPECT_NE(j.out.find("\"steps\":25"), std::string::npos) << j.out;
  const Result again = run("replay --emulate device " + temp_file("decoded_watchdog.trace", d.out));
  EXPECT_EQ(again.exit_code, 0) << again.out;
}

}  // namespace
