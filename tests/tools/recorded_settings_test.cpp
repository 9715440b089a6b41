// Issue 41, "every recording replays": a recording of `ibs run --trace` writes a `setting: NAME
// VALUE` header for every device setting that differs from its default and a `! write PNR VALUE`
// event for every value a channel the trace does not carry changed (../shared/specs/
// trace-format.md); replay applies both, decode shows them, and both refuse an unknown name, a
// value out of range or a write the drive's table does not take, with the line.
//
// For every drive kind of the registry a generated scenario sets each of its declared settings to
// a value other than its default (and the watchdog's reaction where the drive has a choice),
// writes a parameter through the drive's parameter channel and trips its bus watchdog; every file
// the run records replays, and fails without the headers and events that carry those settings.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "../support/run_shell.hpp"
#include "ibs/devices/registry.hpp"
#include "ibs/interbus/trace.hpp"

namespace {

namespace fs = std::filesystem;
using Result = ibs::test::ShellResult;
using ibs::test::run_shell;

Result run(const std::string& args) { return run_shell(std::string(IBS_CLI) + " " + args + " 2>&1"); }

fs::path scratch(const std::string& name) {
  return fs::path(::testing::TempDir()) / ("ibs" + std::to_string(::getpid()) + "_" + name);
}

std::string temp_file(const std::string& name, const std::string& text) {
  const std::string path = scratch(name).string();
  std::ofstream(path) << text;
  return path;
}

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The text without the lines that start with `prefix`.
std::string without(const std::string& text, const std::string& prefix) {
  std::istringstream in(text);
  std::string out;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(prefix, 0) != 0) out += line + "\n";
  }
  return out;
}

struct Generated {
  std::string scenario;
  // What the recording must carry for the replay to match, each line removed once to show that
  // the replay then fails.
  std::vector<std::string> needed;
};

// Per drive kind: every declared setting at another value than its default, a parameter through
// the drive's channel, the bus watchdog tripped by a lost bus (the VF1000's reset_time acts at the
// RESET FAULT of a device fault before it).
const std::map<std::string, Generated>& generated() {
  static const std::map<std::string, Generated> g = {
      {"vf1000",
       {R"(name = "vf1000-settings"
duration = "6 s"
[[device]]
name = "drive"
type = "vf1000"
watchdog_ms = 100
watchdog_reaction = 1      # 907-IBCOD: shut down with E-IBS (factory 0: no action)
keypad = true              # 7.1: the communication word's KEYPAD times
reset_time = "2 s"         # the self-test after RESET FAULT (factory 4 s)
[[timeline]]
at = "0 s"
device = "drive"
read = 85
[[timeline]]
at = "0 s"
device = "drive"
state = "enabled"
[[timeline]]
at = "300 ms"
device = "drive"
frequency = 20.0
[[timeline]]
at = "500 ms"
device = "drive"
fault = "device"
duration = "100 ms"
[[timeline]]
at = "800 ms"              # RESET FAULT: the software reset, reset_time long
device = "drive"
state = "enabled"
[[timeline]]
at = "3500 ms"
device = "drive"
read = 85
[[timeline]]
at = "3500 ms"
device = "drive"
state = "enabled"
[[timeline]]
at = "4500 ms"             # the bus lost for 300 ms: 906-IB-WD runs out, E-IBS
device = "drive"
fault = "lost"
duration = "300 ms"
)",
        {"# setting: watchdog_reaction", "# setting: reset_time", "# setting: keypad"}}},
      {"mc6000",
       {R"(name = "mc6000-settings"
duration = "3 s"
[bus]
cycle_time = "1 ms"
[[device]]
name = "drive"
type = "mc6000"
supi = 9                   # 2 process-data words, 2 PCP words (factory 11)
ibcnf = 1                  # a 16-bit speed in rpm (factory 2)
[[timeline]]
at = "0 s"
device = "drive"
read = 85
[[timeline]]
at = "100 ms"
device = "drive"
write = { parameter = 409, value = 20 }   # 409-BUTWD over PCP: not in the process-data words
[[timeline]]
at = "300 ms"
device = "drive"
state = "enabled"
[[timeline]]
at = "400 ms"
device = "drive"
speed = 100.0
[[timeline]]
at = "1 s"
device = "drive"
fault = "lost"
duration = "100 ms"
[[timeline]]
at = "1500 ms"
device = "drive"
state = "enabled"
)",
        {"! write 409 20", "! write 85 0"}}},
  };
  return g;
}

TEST(RecordedSettings, EveryDriveWithEverySettingChangedAndItsWatchdogTrippedReplays) {
  for (const ibs::devices::DriveKind& kind : ibs::devices::drive_kinds()) {
    const std::string name(kind->name());
    SCOPED_TRACE(name);
    const auto g = generated().find(name);
    ASSERT_NE(g, generated().end()) << "a drive kind without a generated scenario: add one to generated()";
    const std::string scenario = temp_file(name + "_settings.toml", g->second.scenario);
    const fs::path dir = scratch("recorded_settings_" + name);
    fs::remove_all(dir);
    const Result r = run("run " + scenario + " --trace " + dir.string());
    ASSERT_EQ(r.exit_code, 0) << r.out;
    EXPECT_NE(r.out.find(std::string(kind->facts().watchdog_error)), std::string::npos)
        << "the watchdog did not trip:\n" << r.out;
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(dir)) files.push_back(e.path());
    ASSERT_FALSE(files.empty());
    for (const fs::path& file : files) {
      SCOPED_TRACE(file.filename().string());
      const std::string text = read(file);
      const ibs::trace::Trace t = ibs::trace::parse(text, file.string());
      // Every declared setting is in the header, away from its default: in its own header
      // (`# supi: 9`) or in a `setting:` one.
      for (const ibs::devices::SettingSpec& spec : kind->settings()) {
        const ibs::trace::HeaderSetting* own = t.header.setting(spec.name);
        const ibs::trace::DeviceSetting* other = t.header.device_setting(spec.name);
        ASSERT_TRUE(own != nullptr || other != nullptr) << spec.name << " missing:\n" << text.substr(0, 400);
        if (own != nullptr) {
          EXPECT_NE(own->value, spec.fallback) << spec.name;
        }
      }
      const Result replay = run("replay --emulate device " + file.string());
      EXPECT_EQ(replay.exit_code, 0) << replay.out;
      EXPECT_TRUE(std::regex_match(replay.out, std::regex("replay: [0-9]+ steps matched\n"))) << replay.out;
      // decode shows them and its output replays the same.
      const Result decoded = run("decode " + file.string());
      ASSERT_EQ(decoded.exit_code, 0) << decoded.out;
      for (const std::string& needed : g->second.needed) {
        EXPECT_NE(text.find("\n" + needed), std::string::npos) << needed << " is not recorded";
        EXPECT_NE(decoded.out.find("\n" + needed), std::string::npos) << needed << " is not decoded";
        // Without it the replay fails: a mismatch (1), or a later write the drive then refuses (2).
        const Result missing = run("replay --emulate device " +
                                   temp_file(name + "_without.trace", without(text, needed)));
        EXPECT_NE(missing.exit_code, 0) << needed << ":\n" << missing.out;
      }
      EXPECT_EQ(run("replay --emulate device " + temp_file(name + "_decoded.trace", decoded.out)).exit_code, 0);
    }
    fs::remove_all(dir);
  }
}

// The two hand-made files of tests/data: the issue's cases, replayed with and without what carries
// them, and shown by decode (its JSON too).
TEST(RecordedSettings, TheIssuesTwoCasesReplayOnlyWithTheirHeaderAndEvent) {
  const std::string data = IBS_TEST_DATA_DIR;
  struct Case {
    std::string file;
    std::string carrier;  // the line that carries the setting or the write
    std::string json;     // how decode --json shows it
  };
  for (const Case& c : {Case{"vf1000_pd_watchdog_reaction.trace", "# setting: watchdog_reaction 1",
                             R"("settings":{"watchdog_reaction":"1"})"},
                        Case{"mc6000_pd_butwd_written_over_pcp.trace", "! write 409 20",
                             R"({"decoded":"409-BUTWD = 20","event":"write","line":12,"parameter":409,"text":"over PCP","value":20})"}}) {
    SCOPED_TRACE(c.file);
    const std::string path = data + "/" + c.file;
    const Result ok = run("replay --emulate device " + path);
    EXPECT_EQ(ok.exit_code, 0) << ok.out;
    const Result missing = run("replay --emulate device " + temp_file("missing_" + c.file, without(read(path), c.carrier)));
    EXPECT_EQ(missing.exit_code, 1) << missing.out;
    const Result json = run("decode --json " + path);
    ASSERT_EQ(json.exit_code, 0) << json.out;
    EXPECT_NE(json.out.find(c.json), std::string::npos) << json.out;
  }
}

// Refusals, the same in replay and decode, each with its line.
TEST(RecordedSettings, UnknownNamesOutOfRangeValuesAndWritesTheTableRefusesAreErrorsWithTheLine) {
  const std::string vf = "# format: ibs-trace 1\n# device: vf1000\n# words: pd\n";
  const std::string mc = "# format: ibs-trace 1\n# device: mc6000\n# words: pd\n";
  const std::string vf_rows = "0, 0000 0000 0000, 0240 0000 8000\n1, 0006 0000 0000, 0231 0000 8000\n";
  const std::string mc_rows = "0, 0000 0000 0000, 0240 0000 0000\n";
  const std::string mc_next = "1, 0000 0000 0000, 0240 0000 0000\n";
  struct Case {
    const char* name;
    std::string text;
    std::string message;  // after FILE:
  };
  const std::vector<Case> cases = {
      {"unknown_name", vf + "# setting: keypadd true\n" + vf_rows, "4: setting: unknown setting 'keypadd'"},
      {"reaction_out_of_range", vf + "# setting: watchdog_reaction 9\n" + vf_rows,
       "4: 'watchdog_reaction' = 9 is out of range (0..3, 907-IBCOD)"},
      {"reaction_of_a_servo", mc + "# setting: watchdog_reaction 1\n" + mc_rows,
       "4: 'watchdog_reaction' is a VF1000 setting (907-IBCOD)"},
      {"boolean_word", vf + "# setting: keypad yes\n" + vf_rows, "4: setting: keypad: 'yes' is not true or false"},
      {"time_out_of_range", vf + "# setting: reset_time 61 s\n" + vf_rows, "4: 'reset_time' must be above 0 s and at most 60 s"},
      {"time_without_unit", vf + "# setting: reset_time 2\n" + vf_rows, "4: setting: reset_time: '2' is not a time"},
      {"own_header_as_setting", mc + "# setting: supi 9\n" + mc_rows, "4: setting: unknown setting 'supi'"},
      {"setting_of_another_drive", mc + "# setting: keypad true\n" + mc_rows,
       "4: setting: 'keypad' is a VF1000 setting (INTERBUS manual 7.1)"},
      {"write_unknown_parameter", mc + mc_rows + "! write 999 1\n" + mc_next,
       "5: write: parameter 999 is not in the MC6000's table"},
      {"write_too_wide", mc + mc_rows + "! write 409 70000\n" + mc_next, "5: write: 409-BUTWD: 70000 is no value of its type"},
      {"write_actual_value", mc + mc_rows + "! write 77 1\n" + mc_next, "5: write: 77-SPEED is an actual value"},
      {"write_out_of_range", vf + "0, 0000 0000 0000, 0240 0000 8000\n! write 22 60000\n1, 0006 0000 0000, 0231 0000 8000\n",
       "5: write: 22-"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string path = temp_file(std::string("settings_refused_") + c.name + ".trace", c.text);
    const std::string want = path + ":" + c.message;
    const Result device = run("replay --emulate device " + path);
    EXPECT_EQ(device.exit_code, 2) << device.out;
    EXPECT_EQ(device.out.rfind(want, 0), 0U) << device.out << "\nexpected: " << want;
    const Result decode = run("decode " + path);
    EXPECT_EQ(decode.exit_code, 2) << decode.out;
    EXPECT_EQ(decode.out, device.out);
  }
  // A write the table takes but the drive refuses in the state it is in: a replay error with the
  // line (85-SERR holds the power-on bit of `init: power-on`).
  const std::string latched = temp_file("settings_latched.trace", mc + "# init: power-on\n" + mc_rows + "! write 409 20\n" + mc_next);
  const Result r = run("replay --emulate device " + latched);
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_EQ(r.out.rfind(latched + ":6: write 409 20: the MC6000 refuses 409 = 20", 0), 0U) << r.out;
}

}  // namespace
