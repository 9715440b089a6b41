// `ibs master --board` against `ibs run` (docs/board.md, "The same scenario on both"): the master
// side of a scenario run against the virtual board that runs the same file's ring and faults
// (IBS_DDI_SCENARIO, IBS_DDI_MASTER_COMMANDS=ibs-master) reaches the same states in the same
// order and gets every transaction's value as the simulator's run -- for the examples' scenarios,
// and with the master's loop running at a third of and three times the board's cycle time
// (a loop that reads the same bus cycle again, or misses cycles).
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "ibs/sim/simulator.hpp"
#include "rig.hpp"

namespace ibs::test {
namespace {

std::string example(const std::string& name) { return std::string(IBS_SOURCE_DIR) + "/examples/" + name; }

// What the two runs must agree on: each device's states in order (a reached reference without
// the actual value it was seen at, which a cycle's difference moves), and each transaction.
struct Comparable {
  std::vector<std::vector<std::string>> states;
  std::vector<std::string> transactions;
};

Comparable comparable(const sim::Summary& s) {
  Comparable c;
  for (const sim::DeviceReport& d : s.devices) {
    std::vector<std::string> states;
    for (const sim::StateRecord& r : d.states) {
      const auto actual = r.what.find(" (actual ");
      states.push_back(r.what.rfind("reference ", 0) == 0 && actual != std::string::npos ? r.what.substr(0, actual)
                                                                                         : r.what);
    }
    c.states.push_back(states);
  }
  for (const sim::TransactionRecord& t : s.transactions) {
    c.transactions.push_back(t.device + " " + std::string(devices::to_string(t.op)) + " " + std::to_string(t.number) +
                             " = " + std::to_string(t.value) + ": " + std::string(devices::to_string(t.kind)) + " " +
                             std::to_string(t.result_value) + " " + t.result);
  }
  return c;
}

sim::Summary simulated(const sim::Scenario& s) {
  sim::Simulator sim(s);
  sim::SimOptions o;
  o.measure_master_time = false;
  sim.run(o);
  return sim.summary();
}

class Compare : public ::testing::Test {
 protected:
  void SetUp() override {
    setenv("IBS_DDI_MODE", "stepped", 1);
    setenv("IBS_DDI_MASTER_COMMANDS", "ibs-master", 1);
    unsetenv("IBS_DDI_RT_PRIORITY");
    shim::reset();
  }
  void TearDown() override {
    shim::reset();
    unsetenv("IBS_DDI_SCENARIO");
    unsetenv("IBS_DDI_MASTER_COMMANDS");
  }
  // The master side of `path` against the virtual board running the same file.
  static board::RunResult on_board(const std::string& path, Duration period = Duration::zero(),
                                   std::optional<Duration> duration = std::nullopt) {
    setenv("IBS_DDI_SCENARIO", path.c_str(), 1);
    board::RunOptions o;
    o.clock = board::Clock::stepped;
    o.period = period;
    o.duration = duration;
    return board::run(sim::load_scenario(path), o);
  }
  static void expect_same(const Comparable& sim, const Comparable& board) {
    ASSERT_EQ(sim.states.size(), board.states.size());
    for (std::size_t i = 0; i < sim.states.size(); ++i) {
      EXPECT_EQ(sim.states[i], board.states[i]) << "device " << i;
    }
    EXPECT_EQ(sim.transactions, board.transactions);
  }
};

TEST_F(Compare, TheDefaultScenarioAgreesWithIbsRun) {
  const std::string path = example("default.toml");
  const sim::Summary sim = simulated(sim::load_scenario(path));
  const board::RunResult b = on_board(path);
  ASSERT_TRUE(b.started) << b.error.message;
  EXPECT_FALSE(b.error) << b.error.message;
  expect_same(comparable(sim), comparable(b.summary));
  ASSERT_EQ(b.summary.transactions.size(), 8U);  // every one answered, as on the simulator
  EXPECT_EQ(b.summary.devices[0].final_state, "READY");
  EXPECT_TRUE(b.shutdown.drives_safe);
  EXPECT_FALSE(b.shutdown.error) << b.shutdown.error.message;
}

TEST_F(Compare, TheFaultsScenarioAgreesWithIbsRunAndTheBoardSaysWhatItSaw) {
  const std::string path = example("faults.toml");
  const sim::Summary sim = simulated(sim::load_scenario(path));
  const board::RunResult b = on_board(path);
  ASSERT_TRUE(b.started) << b.error.message;
  EXPECT_FALSE(b.error) << b.error.message;
  expect_same(comparable(sim), comparable(b.summary));
  // The drives' faults reach the master through the status words (the servo's FAULT, above) and
  // the diagnostics: the board's bus errors, the fan initialising after its power cycle and the
  // pump lost as peripheral faults, and the master's own restart.
  const auto has = [&](const std::string& device, const std::string& kind) {
    for (const sim::FaultRecord& f : b.summary.faults) {
      if (f.device == device && f.kind == kind) return true;
    }
    return false;
  };
  EXPECT_TRUE(has("", "bus-error"));
  EXPECT_TRUE(has("", "bus-ok"));
  EXPECT_TRUE(has("fan", "peripheral-fault"));
  EXPECT_TRUE(has("pump", "peripheral-fault"));
  EXPECT_TRUE(has("pump", "peripheral-ok"));
  EXPECT_TRUE(has("", "master-restart"));
}

// ---------------------------------------------------------------------------------------------
// Asynchronous loops: the board cycles on its own clock. Stepped here, so that the run is the same
// on any machine: the wrapped ReadWriteData runs the board's cycles at the rate a test wants.

TEST_F(Compare, ALoopAThirdOfTheBoardsCycleAgreesWithIbsRun) {
  const std::string path = example("default.toml");
  const sim::Summary sim = simulated(sim::load_scenario(path));
  master_three_times_as_fast();
  const board::RunResult b = on_board(path, 242us);  // 726 us / 3
  ASSERT_TRUE(b.started) << b.error.message;
  EXPECT_FALSE(b.error) << b.error.message;
  expect_same(comparable(sim), comparable(b.summary));
  EXPECT_GT(b.summary.cycles, 3 * 10000U);
}

TEST_F(Compare, ALoopThreeTimesTheBoardsCycleAgreesWithIbsRun) {
  const std::string path = example("default.toml");
  const sim::Summary sim = simulated(sim::load_scenario(path));
  master_three_times_as_slow();
  const board::RunResult b = on_board(path, 2178us);  // 3 x 726 us
  ASSERT_TRUE(b.started) << b.error.message;
  EXPECT_FALSE(b.error) << b.error.message;
  expect_same(comparable(sim), comparable(b.summary));
  EXPECT_LT(b.summary.cycles, 4000U);
}

}  // namespace
}  // namespace ibs::test
