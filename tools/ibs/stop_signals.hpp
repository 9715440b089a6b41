// SIGINT and SIGTERM as a descriptor, blocked for the process while it lives (no global flag):
// the serving loops of `ibs dfs1 emulate` and `ibs canlust emulate|monitor` ask raised() between
// reads and return, so that the command exits 0.
#pragma once

#include <signal.h>
#include <sys/signalfd.h>
#include <unistd.h>

#include <stdexcept>

namespace ibs::cli {

class StopSignals {
 public:
  StopSignals() {
    sigemptyset(&mask_);
    sigaddset(&mask_, SIGINT);
    sigaddset(&mask_, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &mask_, &old_);
    fd_ = signalfd(-1, &mask_, SFD_NONBLOCK | SFD_CLOEXEC);
    if (fd_ < 0) throw std::runtime_error("signalfd failed");
  }
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;
  ~StopSignals() {
    ::close(fd_);
    pthread_sigmask(SIG_SETMASK, &old_, nullptr);
  }
  // Readable when a signal is pending: poll it to wait for a time or a signal, whichever first.
  [[nodiscard]] int fd() const { return fd_; }
  // Takes the signal (so that unblocking it later does not deliver it again).
  bool raised() {
    signalfd_siginfo info{};
    return ::read(fd_, &info, sizeof info) == static_cast<ssize_t>(sizeof info);
  }

 private:
  sigset_t mask_{};
  sigset_t old_{};
  int fd_ = -1;
};

}  // namespace ibs::cli
