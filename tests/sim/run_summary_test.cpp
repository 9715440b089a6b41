// The run summary of `ibs run --json` (docs/scenarios.md, "Run summary (JSON)"): one schema for an
// INTERBUS and a CANLust run, so that a program reading it finds the same keys whichever bus the
// scenario has.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "ibs/sim/canlust_scenario.hpp"
#include "ibs/sim/report.hpp"
#include "ibs/sim/scenario.hpp"
#include "ibs/sim/simulator.hpp"

namespace ibs::sim {
namespace {

std::set<std::string> keys(const nlohmann::json& j) {
  std::set<std::string> k;
  for (const auto& [key, value] : j.items()) k.insert(key);
  return k;
}

nlohmann::json interbus_summary() {
  Simulator simulator(default_scenario());
  simulator.run();
  return nlohmann::json::parse(format_json(simulator.summary()));
}

nlohmann::json canlust_summary() {
  const auto s = canlust::load_scenario(std::string(IBS_SOURCE_DIR) + "/examples/canlust/conveyors.toml");
  return nlohmann::json::parse(canlust::format_json(canlust::run(s)));
}

// What docs/scenarios.md promises of every run summary, whichever the bus.
void expect_schema(const nlohmann::json& j, const std::string& protocol) {
  SCOPED_TRACE(protocol);
  EXPECT_EQ(keys(j), (std::set<std::string>{"version", "scenario", "protocol", "simulated_s", "wall_s", "threads",
                                            "bus", "devices", "events"}));
  EXPECT_EQ(j["version"], 1);
  EXPECT_EQ(j["protocol"], protocol);
  EXPECT_TRUE(j["scenario"].is_string());
  EXPECT_GT(j["simulated_s"].get<double>(), 0.0);
  EXPECT_GT(j["wall_s"].get<double>(), 0.0);
  EXPECT_GE(j["threads"].get<int>(), 1);
  EXPECT_TRUE(j["bus"].is_object());
  ASSERT_TRUE(j["devices"].is_array());
  ASSERT_FALSE(j["devices"].empty());
  for (const auto& d : j["devices"]) {
    for (const char* k : {"name", "kind", "state", "unit", "reference", "actual", "states"}) {
      EXPECT_TRUE(d.contains(k)) << k << " in " << d.dump();
    }
    for (const auto& s : d["states"]) {
      EXPECT_TRUE(s["at_ms"].is_number()) << s.dump();
      EXPECT_TRUE(s["what"].is_string()) << s.dump();
    }
  }
  ASSERT_TRUE(j["events"].is_array());
  ASSERT_FALSE(j["events"].empty());
  double last = 0.0;
  for (const auto& e : j["events"]) {
    for (const char* k : {"at_ms", "device", "type", "what", "outcome", "ok"}) {
      EXPECT_TRUE(e.contains(k)) << k << " in " << e.dump();
    }
    const std::string type = e["type"];
    EXPECT_TRUE(type == "parameter" || type == "command" || type == "fault") << e.dump();
    EXPECT_GE(e["at_ms"].get<double>(), last) << "events in time order: " << e.dump();
    last = e["at_ms"].get<double>();
  }
}

TEST(RunSummary, InterbusAndCanlustShareTheSchema) {
  const nlohmann::json ib = interbus_summary();
  const nlohmann::json cl = canlust_summary();
  expect_schema(ib, "interbus");
  expect_schema(cl, "canlust");
  EXPECT_EQ(keys(ib), keys(cl));

  // The default INTERBUS scenario: 8 s, both drives READY at the end, every transaction done.
  EXPECT_DOUBLE_EQ(ib["simulated_s"].get<double>(), 8.0);
  EXPECT_EQ(ib["devices"][0]["kind"], ib["devices"][0]["name"]);
  for (const auto& d : ib["devices"]) EXPECT_EQ(d["state"], "READY") << d.dump();
  int parameters = 0;
  for (const auto& e : ib["events"]) {
    if (e["type"] != "parameter") continue;
    ++parameters;
    EXPECT_TRUE(e["ok"].get<bool>()) << e.dump();
  }
  EXPECT_EQ(parameters, 8);
  EXPECT_DOUBLE_EQ(ib["bus"]["cycle_time_ms"].get<double>(), 0.726);

  // The CANLust example: 4 s, the right drive's watchdog tripped, the reads and writes answered.
  EXPECT_DOUBLE_EQ(cl["simulated_s"].get<double>(), 4.0);
  EXPECT_EQ(cl["devices"][1]["name"], "right");
  EXPECT_EQ(cl["devices"][1]["kind"], "cda3000");
  EXPECT_EQ(cl["devices"][1]["state"], "FAULT");
  EXPECT_EQ(cl["devices"][1]["unit"], "Hz");
  bool read_cascy = false;
  for (const auto& e : cl["events"]) {
    read_cascy = read_cascy || (e["device"] == "left" && e["what"] == "read 575-CASCY" && e["type"] == "parameter");
  }
  EXPECT_TRUE(read_cascy) << cl["events"].dump(2);
}

}  // namespace
}  // namespace ibs::sim
