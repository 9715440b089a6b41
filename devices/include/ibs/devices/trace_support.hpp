// Pieces the drives' `words: pd` replay adapters share (../shared/specs/trace-format.md).
#pragma once

#include <optional>

#include "ibs/drivecom/sequencer.hpp"
#include "ibs/interbus/trace.hpp"

namespace ibs::devices {

// The outcome of a `request: state TARGET` as the master's sequencer reports it: ok once the
// target is reached, timeout or nak when it failed, nullopt while it is still on its way.
std::optional<trace::Outcome> trace_outcome(const drivecom::Report& r);

}  // namespace ibs::devices
