// A fixed team of threads for work that splits into independent parts: run() executes part 0 on
// the calling thread and parts 1..n-1 on the team, and returns once every part is done. The
// simulator uses it to step the devices between two cycle ends (they meet only at the bus
// exchange). Between runs the threads spin for a short while, then sleep; run() itself neither
// allocates nor locks.
#pragma once

#include <atomic>
#include <cstdint>
#include <exception>
#include <functional>
#include <thread>
#include <vector>

namespace ibs::sim {

class ForkJoin {
 public:
  // `parts` >= 1; parts - 1 threads are started. `job(part)` must be safe to run concurrently
  // for different parts.
  ForkJoin(unsigned parts, std::function<void(unsigned part)> job);
  ~ForkJoin();
  ForkJoin(const ForkJoin&) = delete;
  ForkJoin& operator=(const ForkJoin&) = delete;
  ForkJoin(ForkJoin&&) = delete;  // the threads hold `this`
  ForkJoin& operator=(ForkJoin&&) = delete;

  // Runs every part once. An exception from a part is rethrown here (the first part's first).
  void run();
  [[nodiscard]] unsigned parts() const { return static_cast<unsigned>(threads_.size()) + 1; }

 private:
  void loop(unsigned part);

  std::function<void(unsigned)> job_;
  std::atomic<std::uint64_t> generation_{0};  // one more per run()
  std::atomic<unsigned> pending_{0};          // parts on the team not yet done in this run
  std::atomic<bool> stop_{false};
  std::vector<std::exception_ptr> errors_;    // per part, written by that part only
  std::vector<std::thread> threads_;
};

}  // namespace ibs::sim
