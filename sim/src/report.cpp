#include "ibs/sim/report.hpp"

#include "ibs/base/number_text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "ibs/devices/registry.hpp"
#include "run_summary.hpp"

namespace ibs::sim {

namespace {

__attribute__((format(printf, 1, 2))) std::string printf_string(const char* format, ...) {
  char buf[512];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buf, sizeof buf, format, args);
  va_end(args);
  return buf;
}

std::string ms(Time t) { return printf_string("%.1f ms", to_ms(t)); }

std::string op_text(const TransactionRecord& r) {
  std::string s = std::string(devices::to_string(r.op)) + " " + std::to_string(r.number);
  if (r.op == devices::ParamOp::write) s += " = " + std::to_string(r.value);
  return s;
}

double budget_percent(double ns, Duration budget) { return 100.0 * ns / static_cast<double>(budget.count()); }

// "; 3 cycles over it, the first at 1.234 ms" / "; no cycle over it".
std::string over_text(const TimingStats& t, Duration budget) {
  for (const OverBudget& o : t.over) {
    if (o.budget != budget) continue;
    if (o.cycles == 0) return "; no cycle over it";
    return printf_string("; %llu cycle%s over it, the first at %s", static_cast<unsigned long long>(o.cycles),
                         o.cycles == 1 ? "" : "s", ms(*o.first).c_str());
  }
  return "";
}

nlohmann::ordered_json stats_json(const TimingStats& t) {
  nlohmann::ordered_json j = {{"cycles", t.cycles},         {"median_ns", t.median_ns}, {"p99_ns", t.p99_ns},
                      {"p999_ns", t.p999_ns},       {"max_ns", t.max_ns},       {"worst_cycle", t.worst_cycle},
                      {"worst_at_ms", to_ms(t.worst_at)}};
  nlohmann::ordered_json over = nlohmann::ordered_json::array();
  for (const OverBudget& o : t.over) {
    nlohmann::ordered_json x = {{"budget_ms", to_ms(o.budget)}, {"cycles", o.cycles}};
    if (o.first) x["first_at_ms"] = to_ms(*o.first);
    over.push_back(x);
  }
  j["over_budget"] = over;
  return j;
}

// The processing period of every drive kind the project knows, against which the master's time
// per cycle is set (the MC6000's 1 ms, the VF1000's 8.2 ms), in the registry's order.
struct Budget {
  Duration period;
  std::string period_text;  // "8.2 ms"
  std::string key;          // "budget_8_2ms_median_percent"
  std::string drives;       // "VF1000"
  int decimals;             // at the median; one fewer at the max
};

std::vector<Budget> budgets() {
  std::vector<Budget> out;
  for (const devices::DriveKind& k : devices::drive_kinds()) {
    const devices::DriveFacts& f = k->facts();
    const auto same = std::find_if(out.begin(), out.end(), [&](const Budget& b) { return b.period == f.sample_period; });
    if (same != out.end()) {
      same->drives += "/" + std::string(f.title);
      continue;
    }
    std::string number = printf_string("%g", to_ms(f.sample_period));
    std::string key = number;
    std::replace(key.begin(), key.end(), '.', '_');
    // One more decimal for every tenfold period: the same significant digits for each budget.
    const int decimals = 4 + static_cast<int>(std::lround(std::log10(to_ms(f.sample_period))));
    out.push_back({f.sample_period, number + " ms", "budget_" + key + "ms_median_percent", std::string(f.title),
                   decimals});
  }
  return out;
}

}  // namespace

std::string format_text(const Summary& s) {
  std::string o;
  const double sim_s = static_cast<double>(s.simulated.count()) / 1e9;
  if (s.headline.empty()) {
    o += printf_string("ibs run: scenario \"%s\", %.3f s simulated in %.3f s of wall time on %u thread%s (%.0fx real time)\n",
                       s.scenario.c_str(), sim_s, s.wall_seconds, s.threads, s.threads == 1 ? "" : "s",
                       s.wall_seconds > 0 ? sim_s / s.wall_seconds : 0.0);
  } else {
    o += s.headline + "\n";
  }
  o += printf_string("bus: %zu device(s), cycle time %.3f ms (%s)\n", s.devices.size(), to_ms(s.cycle_time),
                     s.cycle_time_basis.c_str());
  o += printf_string("     %llu cycles, %llu with valid data\n", static_cast<unsigned long long>(s.cycles),
                     static_cast<unsigned long long>(s.valid_cycles));
  for (const DeviceReport& d : s.devices) {
    o += "\n" + d.name + " (" + d.id_code + ")\n";
    for (const StateRecord& r : d.states) o += printf_string("  %10s  ", ms(r.at).c_str()) + r.what + "\n";
    for (const std::string& e : d.errors) o += "  error: " + e + "\n";
    for (const FailureRecord& f : d.failures) o += "  failure at " + ms(f.at) + ": " + f.what + "\n";
    o += printf_string("  final: %s, reference %s %s, actual %s %s, %llu samples\n", d.final_state.c_str(),
                       quantity_text(d.final_reference, d.unit).c_str(), d.unit.c_str(),
                       quantity_text(d.final_actual, d.unit).c_str(), d.unit.c_str(),
                       static_cast<unsigned long long>(d.samples));
  }
  o += "\nparameter transactions\n";
  if (s.transactions.empty()) o += "  none\n";
  for (const TransactionRecord& r : s.transactions) {
    const std::string dur = r.finished ? printf_string("%.1f ms", to_ms(*r.finished - r.submitted)) : "-";
    o += printf_string("  %10s  %-10s %-14s %9s  ", ms(r.submitted).c_str(), r.device.c_str(), op_text(r).c_str(),
                       dur.c_str()) +
         r.result + "\n";
  }
  o += "\nfaults\n";
  if (s.faults.empty()) o += "  none\n";
  for (const FaultRecord& f : s.faults) {
    o += printf_string("  %10s  %-10s %-15s ", ms(f.at).c_str(), f.device.empty() ? "bus" : f.device.c_str(),
                       f.kind.c_str()) +
         f.detail + "\n";
  }
  if (!s.control.empty()) {
    // The control channel's entries (`ibs run --control`), as applied, like timeline entries.
    o += "\ncontrol entries\n";
    for (const ControlRecord& c : s.control) {
      o += (c.client == 0 ? printf_string("  %10s  line %-5zu ", ms(c.at).c_str(), c.line)
                          : printf_string("  %10s  client %u line %-5zu ", ms(c.at).c_str(), c.client, c.line)) +
           c.entry + "\n";
    }
  }
  if (s.master.cycles > 0) {
    o += printf_string("\nmaster processing per cycle (%zu driver(s)): median %.0f ns, p99 %.0f ns, p99.9 %.0f ns, "
                       "max %.0f ns (cycle %llu at %s) over %llu cycles\n",
                       s.devices.size(), s.master.median_ns, s.master.p99_ns, s.master.p999_ns, s.master.max_ns,
                       static_cast<unsigned long long>(s.master.worst_cycle), ms(s.master.worst_at).c_str(),
                       static_cast<unsigned long long>(s.master.cycles));
    for (const Budget& b : budgets()) {
      o += printf_string("  %s budget (%s processing): %.*f %% at the median, %.*f %% at the max",
                         b.period_text.c_str(), b.drives.c_str(), b.decimals,
                         budget_percent(s.master.median_ns, b.period), b.decimals - 1,
                         budget_percent(s.master.max_ns, b.period));
      o += over_text(s.master, b.period) + "\n";
    }
  }
  if (s.realtime) {
    const RealtimeStats& r = *s.realtime;
    o += printf_string("\nreal time (cycle %s): %s, %s\n", format_time(r.cycle_time).c_str(),
                       r.rt_priority > 0 ? printf_string("SCHED_FIFO priority %d", r.rt_priority).c_str()
                                         : "normal priority",
                       r.memory_locked ? "memory locked" : "memory not locked");
    for (const std::string& n : r.notes) o += "  note: " + n + "\n";
    o += printf_string("  wake-up latency: median %.0f ns, p99 %.0f ns, p99.9 %.0f ns, max %.0f ns (cycle %llu at %s)\n",
                       r.wake.median_ns, r.wake.p99_ns, r.wake.p999_ns, r.wake.max_ns,
                       static_cast<unsigned long long>(r.wake.worst_cycle), ms(r.wake.worst_at).c_str());
    o += printf_string("  overruns (work ended after the next deadline): %llu of %llu cycles",
                       static_cast<unsigned long long>(r.overruns), static_cast<unsigned long long>(r.wake.cycles));
    if (r.worst_overrun) {
      o += printf_string(", first at %s, worst at %s by %.3f ms", ms(*r.first_overrun).c_str(),
                         ms(*r.worst_overrun).c_str(), to_ms(r.worst_overrun_by));
    }
    o += "\n";
  }
  return o;
}

std::string format_json(const Summary& s) {
  using json = nlohmann::ordered_json;
  json bus = {{"cycle_time_ms", to_ms(s.cycle_time)},
              {"cycle_time_basis", s.cycle_time_basis},
              {"cycles", s.cycles},
              {"valid_cycles", s.valid_cycles}};
  bus["master"] = stats_json(s.master);
  for (const Budget& b : budgets()) bus["master"][b.key] = budget_percent(s.master.median_ns, b.period);
  if (s.realtime) {
    const RealtimeStats& r = *s.realtime;
    json rt = {{"cycle_time_ms", to_ms(r.cycle_time)},
                         {"rt_priority", r.rt_priority},
                         {"memory_locked", r.memory_locked},
                         {"notes", r.notes},
                         {"wake_latency", stats_json(r.wake)},
                         {"overruns", r.overruns}};
    if (r.first_overrun) rt["first_overrun_at_ms"] = to_ms(*r.first_overrun);
    if (r.worst_overrun) {
      rt["worst_overrun_at_ms"] = to_ms(*r.worst_overrun);
      rt["worst_overrun_by_ms"] = to_ms(r.worst_overrun_by);
    }
    bus["realtime"] = rt;
  }
  json devices = json::array();
  for (const DeviceReport& d : s.devices) {
    json states = json::array();
    for (const StateRecord& r : d.states) states.push_back({{"at_ms", to_ms(r.at)}, {"what", r.what}});
    json failures = json::array();
    for (const FailureRecord& f : d.failures) {
      failures.push_back({{"at_ms", to_ms(f.at)}, {"failure", f.failure}, {"what", f.what}});
    }
    devices.push_back({{"name", d.name},
                       {"kind", d.kind},
                       {"state", d.final_state},
                       {"unit", d.unit},
                       {"reference", d.final_reference},
                       {"actual", d.final_actual},
                       {"states", states},
                       {"id_code", d.id_code},
                       {"errors", d.errors},
                       {"failures", failures},
                       {"samples", d.samples}});
  }
  // The parameter transactions and the faults, in time order (a transaction at its submission).
  std::vector<std::pair<Time, json>> timed;
  for (const TransactionRecord& r : s.transactions) {
    const bool ok = r.kind == devices::ParamKind::value || r.kind == devices::ParamKind::written ||
                    r.kind == devices::ParamKind::description;
    json t = {{"at_ms", to_ms(r.submitted)},
              {"device", r.device},
              {"type", "parameter"},
              {"what", op_text(r)},
              {"outcome", r.result},
              {"ok", ok},
              {"op", devices::to_string(r.op)},
              {"parameter", r.number},
              {"result", devices::to_string(r.kind)}};
    if (r.op == devices::ParamOp::write) t["value"] = r.value;
    if (r.kind == devices::ParamKind::value) t["value_read"] = r.result_value;
    if (r.answered) t["answered_ms"] = to_ms(*r.answered);
    if (r.finished) {
      t["finished_ms"] = to_ms(*r.finished);
      t["duration_ms"] = to_ms(*r.finished - r.submitted);
    }
    if (r.source_line != 0) t["scenario_line"] = r.source_line;
    timed.emplace_back(r.submitted, std::move(t));
  }
  for (const FaultRecord& f : s.faults) {
    timed.emplace_back(f.at, json{{"at_ms", to_ms(f.at)},
                                  {"device", f.device},
                                  {"type", "fault"},
                                  {"what", f.kind},
                                  {"outcome", f.detail},
                                  {"ok", true}});
  }
  for (const ControlRecord& c : s.control) {
    json j{{"at_ms", to_ms(c.at)}, {"device", c.device}, {"type", "control"}, {"what", c.entry},
           {"outcome", "applied"}, {"ok", true},   {"line", c.line}};
    if (c.client != 0) j["client"] = c.client;
    timed.emplace_back(c.at, std::move(j));
  }
  std::stable_sort(timed.begin(), timed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  json events = json::array();
  for (auto& [at, e] : timed) events.push_back(std::move(e));
  return detail::run_summary(s.scenario, "interbus", s.simulated, s.wall_seconds, s.threads, std::move(bus),
                             std::move(devices), std::move(events))
             .dump(2) +
         "\n";
}

}  // namespace ibs::sim
