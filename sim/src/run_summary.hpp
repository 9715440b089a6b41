// The run summary of `ibs run --json`, one schema for every bus (docs/scenarios.md, "Run summary
// (JSON)"): the INTERBUS simulator (report.cpp) and the CANLust run (sim/canlust) both build it
// here, so that a program reading it finds the same top-level keys and per-device and per-event
// keys whichever bus the scenario has; what only one bus has sits inside those objects.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <utility>

#include "ibs/base/time.hpp"

namespace ibs::sim::detail {

// Raised when a key changes meaning or goes away; new keys keep the version.
inline constexpr int kRunSummaryVersion = 1;

// `bus`: the bus's own counters. `devices`: objects with at least name, kind, state, unit,
// reference, actual, states ([{at_ms, what}]). `events`: objects in time order with at_ms, device
// ("" for the whole bus), type ("parameter", "command", "fault"), what, outcome, ok.
// In this order in the output (ordered_json keeps the order of insertion).
inline nlohmann::ordered_json run_summary(const std::string& scenario, std::string_view protocol, Duration simulated,
                                          double wall_s, unsigned threads, nlohmann::ordered_json bus,
                                          nlohmann::ordered_json devices, nlohmann::ordered_json events) {
  nlohmann::ordered_json j;
  j["version"] = kRunSummaryVersion;
  j["scenario"] = scenario;
  j["protocol"] = protocol;
  j["simulated_s"] = static_cast<double>(simulated.count()) / 1e9;
  j["wall_s"] = wall_s;
  j["threads"] = threads;
  j["bus"] = std::move(bus);
  j["devices"] = std::move(devices);
  j["events"] = std::move(events);
  return j;
}

}  // namespace ibs::sim::detail
