// One entry point for `ibs run`'s scenario files, whichever bus they describe (docs/scenarios.md):
// the file is read and parsed once into the document tree both schemas share (TOML or JSON by the
// extension, every key and value with its line), and its [bus] decides the schema that reads the
// tree: `protocol = "canlust"` the CANLust one (canlust_scenario.hpp), no protocol the INTERBUS one
// (scenario.hpp). Every error is a sim::ScenarioError naming file:line, as either reader's own.
#pragma once

#include <cstdint>
#include <string>
#include <variant>

#include "ibs/sim/canlust_scenario.hpp"
#include "ibs/sim/scenario.hpp"

namespace ibs::sim {

using AnyScenario = std::variant<Scenario, canlust::Scenario>;

AnyScenario load_any_scenario(const std::string& path);

// The same for a text already read (`ibs run -`: standard input), in the format given; `name`
// stands for the file in messages (`<stdin>:12: ...`) and names the scenario when it has no name.
enum class ScenarioFormat : std::uint8_t { toml, json };
AnyScenario load_any_scenario_text(const std::string& text, ScenarioFormat format, const std::string& name);

}  // namespace ibs::sim
