// Simulated time. No component reads a clock: time is always passed in (design.md, cycle path).
#pragma once

#include <chrono>
#include <cstdint>

namespace ibs {

// A span of simulated time in integer nanoseconds.
using Duration = std::chrono::nanoseconds;
// A point in simulated time: nanoseconds since the start of a run.
using Time = std::chrono::nanoseconds;

using namespace std::chrono_literals;

// Milliseconds as a double, for reports.
constexpr double to_ms(Duration d) { return static_cast<double>(d.count()) / 1e6; }

}  // namespace ibs
