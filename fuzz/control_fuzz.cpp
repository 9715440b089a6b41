// The test bench's live control lines (docs/testbench.md): `ibs run --realtime --control` reads
// each as a timeline entry without `at` against the running scenario (sim::parse_control_line);
// `ibs dfs1 emulate --control` reads its own (parse_dfs1_control_line, the DFS-1 wing's event
// reader the bench uses too).
//
// Input: byte 0 chooses the reader (bit 0: DFS-1); the rest is one line of text.
//
// Asserts:
// - parse_control_line refuses only with a sim::ScenarioError whose what() is `control:7: ...`
//   (the channel's line number given, never another); an accepted entry has no `at`, names a
//   device or controller of the bench scenario, and write_control_line writes it so that
//   parse_control_line reads it back equal;
// - parse_dfs1_control_line gives either an event or an error that says what, never both or
//   neither, and throws nothing.
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>

#include "dfs1_cmd.hpp"
#include "fuzz_support.hpp"
#include "ibs/sim/scenario.hpp"

namespace {

using namespace ibs;
using ibs::fuzz::fail;

// A bench: a servo and an inverter on the ring and on LUSTBUS, a DFS-1 controller on its line.
const sim::Scenario& bench() {
  static const sim::Scenario s = sim::parse_scenario_toml(R"(name = "bench"
duration = "8 s"
[[device]]
name = "servo"
type = "mc6000"
lustbus = 1
[[device]]
name = "fan"
type = "vf1000"
lustbus = 2
[lustbus]
pty = true
[dfs1]
pty = true
[[dfs1.controller]]
name = "press"
uid = 7
)",
                                                          "bench.toml");
  return s;
}

void interbus_line(const std::string& text) {
  sim::TimelineEntry e;
  try {
    e = sim::parse_control_line(text, 7, bench());
  } catch (const sim::ScenarioError& err) {
    const std::string what = err.what();
    if (what.rfind("control:7: ", 0) != 0 || what.size() == 11) fail("a refusal without its line: '" + what + "'");
    return;
  } catch (const std::exception& err) {
    fail(std::string("parse_control_line threw something else: ") + err.what());
  }
  if (e.at != Time{0}) fail("an accepted control line has a time");
  if (e.source_line != 7) fail("an accepted control line forgot its line");
  const std::string again = sim::write_control_line(e);
  try {
    if (!(sim::parse_control_line(again, 7, bench()) == e)) fail("write_control_line does not read back equal: " + again);
  } catch (const std::exception& err) {
    fail("write_control_line wrote a line its reader refuses: " + again + ": " + err.what());
  }
}

void dfs1_line(const std::string& text) {
  try {
    const auto parsed = cli::parse_dfs1_control_line(text);
    if (parsed.event.has_value() == !parsed.error.empty()) fail("an event and an error, or neither: " + parsed.error);
  } catch (const std::exception& err) {
    fail(std::string("parse_dfs1_control_line threw: ") + err.what());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
  if ((data[0] & 1U) != 0) {
    dfs1_line(text);
  } else {
    interbus_line(text);
  }
  return 0;
}
