// The CANLust schema on the document tree the scenario reader builds (scenario_internal.hpp), for
// parse_scenario and for the one entry point of scenario_file.hpp that parses a file once.
#pragma once

#include <string>
#include <string_view>

#include "ibs/devices/canlust_face.hpp"
#include "ibs/sim/canlust_scenario.hpp"
#include "scenario_internal.hpp"

namespace ibs::sim::canlust {

// True when the tree's [bus] says protocol = "canlust".
bool is_canlust_tree(const detail::Node& root);
// Reads and checks the tree as a CANLust scenario; throws sim::ScenarioError naming file:line.
Scenario read_tree(const detail::Node& root, const std::string& file);
// The registry's CANLust face of the drive a [[device]]'s `type` names; throws std::logic_error
// for a type the reader would not have taken.
const devices::CanlustFace& canlust_face(std::string_view kind);

}  // namespace ibs::sim::canlust
