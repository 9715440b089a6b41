// One entry point for `ibs run`'s scenario files, whichever bus they describe (docs/scenarios.md):
// the file is read and parsed once into the document tree both schemas share (TOML or JSON by the
// extension, every key and value with its line), and its [bus] decides the schema that reads the
// tree: `protocol = "canlust"` the CANLust one (canlust_scenario.hpp), no protocol the INTERBUS one
// (scenario.hpp). Every error is a sim::ScenarioError naming file:line, as either reader's own.
#pragma once

#include <string>
#include <variant>

#include "ibs/sim/canlust_scenario.hpp"
#include "ibs/sim/scenario.hpp"

namespace ibs::sim {

using AnyScenario = std::variant<Scenario, canlust::Scenario>;

AnyScenario load_any_scenario(const std::string& path);

}  // namespace ibs::sim
