// The summary of a simulated run, as text for a person and as JSON for a program.
#pragma once

#include <string>

#include "ibs/sim/simulator.hpp"

namespace ibs::sim {

std::string format_text(const Summary& s);
std::string format_json(const Summary& s);

}  // namespace ibs::sim
