// The `ibs` command line as a user runs it: exit codes and what it prints.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "ibs/interbus/trace.hpp"

#include "../support/run_shell.hpp"

namespace {

using Result = ibs::test::ShellResult;
using ibs::test::run_shell;

Result run(const std::string& args) { return run_shell(std::string(IBS_CLI) + " " + args + " 2>&1"); }

std::string data(const std::string& name) { return std::string(IBS_TEST_DATA_DIR) + "/" + name; }

std::string temp_file(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

TEST(Cli, VersionPrintsTheProjectVersionAndExitsZero) {
  const Result r = run("--version");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_EQ(r.out, std::string("ibs ") + IBS_VERSION + "\n");
  EXPECT_EQ(run("-V").out, r.out);  // as most tools spell it (issue 27.2)
}

// Help a user can act on (issue 27.6): usage says `ibs`, values are named by what they are, and
// every command's help ends with two examples and its exit codes.
TEST(Cli, HelpEndsWithExamplesAndExitCodes) {
  for (const std::string path : {"", "run", "replay", "decode", "campaign", "layout", "timing", "lustbus emulate",
                                 "lustbus read", "lustbus write", "lustbus describe", "lustbus scan",
                                 "lustbus download", "dfs1 emulate", "dfs1 status", "dfs1 read", "dfs1 write",
                                 "dfs1 speed", "canlust emulate", "canlust start", "canlust stop", "canlust read",
                                 "canlust write", "canlust describe", "canlust download", "canlust monitor",
                                 "canlust send", "canlust play", "completion", "master"}) {
    const Result r = run(path + " --help");
    EXPECT_EQ(r.exit_code, 0) << path << "\n" << r.out;
    EXPECT_NE(r.out.find("Usage: ibs " + path), std::string::npos) << path << "\n" << r.out;
    const auto examples = r.out.find("Examples:\n  ibs ");
    ASSERT_NE(examples, std::string::npos) << path << "\n" << r.out;
    EXPECT_NE(r.out.find("\n  ibs ", examples + 12), std::string::npos) << path << ": two examples\n" << r.out;
    EXPECT_NE(r.out.find("Exit codes: 0 "), std::string::npos) << path << "\n" << r.out;
    for (const char* parser : {" TEXT", " INT ", " INT\n", " UINT", " FLOAT"}) {
      EXPECT_EQ(r.out.find(parser), std::string::npos) << path << ": '" << parser << "'\n" << r.out;
    }
  }
  const Result read = run("lustbus read --help");
  EXPECT_NE(read.out.find("-p,--port PORT"), std::string::npos) << read.out;
  EXPECT_NE(read.out.find("-a,--address,--addr ADDR"), std::string::npos) << read.out;
  EXPECT_NE(read.out.find("--timeout-ms MS"), std::string::npos) << read.out;
  // CANLust by the same names: -p the bus, -a the drive, -j JSON, values named by what they are.
  const Result can_read = run("canlust read --help");
  for (const char* option : {"-p,--bus BUS", "-a,--address,--addr ADDR", "-j,--json", "--timeout-ms MS", "--repeat N",
                             "--interval MS", "--log FILE", "--id-step N"}) {
    EXPECT_NE(can_read.out.find(option), std::string::npos) << option << "\n" << can_read.out;
  }
  const Result monitor = run("canlust monitor --help");
  for (const char* option : {"-f,--filter FILTER", "-n,--count COUNT", "-t,--timestamp a|d|z", "-T,--idle-ms MS",
                             "--duration-ms MS"}) {
    EXPECT_NE(monitor.out.find(option), std::string::npos) << option << "\n" << monitor.out;
  }
}

// `ibs completion bash` completes subcommands and options from the command tree itself.
TEST(Cli, BashCompletionCompletesCommandsAndOptions) {
  const std::string script = ::testing::TempDir() + "ibs-completion.bash";
  ASSERT_EQ(run_shell(std::string(IBS_CLI) + " completion bash > " + script).exit_code, 0);
  const auto complete = [&script](const std::string& words, int cword) {
    return run_shell("bash -c 'source " + script + "; COMP_WORDS=(" + words + "); COMP_CWORD=" + std::to_string(cword) +
                     "; _ibs; echo ${COMPREPLY[@]}'")
        .out;
  };
  EXPECT_EQ(complete("ibs lu", 1), "lustbus\n");
  EXPECT_EQ(complete("ibs lustbus re", 2), "read\n");
  EXPECT_EQ(complete("ibs lustbus read --tim", 3), "--timeout-ms\n");
  EXPECT_EQ(complete("ibs dfs1 status --addr", 3), "--address\n");
  EXPECT_EQ(complete("ibs canlust pl", 2), "play\n");
  EXPECT_EQ(complete("ibs canlust se", 2), "send\n");
  EXPECT_EQ(complete("ibs canlust monitor --ti", 3), "--timestamp\n");
  EXPECT_EQ(run("completion zsh").exit_code, 2);
}

// Progress a pipe can see (issue 27.8): with --progress a line every second on standard error
// wherever it goes; -q says nothing but the summary. The run takes long enough: 5 minutes of the
// default bus simulated (seconds of wall time even on a fast machine).
TEST(Cli, ProgressShowsInAPipeAndQuietSilencesIt) {
  std::ifstream in(std::string(IBS_SOURCE_DIR) + "/examples/default.toml");
  std::string toml{std::istreambuf_iterator<char>(in), {}};
  const auto at = toml.find("duration = \"8 s\"");
  ASSERT_NE(at, std::string::npos);
  toml.replace(at, std::string("duration = \"8 s\"").size(), "duration = \"300 s\"");
  const std::string file = temp_file("progress.toml", toml);
  Result r = run_shell(std::string(IBS_CLI) + " run " + file + " --progress 2>&1 >/dev/null");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("ibs run: simulated "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(" s of 300.0 s ("), std::string::npos) << r.out;
  r = run_shell(std::string(IBS_CLI) + " run " + file + " -q --progress 2>&1 >/dev/null");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_EQ(r.out, "");
}

TEST(Cli, ReplayAndDecodeReadStandardInputForDash) {
  const Result r = run_shell(std::string(IBS_CLI) + " replay --emulate master - < " +
                             data("mc6000_pd_startup_5_3_4.trace") + " 2>&1");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_EQ(r.out, "replay: 6 steps matched\n");
  const Result d = run_shell(std::string(IBS_CLI) + " decode - < " + data("vf1000_pd_startup.trace") + " 2>&1");
  EXPECT_EQ(d.exit_code, 0) << d.out;
  EXPECT_NE(d.out.find("m2s: control"), std::string::npos) << d.out;
  // Errors in standard input name it.
  const Result bad = run_shell("printf '# format: ibs-trace 1\\n# device: toaster\\n' | " + std::string(IBS_CLI) +
                               " decode - 2>&1");
  EXPECT_EQ(bad.exit_code, 2) << bad.out;
  EXPECT_EQ(bad.out.rfind("<stdin>:2: ", 0), 0U) << bad.out;
  const Result twice = run("decode - -");
  EXPECT_EQ(twice.exit_code, 2) << twice.out;
  EXPECT_NE(twice.out.find("standard input"), std::string::npos) << twice.out;
}

TEST(Cli, SeveralFilesEachWithItsResultAndTheWorstExitCode) {
  const Result ok = run("replay --emulate device " + data("vf1000_pd_startup.trace") + " " +
                        data("mc6000_pd_startup_5_3_4.trace"));
  EXPECT_EQ(ok.exit_code, 0) << ok.out;
  EXPECT_EQ(ok.out, "==> " + data("vf1000_pd_startup.trace") + " <==\nreplay: 6 steps matched\n==> " +
                        data("mc6000_pd_startup_5_3_4.trace") + " <==\nreplay: 6 steps matched\n");
  // A mismatch (1) and a missing file (2): every file is still tried, the exit code is the worst.
  std::ifstream in(data("mc6000_pd_startup_5_3_4.trace"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text.replace(text.find("2, 0006 09C4 4000, 0231"), 23, "2, 0006 09C4 4000, 0237");
  const std::string mismatch = temp_file("several_mismatch.trace", text);
  const Result one = run("replay --emulate device " + mismatch + " " + data("vf1000_pd_startup.trace"));
  EXPECT_EQ(one.exit_code, 1) << one.out;
  EXPECT_NE(one.out.find("replay: 6 steps matched"), std::string::npos) << one.out;
  const Result two = run("replay --emulate device " + mismatch + " /nonexistent/x.trace " +
                         data("vf1000_pd_startup.trace"));
  EXPECT_EQ(two.exit_code, 2) << two.out;
  EXPECT_NE(two.out.find("/nonexistent/x.trace:0: "), std::string::npos) << two.out;
  const Result pcap = run("replay --emulate device --pcap /tmp/x.pcap " + mismatch + " " + mismatch);
  EXPECT_EQ(pcap.exit_code, 2) << pcap.out;
}

TEST(Cli, MasterReplayOfATraceWithoutRequestSaysSo) {
  const Result r = run("replay --emulate master " + data("vf1000_pd_emergency_stop.trace"));
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("vf1000_pd_emergency_stop.trace: no `request` header"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("mismatch"), std::string::npos) << r.out;
}

TEST(Cli, DecodingADecodedFileChangesNothing) {
  const Result once = run("decode " + data("mc6000_pcp_read_1word.trace"));
  ASSERT_EQ(once.exit_code, 0) << once.out;
  const Result twice = run("decode " + temp_file("decoded_once.trace", once.out));
  EXPECT_EQ(twice.exit_code, 0) << twice.out;
  EXPECT_EQ(twice.out, once.out);
}

TEST(Cli, DecodeJsonGivesEachRowItsWordsAndReadings) {
  const Result r = run("decode --json " + data("mc6000_pd_startup_5_3_4.trace") + " " +
                       data("vf1000_comm_value_inquiry.trace"));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  std::vector<nlohmann::json> docs;
  std::size_t start = 0;
  while (start < r.out.size()) {
    const std::size_t end = r.out.find('\n', start);
    docs.push_back(nlohmann::json::parse(r.out.substr(start, end - start)));
    start = end + 1;
  }
  ASSERT_EQ(docs.size(), 2U);
  const nlohmann::json& pd = docs[0];
  EXPECT_EQ(pd["header"]["device"], "mc6000");
  EXPECT_EQ(pd["header"]["request"], "state enabled");
  const nlohmann::json& row2 = pd["rows"][2];
  EXPECT_EQ(row2["step"], 2);
  EXPECT_EQ(row2["m2s"], nlohmann::json::array({"0006", "09C4", "4000"}));
  EXPECT_NE(row2["s2m_decoded"].get<std::string>().find("READY"), std::string::npos) << row2;
  EXPECT_EQ(docs[1]["header"]["words"], "comm");
  EXPECT_GT(docs[1]["rows"].size(), 3U);
}

TEST(Cli, ReplayTheStartUpTableBothWays) {
  for (const char* side : {"device", "master"}) {
    const Result r = run(std::string("replay --emulate ") + side + " " + data("mc6000_pd_startup_5_3_4.trace"));
    EXPECT_EQ(r.exit_code, 0) << r.out;
    EXPECT_EQ(r.out, "replay: 6 steps matched\n");
  }
}

TEST(Cli, MismatchExitsOneAndExplainsBothWords) {
  std::ifstream in(data("mc6000_pd_startup_5_3_4.trace"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto pos = text.find("2, 0006 09C4 4000, 0231");
  ASSERT_NE(pos, std::string::npos);
  text.replace(pos, 23, "2, 0006 09C4 4000, 0237");
  const Result r = run("replay --emulate device " + temp_file("mismatch.trace", text));
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_NE(r.out.find("mismatch at step 2"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("expected 0237 0000 0000  status 0237 ENABLED"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("actual   0231 0000 0000  status 0231 READY"), std::string::npos) << r.out;
}

// `replay --json` (issue 27.7): per file one JSON object on one line, as `decode --json` prints,
// with the mismatch where it is and both sides' words and readings; no `==> FILE <==` lines.
TEST(Cli, ReplayJsonGivesEachFileItsResultAndTheMismatchAsAnObject) {
  std::ifstream in(data("mc6000_pd_startup_5_3_4.trace"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text.replace(text.find("2, 0006 09C4 4000, 0231"), 23, "2, 0006 09C4 4000, 0237");
  const std::string bad = temp_file("json_mismatch.trace", text);
  const Result r = run_shell(std::string(IBS_CLI) + " replay --json --emulate device " + bad + " " +
                             data("vf1000_pd_startup.trace") + " 2>/dev/null");
  EXPECT_EQ(r.exit_code, 1) << r.out;
  std::vector<nlohmann::json> docs;
  for (std::size_t start = 0; start < r.out.size();) {
    const std::size_t end = r.out.find('\n', start);
    ASSERT_NE(end, std::string::npos) << r.out;
    docs.push_back(nlohmann::json::parse(r.out.substr(start, end - start)));
    start = end + 1;
  }
  ASSERT_EQ(docs.size(), 2U) << r.out;
  EXPECT_EQ(docs[0]["file"], bad);
  EXPECT_EQ(docs[0]["emulate"], "device");
  EXPECT_EQ(docs[0]["matched"], false);
  EXPECT_EQ(docs[0]["steps_matched"], 2);
  ASSERT_EQ(docs[0]["mismatches"].size(), 1U);
  const nlohmann::json& m = docs[0]["mismatches"][0];
  EXPECT_EQ(m["kind"], "row");
  EXPECT_EQ(m["step"], 2);
  EXPECT_EQ(m["column"], "s2m");
  EXPECT_EQ(m["expected"], nlohmann::json::array({"0237", "0000", "0000"}));
  EXPECT_EQ(m["actual"], nlohmann::json::array({"0231", "0000", "0000"}));
  EXPECT_NE(m["expected_decoded"].get<std::string>().find("ENABLED"), std::string::npos) << m;
  EXPECT_NE(m["actual_decoded"].get<std::string>().find("READY"), std::string::npos) << m;
  EXPECT_GT(m["line"].get<int>(), 0);
  EXPECT_NE(m["message"].get<std::string>().find("mismatch at step 2"), std::string::npos) << m;
  EXPECT_EQ(docs[1]["matched"], true);
  EXPECT_EQ(docs[1]["steps_matched"], 6);
  EXPECT_TRUE(docs[1]["mismatches"].empty());
  // A master whose report is not the header's outcome: the outcome is the mismatch.
  std::string master_text = text;
  master_text.replace(master_text.find("2, 0006 09C4 4000, 0237"), 23, "2, 0006 09C4 4000, 0231");
  const auto outcome = master_text.find("# outcome: ");
  ASSERT_NE(outcome, std::string::npos);
  master_text.replace(outcome, master_text.find('\n', outcome) - outcome, "# outcome: timeout");
  const Result o = run_shell(std::string(IBS_CLI) + " replay --json --emulate master " +
                             temp_file("json_outcome.trace", master_text) + " 2>/dev/null");
  EXPECT_EQ(o.exit_code, 1) << o.out;
  const nlohmann::json doc = nlohmann::json::parse(o.out);
  ASSERT_EQ(doc["mismatches"].size(), 1U) << o.out;
  EXPECT_EQ(doc["mismatches"][0]["kind"], "outcome") << o.out;
  EXPECT_EQ(doc["mismatches"][0]["expected"], "timeout") << o.out;
  EXPECT_EQ(doc["mismatches"][0]["actual"], "ok") << o.out;
  // Bad input stays an error on standard error, never JSON.
  const Result missing = run_shell(std::string(IBS_CLI) + " replay --json --emulate device /nonexistent/x.trace 2>/dev/null");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_EQ(missing.out, "");
}

TEST(Cli, MalformedTraceExitsTwoWithFileAndLine) {
  const std::string path = temp_file("bad.trace", "# format: ibs-trace 1\n# device: mc6000\n# words: pd\n0, 0000 00000, 0240\n");
  const Result r = run("replay --emulate device " + path);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, path + ":4: word '00000' must be exactly four hex digits\n");
  const Result d = run("decode " + path);
  EXPECT_EQ(d.exit_code, 2);
  const Result missing = run("decode /nonexistent.trace");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_EQ(missing.out, "/nonexistent.trace:0: cannot read the file: it does not exist\n");
}

TEST(Cli, BadOptionsExitTwo) {
  EXPECT_EQ(run("replay --emulate bus " + data("mc6000_pd_startup_5_3_4.trace")).exit_code, 2);
  EXPECT_EQ(run("replay " + data("mc6000_pd_startup_5_3_4.trace")).exit_code, 2);
  EXPECT_EQ(run("frobnicate").exit_code, 2);
  EXPECT_EQ(run("").exit_code, 2);
}

TEST(Cli, DecodePrintsAValidTraceWithExplanations) {
  const Result r = run("decode " + data("mc6000_pd_startup_5_3_4.trace"));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto t = ibs::trace::parse(r.out, "decoded");
  ASSERT_EQ(t.rows.size(), 7U);
  EXPECT_NE(t.rows[2].remark.find("status 0231 READY, remote"), std::string::npos) << t.rows[2].remark;
  // The decoded file replays like the original.
  const Result again = run("replay --emulate device " + temp_file("decoded.trace", r.out));
  EXPECT_EQ(again.exit_code, 0) << again.out;
}

TEST(Cli, EveryTraceInTestsDataReplaysThroughTheCommand) {
  // Every transcribed table and example: the device side always; the master side where the
  // trace hands the master a request (the others are device-only by their own comment).
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(IBS_TEST_DATA_DIR)) {
    if (entry.path().extension() != ".trace") continue;
    ++files;
    const std::string path = entry.path().string();
    const Result d = run("replay --emulate device " + path);
    EXPECT_EQ(d.exit_code, 0) << path << "\n" << d.out;
    std::ifstream in(path);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (text.find("# request:") == std::string::npos) continue;
    const Result m = run("replay --emulate master " + path);
    EXPECT_EQ(m.exit_code, 0) << path << "\n" << m.out;
    const Result dec = run("decode " + path);
    EXPECT_EQ(dec.exit_code, 0) << path << "\n" << dec.out;
  }
  EXPECT_GE(files, 5);
}

TEST(Cli, RunTheDefaultScenario) {
  const Result r = run("run");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("reference 2500.25 rpm reached"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("reference 50 Hz reached"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("cycle time 0.726 ms"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("master processing per cycle"), std::string::npos) << r.out;
  // Every parameter transaction of the default scenario succeeds.
  for (const char* what : {"read 85", "write 409 = 100", "write 22 = 1000", "read 409", "read 22",
                           "describe 406", "describe 45"}) {
    EXPECT_NE(r.out.find(what), std::string::npos) << what;
  }
  EXPECT_EQ(r.out.find("NAK"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("negative"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("timeout"), std::string::npos) << r.out;
}

TEST(Cli, RunWritesJsonTracesAndVcd) {
  const std::string dir = ::testing::TempDir() + "ibs_run_traces";
  const std::string vcd = ::testing::TempDir() + "ibs_run.vcd";
  const Result r = run("run --json --trace " + dir + " --vcd " + vcd);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_EQ(r.out.front(), '{');
  EXPECT_NE(r.out.find("\"cycle_time_ms\": 0.726"), std::string::npos) << r.out;
  for (const char* name : {"mc6000.trace", "vf1000.trace"}) {
    const std::string path = dir + "/" + name;
    const Result replay = run("replay --emulate device " + path);
    EXPECT_EQ(replay.exit_code, 0) << path << "\n" << replay.out;
  }
  std::ifstream in(vcd);
  std::string first;
  std::getline(in, first);
  EXPECT_EQ(first.rfind("$date", 0) == 0 || first.rfind("$version", 0) == 0 || first.rfind("$comment", 0) == 0, true)
      << first;
  std::ifstream filter(vcd + ".states.txt");
  const std::string names((std::istreambuf_iterator<char>(filter)), std::istreambuf_iterator<char>());
  EXPECT_NE(names.find("0 NOT_READY"), std::string::npos) << names;
  EXPECT_NE(names.find("4 ENABLED"), std::string::npos) << names;
}

// `ibs run --json` prints the one run summary of docs/scenarios.md, "Run summary (JSON)", for an
// INTERBUS and a CANLust scenario alike: the same top-level keys, the same version.
TEST(Cli, RunJsonIsOneSchemaForBothBuses) {
  const Result ib = run_shell(std::string(IBS_CLI) + " run --json");
  const Result cl =
      run_shell(std::string(IBS_CLI) + " run --json " + std::string(IBS_SOURCE_DIR) + "/examples/canlust/conveyors.toml");
  ASSERT_EQ(ib.exit_code, 0) << ib.out;
  ASSERT_EQ(cl.exit_code, 0) << cl.out;
  const auto a = nlohmann::json::parse(ib.out);
  const auto b = nlohmann::json::parse(cl.out);
  std::vector<std::string> keys_a;
  std::vector<std::string> keys_b;
  for (const auto& [k, v] : a.items()) keys_a.push_back(k);
  for (const auto& [k, v] : b.items()) keys_b.push_back(k);
  EXPECT_EQ(keys_a, keys_b);
  EXPECT_EQ(a["version"], 1);
  EXPECT_EQ(b["version"], 1);
  EXPECT_EQ(a["protocol"], "interbus");
  EXPECT_EQ(b["protocol"], "canlust");
  EXPECT_EQ(a["devices"][1]["kind"], "vf1000");
  EXPECT_EQ(b["devices"][0]["kind"], "cda3000");
  EXPECT_EQ(ib.out.back(), '\n');
  EXPECT_EQ(cl.out.back(), '\n');
}

TEST(Cli, RunTakesAThreadCountAndRefusesABadOne) {
  const Result r = run("run --threads 3");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("reference 2500.25 rpm reached"), std::string::npos) << r.out;
  // Two devices: --threads 3 gives two threads, one device each.
  EXPECT_NE(r.out.find("of wall time on 2 threads"), std::string::npos) << r.out;
  // The full bus on one and on two threads: the same run, the summary says which.
  const std::string full = std::string(IBS_SOURCE_DIR) + "/examples/full_bus.toml";
  const Result one = run("run --threads 1 " + full);
  const Result two = run("run --threads 2 " + full);
  ASSERT_EQ(one.exit_code, 0) << one.out;
  ASSERT_EQ(two.exit_code, 0) << two.out;
  EXPECT_NE(one.out.find("on 1 thread ("), std::string::npos) << one.out;
  EXPECT_NE(two.out.find("on 2 threads ("), std::string::npos) << two.out;
  const auto after_timing = [](const std::string& out) {
    // From the device reports on; the header's wall time and the master's timing differ.
    const std::string from = out.substr(out.find("servo00"));
    return from.substr(0, from.find("master processing"));
  };
  EXPECT_EQ(after_timing(one.out), after_timing(two.out));
  // 0: as many as the machine's usable cores, at most one per 16 servos (64 here: up to 4).
  const Result any = run("run --threads 0 " + full);
  ASSERT_EQ(any.exit_code, 0) << any.out;
  EXPECT_TRUE(any.out.find("on 1 thread (") != std::string::npos || any.out.find("on 2 threads (") != std::string::npos ||
              any.out.find("on 3 threads (") != std::string::npos || any.out.find("on 4 threads (") != std::string::npos)
      << any.out;
  EXPECT_EQ(after_timing(one.out), after_timing(any.out));
  // Without the option: one thread.
  EXPECT_NE(run("run " + full).out.find("on 1 thread ("), std::string::npos);
  EXPECT_NE(one.out.find("reference 1630 rpm reached"), std::string::npos) << one.out;
  for (const char* bad : {"--threads many", "--threads -1", "--threads 1000"}) {
    const Result b = run(std::string("run ") + bad);
    EXPECT_EQ(b.exit_code, 2) << bad;
    EXPECT_NE(b.out.find("--threads"), std::string::npos) << b.out;
  }
}

TEST(Cli, RunRefusesABadScenarioWithFileAndLine) {
  const std::string path = temp_file("bad.toml", "name = \"x\"\nduration = \"1 s\"\n[[device]]\nname = \"m\"\ntype = \"mc6000\"\nsupi = 7\nibcnf = 2\n");
  const Result r = run("run " + path);
  EXPECT_EQ(r.exit_code, 2);
  // The line of the value the refusal names (406-IBCNF).
  EXPECT_NE(r.out.find(path + ":7: device 'm': 406-IBCNF = 2 needs 405-SUPI 10..12, not 7"), std::string::npos)
      << r.out;
  EXPECT_EQ(run("run /nonexistent.toml").exit_code, 2);
}

}  // namespace

namespace {

// Issue 9, defect 3: decode read past the end of a row with fewer words than the device has.
TEST(Cli, DecodeChecksTheWordCountsAsReplayDoes) {
  const std::string path =
      temp_file("short_row.trace", "# format: ibs-trace 1\n# device: vf1000\n# words: pd\n0, 0000, 0000\n");
  const Result d = run("decode " + path);
  EXPECT_EQ(d.exit_code, 2) << d.out;
  EXPECT_EQ(d.out, path + ":4: this vf1000 with words: pd exchanges 3 m2s and 3 s2m words per row; the row has 1 and 1\n");
  const Result r = run("replay --emulate device " + path);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, d.out);
}

// Issue 9, defect 4: a gap that never matches ran until max-gap, up to forever.
TEST(Cli, AGapThatCannotMatchFailsFast) {
  const std::string path = temp_file("endless_gap.trace",
                                     "# format: ibs-trace 1\n# device: vf1000\n# words: pd\n# max-gap: 10000000\n"
                                     "0, 0000 0000 0000, 0240 0000 8000\n...\n1, 0000 0000 0000, 0237 0000 8000\n");
  const Result r = run("replay --emulate device " + path);
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_NE(r.out.find("s2m cannot reach 0237 0000 8000: the device's words have not changed for 50000 steps"),
            std::string::npos)
      << r.out;
  const Result big = run("replay --emulate device " +
                         temp_file("huge_gap.trace", "# format: ibs-trace 1\n# device: vf1000\n# words: pd\n"
                                                     "# max-gap: 9223372036854775807\n0, 0000 0000 0000, 0240 0000 8000\n"));
  EXPECT_EQ(big.exit_code, 2) << big.out;
}

// Issue 9, defect 6: every refusal of a file says FILE:LINE.
TEST(Cli, EveryRefusalOfATraceNamesItsFileAndLine) {
  const std::string pcp = temp_file("pcp_state.trace",
                                    "# format: ibs-trace 1\n# device: mc6000\n# words: pcp\n# request: state enabled\n"
                                    "0, 0000, 0000\n1, 0000, 0000\n");
  const Result r = run("replay --emulate master " + pcp);
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_EQ(r.out.rfind(pcp + ":4: a PCP channel trace cannot carry `request: state enabled`", 0), 0U) << r.out;
  const std::string dir = ::testing::TempDir() + "ibs_cli_dir.trace";
  std::filesystem::create_directories(dir);
  const Result d = run("decode " + dir);
  EXPECT_EQ(d.exit_code, 2);
  EXPECT_EQ(d.out, dir + ":0: cannot read the file: it is a directory\n");
  std::filesystem::remove(dir);
  const std::string fifo = ::testing::TempDir() + "ibs_cli_fifo.trace";
  std::filesystem::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const Result f = run_shell("timeout 20 " + std::string(IBS_CLI) + " decode " + fifo + " 2>&1");
  EXPECT_EQ(f.exit_code, 2) << "a FIFO must be refused, not block the reader: " << f.out;
  EXPECT_EQ(f.out, fifo + ":0: cannot read the file: it is a FIFO (a named pipe), not a regular file\n");
  std::filesystem::remove(fifo);
}

TEST(Cli, ScenarioReadErrorsAndRangesSayWhereAndWhat) {
  // A scenario whose read fails: a .toml name for proc's memory file (read: EIO).
  const std::string link = ::testing::TempDir() + "ibs_mem.toml";
  std::filesystem::remove(link);
  std::filesystem::create_symlink("/proc/self/mem", link);
  const Result r = run("run " + link);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out.rfind(link + ":0: read error: ", 0), 0U) << r.out;
  std::filesystem::remove(link);
  const std::string big = temp_file("big_supi.toml",
                                    "name = \"x\"\nduration = \"1 s\"\n[[device]]\nname = \"a\"\ntype = \"mc6000\"\n"
                                    "supi = 99999999999\n");
  const Result s = run("run " + big);
  EXPECT_EQ(s.exit_code, 2);
  EXPECT_EQ(s.out, big + ":6: 'supi' = 99999999999 is out of range (0..12)\n");
}

// Issue 9, defect 7: on a full disk `ibs run` left a partial VCD or trace, printed the summary
// before the failing write, and left an empty trace directory behind.
TEST(Cli, RunLeavesNoHalfWrittenOutputWhenAWriteFails) {
  const std::string base = ::testing::TempDir() + "ibs_full_disk";
  std::filesystem::remove_all(base);
  std::filesystem::create_directories(base);
  const std::string vcd = base + "/run.vcd";
  const std::string traces = base + "/traces";
  // The file-size limit stands for a full disk: a write past 16 KiB fails (SIGXFSZ ignored).
  const Result r = run_shell("bash -c 'trap \"\" XFSZ; ulimit -f 16; exec " + std::string(IBS_CLI) + " run --vcd " + vcd +
                             " --trace " + traces + "' 2>&1");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_EQ(r.out.find("ibs run:"), std::string::npos) << "no summary for a run that could not be saved: " << r.out;
  EXPECT_EQ(r.out.rfind(vcd + ": ", 0), 0U) << "the message names the file that could not be written: " << r.out;
  std::vector<std::string> left;
  for (const auto& e : std::filesystem::recursive_directory_iterator(base)) left.push_back(e.path().string());
  EXPECT_TRUE(left.empty()) << "left behind: " << (left.empty() ? "" : left.front());
  // Without the limit the same run writes everything.
  const Result ok = run("run --vcd " + vcd + " --trace " + traces);
  EXPECT_EQ(ok.exit_code, 0) << ok.out;
  EXPECT_TRUE(std::filesystem::exists(vcd));
  EXPECT_TRUE(std::filesystem::exists(vcd + ".states.txt"));
  EXPECT_TRUE(std::filesystem::exists(vcd + ".gtkw"));
  EXPECT_FALSE(std::filesystem::is_empty(traces));
  for (const auto& e : std::filesystem::recursive_directory_iterator(base)) {
    EXPECT_EQ(e.path().string().find("ibs-partial"), std::string::npos) << e.path();
  }
  std::filesystem::remove_all(base);
}

}  // namespace

namespace {

// docs/replay.md promises the offending header's line: an IBCNF the servo refuses is reported on
// the `ibcnf` line, a SUPI on the `supi` line.
TEST(Cli, ALayoutErrorNamesTheOffendingHeadersLine) {
  const std::string head = "# format: ibs-trace 1\n# device: mc6000\n# words: pd\n";
  const std::string bad_ibcnf = temp_file("bad_ibcnf.trace", head + "# supi: 11\n# ibcnf: 7\n0, 0000 0000 0000, 0240 0000 0000\n");
  const Result i = run("replay --emulate device " + bad_ibcnf);
  EXPECT_EQ(i.exit_code, 2);
  EXPECT_EQ(i.out, bad_ibcnf + ":5: 406-IBCNF = 7 is out of range (0..4, INTERBUS manual 3.2.3)\n");
  const std::string bad_supi = temp_file("bad_supi.trace", head + "# supi: 13\n# ibcnf: 2\n0, 0000 0000 0000, 0240 0000 0000\n");
  const Result s = run("decode " + bad_supi);
  EXPECT_EQ(s.exit_code, 2);
  EXPECT_EQ(s.out, bad_supi + ":4: 405-SUPI = 13 is out of range (0..12, INTERBUS manual 3.2.2)\n");
}

// `ibs decode` tells the files apart: a candump log of CANLust and a LUSTBUS byte log of --log are
// explained by their own readers, everything else is a trace; --json is for traces only.
TEST(Cli, DecodeDispatchesCandumpAndByteLogs) {
  const std::string candump =
      temp_file("decode-dispatch.candump", "(1795431275.322679) can0 297#0F0000801400\n(1795431275.330000) can0 0DD#01\n");
  Result r = run("decode " + candump);
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("control CDA 1"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("System Start"), std::string::npos) << r.out;
  const std::string log = temp_file("decode-dispatch.log",
                                    "ibs-serial-log 1\n0.000100 tx /dev/pts/9 04 40 32 30 30 37 37 05\n"
                                    "0.030000 rx /dev/pts/9 40 02 32 30 30 37 37 3D 30 34 46 41 34 30 30 30 03 0B\n");
  r = run("decode " + log);
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("MC6000 77-SPEED = 1274.25"), std::string::npos) << r.out;
  // With --json a log gets JSON or an error, never the text decode first (issue 27.7).
  r = run("decode --json " + log);
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("--json is for traces"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("77-SPEED"), std::string::npos) << r.out;
  r = run("decode --json " + candump);
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("--json is for traces"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("System Start"), std::string::npos) << r.out;
}

// `ibs run --realtime`: --rt-priority needs it; a CANLust run in real time paces itself without
// SCHED_FIFO (issue 24), so --rt-priority stays an INTERBUS option.
TEST(Cli, RealtimeOptionsAreChecked) {
  Result r = run("run --rt-priority 10");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("--rt-priority 10 needs --realtime"), std::string::npos) << r.out;
  r = run("run --realtime --rt-priority 100");
  EXPECT_NE(r.exit_code, 0) << r.out;
  r = run("run " + std::string(IBS_SOURCE_DIR) + "/examples/canlust/conveyors.toml --realtime --rt-priority 10");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("--rt-priority is for INTERBUS scenarios"), std::string::npos) << r.out;
}

// The test bench (docs/testbench.md): a scenario that serves a line runs only in real time, and
// says so before anything is opened or written.
TEST(Cli, AScenarioThatServesALineNeedsRealtime) {
  const std::string bench = std::string(IBS_SOURCE_DIR) + "/examples/testbench/bench.toml";
  const Result r = run("run " + bench);
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_EQ(r.out, bench + ": [lustbus] serves a line to your own host software, which talks in real time: run it "
                           "with --realtime\n");
}

// Issue 24: `ibs run --realtime --control -` takes timeline entries without `at` on standard
// input while the run goes on; a bad line is reported and skipped; the summary lists the others.
TEST(Cli, RunControlAppliesLinesFromStandardInput) {
  const std::string scenario = temp_file("control_run.toml",
                                         "duration = \"1500 ms\"\n[[device]]\nname = \"servo\"\ntype = \"mc6000\"\n"
                                         "[[timeline]]\nat = \"0 s\"\ndevice = \"servo\"\nstate = \"enabled\"\n");
  const Result r = run_shell(
      "printf '{\"device\": \"servo\", \"speed\": 500}\\n{\"device\": \"servo\", \"speed\": }\\n"
      "{\"at\": \"1 s\", \"device\": \"servo\", \"speed\": 5}\\n"
      "{\"device\": \"servo\", \"fault\": \"device\", \"cause\": \"E-OP1\", \"duration\": \"0.5 s\"}\\n' | " +
      std::string(IBS_CLI) + " run " + scenario + " --realtime --control - 2>&1");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("control:2: JSON syntax error"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("control:3: control entries apply at once: no 'at'"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("control entries"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(R"(line 1     {"device": "servo", "speed": 500.0})"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(R"(line 4     {"device": "servo", "fault": "device", "duration": "500 ms", "cause": "E-OP1"})"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("error 16 (E-OP1)"), std::string::npos) << r.out;
}

TEST(Cli, RunControlNeedsRealtime) {
  const Result r = run("run --control -");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("needs --realtime: without it the simulation runs faster than real time"),
            std::string::npos)
      << r.out;
}

// A control line with a number no double holds ("1e400", nlohmann's out_of_range, not a syntax
// error) is a bad line like any other: reported with its line and skipped, the emulators go on
// (the LUSTBUS and the DFS-1 emulator ended on it with exit 2; control_fuzz found it).
TEST(Cli, AnOverflowingNumberOnTheControlChannelIsABadLineNotTheEnd) {
  const std::string lines = "(echo 1e400; echo '{\"device\": 1, \"fault\": \"power-cycle\"}'; sleep 1) | timeout 3 ";
  const Result lb = run_shell(lines + IBS_CLI + " lustbus emulate --pty vf1000@1 --control - 2>&1");
  EXPECT_NE(lb.out.find("control:1: not a JSON object: number overflow parsing '1e400'"), std::string::npos) << lb.out;
  EXPECT_NE(lb.out.find("control:2: vf1000@1: power cycle"), std::string::npos) << lb.out;
  const Result d = run_shell(lines + IBS_CLI + " dfs1 emulate --pty dfs1@1 --control - 2>&1");
  EXPECT_NE(d.out.find("control:1: not JSON: number overflow parsing '1e400'"), std::string::npos) << d.out;
  EXPECT_NE(d.out.find("dfs1@1: power cycle"), std::string::npos) << d.out;
}

}  // namespace

// Issue 23, defect 13: a seed of -1 or one past 2^64 - 1 ran as 18446744073709551615 and exited 0.
TEST(Cli, UnsignedOptionsRefuseNegativeAndTooLargeNumbers) {
  for (const std::string seed : {"-1", "18446744073709551616", "99999999999999999999999", "1e3", "+5"}) {
    const Result r = run("campaign --transactions 1 --seed " + seed);
    EXPECT_EQ(r.exit_code, 2) << seed << ": " << r.out;
    EXPECT_NE(r.out.find("--seed"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(seed), std::string::npos) << "the message names the value: " << r.out;
  }
  const Result max = run("campaign --transactions 1 --json --seed 18446744073709551615");
  EXPECT_EQ(max.exit_code, 0) << max.out;
  EXPECT_NE(max.out.find("18446744073709551615"), std::string::npos) << max.out;
  const Result step = run("decode --id-step -2 " + data("vf1000_pd_startup.trace"));
  EXPECT_EQ(step.exit_code, 2) << step.out;
}

// Issue 23, defects 8 and 9: a FIFO given as a scenario or a dataset blocked for ever (the
// CANLust check opened it first), /dev/zero or a 2 GiB sparse file was read up to 2 GiB before its
// message. Every input is a regular file of at most 256 MiB, told at once; a file's kind is told
// from its head.
TEST(Cli, InputsThatCannotBeReadWholeAreRefusedAtOnce) {
  const std::string dir = ::testing::TempDir() + "ibs_inputs_" + std::to_string(::getpid());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  ASSERT_EQ(::mkfifo((dir + "/f.toml").c_str(), 0600), 0);
  ASSERT_EQ(::mkfifo((dir + "/f.json").c_str(), 0600), 0);
  std::filesystem::resize_file(temp_file("ibs_big.toml", ""), std::uintmax_t{2} << 30U);
  std::filesystem::resize_file(temp_file("ibs_big.trace", ""), std::uintmax_t{2} << 30U);
  const std::string big_toml = ::testing::TempDir() + "ibs_big.toml";
  const std::string big_trace = ::testing::TempDir() + "ibs_big.trace";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"run " + dir + "/f.toml", "it is a FIFO (a named pipe), not a regular file"},
      {"run " + dir + "/f.json", "it is a FIFO (a named pipe), not a regular file"},
      {"run " + big_toml, "more than the 256 MiB an input file may have"},
      {"decode " + big_trace, "more than the 256 MiB an input file may have"},
      {"decode " + dir, "it is a directory"},
      {"lustbus download --port /dev/null --addr 1 " + dir + "/f.toml", "it is a FIFO"},
      {"lustbus download --port /dev/null --addr 1 /dev/zero", "it is a device, not a regular file"},
  };
  for (const auto& [args, says] : cases) {
    const Result r = run_shell("timeout 20 " + std::string(IBS_CLI) + " " + args + " 2>&1");
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.out;
    EXPECT_NE(r.out.find(says), std::string::npos) << args << ": " << r.out;
  }
  std::filesystem::remove(big_toml);
  std::filesystem::remove(big_trace);
  std::filesystem::remove_all(dir);
}

// Issue 23, defect 15: a candump log with a bad first line got the trace format's message.
TEST(Cli, ACandumpLogWithABadFirstLineIsToldWhatIsWrongWithIt) {
  const std::string log = temp_file("ibs_bad_candump.log", "(1700000000.000000) can0 6X7#01\n(1700000000.001000) can0 607#01\n");
  const Result r = run("decode " + log);
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find(log + ":1: not a candump log line: '(1700000000.000000) can0 6X7#01'"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("ibs-trace"), std::string::npos) << "not the trace format's message: " << r.out;
}
