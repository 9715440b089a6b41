// Polling a reading, as mbpoll's -1 / -l: `--repeat N` readings (0: until SIGINT or SIGTERM),
// `--interval MS` apart, start to start on the monotonic clock; one line (or JSON object) per
// reading from the command itself, and at the end a summary of what failed on standard error.
// Each reading keeps its own timeouts, so every reading ends; only `--repeat 0` runs until stopped.
#pragma once

#include <poll.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <functional>
#include <ostream>
#include <string>

#include "stop_signals.hpp"

namespace ibs::cli {

struct RepeatOptions {
  unsigned repeat = 1;         // readings; 0: until interrupted
  unsigned interval_ms = 1000;  // from the start of one reading to the start of the next
};

inline void add_repeat_options(CLI::App* cmd, RepeatOptions& r) {
  cmd->add_option("--repeat", r.repeat, "read N times (0: until Ctrl-C), one line or JSON object each (default 1)")
      ->type_name("N");
  cmd->add_option("--interval", r.interval_ms, "with --repeat: MS from one reading's start to the next, 1..3600000 (default 1000)")
      ->type_name("MS")
      ->check(CLI::Range(1U, 3'600'000U));
}

// Runs `once` (which prints its reading and returns its exit code) as `r` says. Bad input
// (`bad_input`) ends at once; otherwise the result is 0 when every reading succeeded, else the
// last failure's code. With more than one reading, `who` and the counts go to `err` at the end:
// "ibs lustbus read: 10 readings, 9 ok, 1 failed"; `failures`, when given, says what failed and is
// added in parentheses when something did: "ibs canlust read: 3 readings, 1 ok, 2 failed (2 timeouts)".
inline int repeat_readings(const RepeatOptions& r, const std::string& who, std::ostream& err, int bad_input,
                           const std::function<int()>& once, const std::function<std::string()>& failures = {}) {
  if (r.repeat == 1) return once();
  StopSignals signals;
  using Clock = std::chrono::steady_clock;
  auto next = Clock::now();
  unsigned done = 0;
  unsigned failed = 0;
  int worst = 0;
  while (r.repeat == 0 || done < r.repeat) {
    const int rc = once();
    ++done;
    if (rc == bad_input) return rc;
    if (rc != 0) {
      ++failed;
      worst = rc;
    }
    if (r.repeat != 0 && done == r.repeat) break;
    next += std::chrono::milliseconds(r.interval_ms);
    // Wait for the next reading's start, or a signal, whichever comes first.
    bool stop = false;
    for (;;) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(next - Clock::now()).count();
      pollfd p{signals.fd(), POLLIN, 0};
      if (left <= 0) {
        stop = ::poll(&p, 1, 0) > 0 && signals.raised();
        break;
      }
      if (::poll(&p, 1, static_cast<int>(left)) > 0 && signals.raised()) {
        stop = true;
        break;
      }
    }
    if (stop) break;
  }
  err << who << ": " << done << (done == 1 ? " reading, " : " readings, ") << (done - failed) << " ok, " << failed
      << " failed";
  if (failed > 0 && failures) err << " (" << failures() << ")";
  err << "\n";
  return worst;
}

}  // namespace ibs::cli
