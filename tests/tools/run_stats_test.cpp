// `ibs run --realtime --stats-every TIME` (docs/robustness.md, "Soak"): one line `ibs-stats: {JSON}`
// an interval on standard error, with the interval's wake-up latency and overruns and the run's
// counters so far; refused without --realtime, with a time that is none, and for a CANLust run.
#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "../support/run_shell.hpp"

namespace {

using ibs::test::run_shell;

std::string temp(const std::string& name) {
  return ::testing::TempDir() + "ibs_stats_" + std::to_string(::getpid()) + "_" + name;
}

TEST(RunStats, OneLineAnIntervalWithTheRunsCounters) {
  const std::string scenario = temp("stats.toml");
  std::ofstream(scenario) << "duration = \"1 s\"\n[[device]]\nname = \"servo\"\ntype = \"mc6000\"\n"
                             "[[timeline]]\nat = \"0 s\"\ndevice = \"servo\"\nstate = \"enabled\"\n"
                             "[[timeline]]\nat = \"100 ms\"\ndevice = \"servo\"\nread = 85\n";
  const std::string err = temp("stats.err");
  const auto r = run_shell(std::string(IBS_CLI) + " run " + scenario + " --realtime --stats-every '250 ms' -q 2> " + err);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  std::ifstream in(err);
  std::vector<nlohmann::json> lines;
  for (std::string line; std::getline(in, line);) {
    ASSERT_EQ(line.rfind("ibs-stats: ", 0), 0U) << line;
    lines.push_back(nlohmann::json::parse(line.substr(11)));
  }
  ASSERT_GE(lines.size(), 4U);  // at 250, 500, 750 ms and the last cycles up to 1 s
  ASSERT_LE(lines.size(), 5U);
  std::uint64_t cycles = 0;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const nlohmann::json& j = lines[i];
    if (i + 1 < lines.size()) {
      EXPECT_GE(j["t_s"].get<double>(), 0.25 * static_cast<double>(i + 1) - 1e-9);
    }
    cycles += j["cycles"].get<std::uint64_t>();
    EXPECT_EQ(j["bus"]["cycles"].get<std::uint64_t>(), cycles) << "the interval's cycles add up to the bus's";
    EXPECT_EQ(j["bus"]["valid_cycles"], j["bus"]["cycles"]);
    EXPECT_LE(j["wake_ns"]["p50"].get<std::int64_t>(), j["wake_ns"]["p99"].get<std::int64_t>());
    EXPECT_LE(j["wake_ns"]["p99"].get<std::int64_t>(), j["wake_ns"]["max"].get<std::int64_t>());
    EXPECT_TRUE(j.contains("overruns"));
    EXPECT_EQ(j["last"], i + 1 == lines.size()) << "the last line is the end's";
    EXPECT_FALSE(j.contains("control")) << "no control channel";
    EXPECT_FALSE(j.contains("bench")) << "no test bench";
  }
  EXPECT_EQ(lines.back()["transactions"], 1) << "the read of 85, done by then";
  ::unlink(scenario.c_str());
  ::unlink(err.c_str());
}

TEST(RunStats, RefusedWithoutRealtimeWithABadTimeAndForCanlust) {
  auto r = run_shell(std::string(IBS_CLI) + " run --stats-every '1 s' 2>&1");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("--stats-every 1 s needs --realtime"), std::string::npos) << r.out;
  r = run_shell(std::string(IBS_CLI) + " run --realtime --stats-every '10 ms' 2>&1");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("--stats-every 10 ms: give at least 100 ms"), std::string::npos) << r.out;
  r = run_shell(std::string(IBS_CLI) + " run --realtime --stats-every soon 2>&1");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  r = run_shell(std::string(IBS_CLI) + " run " + IBS_SOURCE_DIR + "/examples/canlust/conveyors.toml --realtime --stats-every '1 s' 2>&1");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("--stats-every is for INTERBUS scenarios"), std::string::npos) << r.out;
}

}  // namespace
