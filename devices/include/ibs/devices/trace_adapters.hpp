// Replay and decode adapters for every kind of trace the project serves, chosen from the trace's
// `device` and `words` headers (../shared/specs/trace-format.md).
#pragma once

#include <memory>

#include "ibs/interbus/replay.hpp"
#include "ibs/interbus/time.hpp"
#include "ibs/interbus/trace.hpp"

namespace ibs::devices {

// The emulated device / master / explainer for a trace. Throw trace::TraceError naming the
// header's line for a combination the project does not serve or a refused configuration.
std::unique_ptr<trace::DeviceSide> make_device_side(const trace::Trace& t);
std::unique_ptr<trace::MasterSide> make_master_side(const trace::Trace& t);
std::unique_ptr<trace::Explainer> make_explainer(const trace::Trace& t);

// One trace step of a `words: pd` trace is one processing sample of the device.
Duration pd_step_period(trace::DeviceType d);

}  // namespace ibs::devices
