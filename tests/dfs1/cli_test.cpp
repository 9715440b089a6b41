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
#include <sys/socket.h>
#include <sys/un.h>
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
  // The address is -a/--address on every bus (issue 27.2); --uid, the seed's word, stays.
  const CliRun s = run_cli({"dfs1", "status", "-p", emu.pty(), "-a", "2", "-j", "--timeout-ms", "3000"});
  EXPECT_EQ(s.rc, 0) << s.err;
  EXPECT_NE(s.out.find("\"uid\":2"), std::string::npos) << s.out;
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
    // Status (81H) to UID 3: checksum = -(03H + 81H) = 7CH (DFS-1 manual's rule).
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

// `--repeat N --log FILE`: the readings share one log -- one header, every reading's request in
// it, one time base -- instead of each reading truncating it again (only the last one was left).
TEST(Dfs1Cli, RepeatedReadingsShareOneLog) {
  Emulator emu({"dfs1@1"});
  const std::string log = ::testing::TempDir() + "dfs1_cli_repeat_log.txt";
  const CliRun r = run_cli({"dfs1", "status", "--port", emu.pty(), "--uid", "1", "--log", log, "--repeat", "3",
                            "--interval", "50", "--timeout-ms", "3000"});
  ASSERT_EQ(r.rc, 0) << r.err;
  std::ifstream in(log);
  int headers = 0;
  int requests = 0;
  double last_time = -1;
  bool ordered = true;
  for (std::string line; std::getline(in, line);) {
    if (line == "ibs-serial-log 1") {
      ++headers;
      continue;
    }
    const double t = std::stod(line.substr(0, line.find(' ')));
    ordered = ordered && t >= last_time;
    last_time = t;
    if (line.find(" tx " + emu.pty() + " 10 02 01 81 10 03 7E") != std::string::npos) ++requests;
  }
  EXPECT_EQ(headers, 1);
  EXPECT_EQ(requests, 3);
  EXPECT_TRUE(ordered) << "the readings' times restart";
  EXPECT_EQ(emu.stop(SIGTERM), 0);
  std::remove(log.c_str());
}

// `--log -` (issue 27.1): the byte log on standard output, what the command prints (here its
// JSON) on standard error; for `emulate` too, whose `pty:` line then goes there.
TEST(Dfs1Cli, LogDashWritesTheBytesToStandardOutput) {
  const std::string link = ::testing::TempDir() + "dfs1_log_dash_" + std::to_string(::getpid());
  std::remove(link.c_str());
  test::ChildProcess emu({IBS_DFS1_CLI, "dfs1", "emulate", "--pty-link", link, "--log", "-", "dfs1@1"});
  ASSERT_EQ(emu.first_line(), "ibs-serial-log 1");
  const CliRun r =
      run_cli({"dfs1", "status", "--port", link, "--uid", "1", "--log", "-", "--json", "--timeout-ms", "3000"});
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(r.out.rfind("ibs-serial-log 1\n", 0), 0U) << r.out;
  EXPECT_NE(r.out.find(" tx " + link + " 10 02 01 81 10 03 7E"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find('{'), std::string::npos) << r.out;
  const nlohmann::json j = nlohmann::json::parse(r.err);
  EXPECT_EQ(j["uid"], 1) << r.err;
  ASSERT_EQ(emu.stop(SIGTERM), 0);
  const std::string log = emu.rest();
  EXPECT_NE(log.find(" rx "), std::string::npos) << log;
  EXPECT_NE(log.find(" tx "), std::string::npos) << log;
  EXPECT_EQ(log.find("pty: "), std::string::npos) << log;
}

// `emulate --json` (issue 27.7): one JSON object a line per event in the shape of `ibs lustbus
// emulate --json` -- where it serves, the request in and the reply out of the controller it was
// for (not of the other), a corrupt frame, the counters at the end -- and no text.
TEST(Dfs1Cli, EmulateJsonPrintsOneObjectPerEvent) {
  test::ChildProcess emu({IBS_DFS1_CLI, "dfs1", "emulate", "--pty", "--json", "dfs1@1", "dfs1@2"});
  const nlohmann::json first = nlohmann::json::parse(emu.first_line());
  EXPECT_EQ(first["event"], "serving");
  const std::string port = first["pty"].get<std::string>();
  ASSERT_EQ(port.rfind("/dev/pts/", 0), 0U) << emu.first_line();
  const CliRun r = run_cli({"dfs1", "status", "--port", port, "--uid", "2", "--timeout-ms", "3000"});
  ASSERT_EQ(r.rc, 0) << r.err;
  // The status request of UID 1 with a checksum that is not its own (7E is): a corrupt frame.
  const int fd = ::open(port.c_str(), O_RDWR | O_NOCTTY);
  ASSERT_GE(fd, 0);
  const std::vector<std::uint8_t> bad = {0x10, 0x02, 0x01, 0x81, 0x10, 0x03, 0x7F};
  ASSERT_EQ(::write(fd, bad.data(), bad.size()), static_cast<ssize_t>(bad.size()));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  ::close(fd);
  ASSERT_EQ(emu.stop(SIGTERM), 0);
  std::istringstream in(emu.rest());
  int requests = 0;
  int answers = 0;
  int corrupt = 0;
  int summaries = 0;
  for (std::string line; std::getline(in, line);) {
    nlohmann::json e;
    ASSERT_NO_THROW(e = nlohmann::json::parse(line)) << line;
    ASSERT_TRUE(e.contains("time_s")) << e;
    const std::string what = e["event"];
    if (what == "telegram") {
      EXPECT_EQ(e["kind"], "request") << e;
      EXPECT_EQ(e["device"], "dfs1@2") << e;
      EXPECT_EQ(e["address"], 2) << e;
      EXPECT_EQ(e["bytes"].get<std::string>().rfind("10 02 02 81 10 03", 0), 0U) << e;
      ++requests;
    } else if (what == "answer") {
      EXPECT_EQ(e["address"], 2) << e;
      EXPECT_EQ(e["bytes"].get<std::string>().rfind("10 02 02 06", 0), 0U) << e;  // ACK of UID 2
      ++answers;
    } else if (what == "corrupt") {
      EXPECT_EQ(e["what"], "decode") << e;
      EXPECT_EQ(e["bytes"], "10 02 01 81 10 03 7F") << e;
      ++corrupt;
    } else if (what == "summary") {
      ++summaries;
      EXPECT_EQ(e["counters"]["decode_errors"], 1) << e;
    }
  }
  EXPECT_EQ(requests, 1);
  EXPECT_EQ(answers, 1);
  EXPECT_EQ(corrupt, 2);  // each controller reads every frame on the line
  EXPECT_EQ(summaries, 2);
}

// --- `emulate --control` (docs/dfs1.md, "Faults on demand") ---

// `sh -c "exec ibs dfs1 emulate --pty ARGS 2>ERR [<<here-document]"`: the emulator as the child
// itself (exec), its standard error in a file the test reads.
class ControlledEmulator : public test::ChildProcess {
 public:
  ControlledEmulator(const std::string& args, const std::string& err_file, const std::string& stdin_text = "")
      : ChildProcess({"/bin/sh", "-c", command(args, err_file, stdin_text)}), err_file_(err_file) {}
  std::string err() const {
    std::ifstream in(err_file_);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
  // Waits up to 5 s for `text` on standard error.
  bool err_has(const std::string& text) const {
    for (int i = 0; i < 250; ++i) {
      if (err().find(text) != std::string::npos) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return false;
  }

 private:
  static std::string command(const std::string& args, const std::string& err_file, const std::string& stdin_text) {
    std::string c = std::string("exec ") + IBS_DFS1_CLI + " dfs1 emulate --pty " + args + " 2>" + err_file;
    if (!stdin_text.empty()) c += " <<'IBS_EOF'\n" + stdin_text + "IBS_EOF\n";
    return c;
  }
  std::string err_file_;
};

// Connects to the control socket at `path` and sends `text`; closes when `close` (end of input).
int send_control(const std::string& path, const std::string& text, int fd = -1) {
  if (fd < 0) {
    fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    std::snprintf(addr.sun_path, sizeof addr.sun_path, "%s", path.c_str());
    if (::connect(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0) {
      ::close(fd);
      return -1;
    }
  }
  if (::write(fd, text.data(), text.size()) != static_cast<ssize_t>(text.size())) {
    ::close(fd);
    return -1;
  }
  return fd;
}

// The status the host reads, in JSON, once `pred` holds on it (or after 5 s).
template <typename Pred>
nlohmann::json status_until(const std::string& port, int uid, Pred pred) {
  nlohmann::json j;
  for (int i = 0; i < 100; ++i) {
    const CliRun r =
        run_cli({"dfs1", "status", "--port", port, "--uid", std::to_string(uid), "--json", "--timeout-ms", "3000"});
    if (r.rc == 0) {
      j = nlohmann::json::parse(r.out);
      if (pred(j)) return j;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return j;
}

std::string unique_path(const std::string& what) {
  return "/tmp/ibs-dfs1-" + what + "-" + std::to_string(::getpid());
}

TEST(Dfs1Cli, AFaultSentOnTheControlSocketShowsInTheStatusTheHostReads) {
  const std::string sock = unique_path("control.sock");
  const std::string err = unique_path("emulator.err");
  ::unlink(sock.c_str());
  ControlledEmulator emu("--control unix:" + sock + " dfs1@1 dfs1@7", err);
  ASSERT_EQ(emu.first_line().rfind("pty: ", 0), 0U) << emu.first_line();
  const std::string port = emu.pty();

  // A bad line first: reported with its client and number, skipped; the emulator goes on serving.
  int fd = send_control(sock, "{\"device\": \"dfs1@7\", \"fault\": \"melt\"}\n");
  ASSERT_GE(fd, 0);
  EXPECT_TRUE(emu.err_has("control:1:1: \"fault\": \"melt\" is no DFS-1 fault event; allowed: \"device\", "
                          "\"power-cycle\"\n"))
      << emu.err();
  ASSERT_GE(send_control(sock, "not json\n", fd), 0);
  EXPECT_TRUE(emu.err_has("control:1:2: not JSON: ")) << emu.err();
  ASSERT_GE(send_control(sock, "{\"fault\": \"device\", \"cause\": \"IOC\"}\n", fd), 0);
  EXPECT_TRUE(emu.err_has("control:1:3: no \"device\": 2 controllers are served (dfs1@1, dfs1@7); name one"))
      << emu.err();

  ASSERT_GE(send_control(sock, "{\"device\": \"dfs1@7\", \"fault\": \"device\", \"cause\": \"Overvolt\"}\n", fd), 0);
  ::close(fd);  // end of this client's input: the emulator serves on
  const auto j = status_until(port, 7, [](const nlohmann::json& s) { return s["st1"] == 0x02; });
  EXPECT_EQ(j["st1"], 0x02) << j.dump();
  EXPECT_EQ(j["st1_flags"], nlohmann::json::array({"overvolt"})) << j.dump();
  EXPECT_EQ(j["st2"].get<int>() & 0x08, 0x08) << j.dump();  // ST2 fault
  // The applied event on standard error: time, controller, what happened.
  EXPECT_TRUE(emu.err_has(": dfs1@7: fault Overvolt, its cause gone at once; the motor coasts, the fault is latched"))
      << emu.err();
  // The other controller is untouched.
  EXPECT_EQ(status_until(port, 1, [](const nlohmann::json&) { return true; })["st1"], 0);

  // The next client: its own number, its lines from 1; the E-stop opened resets the fault.
  fd = send_control(sock, "{\"device\": 7, \"input\": \"E-stop\", \"level\": \"low\"}\n{\"device\": 9, \"mains\": \"off\"}\n");
  ASSERT_GE(fd, 0);
  EXPECT_TRUE(emu.err_has("control:2:2: \"device\": UID 9 is not served here; served: dfs1@1, dfs1@7")) << emu.err();
  EXPECT_EQ(status_until(port, 7, [](const nlohmann::json& s) { return s["st1"] == 0; })["st1"], 0);
  ::close(fd);
  EXPECT_EQ(emu.stop(SIGTERM), 0);
  ::unlink(err.c_str());
  // The socket is removed at exit.
  EXPECT_NE(::access(sock.c_str(), F_OK), 0);
}

TEST(Dfs1Cli, EndOfStandardInputDoesNotEndTheEmulator) {
  const std::string err = unique_path("stdin.err");
  ControlledEmulator emu("--control - dfs1@4", err, "{\"mains\": \"off\"}\n{\"load\": 300}\n");
  ASSERT_EQ(emu.first_line().rfind("pty: ", 0), 0U) << emu.first_line();
  const auto j = status_until(emu.pty(), 4, [](const nlohmann::json& s) { return s["st1"] == 0x80; });
  EXPECT_EQ(j["st1_flags"], nlohmann::json::array({"bus-not-charged"})) << j.dump();
  EXPECT_TRUE(emu.err_has("control:2: \"load\": 300; allowed: a whole number of percent of the drive's rating, 0..200"))
      << emu.err();
  EXPECT_TRUE(emu.err_has(": dfs1@4: mains off; the bus is not charged")) << emu.err();
  // Standard input has ended long ago; the emulator still answers.
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_EQ(run_cli({"dfs1", "status", "--port", emu.pty(), "--uid", "4", "--timeout-ms", "3000"}).rc, 0);
  EXPECT_EQ(emu.stop(SIGTERM), 0);
  ::unlink(err.c_str());
}

TEST(Dfs1Cli, AControlSocketPathThatExistsIsRefused) {
  const std::string path = unique_path("exists");
  { std::ofstream(path) << "x"; }
  const CliRun r = run_cli({"dfs1", "emulate", "--pty", "--control", "unix:" + path, "dfs1@1"});
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find(path + " exists"), std::string::npos) << r.err;
  std::remove(path.c_str());
  const CliRun bad = run_cli({"dfs1", "emulate", "--pty", "--control", "tcp:1234", "dfs1@1"});
  EXPECT_EQ(bad.rc, 2);
  EXPECT_NE(bad.err.find("give - (standard input) or unix:PATH"), std::string::npos) << bad.err;
}

TEST(Dfs1Cli, ControlLinesAreJsonObjects) {
  EXPECT_TRUE(parse_dfs1_control_line(R"({"device": "dfs1@7", "fault": "device", "cause": "IOC", "duration": "0.5 s"})")
                  .event);
  EXPECT_EQ(parse_dfs1_control_line("[1]").error,
            "expected a JSON object like {\"fault\": \"device\", \"cause\": \"IOC\"}, got an array");
  EXPECT_EQ(parse_dfs1_control_line("\"mains\"").error,
            "expected a JSON object like {\"fault\": \"device\", \"cause\": \"IOC\"}, got a string");
  EXPECT_EQ(parse_dfs1_control_line("{\"mains\": \"off\"").error.rfind("not JSON: ", 0), 0U);
  EXPECT_EQ(parse_dfs1_control_line(R"({"load": true})").error,
            "\"load\": expected a whole number of percent of the drive's rating, 0..200, got a boolean");
  EXPECT_EQ(parse_dfs1_control_line(R"({"input": [3], "level": "high"})").error.rfind("\"input\": expected ", 0), 0U);
  EXPECT_EQ(parse_dfs1_control_line(R"({"mains": "off", "colour": {}})").error,
            "unknown key \"colour\"; a DFS-1 control line takes device, fault, cause, duration, mains, input, level, load");
}

}  // namespace
}  // namespace ibs::cli
