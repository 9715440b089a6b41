// `ibs campaign [--seed N] [--transactions N] [--json]`: the fault campaign of issue 9
// (sim/campaign.hpp, docs/robustness.md "Fault campaign"). Exit 0 without violations, 1 with.
#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "progress.hpp"
#include "ibs/sim/campaign.hpp"
#include "ibs/tool/format.hpp"

namespace ibs::cli {

namespace {

using tool::fixed;

void print_map(std::ostream& os, const char* title, const std::map<std::string, std::uint64_t>& m) {
  os << title << "\n";
  for (const auto& [k, v] : m) os << "  " << k << ": " << v << "\n";
}

nlohmann::json checks_json(const sim::CheckCounts& c) {
  return {{"store_values", c.store_checks},       {"read_values", c.read_checks},
          {"outcomes", c.outcome_checks},         {"deadlines", c.deadline_checks},
          {"enabled_states", c.state_checks},     {"withdrawal_deadlines", c.stop_checks},
          {"watchdog_trips", c.watchdog_trips},   {"watchdog_outages", c.watchdog_late_checks}};
}

}  // namespace

int campaign(const CampaignOptions& o) {
  sim::CampaignOptions opt;
  opt.seed = o.seed;
  opt.transactions = o.transactions;
  opt.enable_during_download = o.enable_during_download;
  // Progress on standard error (progress.hpp): in place on a terminal, a line every few seconds
  // elsewhere, nothing with -q.
  Progress progress(o.progress, "ibs campaign");
  if (progress.enabled()) {
    opt.progress = [&o, &progress](std::uint64_t done, Time t) {
      progress.report(std::to_string(done) + " / " + std::to_string(o.transactions) + " transactions, " +
                      fixed(to_ms(t) / 1000.0, 0) + " s simulated");
    };
  }
  sim::CampaignResult r;
  try {
    r = sim::run_campaign(opt);
  } catch (const std::invalid_argument& e) {
    std::cerr << "campaign: " << e.what() << "\n";
    return kExitBadInput;
  }
  progress.finish();
  if (o.json) {
    nlohmann::json j;
    j["seed"] = r.seed;
    j["simulated_s"] = to_ms(r.simulated) / 1000.0;
    j["wall_s"] = r.wall_seconds;
    j["cycle_time_ms"] = to_ms(r.cycle_time);
    j["devices"] = r.devices;
    j["transactions"] = {{"total", r.transactions}, {"by_outcome", r.transactions_by}, {"special", r.special}};
    j["state_commands"] = {{"total", r.state_commands}, {"by_command", r.state_commands_by}};
    j["faults"] = r.faults;
    j["checks"] = checks_json(r.checks);
    j["violation_count"] = r.violation_count;
    nlohmann::json v = nlohmann::json::array();
    for (const auto& x : r.violations) {
      v.push_back({{"at_ms", to_ms(x.at)}, {"device", x.device}, {"check", x.check}, {"what", x.what}});
    }
    j["violations"] = v;
    std::cout << j.dump(2) << "\n";
  } else {
    std::ostream& os = std::cout;
    os << "fault campaign, seed " << r.seed << "\n";
    os << "simulated " << fixed(to_ms(r.simulated) / 1000.0, 1) << " s in " << fixed(r.wall_seconds, 1)
       << " s wall time, bus cycle " << fixed(to_ms(r.cycle_time), 3) << " ms\n";
    os << "ring:\n";
    for (const auto& d : r.devices) os << "  " << d << "\n";
    os << "transactions: " << r.transactions << "\n";
    for (const auto& [k, v] : r.transactions_by) os << "  " << k << ": " << v << "\n";
    print_map(os, "special parameter traffic:", r.special);
    os << "state commands: " << r.state_commands << "\n";
    for (const auto& [k, v] : r.state_commands_by) os << "  " << k << ": " << v << "\n";
    print_map(os, "faults (as the simulator recorded them):", r.faults);
    const sim::CheckCounts& c = r.checks;
    os << "checks:\n"
       << "  parameter values compared with the model: " << c.store_checks << "\n"
       << "  read values: " << c.read_checks << "\n"
       << "  outcomes and deadlines: " << c.outcome_checks << "\n"
       << "  ENABLED states: " << c.state_checks << "\n"
       << "  withdrawal (e-stop, block power, other target, fault) deadlines: " << c.stop_checks << "\n"
       << "  watchdog trips timed: " << c.watchdog_trips << ", outages beyond a watchdog's time: "
       << c.watchdog_late_checks << "\n";
    os << "violations: " << r.violation_count << "\n";
    for (const auto& x : r.violations) {
      os << "  " << fixed(to_ms(x.at), 3) << " ms " << x.device << " [" << x.check << "] " << x.what << "\n";
    }
    if (r.violation_count > r.violations.size()) {
      os << "  (" << r.violation_count - r.violations.size() << " more not listed)\n";
    }
  }
  return r.violation_count == 0 ? kExitOk : kExitMismatch;
}

}  // namespace ibs::cli
