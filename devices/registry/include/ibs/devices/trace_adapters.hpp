// Replay and decode adapters for every kind of trace the project serves, chosen from the trace's
// `device` and `words` headers through the drive registry (../shared/specs/trace-format.md):
// `words: pd` runs the drive's emulator against its master side, a channel's words (comm, pcp)
// the channel of the drive that has it.
#pragma once

#include <memory>
#include <string>
#include <string_view>

#include "ibs/interbus/replay.hpp"
#include "ibs/interbus/trace.hpp"

namespace ibs::devices {

// The emulated device / master / explainer for a trace. Throw trace::TraceError naming the
// header's line for an unknown drive or target, a combination the project does not serve or a
// refused configuration.
std::unique_ptr<trace::DeviceSide> make_device_side(const trace::Trace& t);
std::unique_ptr<trace::MasterSide> make_master_side(const trace::Trace& t);
std::unique_ptr<trace::Explainer> make_explainer(const trace::Trace& t);

// The trace reader with the registry's vocabulary (registry.hpp): an unknown drive or target is
// refused on its header's line.
trace::Trace parse_trace(std::string_view text, const std::string& file);
trace::Trace load_trace(const std::string& path);

}  // namespace ibs::devices
