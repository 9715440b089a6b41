// Progress of a long command (`ibs run`, `ibs campaign`) on standard error, for a person at a
// terminal and for a pipe or a CI log alike (issue 27.8):
//  - on a terminal, one line rewritten in place four times a second, cleared at the end;
//  - elsewhere (a pipe, a file), a line every 10 s, so that a log shows the command is alive
//    without filling up; `--progress` makes that every second;
//  - `-q` / `--quiet`: nothing.
// Wall-clock reads only here, in the tool layer; the simulation itself reads no clock.
#pragma once

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>

namespace ibs::cli {

struct ProgressOptions {
  bool quiet = false;   // -q, --quiet
  bool always = false;  // --progress: lines every second, wherever standard error goes
};

class Progress {
 public:
  Progress(const ProgressOptions& o, std::string command)
      : command_(std::move(command)),
        tty_(::isatty(STDERR_FILENO) != 0 && !o.always),
        on_(!o.quiet),
        every_(tty_ ? std::chrono::milliseconds(250) : o.always ? std::chrono::milliseconds(1000)
                                                               : std::chrono::milliseconds(10000)),
        last_(std::chrono::steady_clock::now()) {}
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  ~Progress() { finish(); }

  [[nodiscard]] bool enabled() const { return on_; }

  // `text` ("simulated 12.0 s of 60.0 s (20 %)"), shown when its interval has passed.
  void report(const std::string& text) {
    if (!on_) return;
    const auto now = std::chrono::steady_clock::now();
    if (now - last_ < every_) return;
    last_ = now;
    if (tty_) {
      std::fprintf(stderr, "\r  %-68s", text.c_str());
      shown_ = true;
    } else {
      std::fprintf(stderr, "%s: %s\n", command_.c_str(), text.c_str());
    }
    std::fflush(stderr);
  }

  // Clears a terminal's progress line (once).
  void finish() {
    if (tty_ && shown_) std::fprintf(stderr, "\r%72s\r", "");
    shown_ = false;
  }

 private:
  std::string command_;
  bool tty_;
  bool on_;
  std::chrono::milliseconds every_;
  std::chrono::steady_clock::time_point last_;
  bool shown_ = false;
};

}  // namespace ibs::cli
