// The `ibs` command's pictures and captures as a user gets them: `run --pcap`, `replay --pcap`
// (docs/pcap.md), `run --vcd` with its gtkwave save file (docs/vcd.md), `run --plot`
// (docs/simulator.md, "Plots"): what is written, what is printed, that gtkwave opens the save file
// ready to read, what the picture shows, and that bad paths fail cleanly.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "../support/run_shell.hpp"

namespace {

namespace fs = std::filesystem;

using Result = ibs::test::ShellResult;
using ibs::test::run_shell;

Result run(const std::string& args) { return run_shell(std::string(IBS_CLI) + " " + args + " 2>&1"); }

std::string data(const std::string& name) { return std::string(IBS_TEST_DATA_DIR) + "/" + name; }

bool contains(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

// A fresh directory for one test.
std::string fresh_dir(const std::string& name) {
  const std::string dir = ::testing::TempDir() + "ibs_outputs_" + name + "_" + std::to_string(::getpid());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

bool have(const char* program) {
  return std::system((std::string("command -v ") + program + " >/dev/null 2>&1").c_str()) == 0;
}

std::string tshark(const std::string& capture) {
  return "tshark -X lua_script:" + std::string(IBS_SOURCE_DIR) + "/tools/wireshark/interbus.lua -r " + capture;
}

TEST(Captures, RunWritesOnePacketPerCycleAndSaysSo) {
  const std::string dir = fresh_dir("run_pcap");
  const std::string pcap = dir + "/run.pcap";
  const Result r = run("run --pcap " + pcap);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  // 8 s of 0.726 ms cycles: 11019 cycles and the configuration.
  EXPECT_TRUE(contains(r.out, "capture written: " + pcap + " (11020 packets)")) << r.out;
  const std::string f = slurp(pcap);
  ASSERT_GE(f.size(), 24U);
  EXPECT_EQ(f.substr(0, 4), std::string("\x4D\x3C\xB2\xA1", 4));  // nanosecond pcap, little-endian
  EXPECT_EQ(static_cast<unsigned char>(f[20]), 147U);           // LINKTYPE_USER0
  // The first packet's timestamp is when the run started (not 1970): seconds at bytes 24..27,
  // little-endian, within the minute around this test's run; the next packet one cycle later.
  ASSERT_GE(f.size(), 28U);
  const auto le32 = [&f](std::size_t at) {
    return std::uint32_t{static_cast<unsigned char>(f[at])} | std::uint32_t{static_cast<unsigned char>(f[at + 1])} << 8U |
           std::uint32_t{static_cast<unsigned char>(f[at + 2])} << 16U |
           std::uint32_t{static_cast<unsigned char>(f[at + 3])} << 24U;
  };
  const auto now = std::chrono::duration_cast<std::chrono::seconds>(std::chrono::system_clock::now().time_since_epoch()).count();
  EXPECT_LE(static_cast<long long>(le32(24)), now);
  EXPECT_GE(static_cast<long long>(le32(24)), now - 60);
  fs::remove_all(dir);
}

// `-` is standard output (tshark's -w -, issue 27.1): the capture or the dump goes there, the
// summary to standard error; two outputs cannot both take it.
TEST(Captures, DashWritesTheCaptureToStandardOutputAndTheSummaryToStandardError) {
  const std::string dir = fresh_dir("dash_pcap");
  const std::string cli(IBS_CLI);
  Result r = run_shell(cli + " run --pcap - > " + dir + "/out.pcap 2> " + dir + "/err.txt");
  ASSERT_EQ(r.exit_code, 0) << slurp(dir + "/err.txt");
  const std::string f = slurp(dir + "/out.pcap");
  ASSERT_GE(f.size(), 24U);
  EXPECT_EQ(f.substr(0, 4), std::string("\x4D\x3C\xB2\xA1", 4));
  EXPECT_TRUE(contains(slurp(dir + "/err.txt"), "capture written: standard output (11020 packets)"));
  EXPECT_FALSE(fs::exists(dir + "/-"));
  r = run_shell(cli + " run --vcd - 2>/dev/null | grep -c enddefinitions");
  EXPECT_EQ(r.out, "1\n");
  r = run(" run --vcd - --pcap - ");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_TRUE(contains(r.out, "-: standard output is given for two outputs")) << r.out;
  if (have("tshark")) {
    r = run_shell(cli + " run --pcap - 2>/dev/null | tshark -X lua_script:" + std::string(IBS_SOURCE_DIR) +
                  "/tools/wireshark/interbus.lua -r - -c 3 -Y interbus 2>/dev/null | wc -l");
    EXPECT_EQ(r.out, "3\n");
  }
  fs::remove_all(dir);
}

// `--trace -` (issue 27.1): the one trace of a one-device run on standard output, ready for
// `ibs replay -`, the summary on standard error; a run with more traces is refused, saying why.
TEST(Captures, DashWritesTheOneTraceToStandardOutput) {
  const std::string dir = fresh_dir("dash_trace");
  const std::string cli(IBS_CLI);
  const std::string one = "name = \"one\"\nduration = \"2 s\"\n[[device]]\nname = \"servo\"\ntype = \"mc6000\"\n"
                          "supi = 11\nibcnf = 2\nbus = \"remote\"\ninitialised = true\n"
                          "[[timeline]]\nat = \"500 ms\"\ndevice = \"servo\"\nstate = \"enabled\"\n";
  std::ofstream(dir + "/one.toml") << one;
  Result r = run_shell(cli + " run " + dir + "/one.toml --trace - > " + dir + "/out.trace 2> " + dir + "/err.txt");
  ASSERT_EQ(r.exit_code, 0) << slurp(dir + "/err.txt");
  const std::string trace = slurp(dir + "/out.trace");
  EXPECT_EQ(trace.rfind("# format: ibs-trace 1\n", 0), 0U) << trace.substr(0, 200);
  const std::string err = slurp(dir + "/err.txt");
  EXPECT_TRUE(contains(err, "ibs run: scenario \"one\"")) << err;
  EXPECT_TRUE(contains(err, "trace written: standard output")) << err;
  r = run_shell(cli + " run " + dir + "/one.toml --trace - 2>/dev/null | " + cli + " replay --emulate device - 2>&1");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_TRUE(contains(r.out, "steps matched")) << r.out;
  EXPECT_FALSE(fs::exists("-"));
  // Two devices: two traces, refused before the run, nothing on standard output.
  r = run_shell(cli + " run --trace - 2>" + dir + "/err2.txt");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_TRUE(contains(slurp(dir + "/err2.txt"), "--trace -: the scenario has 2 devices")) << slurp(dir + "/err2.txt");
  // A power cycle ends a recording and starts another: two traces after the run, refused.
  std::ofstream(dir + "/cycled.toml") << one << "[[timeline]]\nat = \"1 s\"\ndevice = \"servo\"\nfault = \"power-cycle\"\n";
  r = run_shell(cli + " run " + dir + "/cycled.toml --trace - 2>" + dir + "/err3.txt");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_TRUE(contains(slurp(dir + "/err3.txt"), "--trace -: the run recorded 2 traces of servo")) << slurp(dir + "/err3.txt");
  // Standard output once: with --vcd - too it is refused.
  r = run("run " + dir + "/one.toml --trace - --vcd -");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_TRUE(contains(r.out, "-: standard output is given for two outputs")) << r.out;
  fs::remove_all(dir);
}

// `ibs run -` reads the scenario from standard input in the format --format gives.
TEST(Captures, RunDashReadsTheScenarioFromStandardInput) {
  const std::string cli(IBS_CLI);
  const std::string faults = std::string(IBS_SOURCE_DIR) + "/examples/faults.toml";
  Result r = run_shell(cli + " run - --format toml < " + faults + " 2>&1");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_TRUE(contains(r.out, "ibs run: scenario \"faults\", 12.000 s simulated")) << r.out;
  r = run_shell(cli + " run - < " + faults + " 2>&1");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_TRUE(contains(r.out, "<stdin>:0: give the format of a scenario on standard input: --format toml or --format json")) << r.out;
  r = run_shell("printf 'duration = \"1 s\"\\n[[device]]\\nname = 7\\n' | " + cli + " run - --format toml 2>&1");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_TRUE(contains(r.out, "<stdin>:")) << r.out;
}

TEST(Captures, ABadPathFailsBeforeTheRunAndLeavesNothing) {
  const std::string dir = fresh_dir("bad_pcap");
  const Result r = run("run --vcd " + dir + "/run.vcd --pcap " + dir + "/missing/run.pcap");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_EQ(r.out.rfind(dir + "/missing/run.pcap: cannot create the file", 0), 0U) << r.out;
  EXPECT_TRUE(fs::is_empty(dir)) << "nothing is left behind";
  const Result rp = run("replay --emulate device " + data("vf1000_comm_value_inquiry.trace") + " --pcap " + dir +
                        "/missing/replay.pcap");
  EXPECT_EQ(rp.exit_code, 2) << rp.out;
  EXPECT_TRUE(contains(rp.out, dir + "/missing/replay.pcap: cannot create the file")) << rp.out;
  EXPECT_TRUE(fs::is_empty(dir));
  fs::remove_all(dir);
}

// The test bench's lines as captures (docs/pcap.md, "Serial lines") need a scenario that serves
// them; asked of one that does not, the run is refused before it starts and writes nothing.
TEST(Captures, ABenchLineCaptureNeedsTheLineServed) {
  const std::string dir = fresh_dir("bench_line_pcap");
  const Result r = run("run --lustbus-pcap " + dir + "/lustbus.pcap");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_EQ(r.out, "--lustbus-pcap " + dir + "/lustbus.pcap: the scenario serves no [lustbus] line to capture "
                   "(docs/testbench.md)\n");
  EXPECT_TRUE(fs::is_empty(dir));
  fs::remove_all(dir);
}

TEST(Captures, AFullDiskLeavesNoHalfWrittenCapture) {
  const std::string dir = fresh_dir("full_pcap");
  const std::string pcap = dir + "/run.pcap";
  // The file-size limit stands for a full disk: a write past 16 KiB fails (SIGXFSZ ignored).
  const Result r = run_shell("bash -c 'trap \"\" XFSZ; ulimit -f 16; exec " + std::string(IBS_CLI) + " run --pcap " +
                             pcap + "' 2>&1");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_EQ(r.out.rfind(pcap + ": ", 0), 0U) << r.out;
  EXPECT_FALSE(contains(r.out, "ibs run:")) << "no summary for a run that could not be saved";
  EXPECT_TRUE(fs::is_empty(dir)) << "nothing is left behind";
  fs::remove_all(dir);
}

TEST(Captures, ReplayWritesARingOfOneRowByRow) {
  const std::string dir = fresh_dir("replay_pcap");
  const std::string pcap = dir + "/inquiry.pcap";
  const Result r = run("replay --emulate device " + data("vf1000_comm_value_inquiry.trace") + " --pcap " + pcap);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_EQ(r.out, "replay: 7 steps matched\n");
  ASSERT_TRUE(fs::exists(pcap));
  if (!have("tshark")) GTEST_SKIP() << "tshark is not installed (Debian package tshark)";
  // Exactly the rows of the table (INTERBUS manual 4.1.3.1.1), one per packet, 16.4 ms apart.
  const auto rows = lines_of(run_shell(tshark(pcap) + " -T fields -E separator=';' -e frame.time_relative"
                                                      " -e interbus.comm.master -e interbus.comm.inverter 2>/dev/null")
                                 .out);
  const std::vector<std::string> want{
      "0.000000000;;",
      "0.000000000;0x0000;0x8000",
      "0.016400000;0x2416;0x8000",
      "0.032800000;0x2416;0xa003",
      "0.049200000;0x0400;0xa003",
      "0.065600000;0x0400;0x88e8",
      "0.082000000;0x0000;0x88e8",
      "0.098400000;0x0000;0x8000",
  };
  EXPECT_EQ(rows, want);
  const std::string verbose = run_shell(tshark(pcap) + " -V 2>/dev/null").out;
  EXPECT_TRUE(contains(verbose, "Written by: ibs replay --emulate device (1)")) << verbose.substr(0, 2000);
  EXPECT_TRUE(contains(verbose, "First word: 3"));
  EXPECT_TRUE(contains(verbose, "Communication word (master): 0x2416 (toggle 1, CODE 1 value inquiry, byte 16H)"));
  EXPECT_TRUE(contains(verbose, "[As a parameter number: 22]"));
  EXPECT_TRUE(contains(verbose, "Communication word (inverter): 0x88e8 (ready, toggle 0, ACK, data E8H)"));
  fs::remove_all(dir);
}

TEST(Captures, AMismatchingReplayStillWritesItsCaptureUpToTheMismatch) {
  const std::string dir = fresh_dir("mismatch_pcap");
  std::string text = slurp(data("mc6000_pd_startup_5_3_4.trace"));
  const auto pos = text.find("2, 0006 09C4 4000, 0231");
  ASSERT_NE(pos, std::string::npos);
  text.replace(pos, 23, "2, 0006 09C4 4000, 0237");
  const std::string trace = dir + "/mismatch.trace";
  std::ofstream(trace) << text;
  const std::string pcap = dir + "/mismatch.pcap";
  const Result r = run("replay --emulate device " + trace + " --pcap " + pcap);
  EXPECT_EQ(r.exit_code, 1) << r.out;
  ASSERT_TRUE(fs::exists(pcap));
  if (!have("tshark")) GTEST_SKIP() << "tshark is not installed (Debian package tshark)";
  // Rows 0 and 1 matched; row 2 shows the device's actual answer (READY), not the file's.
  const auto rows = lines_of(
      run_shell(tshark(pcap) + " -T fields -E separator=';' -e interbus.control -e interbus.state 2>/dev/null").out);
  const std::vector<std::string> want{";", "0x0000;START-UP INHIBIT", "0x0006;START-UP INHIBIT", "0x0006;READY"};
  EXPECT_EQ(rows, want);
  fs::remove_all(dir);
}

// docs/pcap.md: the steps of `! no-data N` are cycles without valid data (flags bit 0 clear),
// one packet each, between the rows' packets, `step-time` apart.
TEST(Captures, ADeviceReplayCapturesTheStepsWithoutDataAsInvalidCycles) {
  const std::string dir = fresh_dir("no_data_pcap");
  const std::string pcap = dir + "/watchdog.pcap";
  const Result r = run("replay --emulate device " + data("mc6000_pd_watchdog_no_data.trace") + " --pcap " + pcap);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const std::string f = slurp(pcap);
  ASSERT_GE(f.size(), 24U);
  auto u32 = [&](std::size_t at) {  // the pcap headers are little-endian (the magic says so)
    return static_cast<std::uint32_t>(static_cast<unsigned char>(f[at])) |
           static_cast<std::uint32_t>(static_cast<unsigned char>(f[at + 1])) << 8U |
           static_cast<std::uint32_t>(static_cast<unsigned char>(f[at + 2])) << 16U |
           static_cast<std::uint32_t>(static_cast<unsigned char>(f[at + 3])) << 24U;
  };
  std::string validity;  // per cycle packet: 'v' valid, '-' without data
  std::vector<std::uint32_t> ns;
  std::vector<std::uint32_t> secs;
  for (std::size_t at = 24; at + 16 <= f.size();) {
    const std::uint32_t len = u32(at + 8);
    const std::size_t packet = at + 16;
    ASSERT_LE(packet + len, f.size());
    if (len > 8 && f[packet + 3] == 2) {
      validity += (static_cast<unsigned char>(f[packet + 8]) & 1U) != 0 ? 'v' : '-';
      ns.push_back(u32(at + 4));
      secs.push_back(u32(at));
    }
    at = packet + len;
  }
  // Rows 0..2, the 25 steps without data (steps 3..27), rows 28 and 29.
  EXPECT_EQ(validity, "vvv" + std::string(25, '-') + "vv");
  ASSERT_EQ(ns.size(), 30U);
  // step-time 1 ms: row 29 is 29 ms after row 0 (the capture counts from the replay's wall-clock
  // start, docs/pcap.md, so the difference is what tells).
  const auto at_ns = [&](std::size_t i) { return std::int64_t{secs[i]} * 1'000'000'000 + std::int64_t{ns[i]}; };
  EXPECT_EQ(at_ns(29) - at_ns(0), 29'000'000);
  fs::remove_all(dir);
}

TEST(Captures, AMasterReplayCapturesThePcpChannel) {
  const std::string dir = fresh_dir("master_pcap");
  const std::string pcap = dir + "/read.pcap";
  const Result r = run("replay --emulate master " + data("mc6000_pcp_read_4words.trace") + " --pcap " + pcap);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  if (!have("tshark")) GTEST_SKIP() << "tshark is not installed (Debian package tshark)";
  const auto msgs = lines_of(run_shell(tshark(pcap) + " -Y interbus.pcp.message -T fields -E separator=';'"
                                                      " -e interbus.pcp.message.direction"
                                                      " -e interbus.pcp.message.service 2>/dev/null")
                                 .out);
  const std::vector<std::string> want{"master -> servo;Initiate.req", "servo -> master;Initiate.conf",
                                      "master -> servo;Read.req", "servo -> master;Read.conf"};
  EXPECT_EQ(msgs, want);
  fs::remove_all(dir);
}

// Issue 27.15: each reassembled PCP message names the device whose channel carried it, one
// name per message beside its service (`interbus.device` lists every device of the packet).
TEST(Captures, EachPcpMessageNamesItsDevice) {
  if (!have("tshark")) GTEST_SKIP() << "tshark is not installed (Debian package tshark)";
  const std::string dir = fresh_dir("pcp_devices");
  std::ofstream(dir + "/two.toml") << R"(name = "two servos"
duration = "600 ms"
[[device]]
name = "left"
type = "mc6000"
supi = 11
ibcnf = 2
initialised = true
[[device]]
name = "right"
type = "mc6000"
supi = 11
ibcnf = 2
initialised = true
[[timeline]]
at = "0 s"
device = "left"
read = 85
[[timeline]]
at = "300 ms"
device = "right"
read = 409
)";
  const std::string pcap = dir + "/two.pcap";
  const Result r = run("run " + dir + "/two.toml --pcap " + pcap);
  if (contains(r.out, "without libpcap")) GTEST_SKIP() << r.out;
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto msgs = lines_of(run_shell(tshark(pcap) + " -Y interbus.pcp.message -T fields -E separator=';'"
                                                      " -e interbus.pcp.message.device -e interbus.pcp.message.service"
                                                      " -e interbus.pcp.message.parameter -e interbus.device 2>/dev/null")
                                 .out);
  const std::vector<std::string> want{
      "left;Initiate.req;;left,right",  "left;Initiate.conf;;left,right", "left;Read.req;85;left,right",
      "left;Read.conf;;left,right",     "right;Initiate.req;;left,right", "right;Initiate.conf;;left,right",
      "right;Read.req;409;left,right", "right;Read.conf;;left,right"};
  EXPECT_EQ(msgs, want);
  const std::string verbose = run_shell(tshark(pcap) + " -V 2>/dev/null").out;
  EXPECT_TRUE(contains(verbose, "PCP message master -> servo (right): Read.req, 10 bytes, index 5D99H"));
  fs::remove_all(dir);
}

// Issue 27.15: the CANLust dissector shows a parameter's value as the wing's data type and unit
// say (406-REFF INT32Q16 in Hz, 575-CASCY USIGN16 in ms), each reply with the request it answers;
// a valid capture raises no expert info (bytes 3-6 are characters only in a string transfer).
TEST(Captures, CanlustRepliesShowValuesWithTheirUnits) {
  if (!have("tshark")) GTEST_SKIP() << "tshark is not installed (Debian package tshark)";
  const std::string dir = fresh_dir("canlust_values");
  const std::string pcap = dir + "/conveyors.pcap";
  const Result r = run("run " + std::string(IBS_SOURCE_DIR) + "/examples/canlust/conveyors.toml --pcap " + pcap);
  if (contains(r.out, "without libpcap")) GTEST_SKIP() << r.out;
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const std::string lua = " -X lua_script:" + std::string(IBS_SOURCE_DIR) + "/tools/wireshark/canlust.lua -r " + pcap;
  const auto rows = lines_of(run_shell("tshark" + lua +
                                       " -Y 'canlust.kind == 4 || canlust.kind == 5' -T fields -E separator=';'"
                                       " -e can.id -e canlust.parameter_name -e canlust.data_type -e canlust.value"
                                       " -e canlust.unit -e canlust.text 2>/dev/null")
                                 .out);
  const std::vector<std::string> want{
      "1103;575-CASCY;USIGN16;;;",      // read request: no value
      "1105;575-CASCY;USIGN16;40;ms;",  // write request
      "1323;575-CASCY;USIGN16;20;ms;",  // the read's reply
      "1325;575-CASCY;USIGN16;40;ms;",  // the write's echo
      "1105;406-REFF;INT32Q16;;;",
      "1325;406-REFF;INT32Q16;-12.25;Hz;"};
  EXPECT_EQ(rows, want);
  const std::string verbose = run_shell("tshark" + lua + " -V 2>/dev/null").out;
  EXPECT_TRUE(contains(verbose, "Value read: -12.25 Hz (INT32Q16)")) << verbose.substr(0, 3000);
  EXPECT_TRUE(contains(verbose, "[Request in frame: "));
  const auto expert = verbose.find("Expert Info");
  EXPECT_EQ(expert, std::string::npos) << verbose.substr(expert > 2000 ? expert - 2000 : 0, 2200);
  fs::remove_all(dir);
}

TEST(Pictures, RunVcdWritesASaveFileBesideIt) {
  const std::string dir = fresh_dir("gtkw");
  const std::string vcd = dir + "/run.vcd";
  const Result r = run("run --vcd " + vcd);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_TRUE(contains(r.out, "VCD written: " + vcd + " (open it with: gtkwave " + vcd + ".gtkw;")) << r.out;
  const std::string g = slurp(vcd + ".gtkw");
  for (const std::string& what : std::vector<std::string>{"[dumpfile] \"" + vcd + "\"\n", "[savefile] \"" + vcd + ".gtkw\"\n", "[timestart] 0\n",
        "@2022\n^1 " + vcd + ".states.txt\nmc6000.state[3:0]\n", "@200\n-reference, actual: rpm\n@88420\nmc6000.reference_rpm\n@20000\n-\n-\n",
        "@88420\nmc6000.actual_rpm\n", "-reference, actual: Hz\n", "vf1000.reference_Hz\n", "vf1000.actual_Hz\n",
        "@22\nvf1000.master_control[15:0]\nvf1000.master_status[15:0]\n", "@28\nbus.cycle_valid\n",
        "-mc6000 (ID code 4DBH)\n", "-vf1000 (ID code 33BH)\n"}) {
    EXPECT_TRUE(contains(g, what)) << what << "\n" << g;
  }
  // The dump itself: the words by their meaning in each layout, and when the run was made.
  const std::string v = slurp(vcd);
  for (const std::string& what : std::vector<std::string>{
           " control_word $end", " reference_q16_high $end", " status_word $end", " actual_q16_high $end",
           " frequency_reference $end", " communication_word $end", " actual_frequency $end"}) {
    EXPECT_TRUE(contains(v, what)) << what << "\n" << v.substr(0, 2000);
  }
  EXPECT_FALSE(contains(v, " m2s_w")) << v.substr(0, 2000);
  const auto date = v.find("$date\n\t");
  ASSERT_NE(date, std::string::npos) << v.substr(0, 300);
  int y = 0, mo = 0, d = 0, h = 0, mi = 0, sec = 0;
  EXPECT_EQ(std::sscanf(v.c_str() + date + 7, "%4d-%2d-%2d %2d:%2d:%2d UTC", &y, &mo, &d, &h, &mi, &sec), 6) << v.substr(date, 60);
  EXPECT_GE(y, 2026);
  fs::remove_all(dir);
}

// gtkwave itself, headless under Xvfb: it opens the save file alone, finds the dump, shows the
// signals in their formats, names the states through the filter and shows the whole run.
TEST(Pictures, GtkwaveOpensTheRunReadyToRead) {
  if (!have("gtkwave")) GTEST_SKIP() << "gtkwave is not installed (Debian package gtkwave)";
  if (!have("xvfb-run")) GTEST_SKIP() << "xvfb-run is not installed (Debian package xvfb): gtkwave needs a display";
  const std::string dir = fresh_dir("gtkwave");
  const std::string vcd = dir + "/run.vcd";
  ASSERT_EQ(run("run --vcd " + vcd).exit_code, 0);
  const std::string out = dir + "/probe.out";
  std::ofstream(dir + "/probe.tcl")
      << "set f [open \"" << out << "\" w]\n"
      << "puts $f \"window [gtkwave::getWindowStartTime] [gtkwave::getWindowEndTime]\"\n"
      << "gtkwave::setMarker 3000000000\n"
      << "foreach s [gtkwave::getDisplayedSignals] {\n"
      << "  puts $f \"$s|[gtkwave::getTraceFlagsFromName $s]|[gtkwave::getTraceValueAtMarkerFromName $s]\"\n"
      << "}\n"
      << "close $f\n"
      << "gtkwave::/File/Quit\n";
  const Result g = run_shell("cd " + dir + " && timeout 120 xvfb-run -a -s '-screen 0 1600x1000x24' gtkwave -S probe.tcl " +
                             vcd + ".gtkw 2>&1");
  const auto lines = lines_of(slurp(out));
  ASSERT_FALSE(lines.empty()) << "gtkwave wrote nothing (exit " << g.exit_code << "):\n" << g.out;
  // Zoomed to the whole run (8 s), not beyond twice that.
  long long start = -1, end = -1;
  ASSERT_EQ(std::sscanf(lines[0].c_str(), "window %lld %lld", &start, &end), 2) << lines[0];
  EXPECT_EQ(start, 0);
  EXPECT_GE(end, 8'000'000'000LL);
  EXPECT_LE(end, 16'000'000'000LL);
  const std::vector<std::string> want{
      "bus.cycle_valid|40|1",                        // flags 28H: binary
      "mc6000.state[3:0]|8226|ENABLED",              // 2022H: hex through the filter, by name
      "mc6000.reference_rpm|558112|2500.25",         // 88420H: analog step, full scale
      "mc6000.master_control[15:0]|34|000F",         // 22H: hex
      "mc6000.master_status[15:0]|34|0637",
      "vf1000.state[3:0]|8226|ENABLED",
      "vf1000.reference_Hz|558112|50",
      "mc6000.control_word[15:0]|34|000F",           // the words by their meaning in the layout
      "vf1000.frequency_reference[15:0]|34|03E8",      // 50 Hz in 0.05 Hz steps
  };
  for (const auto& w : want) EXPECT_NE(std::find(lines.begin(), lines.end(), w), lines.end()) << w << "\n" << slurp(out);
  fs::remove_all(dir);
}

// The texts of an SVG: every <text> element's content (gnuplot writes titles, labels and tic
// labels as text, series as paths in groups with ids).
std::vector<std::string> svg_texts(const std::string& svg) {
  std::vector<std::string> texts;
  std::size_t pos = 0;
  while ((pos = svg.find("<text", pos)) != std::string::npos) {
    const auto end = svg.find("</text>", pos);
    if (end == std::string::npos) break;
    std::string t;
    bool in_tag = false;
    for (std::size_t i = svg.find('>', pos) + 1; i < end; ++i) {
      if (svg[i] == '<') in_tag = true;
      else if (svg[i] == '>') in_tag = false;
      else if (!in_tag) t += svg[i];
    }
    texts.push_back(t);
    pos = end;
  }
  return texts;
}

TEST(Pictures, PlotDrawsEachDrivesSeriesAxesAndEvents) {
  if (!have("gnuplot")) GTEST_SKIP() << "gnuplot is not installed (Debian package gnuplot-nox)";
  const std::string dir = fresh_dir("plot_svg");
  const std::string svg = dir + "/faults.svg";
  const Result r = run("run " + std::string(IBS_SOURCE_DIR) + "/examples/faults.toml --plot " + svg);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_TRUE(contains(r.out, "plot written: " + svg + "\n")) << r.out;
  const std::string text = slurp(svg);
  ASSERT_EQ(text.rfind("<?xml", 0), 0U) << text.substr(0, 200);
  EXPECT_TRUE(contains(text, "</svg>"));
  const auto texts = svg_texts(text);
  const auto has = [&](const std::string& t) { return std::find(texts.begin(), texts.end(), t) != texts.end(); };
  // Per drive: its title, the series in the key, the axes labelled, the states named.
  // Both viewpoints (issue 27.14), both kinds of transaction, and the events close together under
  // one label (the servo's device fault 0.2 s after a corrupted cycle).
  for (const char* what : {"servo (ID code 4DBH)", "fan (ID code 33BH)", "pump (ID code 33BH)", "reference (rpm)",
                           "actual, master's view (rpm)", "actual, device (rpm)", "reference (Hz)",
                           "actual, master's view (Hz)", "actual, device (Hz)", "reference, actual (rpm)",
                           "reference, actual (Hz)", "state, master's view", "state, device", "time (s)", "ENABLED",
                           "FAULT", "EMERGENCY STOP ACTIVE", "fault events", "power-cycle", "fault-cleared",
                           "2 events: corrupt, device-fault", "done transactions", "failed transactions", "read 85",
                           "ibs run: faults, 12 s simulated"}) {
    EXPECT_TRUE(has(what)) << what;
  }
  // Every series is drawn: two value curves, the state steps and the transaction bars or the
  // fault key of each of the three drives.
  EXPECT_TRUE(contains(text, "<g id=\"gnuplot_plot_1a\""));
  EXPECT_TRUE(contains(text, "<g id=\"gnuplot_plot_2a\""));
  EXPECT_TRUE(contains(text, "<g id=\"gnuplot_plot_1f\""));
  fs::remove_all(dir);
}

TEST(Pictures, PlotDrawsAPngToo) {
  if (!have("gnuplot")) GTEST_SKIP() << "gnuplot is not installed (Debian package gnuplot-nox)";
  const std::string dir = fresh_dir("plot_png");
  const std::string png = dir + "/run.PNG";
  const Result r = run("run --plot " + png);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const std::string image = slurp(png);
  EXPECT_EQ(image.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_GT(image.size(), 20000U);
  fs::remove_all(dir);
}

TEST(Pictures, PlotRefusesWhatItCannotDrawBeforeTheRun) {
  const std::string dir = fresh_dir("plot_bad");
  const Result ext = run("run --vcd " + dir + "/run.vcd --plot " + dir + "/run.pdf");
  EXPECT_EQ(ext.exit_code, 2) << ext.out;
  EXPECT_EQ(ext.out, dir + "/run.pdf: --plot draws FILE.svg or FILE.png; say which by the extension\n");
  // Without gnuplot on the PATH: said clearly, nothing run, nothing written.
  const Result none = run_shell("env PATH=" + dir + " " + std::string(IBS_CLI) + " run --vcd " + dir +
                                "/run.vcd --plot " + dir + "/run.svg 2>&1");
  EXPECT_EQ(none.exit_code, 2) << none.out;
  EXPECT_EQ(none.out, dir + "/run.svg: --plot needs gnuplot, which is not installed (Debian package gnuplot-nox); "
                            "nothing was run or written\n");
  const Result missing = run("run --plot " + dir + "/missing/run.svg");
  EXPECT_EQ(missing.exit_code, 2) << missing.out;
  if (have("gnuplot")) {
    EXPECT_TRUE(contains(missing.out, dir + "/missing/run.svg: cannot create the file")) << missing.out;
  }
  EXPECT_TRUE(fs::is_empty(dir)) << "nothing is left behind";
  fs::remove_all(dir);
}

}  // namespace

namespace {

// Issue 23, defect 6: `--vcd O --pcap O` left O with VCD bytes written over the capture.
TEST(OutputFileRules, OneFileForTwoOutputsIsRefusedAndLeftAsItWas) {
  const std::string dir = fresh_dir("two_outputs");
  const std::string o = dir + "/O";
  std::ofstream(o) << "the user's capture";
  const Result r = run("run --vcd " + o + " --pcap " + dir + "/./O");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_TRUE(contains(r.out, "the same file is given for two outputs")) << r.out;
  EXPECT_EQ(slurp(o), "the user's capture");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1) << "no temporary left";
  fs::remove_all(dir);
}

// Issue 23, defect 12: a directory where the VCD's save file goes left g.vcd and g.vcd.states.txt.
TEST(OutputFileRules, AnOutputThatIsADirectoryLeavesNothingBehind) {
  const std::string dir = fresh_dir("dir_output");
  fs::create_directory(dir + "/g.vcd.gtkw");
  const Result r = run("run --vcd " + dir + "/g.vcd");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_TRUE(contains(r.out, dir + "/g.vcd.gtkw: is a directory")) << r.out;
  EXPECT_FALSE(fs::exists(dir + "/g.vcd"));
  EXPECT_FALSE(fs::exists(dir + "/g.vcd.states.txt"));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1) << "only the directory";
  const Result p = run("run --pcap " + dir + "/g.vcd.gtkw");
  EXPECT_EQ(p.exit_code, 2) << p.out;
  EXPECT_TRUE(fs::is_empty(dir + "/g.vcd.gtkw"));
  fs::remove_all(dir);
}

// Issue 23, defect 10: a symbolic link or a FIFO given as an output was replaced by a regular file.
TEST(OutputFileRules, ALinkIsFollowedAndAFifoWrittenThroughNeverReplaced) {
  const std::string dir = fresh_dir("special_outputs");
  const std::string target = dir + "/target.pcap";
  std::ofstream(target) << "old";
  fs::create_symlink(target, dir + "/link.pcap");
  Result r = run("run --pcap " + dir + "/link.pcap");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_TRUE(fs::is_symlink(dir + "/link.pcap")) << "the link stays a link";
  EXPECT_EQ(slurp(target).substr(0, 4), std::string("\x4D\x3C\xB2\xA1", 4)) << "its target holds the capture";

  const std::string fifo = dir + "/fifo.pcap";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  r = run("run --pcap " + fifo);
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_TRUE(contains(r.out, fifo + ": a FIFO that no process reads")) << r.out;
  // With a reader, the capture goes through the FIFO, which stays a FIFO. The reader is this test:
  // it holds the FIFO open before ibs starts (read-write, so its own open never waits for a
  // writer) and reads until ibs has exited. A reader started in the background had to win a race
  // with ibs; on a loaded machine it lost, ibs was refused and the reader waited for ever.
  const int fd = ::open(fifo.c_str(), O_RDWR | O_NONBLOCK);
  ASSERT_GE(fd, 0);
  std::atomic<bool> ibs_ended{false};
  std::string got;
  std::thread reader([&] {
    std::array<char, 65536> buf{};
    const auto drain = [&] {
      for (ssize_t n; (n = ::read(fd, buf.data(), buf.size())) > 0;) got.append(buf.data(), static_cast<size_t>(n));
    };
    while (!ibs_ended.load()) {
      drain();
      pollfd p{fd, POLLIN, 0};
      ::poll(&p, 1, 50);
    }
    drain();  // what ibs wrote before it ended
  });
  r = run("run --pcap " + fifo);
  ibs_ended = true;
  reader.join();
  ::close(fd);
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_TRUE(fs::is_fifo(fifo));
  EXPECT_EQ(got.substr(0, 4), std::string("\x4D\x3C\xB2\xA1", 4)) << "the reader got the capture";
  EXPECT_EQ(got.size(), fs::file_size(target)) << "all of it: the same run as through the link";
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 3) << "no temporary left";
  fs::remove_all(dir);
}

}  // namespace

namespace {

// Issue 23, defect 11: SIGINT or SIGTERM during `run --vcd --pcap --trace D` left
// *.ibs-partial-PID files of 120-140 MB and an empty D. The run stops, removes what it began and
// says so; exit 130.
TEST(OutputFileRules, ASignalDuringARunLeavesNothingAndSaysSo) {
  for (const char* sig : {"INT", "TERM"}) {
    const std::string dir = fresh_dir(std::string("signal_") + sig);
    const std::string scenario = dir + "/long.toml";
    std::ofstream(scenario) << "name = \"long\"\nduration = \"3600 s\"\n\n[[device]]\nname = \"fan\"\ntype = \"vf1000\"\n";
    // A script's background job ignores SIGINT (bash): env gives it the default back, as a
    // terminal's Ctrl-C would find it.
    const Result r = run_shell(
        "cd " + dir + " && { env --default-signal=INT " + std::string(IBS_CLI) + " run " + scenario +
        " --vcd run.vcd --pcap run.pcap --trace traces > out.txt 2> err.txt & pid=$!; "
        "for i in $(seq 1 100); do ls | grep -q ibs-partial && break; sleep 0.1; done; "
        "sleep 0.3; kill -" + sig + " $pid; wait $pid; echo \"exit $?\" > rc.txt; cat rc.txt err.txt; }");
    EXPECT_TRUE(contains(r.out, "exit 130")) << sig << ": " << r.out;
    EXPECT_TRUE(contains(r.out, "ibs run: interrupted by a signal after ")) << r.out;
    EXPECT_TRUE(contains(r.out, "no output was written")) << r.out;
    std::vector<std::string> left;
    for (const auto& e : fs::directory_iterator(dir)) left.push_back(e.path().filename().string());
    std::sort(left.begin(), left.end());
    EXPECT_EQ(left, (std::vector<std::string>{"err.txt", "long.toml", "out.txt", "rc.txt"})) << sig;
    fs::remove_all(dir);
  }
}

}  // namespace

namespace {

// The test bench's line capture is an output of the run like its --pcap: a signal during the run
// leaves neither (issue 36).
TEST(OutputFileRules, ASignalDuringABenchRunLeavesNoLineCapture) {
  const std::string dir = fresh_dir("signal_bench");
  const std::string scenario = std::string(IBS_SOURCE_DIR) + "/examples/testbench/bench.toml";
  const Result r = run_shell(
      "cd " + dir + " && { env --default-signal=INT " + std::string(IBS_CLI) + " run --realtime " + scenario +
      " --pcap run.pcap --lustbus-pcap line.pcap > out.txt 2> err.txt & pid=$!; "
      "for i in $(seq 1 100); do ls | grep -q line.pcap.ibs-partial && break; sleep 0.1; done; "
      "sleep 0.3; kill -INT $pid; wait $pid; echo \"exit $?\" > rc.txt; cat rc.txt err.txt; }");
  EXPECT_TRUE(contains(r.out, "exit 130")) << r.out;
  EXPECT_TRUE(contains(r.out, "no output was written")) << r.out;
  std::vector<std::string> left;
  for (const auto& e : fs::directory_iterator(dir)) left.push_back(e.path().filename().string());
  std::sort(left.begin(), left.end());
  EXPECT_EQ(left, (std::vector<std::string>{"err.txt", "out.txt", "rc.txt"}));
  fs::remove_all(dir);
}

// Issue 23, defect 5: `ibs run examples/canlust/conveyors.toml --pcap U.pcap` wrote U.pcap.tmp
// over the user's file of that name and then removed it. The CANLust capture takes the rules of
// every output.
TEST(OutputFileRules, ACanlustCaptureLeavesTheUsersFilesAlone) {
  const std::string dir = fresh_dir("canlust_pcap");
  std::ofstream(dir + "/U.pcap.tmp") << "the user's own file";
  const std::string scenario = std::string(IBS_SOURCE_DIR) + "/examples/canlust/conveyors.toml";
  const Result r = run("run " + scenario + " --pcap " + dir + "/U.pcap");
  if (contains(r.out, "without libpcap")) GTEST_SKIP() << r.out;
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_EQ(slurp(dir + "/U.pcap.tmp"), "the user's own file");
  EXPECT_EQ(slurp(dir + "/U.pcap").substr(0, 4), std::string("\xD4\xC3\xB2\xA1", 4)) << "a pcap file";
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 2) << "no temporary left";
  // A capture that cannot be created fails before the run and leaves nothing.
  const Result bad = run("run " + scenario + " --pcap " + dir + "/missing/U.pcap");
  EXPECT_EQ(bad.exit_code, 2) << bad.out;
  EXPECT_TRUE(contains(bad.out, dir + "/missing/U.pcap: ")) << bad.out;
  EXPECT_FALSE(contains(bad.out, "ibs-partial")) << "the user's name, not the temporary's: " << bad.out;
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 2);
  fs::remove_all(dir);
}

}  // namespace
