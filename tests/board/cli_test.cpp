// `ibs master --board` as a user runs it (docs/board.md): against ibs's virtual board, which the
// tool links in; its help, its refusals with the DDI call and code and exit 2, a run's summary in
// the schema of `ibs run --json`, and SIGINT / SIGTERM, after which the drives are stopped, the
// board is shut down and the summary is printed (exit 130).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "../support/run_shell.hpp"

namespace {

using ibs::test::run_shell;
using Result = ibs::test::ShellResult;

Result run(const std::string& env, const std::string& args) {
  return run_shell(env + " " + std::string(IBS_CLI) + " master " + args + " 2>&1");
}

TEST(MasterCli, HelpNamesTheBoardAndEndsWithExamplesAndExitCodes) {
  const Result r = run("", "--help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* s : {"Usage: ibs master", "--board NODE", "--duration S", "-j,--json", "Examples:\n  ibs master ",
                        "Exit codes: 0 ok; 2 bad input, or a DDI error (the call and its code); 130 interrupted"}) {
    EXPECT_NE(r.out.find(s), std::string::npos) << s << "\n" << r.out;
  }
  EXPECT_EQ(run("", "").exit_code, 2);  // --board is required
}

TEST(MasterCli, ABoardThatIsNotThereIsTheCallAndItsCodeAndExit2) {
  Result r = run("IBS_DDI_MODE=stepped", "--board IBB2N1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "ibs master: DDI_DevOpenNode(IBB2N1_D): ERR_INVLD_BOARD_NUM (0080H): no such board\n");
  r = run("IBS_DDI_MODE=stepped", "--board IBB1N1_D");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.out.find("give the board without the node suffix (IBB1N1)"), std::string::npos) << r.out;
  // The board runs another ring: refused before any process data, with the device named.
  const std::string scenario = std::string(IBS_SOURCE_DIR) + "/examples/faults.toml";
  r = run("IBS_DDI_MODE=stepped IBS_DDI_SCENARIO=" + scenario, "--board IBB1N1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.out.find("configuration mismatch: the board's active configuration has 3 devices, the master's 2 "
                       "(mc6000, vf1000)"),
            std::string::npos)
      << r.out;
  r = run("", "--board IBB1N1 /nonexistent.toml");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.out.find("/nonexistent.toml"), std::string::npos) << r.out;
}

TEST(MasterCli, ARunPrintsTheSummaryOfIbsRunAsJson) {
  const Result r = run("IBS_DDI_MODE=stepped", "--board IBB1N1 --duration 1.5 --json");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["version"], 1);
  EXPECT_EQ(j["scenario"], "default");
  EXPECT_EQ(j["protocol"], "interbus");
  ASSERT_EQ(j["devices"].size(), 2U);
  for (const auto& d : j["devices"]) {
    std::vector<std::string> states;
    for (const auto& s : d["states"]) states.push_back(s["what"]);
    EXPECT_EQ(states, (std::vector<std::string>{"START-UP INHIBIT", "READY", "ENABLED"})) << d["name"];
  }
  int parameters = 0;
  for (const auto& e : j["events"]) {
    if (e["type"] != "parameter") continue;
    ++parameters;
    EXPECT_EQ(e["ok"], true) << e.dump();
  }
  EXPECT_EQ(parameters, 8);
  EXPECT_EQ(j["board"]["node"], "IBB1N1");
  EXPECT_EQ(j["board"]["cycle_time_ms"], 0.726);
  EXPECT_EQ(j["board"]["shutdown"]["drives_safe"], true);
  EXPECT_EQ(j["board"]["shutdown"]["states"]["mc6000"], "READY");
}

// SIGINT or SIGTERM in the middle of the default scenario (8 s): the drives, both ENABLED by then,
// go to READY, the board stops, the summary says so, and the command exits 130 well before 8 s.
TEST(MasterCli, ASignalStopsTheDrivesShutsTheBoardDownAndPrintsTheSummary) {
  for (const int sig : {SIGINT, SIGTERM}) {
    const std::string out = ::testing::TempDir() + "master_signal.txt";
    const auto start = std::chrono::steady_clock::now();
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      FILE* f = std::freopen(out.c_str(), "w", stdout);
      if (f == nullptr) _exit(99);
      setenv("IBS_DDI_MODE", "realtime", 1);
      execl(IBS_CLI, "ibs", "master", "--board", "IBB1N1", static_cast<char*>(nullptr));
      _exit(98);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2500));  // past 1.2 s: both ENABLED
    kill(pid, sig);
    int status = 0;
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 130);
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(8));  // the run alone is 8 s
    std::ifstream in(out);
    const std::string text{std::istreambuf_iterator<char>(in), {}};
    EXPECT_NE(text.find("ibs master: scenario \"default\""), std::string::npos) << text;
    EXPECT_NE(text.find("interrupted by a signal"), std::string::npos) << text;
    EXPECT_NE(text.find("shutdown: every drive in a safe state (mc6000 READY, vf1000 READY); data transfer stopped, "
                        "nodes closed"),
              std::string::npos)
        << text;
  }
}

}  // namespace
