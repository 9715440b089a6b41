// How a device starts a run: the one list the emulators, the simulator and the trace format's
// `init` header share (../shared/specs/trace-format.md). A trace names three of them: `init:
// operational`, `init: power-on` (initialised with the power-on bit still set) and `init: fault`.
#pragma once

#include <cstdint>

namespace ibs {

enum class DeviceStart : std::uint8_t {
  power_on,     // switched on now: initialising (NOT READY, module error on the bus)
  initialised,  // initialisation done, the power-on bit still set in 85-SIOF/SERR
  operational,  // running, 85-SIOF/SERR read and clear
  fault,        // a latched fault whose cause has gone (DRIVECOM FAULT)
};

}  // namespace ibs
