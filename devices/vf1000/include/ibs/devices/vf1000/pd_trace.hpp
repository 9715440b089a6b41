// `words: pd` traces of the VF1000: one row is one 8.2 ms inverter sample of the three words
// (control/status, reference/actual, communication word); ../shared/specs/trace-format.md.
#pragma once

#include <memory>

#include "ibs/interbus/replay.hpp"

namespace ibs::devices::vf1000 {

// The master: the DRIVECOM sequencer computes bits 0-3 and 7; the ramp and direction bits and
// the reference come from the file.
std::unique_ptr<trace::MasterSide> make_pd_master(Duration step);
std::unique_ptr<trace::Explainer> make_pd_explainer();

}  // namespace ibs::devices::vf1000
