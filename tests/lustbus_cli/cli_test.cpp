// `ibs lustbus ...`: `emulate --pty` as a process (prints `pty: PATH` first, serves, exits 0 on
// SIGTERM and SIGINT), read / write / describe / scan in process against it, JSON, a NAK exiting 1
// with its cause, bad input exiting 2 with the parameter, value and limit, and the byte log.
#include <gtest/gtest.h>
#include <filesystem>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>
#include <sys/socket.h>
#include <sys/un.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <fcntl.h>
#include <poll.h>
#include <fstream>
#include <thread>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "ibs/devices/drives.hpp"
#include "lustbus_cmd.hpp"
#include "serial_decode.hpp"

#include "../support/cli_harness.hpp"

namespace ibs::cli {
namespace {

using test::CliRun;

CliRun run_cli(std::vector<std::string> args) {
  return test::run_cli_group<LustbusCommandState>(std::move(args), kExitLustbusBadInput, add_lustbus_commands,
                                                  run_lustbus_commands);
}

// `lustbus emulate --pty DEVICES...` as a child process; the first line of its output is the pty.
class Emulator : public test::ChildProcess {
 public:
  explicit Emulator(const std::vector<std::string>& devices) : ChildProcess(argv(devices)) {}

 private:
  static std::vector<std::string> argv(const std::vector<std::string>& devices) {
    std::vector<std::string> a = {IBS_CLI, "lustbus", "emulate", "--pty"};
    a.insert(a.end(), devices.begin(), devices.end());
    return a;
  }
};

std::vector<std::string> cmd(std::vector<std::string> a, const std::string& port) {
  std::vector<std::string> v = {"lustbus"};
  v.insert(v.end(), a.begin(), a.end());
  v.insert(v.end(), {"--port", port, "--timeout-ms", "2000"});
  return v;
}

// Writes `text` to the Unix socket at `path` as one client (connects, writes, closes).
bool send_to_socket(const std::string& path, const std::string& text) {
  const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
  if (fd < 0) return false;
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::snprintf(addr.sun_path, sizeof addr.sun_path, "%s", path.c_str());
  bool ok = false;
  for (int i = 0; i < 100 && !ok; ++i) {
    ok = ::connect(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) == 0;
    if (!ok) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ok = ok && ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  ::close(fd);
  return ok;
}

// A parameter's raw value read with `ibs lustbus read --json` until `done(raw)` (up to 3 s).
template <typename F>
long read_until(const std::string& port, std::vector<std::string> what, F&& done) {
  long raw = -1;
  for (int i = 0; i < 30; ++i) {
    std::vector<std::string> a = {"read"};
    a.insert(a.end(), what.begin(), what.end());
    a.push_back("--json");
    const CliRun r = run_cli(cmd(a, port));
    if (r.rc == 0) {
      raw = nlohmann::json::parse(r.out)["raw"].get<long>();
      if (done(raw)) return raw;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return raw;
}

// Issue 24: `emulate --control unix:PATH` takes events for the drives it serves; a device fault
// injected over the socket is what the host then reads as the drive's error (11-STAT 80H, seed
// 000 8.1.1), an MC6000 input shows in 408-IBSTA bit 14 (INTERBUS manual 5.3.2).
TEST(LustbusCli, EmulateTakesEventsOnItsControlSocket) {
  const std::string socket = ::testing::TempDir() + "lustbus_control_" + std::to_string(::getpid()) + ".sock";
  ::unlink(socket.c_str());
  Emulator emu({"--control", "unix:" + socket, "vf1000@1", "mc6000@3"});
  ASSERT_EQ(emu.first_line().rfind("pty: ", 0), 0U) << emu.first_line();
  const std::string port = emu.pty();
  const auto stat_error = [](long raw) { return (raw & 0x80) != 0; };
  EXPECT_FALSE(stat_error(read_until(port, {"--addr", "1", "--device", "vf1000", "STAT"}, [](long) { return true; })));
  ASSERT_TRUE(send_to_socket(socket, "{\"device\": 1, \"fault\": \"device\", \"cause\": \"E-IBS\"}\n"
                                     "{\"device\": \"mc6000@3\", \"input\": \"IS00\", \"level\": \"high\"}\n"));
  EXPECT_TRUE(stat_error(read_until(port, {"--addr", "1", "--device", "vf1000", "STAT"}, stat_error)))
      << "11-STAT shows the injected error";
  const long ibsta = read_until(port, {"--addr", "3", "--device", "mc6000", "408"}, [](long raw) { return (raw & 0x4000) != 0; });
  EXPECT_EQ(ibsta & 0x4000, 0x4000) << "IS00 in 408-IBSTA bit 14";
  EXPECT_EQ(emu.stop(SIGTERM), 0);
  EXPECT_NE(::access(socket.c_str(), F_OK), 0) << "the socket is removed at exit";
}

TEST(LustbusCli, EmulatePrintsThePtyFirstAndExitsZeroOnSignals) {
  Emulator a({"vf1000@1"});
  ASSERT_EQ(a.first_line().rfind("pty: /dev/pts/", 0), 0U) << a.first_line();
  EXPECT_EQ(a.stop(SIGTERM), 0);
  Emulator b({"mc6000@2"});
  ASSERT_EQ(b.first_line().rfind("pty: ", 0), 0U);
  EXPECT_EQ(b.stop(SIGINT), 0);
}

// --pty-link PATH (socat's pty,link=): a stable name for the pty while the emulator runs, removed
// at exit; a PATH that exists is refused before anything is served, and left as it was.
TEST(LustbusCli, PtyLinkNamesThePtyWhileItRunsAndNeverReplacesAFile) {
  const std::string dir = ::testing::TempDir() + "lustbus_pty_link";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string link = dir + "/drive";
  {
    test::ChildProcess emu({IBS_CLI, "lustbus", "emulate", "--pty-link", link, "vf1000@1"});
    ASSERT_EQ(emu.first_line().rfind("pty: /dev/pts/", 0), 0U) << emu.first_line();
    ASSERT_TRUE(std::filesystem::is_symlink(link));
    EXPECT_EQ(std::filesystem::read_symlink(link).string(), emu.pty());
    // A host uses the link as its port.
    const CliRun r = run_cli(cmd({"read", "--addr", "1", "--device", "vf1000", "FSSEL"}, link));
    EXPECT_EQ(r.rc, 0) << r.err;
    // One name for one thing (issue 27.2): -a/--address (--addr stays), -p/--port, -j/--json.
    for (const std::vector<std::string>& a :
         {std::vector<std::string>{"lustbus", "read", "-p", link, "-a", "1", "--device", "vf1000", "FSSEL", "-j"},
          std::vector<std::string>{"lustbus", "read", "--port", link, "--address", "1", "--device", "vf1000", "FSSEL", "--json"}}) {
      const CliRun s = run_cli(a);
      ASSERT_EQ(s.rc, 0) << s.err;
      EXPECT_EQ(nlohmann::json::parse(s.out)["address"], 1) << s.out;
    }
    // Polling (issue 27.4, mbpoll's -1/-l): one JSON object per reading, the count at the end.
    const CliRun polled =
        run_cli({"lustbus", "read", "-p", link, "-a", "1", "--device", "vf1000", "FSSEL", "-j", "--repeat", "3", "--interval", "20"});
    ASSERT_EQ(polled.rc, 0) << polled.err;
    std::istringstream lines(polled.out);
    int objects = 0;
    for (std::string line; std::getline(lines, line);) {
      EXPECT_EQ(nlohmann::json::parse(line)["raw"], 0) << line;  // 4-FSSEL of a drive on LUSTBUS alone (VF-E20)
      ++objects;
    }
    EXPECT_EQ(objects, 3) << polled.out;
    EXPECT_NE(polled.err.find("ibs lustbus read: 3 readings, 3 ok, 0 failed"), std::string::npos) << polled.err;
    // With --log the readings share one log: one header, and three times the bytes one reading
    // sends (each reading truncated it again before).
    const std::string one_log = dir + "/one.log";
    const std::string three_log = dir + "/three.log";
    ASSERT_EQ(run_cli({"lustbus", "read", "-p", link, "-a", "1", "--device", "vf1000", "FSSEL", "--log", one_log}).rc, 0);
    const CliRun logged = run_cli({"lustbus", "read", "-p", link, "-a", "1", "--device", "vf1000", "FSSEL", "--repeat",
                                   "3", "--interval", "20", "--log", three_log});
    ASSERT_EQ(logged.rc, 0) << logged.err;
    const auto sent = [](const std::string& path, int& headers) {
      std::ifstream in(path);
      std::string bytes;
      headers = 0;
      for (std::string line; std::getline(in, line);) {
        if (line == "ibs-serial-log 1") ++headers;
        else if (const auto at = line.find(" tx "); at != std::string::npos) bytes += line.substr(line.find(' ', at + 4)) + ";";
      }
      return bytes;
    };
    int one_headers = 0;
    int three_headers = 0;
    const std::string one = sent(one_log, one_headers);
    const std::string three = sent(three_log, three_headers);
    EXPECT_EQ(one_headers, 1);
    EXPECT_EQ(three_headers, 1);
    ASSERT_FALSE(one.empty());
    EXPECT_EQ(three, one + one + one);
    EXPECT_EQ(emu.stop(SIGTERM), 0);
  }
  EXPECT_FALSE(std::filesystem::exists(std::filesystem::symlink_status(link))) << "the link stays after exit";
  // A path that exists is never replaced.
  { std::ofstream(link) << "mine\n"; }
  const CliRun r = run_cli({"lustbus", "emulate", "--pty-link", link, "vf1000@1"});
  EXPECT_EQ(r.rc, kExitLustbusBadInput);
  EXPECT_NE(r.err.find("--pty-link " + link + ": exists already"), std::string::npos) << r.err;
  std::ifstream in(link);
  std::string text;
  std::getline(in, text);
  EXPECT_EQ(text, "mine");
  std::filesystem::remove_all(dir);
}

TEST(LustbusCli, ReadWriteDescribeScanWithJsonAndLog) {
  Emulator emu({"vf1000@1", "mc6000@3"});
  const std::string port = emu.pty();
  const std::string log = ::testing::TempDir() + "lustbus_cli.log";
  CliRun r = run_cli(cmd({"write", "--addr", "1", "--device", "vf1000", "FSSIO", "23.15", "--log", log}, port));
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(r.out, "vf1000@1 5-FSSIO := 23.15 Hz (01CFH)\n");
  r = run_cli(cmd({"read", "--addr", "1", "--device", "vf1000", "5", "--json"}, port));
  ASSERT_EQ(r.rc, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["raw"], 463);
  EXPECT_DOUBLE_EQ(j["value"].get<double>(), 23.15);
  EXPECT_EQ(j["unit"], "Hz");
  r = run_cli(cmd({"write", "--addr", "3", "--device", "mc6000", "RSIO", "0x842666", "--json"}, port));
  ASSERT_EQ(r.rc, 0) << r.err;
  j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["raw"], 0x842666);
  r = run_cli(cmd({"describe", "--addr", "1", "--device", "vf1000", "VB2"}, port));
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(r.out, "vf1000@1 45-VB2: VB2, kind 2, PT_FIXPOINT16, min 0.00, max 25.00, default 8.00\n");
  r = run_cli(cmd({"describe", "--addr", "3", "--device", "mc6000", "417", "--json"}, port));
  ASSERT_EQ(r.rc, 0) << r.err;
  j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["value"]["name"], "RSSL1");
  EXPECT_EQ(j["value"]["max"], "7");
  // The description's binary VALUE goes out as hex bytes: no JSON string holds a NUL (issue 27.7).
  EXPECT_EQ(r.out.find("\\u0000"), std::string::npos) << r.out;
  EXPECT_FALSE(j.contains("raw")) << r.out;
  EXPECT_EQ(j["raw_hex"].get<std::string>().rfind("52 53 53 4C 31 ", 0), 0U) << r.out;  // "RSSL1"
  for (const auto& [key, v] : j["value"].items()) {
    if (v.is_string()) {
      EXPECT_EQ(v.get<std::string>().find('\0'), std::string::npos) << key;
    }
  }
  r = run_cli({"lustbus", "scan", "--port", port});
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(r.out,
            "address 1: VF1000 (inverter), 91-TYPE 1000\n"
            "address 3: MC6000 (servo), 91-TYPE 6000\n");
  std::ifstream in(log);
  std::string first;
  std::getline(in, first);
  EXPECT_EQ(first, "ibs-serial-log 1");
  std::string line;
  std::getline(in, line);
  EXPECT_NE(line.find(" tx "), std::string::npos) << line;
  EXPECT_NE(line.find("04 41 02 30 30 31 30 35 3D 30 31 43 46 03"), std::string::npos) << line;
  EXPECT_EQ(emu.stop(SIGTERM), 0);
}

// `--log -` (issue 27.1): the byte log on standard output, what the command prints on standard
// error; for the host commands and for `emulate`, whose `pty:` line then goes there too.
TEST(LustbusCli, LogDashWritesTheBytesToStandardOutput) {
  const std::string link = ::testing::TempDir() + "lustbus_log_dash_" + std::to_string(::getpid());
  std::filesystem::remove(link);
  test::ChildProcess emu({IBS_CLI, "lustbus", "emulate", "--pty-link", link, "--log", "-", "vf1000@1"});
  ASSERT_EQ(emu.first_line(), "ibs-serial-log 1");
  CliRun r = run_cli(cmd({"write", "--addr", "1", "--device", "vf1000", "FSSIO", "23.15", "--log", "-"}, link));
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(r.err, "vf1000@1 5-FSSIO := 23.15 Hz (01CFH)\n");
  EXPECT_EQ(r.out.rfind("ibs-serial-log 1\n", 0), 0U) << r.out;
  EXPECT_NE(r.out.find(" tx " + link), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("04 41 02 30 30 31 30 35 3D 30 31 43 46 03"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("FSSIO"), std::string::npos) << r.out;
  ASSERT_EQ(emu.stop(SIGTERM), 0);
  // The emulator's side of the same telegram: received, then its answer sent.
  const std::string log = emu.rest();
  EXPECT_NE(log.find(" rx "), std::string::npos) << log;
  EXPECT_NE(log.find(" tx "), std::string::npos) << log;
  EXPECT_EQ(log.find("pty: "), std::string::npos) << log;
}

// Every line of `text` as JSON; a line that is not fails the test.
std::vector<nlohmann::json> json_lines(const std::string& text) {
  std::vector<nlohmann::json> v;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    try {
      v.push_back(nlohmann::json::parse(line));
    } catch (const nlohmann::json::exception&) {
      ADD_FAILURE() << "not JSON: " << line;
    }
  }
  return v;
}

// `emulate --json` (issue 27.7): one JSON object a line per event -- where it serves, each
// telegram in and answer out with time, device and address, a corrupt telegram, an event from the
// control channel (a fault, a load), the counters at the end -- and no text on standard output.
TEST(LustbusCli, EmulateJsonPrintsOneObjectPerEvent) {
  const std::string errors = ::testing::TempDir() + "lustbus_emulate_json_err.txt";
  test::ChildProcess emu({"/bin/sh", "-c",
                          std::string("exec ") + IBS_CLI + " lustbus emulate --pty --json --control - vf1000@1 mc6000@3 2>" +
                              errors + " <<'IBS_EOF'\n{\"device\": \"mc6000@3\", \"load\": 2.5}\nIBS_EOF\n"});
  const nlohmann::json first = nlohmann::json::parse(emu.first_line());
  EXPECT_EQ(first["event"], "serving");
  EXPECT_EQ(first["time_s"], 0.0);
  const std::string port = first["pty"].get<std::string>();
  ASSERT_EQ(port.rfind("/dev/pts/", 0), 0U) << emu.first_line();
  CliRun r = run_cli(cmd({"write", "--addr", "1", "--device", "vf1000", "FSSIO", "23.15"}, port));
  ASSERT_EQ(r.rc, 0) << r.err;
  // EOT, 'A', STX, 00105=03E8, ETX and a BCC that is not theirs: NAK (3).
  const int fd = ::open(port.c_str(), O_RDWR | O_NOCTTY);
  ASSERT_GE(fd, 0);
  const std::vector<std::uint8_t> bad = {0x04, 0x41, 0x02, '0', '0', '1', '0', '5', '=', '0', '3', 'E', '8', 0x03, 0x00};
  ASSERT_EQ(::write(fd, bad.data(), bad.size()), static_cast<ssize_t>(bad.size()));
  std::vector<std::uint8_t> got;
  for (const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
       got.size() < 2 && std::chrono::steady_clock::now() < until;) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 50) <= 0) continue;
    std::uint8_t b[16];
    const ssize_t n = ::read(fd, b, sizeof b);
    if (n > 0) got.insert(got.end(), b, b + n);
  }
  ::close(fd);
  EXPECT_EQ(got, (std::vector<std::uint8_t>{0x41, 0x15}));
  ASSERT_EQ(emu.stop(SIGTERM), 0);
  const std::vector<nlohmann::json> events = json_lines(emu.rest());
  int selects = 0;
  int answers = 0;
  int corrupt = 0;
  int controls = 0;
  int summaries = 0;
  double last = 0.0;
  for (const nlohmann::json& e : events) {
    ASSERT_TRUE(e.contains("time_s") && e.contains("event")) << e;
    EXPECT_GE(e["time_s"].get<double>(), last) << e;
    last = e["time_s"].get<double>();
    const std::string what = e["event"];
    if (what == "telegram" && e["kind"] == "select") {
      EXPECT_EQ(e["device"], "vf1000@1") << e;
      EXPECT_EQ(e["address"], 1) << e;
      // EOT, 'A', STX, 00105=01CF, ETX, BCC (6.2).
      EXPECT_EQ(e["bytes"].get<std::string>().rfind("04 41 02 30 30 31 30 35 3D 30 31 43 46 03 ", 0), 0U) << e;
      EXPECT_EQ(e["bytes"].get<std::string>().size(), 15U * 3 - 1) << e;
      ++selects;
    } else if (what == "answer") {
      EXPECT_EQ(e["address"], 1) << e;
      ++answers;
    } else if (what == "corrupt") {
      EXPECT_EQ(e["what"], "checksum") << e;
      EXPECT_EQ(e["bytes"], "04 41 02 30 30 31 30 35 3D 30 33 45 38 03 00") << e;
      ++corrupt;
    } else if (what == "control") {
      EXPECT_EQ(e["device"], "mc6000@3") << e;
      EXPECT_EQ(e["address"], 3) << e;
      EXPECT_EQ(e["control_line"], 1) << e;
      EXPECT_EQ(e["taken"], true) << e;
      ++controls;
    } else if (what == "summary") {
      ++summaries;
      EXPECT_EQ(e["counters"]["checksum_errors"], e["address"] == 1 ? 1 : 0) << e;
    }
  }
  // 9.2: the first SELECT meets the power-on bit (NAK), the host reads 85 and selects again.
  EXPECT_EQ(selects, 2);
  EXPECT_EQ(answers, 4);  // NAK, the 85 value, ACK, NAK for the bad BCC
  EXPECT_EQ(corrupt, 1);
  EXPECT_EQ(controls, 1);
  EXPECT_EQ(summaries, 2);
}

TEST(LustbusCli, NakExitsOneWithTheCause) {
  Emulator emu({"vf1000@1"});
  const std::string port = emu.pty();
  // 7.1: control on the serial interface, then the start.
  ASSERT_EQ(run_cli(cmd({"write", "--addr", "1", "--device", "vf1000", "MODE", "0"}, port)).rc, 0);
  ASSERT_EQ(run_cli(cmd({"write", "--addr", "1", "--device", "vf1000", "CSEL", "3"}, port)).rc, 0);
  // A reference above 0 Hz: at 0 Hz the inverter shuts the motor down (INTERBUS manual 5.2.3, VF-E19).
  ASSERT_EQ(run_cli(cmd({"write", "--addr", "1", "--device", "vf1000", "FSSEL", "8"}, port)).rc, 0);
  ASSERT_EQ(run_cli(cmd({"write", "--addr", "1", "--device", "vf1000", "FSSIO", "5"}, port)).rc, 0);
  ASSERT_EQ(run_cli(cmd({"write", "--addr", "1", "--device", "vf1000", "CNTL", "0x80"}, port)).rc, 0);
  // 3: an EEPROM parameter while the power stage runs: NAK, 40H.
  const CliRun r = run_cli(cmd({"write", "--addr", "1", "--device", "vf1000", "MODE", "4"}, port));
  EXPECT_EQ(r.rc, 1);
  EXPECT_NE(r.err.find("vf1000@1 1-MODE: nak, 85-SIOF 40H: no change permitted"), std::string::npos)
      << r.err;
  const CliRun none = run_cli({"lustbus", "read", "--addr", "9", "--device", "vf1000", "5", "--port", port, "--timeout-ms", "200"});
  EXPECT_EQ(none.rc, 1);
  EXPECT_NE(none.err.find("no answer"), std::string::npos) << none.err;
}

TEST(LustbusCli, BadInputExitsTwoWithAClearMessage) {
  const std::string port = "/dev/null-no-such-port";
  CliRun r = run_cli(cmd({"write", "--addr", "1", "--device", "vf1000", "FSSEL", "26"}, port));
  EXPECT_EQ(r.rc, 2);
  EXPECT_EQ(r.err, "ibs lustbus write: 4-FSSEL: value 26 is above the maximum 25\n");
  r = run_cli(cmd({"write", "--addr", "1", "--device", "vf1000", "FSSIO", "-1"}, port));
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("5-FSSIO: value -1 does not fit PT_FIXPOINT16"), std::string::npos) << r.err;
  r = run_cli(cmd({"write", "--addr", "1", "--device", "vf1000", "TYPE", "1"}, port));
  EXPECT_EQ(r.err, "ibs lustbus write: 91-TYPE is read-only\n");
  r = run_cli(cmd({"read", "--addr", "1", "--device", "vf1000", "FOO"}, port));
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("parameter 'FOO'"), std::string::npos) << r.err;
  r = run_cli(cmd({"read", "--addr", "1", "--device", "mc7000", "5"}, port));
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("--device 'mc7000'"), std::string::npos) << r.err;
  r = run_cli(cmd({"write", "--addr", "3", "--device", "mc6000", "RSSL1", "0x1FF"}, port));
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("not a 8-bit hex number"), std::string::npos) << r.err;
  r = run_cli(cmd({"read", "--addr", "31", "--device", "vf1000", "5"}, port));
  EXPECT_EQ(r.rc, 2);
  r = run_cli(cmd({"read", "--addr", "1", "--device", "vf1000", "5"}, port));
  EXPECT_EQ(r.rc, 2);  // the port does not open
  r = run_cli({"lustbus", "emulate", "--pty", "vf1000@31"});
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("device 'vf1000@31'"), std::string::npos) << r.err;
  r = run_cli({"lustbus", "emulate", "--pty", "vf1000@2", "mc6000@2"});
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("address 2 is given twice"), std::string::npos) << r.err;
}

// Issue: the drives' settings are the wings' declarations. `emulate` offers one option per setting a
// LUSTBUS face declares, and --keypad (both drives' KEYPAD, LUSTBUS manual 10) reaches them.
TEST(LustbusCli, EmulateTakesTheSettingsTheLustbusFacesDeclare) {
  for (const devices::Drive* d : devices::drives_on(devices::Bus::lustbus)) {
    for (const devices::SettingSpec& spec : d->lustbus->settings) {
      SCOPED_TRACE(std::string(d->name) + " " + std::string(spec.name));
      CLI::App app{"test"};
      LustbusCommandState state;
      add_lustbus_commands(app, state);
      const CLI::Option* option = state.emulate->get_option_no_throw("--" + std::string(spec.name));
      ASSERT_NE(option, nullptr);
      EXPECT_NE(option->get_description().find(std::string(spec.meaning)), std::string::npos)
          << option->get_description();
    }
  }
  CLI::App app{"test"};
  LustbusCommandState state;
  add_lustbus_commands(app, state);
  std::vector<std::string> args = {"lustbus", "emulate", "--pty", "--keypad", "vf1000@1", "mc6000@3"};
  std::reverse(args.begin(), args.end());
  app.parse(args);
  const devices::SettingValue* keypad = state.emulate_options.settings.find("keypad");
  ASSERT_NE(keypad, nullptr);
  EXPECT_EQ(keypad->value, 1);
  // Both drives declare a KEYPAD for LUSTBUS (LUSTBUS manual 10): both take it.
  const std::vector<ServedLustbusDrive> served = {
      {"vf1000@1", devices::find_drive("vf1000", devices::Bus::lustbus)->lustbus},
      {"mc6000@3", devices::find_drive("mc6000", devices::Bus::lustbus)->lustbus}};
  const auto settings = lustbus_drive_settings(state.emulate_options.settings, served);
  ASSERT_EQ(settings.size(), 2U);
  for (const devices::SettingValues& s : settings) EXPECT_TRUE(s.given("keypad"));
  // A setting of another face is no option of `emulate`: reset_time is the VF1000's INTERBUS one.
  const CliRun r = run_cli({"lustbus", "emulate", "--pty", "--reset_time", "2", "vf1000@1"});
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("--reset_time"), std::string::npos) << r.err;
}

TEST(LustbusCli, EmulateWithAKeypadServes) {
  test::ChildProcess emu({IBS_CLI, "lustbus", "emulate", "--pty", "--keypad", "vf1000@1", "mc6000@3"});
  ASSERT_EQ(emu.first_line().rfind("pty: ", 0), 0U) << emu.first_line();
  CliRun r = run_cli(cmd({"read", "--addr", "1", "--device", "vf1000", "TYPE"}, emu.pty()));
  EXPECT_EQ(r.rc, 0) << r.err;
  r = run_cli(cmd({"read", "--addr", "3", "--device", "mc6000", "TYPE"}, emu.pty()));
  EXPECT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(emu.stop(SIGTERM), 0);
}

// A setting goes to the drives whose face declares it; one that no served drive declares, or a
// value out of its range, is refused naming it (faces of a test's own, so that one declares a
// setting the other does not).
TEST(LustbusCli, ADriveSettingGoesOnlyToTheDrivesThatDeclareIt) {
  static constexpr devices::SettingSpec kLevel{.name = "level",
                                               .kind = devices::SettingKind::integer,
                                               .min = 0,
                                               .max = 3,
                                               .fallback = 0,
                                               .unit = "",
                                               .parameter = "",
                                               .seed = "LUSTBUS manual 10",
                                               .faces = static_cast<std::uint8_t>(devices::SettingFace::lustbus),
                                               .meaning = "a level",
                                               .range = "0..3",
                                               .elsewhere = ""};
  static constexpr std::array kSettings{kLevel};
  devices::LustbusFace with;
  with.settings = kSettings;
  const devices::LustbusFace without;
  devices::SettingValues given;
  given.set_integer("level", 2);
  const std::vector<ServedLustbusDrive> both = {{"a@1", &with}, {"b@2", &without}};
  const auto settings = lustbus_drive_settings(given, both);
  ASSERT_EQ(settings.size(), 2U);
  EXPECT_EQ(settings[0].value(kLevel), 2);
  EXPECT_TRUE(settings[1].empty());
  EXPECT_TRUE(lustbus_drive_settings({}, both)[0].empty());
  const std::vector<ServedLustbusDrive> other = {{"b@2", &without}, {"b@3", &without}};
  try {
    (void)lustbus_drive_settings(given, other);
    ADD_FAILURE() << "a setting no served drive declares was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "--level applies to none of the drives served (b@2, b@3): no LUSTBUS face of theirs declares 'level'");
  }
  given.set_integer("level", 5);
  try {
    (void)lustbus_drive_settings(given, both);
    ADD_FAILURE() << "a value out of range was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "device 'a@1': --level 5 is out of range (0..3, LUSTBUS manual 10)");
  }
  given.set_boolean("level", true);
  EXPECT_THROW((void)lustbus_drive_settings(given, both), std::invalid_argument);
}

// At its end `emulate` says on stderr, drive by drive, what its receiver took, answered and threw
// away, as `ibs dfs1 emulate` does for its controllers: a SELECT with a wrong BCC (3: NAK), a
// telegram whose host fell silent (LB-D23), an improper one (3: no answer), an answer the host's EOT
// cut (3). The VF1000 at 1 hears them all; the MC6000 at 3 only the ENQUIRY addressed to it.
TEST(LustbusCli, EmulateTellsWhatItServedAndDiscardedWhenItEnds) {
  const std::string errors = ::testing::TempDir() + "lustbus_emulate_counts.txt";
  // A reaction time of 200 ms: an EOT right after an ENQUIRY comes before its answer is due.
  test::ChildProcess emu({"/bin/sh", "-c",
                          std::string("exec ") + IBS_CLI + " lustbus emulate --pty --reaction-ms 200 vf1000@1 mc6000@3 2>" +
                              errors});
  ASSERT_EQ(emu.first_line().rfind("pty: ", 0), 0U) << emu.first_line();
  const std::string port = emu.pty();
  // 9.2: the first SELECT after the start meets the power-on bit of 85-SIOF: NAK; the host reads
  // 85 (an ENQUIRY, which clears it) and repeats the SELECT: 2 SELECTs, 1 ENQUIRY, 3 answers.
  CliRun r = run_cli(cmd({"write", "--addr", "1", "--device", "vf1000", "FSSIO", "23.15"}, port));
  ASSERT_EQ(r.rc, 0) << r.err;
  r = run_cli(cmd({"read", "--addr", "3", "--device", "mc6000", "TYPE"}, port));
  ASSERT_EQ(r.rc, 0) << r.err;
  // Writes `bytes` as a host would, waits (up to 10 s, for a loaded machine) for `answer`, then
  // stays silent for `then` -- longer than the fragment timeout where it matters -- and closes.
  const auto raw = [&port](std::vector<std::uint8_t> bytes, std::vector<std::uint8_t> answer,
                           std::chrono::milliseconds then) {
    const int fd = ::open(port.c_str(), O_RDWR | O_NOCTTY);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(::write(fd, bytes.data(), bytes.size()), static_cast<ssize_t>(bytes.size()));
    std::vector<std::uint8_t> got;
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (got.size() < answer.size() && std::chrono::steady_clock::now() < until) {
      pollfd p{fd, POLLIN, 0};
      if (::poll(&p, 1, 50) <= 0) continue;
      std::uint8_t b[64];
      const ssize_t n = ::read(fd, b, sizeof b);
      if (n > 0) got.insert(got.end(), b, b + n);
    }
    EXPECT_EQ(got, answer);
    std::this_thread::sleep_for(then);
    ::close(fd);
  };
  // EOT, 'A' (address 1), STX, 00105=03E8, ETX and a BCC that is not theirs: NAK (3).
  raw({0x04, 0x41, 0x02, '0', '0', '1', '0', '5', '=', '0', '3', 'E', '8', 0x03, 0x00}, {0x41, 0x15},
      std::chrono::milliseconds(10));
  // A SELECT begun and left (its host died): the next EOT, 400 ms later, finds it stale (LB-D23:
  // 50 ms at 9600 Bd).
  raw({0x04, 0x41, 0x02, '0', '0'}, {}, std::chrono::milliseconds(400));
  // An ADR followed by a character no telegram has there: no answer (3).
  raw({0x04, 0x41, 'X'}, {}, std::chrono::milliseconds(10));
  // An ENQUIRY of 1-MODE and at once the EOT: the answer, due in 200 ms, is cut (3).
  raw({0x04, 0x41, '0', '0', '1', '0', '1', 0x05, 0x04}, {}, std::chrono::milliseconds(400));
  ASSERT_EQ(emu.stop(SIGINT), 0);
  std::ifstream in(errors);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find("ibs lustbus emulate: vf1000@1: 2 ENQUIRY(s), 2 SELECT(s), 0 broadcast(s), 4 answer(s) sent, "
                            "1 BCC error(s), 1 improper telegram(s) dropped, 1 fragment(s) dropped after silence, "
                            "1 answer(s) cut by EOT\n"),
            std::string::npos)
      << text.str();
  EXPECT_NE(text.str().find("ibs lustbus emulate: mc6000@3: 1 ENQUIRY(s), 0 SELECT(s), 0 broadcast(s), 1 answer(s) sent, "
                            "0 BCC error(s), 0 improper telegram(s) dropped, 0 fragment(s) dropped after silence, "
                            "0 answer(s) cut by EOT\n"),
            std::string::npos)
      << text.str();
}

// 11.4: a dataset file through the 80-SLOAD handshake; a dataset the servo rejects exits 1 with
// the first invalid parameter; a malformed line exits 2 naming it.
TEST(LustbusCli, DownloadADatasetFile) {
  Emulator emu({"mc6000@3"});
  const std::string port = emu.pty();
  const std::string good = ::testing::TempDir() + "lustbus_good.txt";
  std::ofstream(good) << "# speed control on the serial interface (7.2.1)\n"
                         "CFCON 2\nCLSEL 2\nRSSL1 3   # RSIO\n420 0\nRSIO 132.15\n";
  CliRun r = run_cli(cmd({"download", "--addr", "3", good}, port));
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(r.out, "mc6000@3: 5 parameters downloaded, 80-SLOAD = 0\n");
  r = run_cli(cmd({"read", "--addr", "3", "--device", "mc6000", "RSSL1"}, port));
  EXPECT_EQ(r.out, "mc6000@3 417-RSSL1 = 3 (03H)\n");

  const std::string bad = ::testing::TempDir() + "lustbus_bad.txt";
  std::ofstream(bad) << "RSSL2 3\nRSSL3 9\n";
  r = run_cli(cmd({"download", "--addr", "3", bad, "--json"}, port));
  EXPECT_EQ(r.rc, 1);
  EXPECT_NE(r.err.find("first invalid parameter 419"), std::string::npos) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["rejected_parameter"], 419);
  r = run_cli(cmd({"read", "--addr", "3", "--device", "mc6000", "RSSL2"}, port));
  EXPECT_EQ(r.out, "mc6000@3 418-RSSL2 = 0 (00H)\n");

  const std::string broken = ::testing::TempDir() + "lustbus_broken.txt";
  std::ofstream(broken) << "RSSL2 3\nSPEED 1\n";
  r = run_cli(cmd({"download", "--addr", "3", broken}, port));
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("lustbus_broken.txt:2: 77-SPEED cannot be part of a dataset"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(emu.stop(SIGTERM), 0);
}

// `ibs decode` of a byte log (docs/lustbus.md, "Reading a byte log"): every telegram and answer
// explained, the host's side found by its EOT, BCCs checked, descriptions read by length.
TEST(LustbusLogDecode, ExplainsTelegramByTelegram) {
  const std::string file = ::testing::TempDir() + "lustbus-decode.log";
  {
    std::ofstream f(file);
    f << "ibs-serial-log 1\n"
         // 6.1.1.2: ENQUIRY 20077 via address 0, the answer 04FA4000 (BCC 0BH), EOT.
         "0.000100 tx /dev/pts/9 04 40 32 30 30 37 37 05\n"
         "0.030000 rx /dev/pts/9 40 02 32 30 30 37 37 3D 30 34 46 41 34 30 30 30 03 0B\n"
         "0.032000 tx /dev/pts/9 04\n"
         // 7.2.1's last: SELECT 20416=1 (BCC 3EH), ACK.
         "0.040000 tx /dev/pts/9 04 43 02 32 30 34 31 36 3D 31 03 3E\n"
         "0.050000 rx /dev/pts/9 43 06\n"
         "0.051000 tx /dev/pts/9 04\n"
         // A SELECT with a wrong BCC, answered NAK.
         "0.060000 tx /dev/pts/9 04 41 02 30 30 31 30 35 3D 30 33 45 38 03 75\n"
         "0.070000 rx /dev/pts/9 41 15\n"
         "0.071000 tx /dev/pts/9 04 41 30 30 31\n"
         "0.072000 tx /dev/pts/9 04\n";
  }
  std::ostringstream out;
  std::ostringstream err;
  const auto rc = decode_lustbus_log(file, out, err);
  ASSERT_TRUE(rc);
  EXPECT_EQ(*rc, 0) << err.str();
  const std::string text = out.str();
  EXPECT_NE(text.find("host = tx (/dev/pts/9)"), std::string::npos) << text;
  EXPECT_NE(text.find("0.000100 host  ENQUIRY @ (address 0) 20077: MC6000 77-SPEED"), std::string::npos) << text;
  EXPECT_NE(text.find("0.030000 drive @ 20077=04FA4000 BCC ok: MC6000 77-SPEED = 1274.25"), std::string::npos) << text;
  EXPECT_NE(text.find("0.040000 host  SELECT C (address 3) 20416=1 BCC ok: MC6000 416-SCTL1 := 1"), std::string::npos) << text;
  EXPECT_NE(text.find("0.050000 drive C ACK"), std::string::npos) << text;
  EXPECT_NE(text.find("BCC WRONG (75, should be 74)"), std::string::npos) << text;
  EXPECT_NE(text.find("0.070000 drive A NAK (the cause is in 85-SIOF/SERR, 9.2)"), std::string::npos) << text;
  EXPECT_NE(text.find("0.071000 host  broken telegram (EOT before its end): A001"), std::string::npos) << text;
}

// After a NAK the host reads the cause with the shared CODE 00085 (2.4.2, 9.2), which both families
// answer, each in its own form: the MC6000's 85-SERR as two hex digits, the VF1000's 85-SIOF as
// four characters. The log does not say which drive is at the address; the answer's form does.
TEST(LustbusLogDecode, TheSharedCode85IsReadInTheFormOfTheDriveThatAnswered) {
  const std::string file = ::testing::TempDir() + "lustbus-decode-85.log";
  {
    std::ofstream f(file);
    f << "ibs-serial-log 1\n"
         // An MC6000 at C refuses 428-RSIO := 1 while its power-on bit is set; the host reads 00085.
         "0.000355 tx /dev/pts/0 04 43 02 32 30 34 32 38 3D 31 30 30 30 30 03 33\n"
         "0.024734 rx /dev/pts/0 43 15\n"
         "0.024875 tx /dev/pts/0 04\n"
         "0.024888 tx /dev/pts/0 04 43 30 30 30 38 35 05\n"
         "0.042101 rx /dev/pts/0 43 02 30 30 30 38 35 3D 30 31 03 02\n"
         "0.042163 tx /dev/pts/0 04\n";
  }
  std::ostringstream out;
  std::ostringstream err;
  const auto rc = decode_lustbus_log(file, out, err);
  ASSERT_TRUE(rc);
  EXPECT_EQ(*rc, 0) << err.str();
  const std::string text = out.str();
  EXPECT_NE(text.find("0.042101 drive C 00085=01 BCC ok: MC6000 85-SERR (shared CODE) = 1 (01H: power on)"),
            std::string::npos)
      << text;
  EXPECT_EQ(text.find("not exactly four characters"), std::string::npos) << text;
}

TEST(LustbusLogDecode, BadLinesAndOtherFiles) {
  const std::string dir = ::testing::TempDir();
  std::ostringstream out;
  std::ostringstream err;
  {
    std::ofstream f(dir + "lb-bad.log");
    f << "ibs-serial-log 1\n0.1 tx /dev/pts/1 04 40\n0.2 up /dev/pts/1 06\n";
  }
  auto rc = decode_lustbus_log(dir + "lb-bad.log", out, err);
  ASSERT_TRUE(rc);
  EXPECT_EQ(*rc, 2);
  EXPECT_NE(err.str().find("lb-bad.log:3: 'up' is neither tx nor rx"), std::string::npos) << err.str();
  {
    std::ofstream f(dir + "lb-hex.log");
    f << "ibs-serial-log 1\n0.1 tx /dev/pts/1 04 4G\n";
  }
  rc = decode_lustbus_log(dir + "lb-hex.log", out, err);
  ASSERT_TRUE(rc);
  EXPECT_EQ(*rc, 2);
  EXPECT_NE(err.str().find("lb-hex.log:2: '4G' is not a byte in two hex digits"), std::string::npos) << err.str();
  {
    std::ofstream f(dir + "lb-dfs1.log");
    f << "ibs-serial-log 1\n0.1 tx /dev/pts/1 10 02 01 81 10 03 7E\n";
  }
  rc = decode_lustbus_log(dir + "lb-dfs1.log", out, err);
  ASSERT_TRUE(rc);
  EXPECT_EQ(*rc, 2);
  EXPECT_NE(err.str().find("not a LUSTBUS byte log"), std::string::npos) << err.str();
  {
    std::ofstream f(dir + "lb-trace.txt");
    f << "# a trace\n";
  }
  EXPECT_FALSE(decode_lustbus_log(dir + "lb-trace.txt", out, err));
  EXPECT_FALSE(decode_lustbus_log(dir + "no-such-file", out, err));
}

}  // namespace
}  // namespace ibs::cli
