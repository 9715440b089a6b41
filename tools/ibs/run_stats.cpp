#include "run_stats.hpp"

#include <unistd.h>

#include <cstdarg>
#include <cstdio>
#include <stdexcept>

#include "ibs/base/time_text.hpp"

namespace ibs::cli {

namespace {

// Appends to a fixed buffer; what does not fit is cut (the line stays one line).
class Line {
 public:
  void add(const char* format, ...) __attribute__((format(printf, 2, 3))) {
    if (used_ >= sizeof buf_) return;
    va_list args;
    va_start(args, format);
    const int n = std::vsnprintf(buf_ + used_, sizeof buf_ - used_, format, args);
    va_end(args);
    if (n > 0) used_ = std::min(sizeof buf_ - 1, used_ + static_cast<std::size_t>(n));
  }
  // A name as a JSON string's characters (the scenario's names are plain; anything else is '?').
  void name(std::string_view s) {
    for (const char c : s) add("%c", (c == '"' || c == '\\' || static_cast<unsigned char>(c) < 0x20) ? '?' : c);
  }
  void write_out() {
    if (used_ >= sizeof buf_ - 1) used_ = sizeof buf_ - 2;
    buf_[used_++] = '\n';
    std::size_t at = 0;
    while (at < used_) {
      const ssize_t n = ::write(STDERR_FILENO, buf_ + at, used_ - at);
      if (n <= 0) return;
      at += static_cast<std::size_t>(n);
    }
  }

 private:
  char buf_[8192];
  std::size_t used_ = 0;
};

}  // namespace

StatsEvery parse_stats_every(const std::string& text) {
  StatsEvery s;
  try {
    s.every = parse_time(text);
  } catch (const std::invalid_argument& e) {
    s.error = "--stats-every " + text + ": " + e.what();
    return s;
  }
  if (s.every < std::chrono::milliseconds(100)) s.error = "--stats-every " + text + ": give at least 100 ms";
  return s;
}

void write_stats_line(const sim::RealtimeInterval& iv, sim::Simulator& simulator, const control::Channel* control,
                      const Bench* bench) {
  const sim::Summary& s = simulator.summary();
  std::size_t errors = 0;
  std::size_t failures = 0;
  for (const sim::DeviceReport& d : s.devices) {
    errors += d.errors.size();
    failures += d.failures.size();
  }
  Line l;
  l.add("ibs-stats: {\"t_s\":%.3f,\"last\":%s,\"cycles\":%llu,\"overruns\":%llu,", to_ms(iv.now) / 1000.0,
        iv.last ? "true" : "false", static_cast<unsigned long long>(iv.cycles),
        static_cast<unsigned long long>(iv.overruns));
  l.add("\"wake_ns\":{\"p50\":%lld,\"p99\":%lld,\"p999\":%lld,\"max\":%lld},", static_cast<long long>(iv.wake_p50_ns),
        static_cast<long long>(iv.wake_p99_ns), static_cast<long long>(iv.wake_p999_ns),
        static_cast<long long>(iv.wake_max_ns));
  l.add("\"bus\":{\"cycles\":%llu,\"valid_cycles\":%llu},\"faults\":%zu,\"errors\":%zu,\"failures\":%zu,"
        "\"transactions\":%zu,\"control_entries\":%zu",
        static_cast<unsigned long long>(s.cycles), static_cast<unsigned long long>(s.valid_cycles), s.faults.size(),
        errors, failures, s.transactions.size(), s.control.size());
  if (control != nullptr) {
    const control::Counters& c = control->counters();
    l.add(",\"control\":{\"clients\":%zu,\"accepted\":%llu,\"refused\":%llu,\"closed\":%llu,\"lines\":%llu,"
          "\"overlong\":%llu,\"bytes\":%llu}",
          control->clients(), static_cast<unsigned long long>(c.accepted), static_cast<unsigned long long>(c.refused),
          static_cast<unsigned long long>(c.closed), static_cast<unsigned long long>(c.lines),
          static_cast<unsigned long long>(c.overlong), static_cast<unsigned long long>(c.bytes));
  }
  if (bench != nullptr) {
    l.add(",\"bench\":[");
    for (std::size_t i = 0; i < bench->served(); ++i) {
      const Bench::Counters c = bench->counters(i);
      l.add("%s{\"name\":\"", i == 0 ? "" : ",");
      l.name(c.name);
      l.add("\",\"line\":\"%.*s\",\"address\":%d,\"telegrams\":%llu,\"answers\":%llu,\"errors\":%llu,\"dropped\":%llu}",
            static_cast<int>(c.line.size()), c.line.data(), c.address, static_cast<unsigned long long>(c.telegrams),
            static_cast<unsigned long long>(c.answers), static_cast<unsigned long long>(c.errors),
            static_cast<unsigned long long>(c.dropped));
    }
    l.add("]");
  }
  l.add("}");
  l.write_out();
}

}  // namespace ibs::cli
