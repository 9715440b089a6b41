// The scenario loader of `ibs run` (sim/scenario.hpp, docs/scenarios.md) from arbitrary text, in
// TOML and in JSON, then validation, the writers' round trip, the simulator's constructor and a
// short run.
//
// Input: byte 0 chooses the format (bit 0: JSON) and whether to also try parse_time on the text;
// the rest is the file's text.
//
// Asserts:
// - every refusal is a sim::ScenarioError whose what() is `FILE:LINE: message`, with this file and
//   a line of the input (1..number of lines): "every problem names its file and line"; anything
//   else that escapes is a finding;
// - a scenario the reader accepts passes validate_scenario(), is written by both writers into
//   text that both readers read back equal (operator==, "every valid scenario survives a
//   write/parse round trip equal");
// - the simulator builds it without refusing (the reader checked layouts and bus limits) and
//   runs it for a short, bounded stretch (at most 100 bus cycles and 20 ms of simulated time, so
//   that an input runs in milliseconds) without an exception;
// - parse_time of any text either refuses with std::invalid_argument or gives a time that
//   format_time writes and parse_time reads back exactly.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "fuzz_support.hpp"
#include "ibs/sim/scenario.hpp"
#include "ibs/sim/simulator.hpp"

namespace {

using namespace ibs;
using ibs::fuzz::fail;

void check_refusal(const sim::ScenarioError& e, const std::string& file, std::size_t lines, const char* stage) {
  const std::string why = ibs::fuzz::file_line_problem(e.what(), file, lines);
  if (!why.empty()) fail(std::string(stage) + ": the refusal '" + e.what() + "' " + why);
  if (e.file() != file || e.line() < 1 || e.line() > lines) {
    fail(std::string(stage) + ": ScenarioError names " + e.file() + " line " + std::to_string(e.line()));
  }
}

void check_time(std::string_view text) {
  Duration d{};
  try {
    d = sim::parse_time(text);
  } catch (const std::invalid_argument&) {
    return;
  } catch (const std::exception& e) {
    fail(std::string("parse_time threw something other than invalid_argument: ") + e.what());
  }
  const std::string f = sim::format_time(d);
  try {
    if (sim::parse_time(f) != d) fail("parse_time(format_time(" + std::to_string(d.count()) + " ns)) = " + f + " reads back differently");
  } catch (const std::exception& e) {
    fail("format_time(" + std::to_string(d.count()) + " ns) = '" + f + "' does not parse: " + e.what());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const bool json = (data[0] & 1U) != 0;
  const std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
  if ((data[0] & 2U) != 0 && text.size() < 64) check_time(text);
  const std::string file = json ? "fuzz.json" : "fuzz.toml";
  const std::size_t lines = ibs::fuzz::count_lines(text);

  std::optional<sim::Scenario> s;
  try {
    s = json ? sim::parse_scenario_json(text, file) : sim::parse_scenario_toml(text, file);
  } catch (const sim::ScenarioError& e) {
    check_refusal(e, file, lines, "parse");
    return 0;
  } catch (const std::exception& e) {
    fail(std::string("parse: an exception other than ScenarioError escaped: ") + e.what());
  } catch (...) {
    fail("parse: a non-standard exception escaped");
  }

  try {
    sim::validate_scenario(*s, file);
  } catch (const std::exception& e) {
    fail(std::string("a scenario the reader accepted fails validation: ") + e.what());
  }
  for (const bool as_json : {false, true}) {
    const std::string out = as_json ? sim::write_scenario_json(*s) : sim::write_scenario_toml(*s);
    const std::string out_file = as_json ? "written.json" : "written.toml";
    try {
      const sim::Scenario back = as_json ? sim::parse_scenario_json(out, out_file) : sim::parse_scenario_toml(out, out_file);
      if (!(back == *s)) fail("the scenario written as " + out_file + " reads back different:\n" + out);
    } catch (const std::exception& e) {
      fail("the scenario written as " + out_file + " does not read back: " + e.what() + "\n" + out);
    }
  }

  try {
    sim::Simulator simulator(*s);
    sim::SimOptions options;
    options.measure_master_time = false;
    const Duration cycle = simulator.cycle_time();
    const Time end = std::min<Time>({s->duration, cycle * 100, Time{20ms}});
    simulator.run_until(end, options);
    (void)simulator.summary();
  } catch (const std::exception& e) {
    fail(std::string("the simulator refused or failed on a scenario the reader accepted: ") + e.what());
  }
  return 0;
}
