#include "ibs/sim/fork_join.hpp"

#include <utility>

namespace ibs::sim {

namespace {

// A wait of a few microseconds is the common case (the other side is finishing a bus cycle), so
// both sides spin briefly, then yield the processor (the other side may be waiting for it: more
// threads than free cores), and only then ask the kernel to put them to sleep.
constexpr int kSpins = 32;
constexpr int kYields = 256;

inline void relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#endif
}

// Waits until `a` no longer holds `value`.
template <class T>
void wait_while(const std::atomic<T>& a, T value) {
  for (int i = 0; i < kSpins; ++i) {
    if (a.load(std::memory_order_acquire) != value) return;
    relax();
  }
  for (int i = 0; i < kYields; ++i) {
    if (a.load(std::memory_order_acquire) != value) return;
    std::this_thread::yield();
  }
  while (a.load(std::memory_order_acquire) == value) a.wait(value, std::memory_order_acquire);
}

}  // namespace

ForkJoin::ForkJoin(unsigned parts, std::function<void(unsigned part)> job)
    : job_(std::move(job)), errors_(parts == 0 ? 1 : parts) {
  threads_.reserve(errors_.size() - 1);
  for (unsigned p = 1; p < errors_.size(); ++p) threads_.emplace_back([this, p] { loop(p); });
}

ForkJoin::~ForkJoin() {
  stop_.store(true, std::memory_order_relaxed);
  generation_.fetch_add(1, std::memory_order_release);
  generation_.notify_all();
  for (auto& t : threads_) t.join();
}

void ForkJoin::run() {
  if (threads_.empty()) {
    job_(0);
    return;
  }
  pending_.store(static_cast<unsigned>(threads_.size()), std::memory_order_relaxed);
  generation_.fetch_add(1, std::memory_order_release);
  generation_.notify_all();
  try {
    job_(0);
  } catch (...) {
    errors_[0] = std::current_exception();
  }
  for (unsigned left = pending_.load(std::memory_order_acquire); left != 0;
       left = pending_.load(std::memory_order_acquire)) {
    wait_while(pending_, left);
  }
  std::exception_ptr first;
  for (auto& e : errors_) {
    if (e && !first) first = e;
    e = nullptr;
  }
  if (first) std::rethrow_exception(first);
}

void ForkJoin::loop(unsigned part) {
  std::uint64_t seen = 0;
  while (true) {
    wait_while(generation_, seen);
    seen = generation_.load(std::memory_order_acquire);
    if (stop_.load(std::memory_order_relaxed)) return;
    try {
      job_(part);
    } catch (...) {
      errors_[part] = std::current_exception();
    }
    if (pending_.fetch_sub(1, std::memory_order_acq_rel) == 1) pending_.notify_one();
  }
}

}  // namespace ibs::sim
