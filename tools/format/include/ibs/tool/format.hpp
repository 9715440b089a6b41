// The tool layer's text formatting (issue 27), one module instead of the command line's local
// hex / hex2 / fixed / seconds helpers and its snprintf calls: built on {fmt} (fmt::format, Debian
// libfmt-dev), which a caller may also use directly for a one-off line.
//
// For the command line and the code that prints for it (tools/ibs, sim/canlust) only. The cycle
// path and the installed libraries (ibs::master, ibs::sim, the transports, the floors) do not use
// it: they format with the standard library, so that neither the cycle nor an application linking
// the installed package depends on {fmt} (docs/architecture.md, "Layers"). Configuration and
// report time: these allocate.
#pragma once

#include <fmt/format.h>

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "ibs/base/time.hpp"

namespace ibs::tool {

// `v` in upper-case hex with at least `digits` digits: hex(0x3E8, 4) = "03E8", hex(0x373, 3) = "373".
std::string hex(std::uint64_t v, int digits);
inline std::string hex2(std::uint64_t v) { return hex(v, 2); }
inline std::string hex4(std::uint64_t v) { return hex(v, 4); }

// Bytes in upper-case hex, one space between: "40 02 00 00" (candump's and the byte log's form);
// "" for none.
std::string hex_bytes(std::span<const std::uint8_t> bytes);

// `v` with `decimals` decimals, rounded as printf's %.*f does: fixed(2.5, 3) = "2.500".
std::string fixed(double v, int decimals);
// The same with its unit after a space: fixed(1.5, 3, "s") = "1.500 s", fixed(20.5, 2, "Hz") =
// "20.50 Hz", fixed(50, 1, "%") = "50.0 %".
std::string fixed(double v, int decimals, std::string_view unit);

// A time in seconds with milliseconds: seconds(1234567 us) = "1.235 s" (the events of a run and of
// an emulator's control channel).
std::string seconds(Time t);

}  // namespace ibs::tool
