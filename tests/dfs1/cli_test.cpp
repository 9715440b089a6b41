// `ibs dfs1 ...`: `emulate --pty` as a process (prints `pty: PATH` first, serves, exits 0 on
// SIGTERM and SIGINT), the client commands in process against it, their JSON, exit codes and the
// byte log.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <thread>
#include <chrono>
#include <poll.h>
#include <pty.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "dfs1_cmd.hpp"

#include "../support/cli_harness.hpp"

namespace ibs::cli {
namespace {

using test::CliRun;

CliRun run_cli(std::vector<std::string> args) {
  return test::run_cli_group<Dfs1CommandState>(std::move(args), kExitDfs1BadInput, add_dfs1_commands,
                                               run_dfs1_commands);
}

// `dfs1 emulate --pty DEVICES...` as a child process; the first line of its output is the pty.
class Emulator : public test::ChildProcess {
 public:
  explicit Emulator(const std::vector<std::string>& devices) : ChildProcess(argv(devices)) {}

 private:
  static std::vector<std::string> argv(const std::vector<std::string>& devices) {
    std::vector<std::string> a = {IBS_DFS1_CLI, "dfs1", "emulate", "--pty"};
    a.insert(a.end(), devices.begin(), devices.end());
    return a;
  }
};

TEST(Dfs1Cli, EmulatePrintsThePtyFirstAndExitsZeroOnSigterm) {
  Emulator emu({"dfs1@1", "dfs1@2"});
  ASSERT_EQ(emu.first_line().rfind("pty: /dev/pts/", 0), 0U) << emu.first_line();
  const CliRun r =
      run_cli({"dfs1", "status", "--port", emu.pty(), "--uid", "2", "--timeout-ms", "3000"});
  EXPECT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.out.find("uid 2: commanded 0 rpm, actual 0 rpm, load 0 %"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("ST2 31H: at-speed forward zero-speed"), std::string::npos) << r.out;
  EXPECT_EQ(emu.stop(SIGTERM), 0);
}

// Issue 23, defect 1, as it was seen: a host writes P6 := 99 and dies before its frame ends; the
// next host's read must get its answer, and P6 must keep its value -- at every cut point.
TEST(Dfs1Cli, AFrameADyingHostLeftIsNotCompletedByTheNextHost) {
  Emulator emu({"dfs1@1"});
  const std::string port = emu.pty();
  CliRun r = run_cli({"dfs1", "read", "--port", port, "--uid", "1", "6", "--json", "--timeout-ms", "3000"});
  ASSERT_EQ(r.rc, 0) << r.err;
  const auto p6 = nlohmann::json::parse(r.out)["value"].get<long>();
  ASSERT_NE(p6, 99);
  const std::vector<std::uint8_t> write_p6 = {0x10, 0x02, 0x01, 0x86, 0x06, 0x00, 0x00,
                                              0x00, 0x63, 0x10, 0x03, 0x10, 0x10};
  for (std::size_t cut = 1; cut < write_p6.size(); ++cut) {
    const int fd = ::open(port.c_str(), O_RDWR | O_NOCTTY);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(::write(fd, write_p6.data(), cut), static_cast<ssize_t>(cut));
    ::close(fd);
    // Longer than the fragment timeout (50 ms at the emulator's rate), as a next host would come.
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    r = run_cli({"dfs1", "read", "--port", port, "--uid", "1", "6", "--json", "--timeout-ms", "3000"});
    ASSERT_EQ(r.rc, 0) << "cut after " << cut << " bytes: " << r.err;
    EXPECT_EQ(nlohmann::json::parse(r.out)["value"].get<long>(), p6) << "cut after " << cut << " bytes";
  }
  EXPECT_EQ(emu.stop(SIGTERM), 0);
}

// Issue 23, defect 7: against a device that answers with an endless trickle of bytes `dfs1 read`
// did not exit. It ends at its overall deadline and says what it heard.
TEST(Dfs1Cli, AHostAgainstADeviceThatKeepsSendingEnds) {
  int master = -1;
  int slave = -1;
  char name[128] = {};
  ASSERT_EQ(::openpty(&master, &slave, name, nullptr, nullptr), 0);
  std::atomic<bool> stop{false};
  std::thread babbler([&] {
    // DLE STX and body bytes, one every 2 ms: every byte keeps a frame open.
    const unsigned char open_frame[] = {0x10, 0x02, 0x01, 0x06};
    std::size_t i = 0;
    while (!stop) {
      const unsigned char b = i < sizeof open_frame ? open_frame[i] : 0x55;
      i = (i + 1) % 12;  // DLE STX again after eight body bytes: a frame is always open
      (void)::write(master, &b, 1);
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
  });
  const CliRun r = run_cli({"dfs1", "read", "--port", name, "--uid", "1", "6", "--timeout-ms", "100", "--json"});
  stop = true;
  babbler.join();
  ::close(slave);
  ::close(master);
  EXPECT_EQ(r.rc, 1) << r.err;
  EXPECT_NE(r.err.find("heard "), std::string::npos) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  // "line busy" at the overall deadline; on a loaded machine the babbling thread may stall longer
  // than the inter-byte timeout first (Dfs1Host.ADeviceThatKeepsSendingEndsAtTheOverallDeadline
  // pins the deadline in simulated time).
  EXPECT_TRUE(j["outcome"] == "line busy" || j["outcome"] == "inter-byte timeout") << r.out;
  if (j["outcome"] == "line busy") {
    EXPECT_NE(r.err.find("line busy (no response ended within"), std::string::npos) << r.err;
  }
  EXPECT_GT(j["bytes_heard"].get<int>(), 10);
}

TEST(Dfs1Cli, EmulateExitsZeroOnSigint) {
  Emulator emu({"dfs1@5"});
  ASSERT_EQ(emu.first_line().rfind("pty: ", 0), 0U);
  EXPECT_EQ(emu.stop(SIGINT), 0);
}

TEST(Dfs1Cli, ReadWriteSpeedStatusWithJson) {
  Emulator emu({"dfs1@1", "dfs1@7"});
  const std::string port = emu.pty();
  CliRun r = run_cli(
      {"dfs1", "read", "--port", port, "--uid", "7", "56", "--json", "--timeout-ms", "3000"});
  ASSERT_EQ(r.rc, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["value"], 2);
  EXPECT_EQ(j["parameter"], 56);
  EXPECT_EQ(j["outcome"], "ack");

  r = run_cli({"dfs1", "speed", "--port", port, "--uid", "7", "500", "--timeout-ms", "3000"});
  EXPECT_EQ(r.rc, 1);
  EXPECT_NE(r.err.find("NAK 80H not in remote"), std::string::npos) << r.err;

  r = run_cli({"dfs1", "write", "--port", port, "--uid", "7", "3", "15", "--timeout-ms", "3000"});
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(r.out, "uid 7 write parameter 3 = 15: ack\n");

  r = run_cli(
      {"dfs1", "speed", "--port", port, "--uid", "7", "-500", "--json", "--timeout-ms", "3000"});
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["value"], -500);

  r = run_cli({"dfs1", "status", "--port", port, "--uid", "7", "--json", "--timeout-ms", "3000"});
  ASSERT_EQ(r.rc, 0) << r.err;
  j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["commanded_speed"], -500);
  EXPECT_EQ(j["st2"].get<int>() & 0x80, 0x80);  // remote

  r = run_cli(
      {"dfs1", "read", "--port", port, "--uid", "1", "99", "--json", "--timeout-ms", "3000"});
  EXPECT_EQ(r.rc, 1);
  j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["outcome"], "nak");
  EXPECT_EQ(j["error"], 0x82);
  EXPECT_EQ(j["error_name"], "illegal parameter number");

  r = run_cli({"dfs1", "status", "--port", port, "--uid", "9", "--timeout-ms", "100"});
  EXPECT_EQ(r.rc, 1);
  EXPECT_NE(r.err.find("timeout (no answer within 100 ms)"), std::string::npos) << r.err;

  r = run_cli({"dfs1", "speed", "--port", port, "--uid", "0", "--execute", "--json"});
  EXPECT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["outcome"], "sent");
  EXPECT_EQ(emu.stop(SIGTERM), 0);
}

// `emulate --port PATH` serves a port that already exists (here the slave of a pty the test made,
// as a USB adapter's /dev/ttyUSB0 would be), says so on its first line once the port is open, takes
// --baud and writes every byte to --log. The test speaks raw bytes on the pty's master side.
TEST(Dfs1Cli, EmulateServesAGivenPortWithItsBaudAndLog) {
  int master = -1;
  int slave = -1;
  char name[128] = {};
  ASSERT_EQ(::openpty(&master, &slave, name, nullptr, nullptr), 0);
  const std::string path = name;
  const std::string log = ::testing::TempDir() + "dfs1_emulate_port_log.txt";
  {
    test::ChildProcess emu({IBS_DFS1_CLI, "dfs1", "emulate", "--port", path, "--baud", "19200", "--log", log,
                            "dfs1@3"});
    ASSERT_EQ(emu.first_line(), "port: " + path);
    // Status (81H) to UID 3: checksum = -(03H + 81H) = 7CH (seed 004's rule).
    const unsigned char request[] = {0x10, 0x02, 0x03, 0x81, 0x10, 0x03, 0x7C};
    ASSERT_EQ(::write(master, request, sizeof request), static_cast<ssize_t>(sizeof request));
    std::string answer;
    pollfd p{master, POLLIN, 0};
    while (answer.size() < 6 && ::poll(&p, 1, 3000) > 0) {
      unsigned char buf[64];
      const ssize_t n = ::read(master, buf, sizeof buf);
      if (n <= 0) break;
      answer.append(reinterpret_cast<const char*>(buf), static_cast<std::size_t>(n));
    }
    ASSERT_GE(answer.size(), 4U) << "no answer on the port";
    EXPECT_EQ(static_cast<unsigned char>(answer[0]), 0x10);
    EXPECT_EQ(static_cast<unsigned char>(answer[1]), 0x02);
    EXPECT_EQ(static_cast<unsigned char>(answer[2]), 0x03) << "the answer of UID 3";
    EXPECT_EQ(emu.stop(SIGTERM), 0);
  }
  ::close(slave);
  ::close(master);
  std::ifstream in(log);
  std::string all((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(all.find(" rx " + path + " 10 02 03 81 10 03 7C"), std::string::npos) << all;
  EXPECT_NE(all.find(" tx " + path + " 10 02 03"), std::string::npos) << all;
}

TEST(Dfs1Cli, BadInputIsExitTwo) {
  EXPECT_EQ(run_cli({"dfs1", "status", "--port", "/dev/ibs-no-such-port", "--uid", "1"}).rc, 2);
  const CliRun zero = run_cli({"dfs1", "status", "--port", "/dev/null", "--uid", "0"});
  EXPECT_EQ(zero.rc, 2);
  EXPECT_NE(zero.err.find("UID 0 is the global address"), std::string::npos) << zero.err;
  EXPECT_EQ(run_cli({"dfs1", "status", "--port", "/dev/null", "--uid", "256"}).rc, 2);
  EXPECT_EQ(run_cli({"dfs1", "speed", "--port", "/dev/null", "--uid", "1"}).rc, 2);
  EXPECT_EQ(run_cli({"dfs1", "emulate", "--pty", "vf1000@1"}).rc, 2);
  EXPECT_EQ(run_cli({"dfs1", "emulate", "--pty", "dfs1@0"}).rc, 2);
  EXPECT_EQ(run_cli({"dfs1", "emulate", "--pty", "dfs1@3", "dfs1@3"}).rc, 2);
  EXPECT_EQ(run_cli({"dfs1", "emulate", "dfs1@3"}).rc, 2);     // neither --port nor --pty
  EXPECT_EQ(run_cli({"dfs1", "status", "--uid", "1"}).rc, 2);  // --port missing
}

TEST(Dfs1Cli, LogRecordsEveryByteWithTimeAndDirection) {
  Emulator emu({"dfs1@1"});
  const std::string log = ::testing::TempDir() + "dfs1_cli_log.txt";
  const CliRun r = run_cli(
      {"dfs1", "status", "--port", emu.pty(), "--uid", "1", "--log", log, "--timeout-ms", "3000"});
  ASSERT_EQ(r.rc, 0) << r.err;
  std::ifstream in(log);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "ibs-serial-log 1");
  std::getline(in, line);
  EXPECT_NE(line.find(" tx " + emu.pty() + " 10 02 01 81 10 03 7E"), std::string::npos) << line;
  std::string rx;
  while (std::getline(in, line)) rx += line.substr(line.rfind(emu.pty()) + emu.pty().size());
  // The 23 bytes of the status answer, maybe in several reads.
  EXPECT_EQ(rx.rfind(" 10 02 01 06", 0), 0U) << rx;
  EXPECT_EQ(emu.stop(SIGTERM), 0);
  std::remove(log.c_str());
}

}  // namespace
}  // namespace ibs::cli
