// Simulated time. No component reads a clock: time is always passed in (design.md, cycle path).
#pragma once

// Every ibs header comes here; a program built with an older standard learns why at once instead of
// from the first C++20 construct. The pkg-config files name the flag (`pkg-config --variable=cxx_std`).
#if !defined(__cplusplus) || __cplusplus < 202002L
#error "ibs needs C++20 or later: compile with -std=c++20 (or newer)"
#endif

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
