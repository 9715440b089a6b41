// `ibs run --realtime --stats-every TIME` (docs/robustness.md, "Soak"): every TIME one line
// `ibs-stats: {JSON}` on standard error with what a long run is watched by -- the wake-up latency
// and the overruns of the cycles since the last line, the bus's cycles, the summary's faults,
// errors and transactions so far, the control channel's counters and every served drive's and
// controller's counters of the test bench. Formed in a fixed buffer and written with one write():
// it runs on the simulator's thread between two deadlines and allocates nothing.
#pragma once

#include <optional>
#include <string>

#include "bench.hpp"
#include "ibs/base/time.hpp"
#include "ibs/control/channel.hpp"
#include "ibs/sim/realtime.hpp"
#include "ibs/sim/simulator.hpp"

namespace ibs::cli {

// The interval of `--stats-every TEXT`, or the refusal's words.
struct StatsEvery {
  Duration every{0};
  std::string error;
};
StatsEvery parse_stats_every(const std::string& text);

// Writes the line for `iv` to standard error.
void write_stats_line(const sim::RealtimeInterval& iv, sim::Simulator& simulator, const control::Channel* control,
                      const Bench* bench);

}  // namespace ibs::cli
