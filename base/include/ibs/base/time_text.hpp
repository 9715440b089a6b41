// Times in files: a decimal number, optional spaces and a unit (ns, us, ms, s), e.g. "6 s",
// "250 ms", "8.2 ms"; a whole number of nanoseconds, 0 .. 24 h. Scenario files and the trace
// header `step-time` read them with the same rules. Configuration-time work (it allocates and
// throws); not in the embedded build.
#pragma once

#include "ibs/base/build.hpp"
#if IBS_EMBEDDED
#error "time texts are read from files, which the embedded build does not read (docs/embedding.md)"
#endif

#include <string>
#include <string_view>

#include "ibs/base/time.hpp"

namespace ibs {

// Throws std::invalid_argument saying what is wrong.
Duration parse_time(std::string_view text);
// The largest unit that keeps the number at least 1 ("1.5 s", "8.2 ms", "726 us", "0 s"), which
// parse_time reads back exactly.
std::string format_time(Duration d);

}  // namespace ibs
