// Replay and decode adapters for every kind of trace the project serves, chosen from the trace's
// `device` and `words` headers through the drive registry (../shared/specs/trace-format.md):
// `words: pd` runs the drive's emulator against its master side, a channel's words (comm, pcp)
// the channel of the drive that has it.
#pragma once

#include <memory>
#include <string>
#include <string_view>

#include "ibs/devices/registry.hpp"
#include "ibs/interbus/replay.hpp"
#include "ibs/interbus/trace.hpp"

namespace ibs::devices {

// How every command judges a trace (`ibs replay` with either side, `ibs decode`): the format's
// own rules (trace::validate), the drive and DRIVECOM target the header names, the settings the
// drive takes (supi/ibcnf, watchdog_ms in its range), the words it serves, a request the emulated
// side can carry (`state` in a pd trace, read/write/describe in a channel's), events only where
// the emulated side can act on them (pd traces: the device model), and the rows' word counts.
// Throws trace::TraceError `FILE:LINE` naming the offending line. Only what depends on the side
// a replay emulates stays with it: m2s patterns cannot drive a device (--emulate device), and
// --emulate master needs a `request` (tools/ibs/replay_cmd.cpp).
void validate_trace(const trace::Trace& t);

// The emulated device / master / explainer for a trace; each validates the trace first
// (validate_trace) and throws its TraceError.
std::unique_ptr<trace::DeviceSide> make_device_side(const trace::Trace& t);
std::unique_ptr<trace::MasterSide> make_master_side(const trace::Trace& t);
std::unique_ptr<trace::Explainer> make_explainer(const trace::Trace& t);

// The `setting: NAME VALUE` headers a recording of a device of `kind` writes
// (../shared/specs/trace-format.md, "Headers"): each of its declared settings that has no header of
// its own (as `supi` has) and differs from its default, in the scenario's syntax without quotes
// ("true", "2 s"), and `watchdog_reaction` when the settings give one. The trace validation reads
// them back (an unknown name or a value out of the setting's range is refused on its line).
void write_device_settings(const DriveKind& kind, const DeviceSettings& settings, trace::Header& h);

// The trace reader with the registry's vocabulary (registry.hpp): an unknown drive or target is
// refused on its header's line.
trace::Trace parse_trace(std::string_view text, const std::string& file);
trace::Trace load_trace(const std::string& path);

}  // namespace ibs::devices
