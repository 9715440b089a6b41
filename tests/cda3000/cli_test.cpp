// `ibs canlust ...` over CAN over UDP on loopback: `emulate` as its own process (fork/exec of the
// built ibs), the master driver in this process driving its drives to ENABLED, the client
// commands against it with their JSON, exit codes and messages, the candump log read back by
// `ibs decode`, and the pcap decoded by tshark with the Lua dissector (skipped without tshark).
#include <arpa/inet.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <array>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <sstream>
#include <cerrno>
#include <cstring>
#include <ctime>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "canlust_cmd.hpp"
#include "ibs/can/candump.hpp"
#include "ibs/can/udp.hpp"
#include "ibs/devices/cda3000/driver.hpp"

#include "../support/cli_harness.hpp"
#include "../support/run_shell.hpp"

namespace ibs::cli {
namespace {

namespace dev = ::ibs::devices::cda3000;
namespace cl = ::ibs::canlust;

using can::candump_line;  // the log format lives in transports/can (tests/canlust/candump_test.cpp)
using can::parse_candump_line;
using test::CliRun;

CliRun run_cli(std::vector<std::string> args) {
  return test::run_cli_group<CanlustCommandState>(std::move(args), kExitCanBadInput, add_canlust_commands,
                                                  run_canlust_commands);
}

// A UDP port free at the moment of asking.
std::uint16_t free_udp_port() {
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
  socklen_t len = sizeof a;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
  ::close(fd);
  return ntohs(a.sin_port);
}

std::string temp_path(const std::string& name) {
  return ::testing::TempDir() + "/" + name + "_" + std::to_string(::getpid());
}

// `ibs canlust emulate ARGS...` as a child process; its first line is "bus: ...".
class Emulator : public test::ChildProcess {
 public:
  explicit Emulator(const std::vector<std::string>& args) : ChildProcess(argv(args)) {}

 private:
  static std::vector<std::string> argv(const std::vector<std::string>& args) {
    std::vector<std::string> a = {IBS_CLI, "canlust", "emulate"};
    a.insert(a.end(), args.begin(), args.end());
    return a;
  }
};

struct Ports {
  std::uint16_t emulator = free_udp_port();
  std::uint16_t client = free_udp_port();
  std::string emulator_bus() const {
    return "udp:" + std::to_string(emulator) + ":127.0.0.1:" + std::to_string(client);
  }
  std::string client_bus() const { return "udp:" + std::to_string(client) + ":127.0.0.1:" + std::to_string(emulator); }
};

// The issue's two processes: `ibs canlust emulate` with two drives, the master driver here, over
// CAN over UDP; real time from the steady clock.
TEST(CanlustCli, MasterDriverDrivesTheEmulatorInAnotherProcessOverUdp) {
  auto opened = can::UdpCanTransport::open({"127.0.0.1", 0, "127.0.0.1", 0});
  ASSERT_TRUE(opened) << opened.error;
  can::UdpCanTransport& bus = *opened.transport;
  Emulator emu({"--bus", "udp:0:127.0.0.1:" + std::to_string(bus.local_port()), "cda3000@1", "cda3000@2"});
  ASSERT_EQ(emu.first_line().rfind("bus: udp:127.0.0.1:", 0), 0U) << emu.first_line();

  dev::DriverConfig cfg;
  cfg.drives = {{1, 2, 400.0}, {2, 2, 400.0}};
  dev::Driver d(cfg);
  const auto t0 = std::chrono::steady_clock::now();
  const auto now = [&] { return std::chrono::duration_cast<Duration>(std::chrono::steady_clock::now() - t0); };
  const auto run_until = [&](auto done, Duration limit) {
    while (now() < limit) {
      d.cycle(now());
      while (auto f = d.take_frame()) bus.send(*f);
      if (done()) return true;
      const auto r = bus.receive(2ms);
      if (r.status == can::IoStatus::ok) d.receive(r.frame, now());
    }
    return done();
  };
  ASSERT_TRUE(run_until([&] { return d.all_logged_on(); }, 3s));
  d.system_start(now());
  d.request(1, drivecom::Target::enabled, now());
  d.request(2, drivecom::Target::enabled, now());
  d.set_reference_hz(1, 20.5);
  d.set_reference_hz(2, -10.0);
  const bool running = run_until(
      [&] {
        return std::abs(d.drive(1).actual_hz - 20.5) < 0.1 && std::abs(d.drive(2).actual_hz + 10.0) < 0.1;
      },
      now() + 8s);
  EXPECT_TRUE(running) << drivecom::describe(d.drive(1).sequencer) << " / " << drivecom::describe(d.drive(2).sequencer);
  EXPECT_EQ(d.drive(1).state, drivecom::State::enabled);
  EXPECT_EQ(d.drive(1).status_word & 0x0400U, 0x0400U);  // reference reached
  // Parameters through the driver: 406-REFF shows the reference, 578-OPTN2 is "LCAN".
  const auto reff = d.read(1, dev::kReff);
  const auto optn2 = d.read(2, dev::kOptn2);
  ASSERT_TRUE(reff && optn2);
  ASSERT_TRUE(run_until([&] { return d.parameters().idle(); }, now() + 3s));
  EXPECT_EQ(d.parameters().poll(reff.id).outcome->value, 0x00148000U);
  EXPECT_EQ(d.parameters().poll(optn2.id).outcome->text.view(), "LCAN");
  EXPECT_EQ(emu.stop(SIGTERM), 0);
}

TEST(CanlustCli, EmulateExitsZeroOnSigint) {
  const Ports p;
  Emulator emu({"--bus", p.emulator_bus(), "cda3000@3"});
  ASSERT_EQ(emu.first_line().rfind("bus: ", 0), 0U);
  EXPECT_EQ(emu.stop(SIGINT), 0);
}

std::vector<nlohmann::json> json_lines(const std::string& text) {
  std::vector<nlohmann::json> v;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty()) v.push_back(nlohmann::json::parse(line));
  }
  return v;
}

// `emulate --json`: the serving event first, then one object per frame a drive took or sent, per
// state change and per control event, in the shape of `lustbus emulate --json` (docs/canlust.md,
// "Events as JSON").
TEST(CanlustCli, EmulateJsonPrintsOneObjectPerEvent) {
  const Ports p;
  const std::string errors = temp_path("canlust_emulate_json") + ".err";
  test::ChildProcess emu({"/bin/sh", "-c",
                          std::string("exec ") + IBS_CLI + " canlust emulate --json --control - --bus " +
                              p.emulator_bus() + " cda3000@1 cda3000@4 2>" + errors +
                              " <<'IBS_EOF'\n{\"device\": 4, \"fault\": \"device\", \"cause\": \"E-OTI\"}\nIBS_EOF\n"});
  const nlohmann::json first = nlohmann::json::parse(emu.first_line());
  EXPECT_EQ(first["event"], "serving");
  EXPECT_EQ(first["time_s"], 0.0);
  EXPECT_EQ(first["bus"].get<std::string>().rfind("udp:127.0.0.1:", 0), 0U) << first;
  // Read as it comes: the logon and status telegrams alone could fill the pipe of a slow run.
  std::string printed;
  std::thread reader([&] { printed = emu.rest(); });
  const auto cli = [&](std::vector<std::string> args) {
    args.insert(args.begin(), {"canlust"});
    args.insert(args.end(), {"--bus", p.client_bus()});
    return run_cli(args);
  };
  auto r = cli({"read", "--address", "1", "360"});
  EXPECT_EQ(r.rc, 0) << r.err;
  // A request for an address nobody serves: no drive tells it.
  EXPECT_EQ(cli({"read", "--address", "9", "360", "--timeout-ms", "100"}).rc, 1);
  r = cli({"start", "--listen-ms", "200"});
  EXPECT_EQ(r.rc, 0) << r.err;
  const int rc = emu.stop(SIGTERM);
  reader.join();
  ASSERT_EQ(rc, 0);
  std::ifstream in(errors);
  EXPECT_EQ(std::string((std::istreambuf_iterator<char>(in)), {}), "");  // nothing on stderr: all is JSON
  std::remove(errors.c_str());

  int requests = 0;
  int replies = 0;
  int systems = 0;
  int controls = 0;
  int errors_sent = 0;
  bool fault = false;
  int started = 0;
  int summaries = 0;
  double last = 0.0;
  for (const nlohmann::json& e : json_lines(printed)) {
    ASSERT_TRUE(e.contains("time_s") && e.contains("event")) << e;
    EXPECT_GE(e["time_s"].get<double>(), last) << e;
    last = e["time_s"].get<double>();
    const std::string what = e["event"];
    ASSERT_TRUE(e.contains("device") && e.contains("address")) << e;
    EXPECT_EQ(e["device"], e["address"] == 1 ? "cda3000@1" : "cda3000@4") << e;
    if (what == "telegram" && e["kind"] == "parameter request") {
      // 1101 + 2 x 1 = 44FH (D1); 360 = 168H read (mode 05).
      EXPECT_EQ(e["address"], 1) << e;
      EXPECT_EQ(e["id"], 0x44F) << e;
      EXPECT_EQ(e["id_hex"], "44F") << e;
      EXPECT_EQ(e["bytes"].get<std::string>().rfind("68 01 05 ", 0), 0U) << e;
      EXPECT_NE(e["text"].get<std::string>().find("360-DISP"), std::string::npos) << e;
      ++requests;
    } else if (what == "telegram") {
      EXPECT_EQ(e["kind"], "system start/stop") << e;
      EXPECT_EQ(e["id"], 221) << e;
      EXPECT_EQ(e["bytes"], "01") << e;  // System Start (5.5.4)
      ++systems;
    } else if (what == "answer" && e["kind"] == "parameter reply") {
      EXPECT_EQ(e["address"], 1) << e;
      EXPECT_EQ(e["id_hex"], "52B") << e;
      ++replies;
    } else if (what == "answer" && e["kind"] == "error") {
      EXPECT_EQ(e["address"], 4) << e;  // 6.2: the error telegram of the faulted drive
      ++errors_sent;
    } else if (what == "control") {
      EXPECT_EQ(e["address"], 4) << e;
      EXPECT_EQ(e["what"], "fault E-OTI") << e;
      EXPECT_EQ(e["taken"], true) << e;
      EXPECT_EQ(e["control_line"], 1) << e;
      EXPECT_EQ(e["result"], "8 E-OTI (drive unit overheating), FAULT, error telegram sent") << e;
      ++controls;
    } else if (what == "state") {
      if (e["address"] == 4 && e["state"] == "FAULT") fault = true;
      if (e["system"] == "System Start") ++started;
      if (e["address"] == 1) {
        EXPECT_NE(e["state"], "FAULT") << e;  // the fault was drive 4's only
      }
    } else if (what == "summary") {
      EXPECT_EQ(e["counters"]["telegrams"], e["address"] == 1 ? 2 : 1) << e;
      EXPECT_GT(e["counters"]["answers"].get<int>(), 0) << e;
      ++summaries;
    }
  }
  EXPECT_EQ(requests, 1);
  EXPECT_EQ(replies, 1);
  EXPECT_EQ(systems, 2);  // every drive tells the broadcast
  EXPECT_EQ(controls, 1);
  EXPECT_EQ(errors_sent, 1);
  EXPECT_TRUE(fault);
  EXPECT_EQ(started, 2);
  EXPECT_EQ(summaries, 2);
}

TEST(CanlustCli, ParameterCommandsWithJsonAndExitCodes) {
  const Ports p;
  const std::string pcap = temp_path("canlust_cli") + ".pcap";
  Emulator emu({"--bus", p.emulator_bus(), "--pcap", pcap, "cda3000@1", "cda3000@4"});
  ASSERT_EQ(emu.first_line().rfind("bus: ", 0), 0U);
  const std::string bus = p.client_bus();
  const auto cli = [&](std::vector<std::string> args) {
    args.insert(args.begin(), {"canlust"});
    args.insert(args.end(), {"--bus", bus});
    return run_cli(args);
  };

  auto r = cli({"read", "--address", "1", "360"});
  EXPECT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(r.out, "CDA 1 360-DISP: 406\n");

  r = cli({"write", "--address", "4", "CAWDG", "120", "--json"});
  EXPECT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.out.find("\"command\":\"write\""), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"name\":\"574-CAWDG\""), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"outcome\":\"done\""), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"text\":\"120 ms\""), std::string::npos) << r.out;

  r = cli({"read", "--address", "4", "574-CAWDG", "--json"});
  EXPECT_NE(r.out.find("\"value\":120"), std::string::npos) << r.out;
  EXPECT_EQ(cli({"write", "--address", "4", "CAWDG", "0"}).rc, 0);  // no watchdog trip after the start below

  r = cli({"write", "--address", "1", "RSSL1", "OPTN2"});
  EXPECT_EQ(r.out, "CDA 1 280-RSSL1 = 6 (OPTN2): done\n") << r.err;

  r = cli({"write", "--address", "1", "90-NAME", "Line 3 / pump"});
  EXPECT_EQ(r.rc, 0) << r.err;
  r = cli({"read", "--address", "1", "NAME", "--json"});
  EXPECT_NE(r.out.find("\"value\":\"Line 3 / pump\""), std::string::npos) << r.out;

  r = cli({"describe", "--address", "1", "575"});
  EXPECT_EQ(r.out, "CDA 1 575-CASCY: CASCY, USIGN16, 1..32000 ms, factory 80 ms, writable, flash\n") << r.err;

  // Bad input: exit 2 with where and what; nothing is sent.
  r = cli({"write", "--address", "1", "CAWDG", "300"});
  EXPECT_EQ(r.rc, 2);
  EXPECT_EQ(r.err, "ibs canlust write: 574-CAWDG: 300 ms is above the maximum 255 ms\n");
  r = cli({"write", "--address", "1", "CLSEL", "SIO"});
  EXPECT_EQ(r.rc, 2);
  EXPECT_EQ(r.err, "ibs canlust write: 260-CLSEL: 'SIO' is not a number or one of TERM, OPTN2\n");
  r = cli({"write", "--address", "1", "406", "1"});
  EXPECT_EQ(r.rc, 2);
  EXPECT_EQ(r.err, "ibs canlust write: 406-REFF is read-only\n");
  r = cli({"read", "--address", "1", "CAWDX"});
  EXPECT_EQ(r.rc, 2);
  r = cli({"read", "--address", "100", "360"});
  EXPECT_EQ(r.rc, 2);
  EXPECT_EQ(r.err, "ibs canlust read: --address must be 0..99\n");

  // The drive refuses, or nobody answers: exit 1 with the decoded reason.
  r = cli({"read", "--address", "1", "999", "--json"});
  EXPECT_EQ(r.rc, 1);
  EXPECT_NE(r.out.find("\"status_text\":\"unknown parameter\""), std::string::npos) << r.out;
  EXPECT_EQ(r.err, "ibs canlust read: CDA 1 parameter 999: refused, status unknown parameter\n");
  r = cli({"write", "--address", "1", "570", "1"});  // CAMOD: no CAN master emulated (D26)
  EXPECT_EQ(r.rc, 1);
  EXPECT_NE(r.err.find("change not permitted"), std::string::npos) << r.err;
  r = cli({"read", "--address", "9", "360", "--timeout-ms", "100"});
  EXPECT_EQ(r.rc, 1);
  EXPECT_NE(r.err.find("timeout"), std::string::npos) << r.err;

  // System Start: the drives' first status telegrams.
  r = cli({"start", "--listen-ms", "200"});
  EXPECT_EQ(r.rc, 0);
  EXPECT_NE(r.out.find("CDA 1: status 0240 START-UP INHIBIT"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("CDA 4: status 0240 START-UP INHIBIT"), std::string::npos) << r.out;

  // The monitor sees the cyclic status and writes the candump log that `ibs decode` explains.
  const std::string log = temp_path("canlust_monitor") + ".log";
  r = cli({"monitor", "--duration-ms", "250", "--log", log});
  EXPECT_EQ(r.rc, 0);
  EXPECT_NE(r.out.find("  373   [6]  40 02 00 00 00 00        status CDA 1: 0240 START-UP INHIBIT"), std::string::npos)
      << r.out;
  std::ostringstream dout;
  std::ostringstream derr;
  EXPECT_EQ(decode_candump_log(log, 2, 2, dout, derr), 0) << derr.str();
  EXPECT_TRUE(std::regex_search(dout.str(), std::regex(R"(\(\d+\.\d{6}\) udp\d+ 373#400200000000 +status CDA 1: 0240)")))
      << dout.str();
  r = cli({"stop", "--json", "--listen-ms", "100"});
  EXPECT_NE(r.out.find("\"command\":\"stop\""), std::string::npos);
  EXPECT_EQ(emu.stop(SIGTERM), 0);

  // The emulator's capture through tshark and the Lua dissector.
  if (std::system("command -v tshark >/dev/null 2>&1") != 0) GTEST_SKIP() << "tshark is not installed (Debian package tshark)";
  const std::string cmd = "tshark -X lua_script:" + std::string(IBS_SOURCE_DIR) + "/tools/wireshark/canlust.lua -r " +
                          pcap + " -T fields -E separator=';' -e can.id -e canlust.parameter_name -e canlust.data"
                          " -e canlust.drivecom_state 2>/dev/null";
  std::string out;
  if (FILE* pipe = ::popen(cmd.c_str(), "r")) {
    char buf[4096];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, pipe)) > 0) out.append(buf, n);
    ::pclose(pipe);
  }
  EXPECT_NE(out.find("1545;;;\n"), std::string::npos) << out;                   // logon CDA 1
  EXPECT_NE(out.find("1323;360-DISP;0x00000196;\n"), std::string::npos) << out;  // 7.1.3's reply
  EXPECT_NE(out.find("1329;574-CAWDG;0x00000078;\n"), std::string::npos) << out;
  EXPECT_NE(out.find("883;;;START-UP INHIBIT\n"), std::string::npos) << out;
  // The replies by what their request asked (issue 27.15): a value with its unit, the characters
  // of a string transfer, a description's items; no expert info on these valid frames.
  const auto tshark_out = [](const std::string& c) {
    std::string text;
    if (FILE* pipe = ::popen(c.c_str(), "r")) {
      char buf[4096];
      std::size_t n;
      while ((n = std::fread(buf, 1, sizeof buf, pipe)) > 0) text.append(buf, n);
      ::pclose(pipe);
    }
    return text;
  };
  const std::string base = "tshark -X lua_script:" + std::string(IBS_SOURCE_DIR) + "/tools/wireshark/canlust.lua -r " + pcap;
  const std::string values = tshark_out(base + " -Y canlust.kind==5 -T fields -E separator=';' -e canlust.parameter_name"
                                               " -e canlust.value -e canlust.unit -e canlust.text"
                                               " -e canlust.description.data_type -e canlust.checksum 2>/dev/null");
  EXPECT_NE(values.find("360-DISP;406;;;;\n"), std::string::npos) << values;
  EXPECT_NE(values.find("574-CAWDG;120;ms;;;\n"), std::string::npos) << values;  // the write's echo, the read
  EXPECT_NE(values.find("90-NAME;;;Line;;\n"), std::string::npos) << values;      // a string read's first block
  EXPECT_NE(values.find("90-NAME;;; pum;;\n90-NAME;;;p;;\n"), std::string::npos) << values;  // ... to the terminator
  EXPECT_NE(values.find("575-CASCY;;;;USIGN16;\n"), std::string::npos) << values;  // description item 0
  EXPECT_NE(values.find("575-CASCY;32000;ms;;;\n"), std::string::npos) << values;  // item 2, the maximum
  EXPECT_NE(values.find("575-CASCY;;;CASC;;\n"), std::string::npos) << values;     // item 5, the name
  EXPECT_NE(values.find("90-NAME;;;;;0x"), std::string::npos) << values;          // List_End: the checksum
  const std::string verbose = tshark_out(base + " -V 2>/dev/null");
  EXPECT_EQ(verbose.find("Expert Info"), std::string::npos);
  std::remove(pcap.c_str());
  std::remove(log.c_str());
}

TEST(CanlustCli, BadBusAndDevicesAreRefused) {
  auto r = run_cli({"canlust", "emulate", "--bus", "udp:70000:127.0.0.1:1", "cda3000@1"});
  EXPECT_EQ(r.rc, 2);
  EXPECT_EQ(r.err, "ibs canlust emulate: --bus 'udp:70000:127.0.0.1:1': LOCALPORT '70000' is not a port number "
                   "(0..65535) (expected udp:LOCALPORT:HOST:PORT or socketcan:IFACE)\n");
  r = run_cli({"canlust", "emulate", "--bus", "udp:0:127.0.0.1:1", "cda3000@1", "cda3000@1"});
  EXPECT_EQ(r.err, "ibs canlust emulate: device 'cda3000@1': address given twice\n");
  r = run_cli({"canlust", "emulate", "--bus", "udp:0:127.0.0.1:1", "vf1000@1"});
  EXPECT_EQ(r.rc, 2);
  r = run_cli({"canlust", "emulate", "--factory", "--bus", "udp:0:127.0.0.1:1", "cda3000@9"});
  EXPECT_EQ(r.err, "ibs canlust emulate: device 'cda3000@9': expected cda3000@ADDR with ADDR 0..7 (the connector's address, 2.1)\n");
  r = run_cli({"canlust", "emulate", "--cacnf", "5", "--bus", "udp:0:127.0.0.1:1", "cda3000@1"});
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("--cacnf must be 1..4 (492-CACNF)"), std::string::npos) << r.err;
  r = run_cli({"canlust", "read", "--bus", "carrier-pigeon", "--address", "1", "360"});
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("unknown bus type 'carrier-pigeon'"), std::string::npos);
  r = run_cli({"canlust", "read", "--bus", "socketcan:vcan9", "--address", "1", "360"});
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("--bus 'socketcan:vcan9': "), std::string::npos) << r.err;
}

// Issue 23, defect 4: `canlust read ... --log EXISTING --pcap /nonexistent/x.pcap` exited 2 and
// left EXISTING at 0 bytes (emulate too). Nothing is emptied or made before both open.
TEST(CanlustCli, AFailingRecordingEmptiesNoFile) {
  const std::string log = ::testing::TempDir() + "ibs_canlust_existing.log";
  const std::string fresh = ::testing::TempDir() + "ibs_canlust_fresh.log";
  std::remove(fresh.c_str());
  {
    std::ofstream out(log);
    out << "the user's log\n";
  }
  for (const std::string cmd : {"read", "emulate"}) {
    std::vector<std::string> args = {"canlust", cmd, "--bus", "udp:0:127.0.0.1:1", "--log", log, "--pcap",
                                     "/nonexistent/x.pcap"};
    if (cmd == "read") {
      args.insert(args.end(), {"--address", "1", "360"});
    } else {
      args.push_back("cda3000@1");
    }
    const auto r = run_cli(args);
    EXPECT_EQ(r.rc, 2) << cmd << ": " << r.err;
    std::ifstream in(log);
    const std::string text((std::istreambuf_iterator<char>(in)), {});
    EXPECT_EQ(text, "the user's log\n") << cmd;
    args[5] = fresh;
    EXPECT_EQ(run_cli(args).rc, 2);
    EXPECT_FALSE(std::filesystem::exists(fresh)) << cmd << ": a log made for the failed command is removed";
  }
  std::remove(log.c_str());
}

// The dissector's copy of the CDA3000 parameter table (names, data types, units) is the wing's:
// the data type says how it shows a value read or written (406-REFF -12.25 Hz).
TEST(CanlustDissector, ParameterTableIsTheWings) {
  std::ifstream in(std::string(IBS_SOURCE_DIR) + "/tools/wireshark/canlust.lua");
  const std::string lua((std::istreambuf_iterator<char>(in)), {});
  const auto start = lua.find("local cda3000 = {");
  ASSERT_NE(start, std::string::npos);
  const std::string table = lua.substr(start, lua.find("\n}", start) - start);
  std::map<int, std::array<std::string, 3>> rows;
  const std::regex row(R"re(\[(\d+)\] = \{ "([^"]+)", "([^"]+)", "([^"]*)" \})re");
  for (auto it = std::sregex_iterator(table.begin(), table.end(), row); it != std::sregex_iterator(); ++it) {
    rows[std::stoi((*it)[1])] = {(*it)[2], (*it)[3], (*it)[4]};
  }
  ASSERT_EQ(rows.size(), dev::kParameters.size());
  for (const auto& p : dev::kParameters) {
    const std::array<std::string, 3> want{dev::display_name(p), std::string(cl::to_string(p.type)),
                                          std::string(p.unit)};
    EXPECT_EQ(rows[p.number], want) << p.number;
  }
}

// candump's log format, both ways.
TEST(Candump, LinesBothWays) {
  const auto t = std::chrono::system_clock::time_point(std::chrono::microseconds(1795431275322679LL));
  const auto f = cl::CanFrame::make(663, {0x0F, 0x00, 0x00, 0x80, 0x14, 0x00});
  EXPECT_EQ(candump_line(f, t, "can0"), "(1795431275.322679) can0 297#0F0000801400");
  const auto r = parse_candump_line("(1795431275.322679) can0 297#0F0000801400");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->frame, f);
  EXPECT_EQ(r->interface_name, "can0");
  EXPECT_EQ(candump_line(cl::CanFrame::make(1545, {}), t, "udp1"), "(1795431275.322679) udp1 609#");
  cl::CanFrame rtr;
  rtr.id = 0x123;
  rtr.rtr = true;
  rtr.dlc = 2;
  EXPECT_EQ(parse_candump_line(candump_line(rtr, t, "c"))->frame, rtr);
  EXPECT_FALSE(parse_candump_line("(1.5) can0 12345678#00")->classic);
  EXPECT_FALSE(parse_candump_line("not a line"));
  EXPECT_FALSE(parse_candump_line("(1.5) can0 297#0F0"));
}

TEST(Candump, DecodeSaysWhereALineIsBad) {
  const std::string path = temp_path("bad_candump") + ".log";
  {
    std::ofstream o(path);
    o << "(1.000001) can0 297#0F0000801400\n(2.000000) can0 zz#00\n";
  }
  std::ostringstream out;
  std::ostringstream err;
  EXPECT_EQ(decode_candump_log(path, 2, 2, out, err), 2);
  EXPECT_EQ(err.str(), path + ":2: not a candump log line: '(2.000000) can0 zz#00'\n");
  std::remove(path.c_str());
}

// `ibs canlust download FILE` (CANLust manual, "Downloading parameter data sets"; D39): the set goes
// through 80-SLOAD and is in the drive's EEPROM; a bad line is refused with FILE:LINE before
// anything is sent (exit 2); a set the drive finds implausible is rejected with the parameter and
// its line (exit 1), the old set stays; the file is only read.
TEST(CanlustCli, DownloadADataSetFile) {
  const Ports p;
  Emulator emu({"--bus", p.emulator_bus(), "cda3000@1"});
  ASSERT_EQ(emu.first_line().rfind("bus: ", 0), 0U);
  const std::string bus = p.client_bus();
  const auto cli = [&](std::vector<std::string> args) {
    args.insert(args.begin(), {"canlust"});
    args.insert(args.end(), {"--bus", bus});
    return run_cli(args);
  };
  const std::string good = temp_path("canlust_set") + ".txt";
  const std::string text = "# conveyor 3\nCASCY 40   # status every 40 ms\n574-CAWDG 0\nCDSSL CDS2\n";
  std::ofstream(good) << text;
  auto r = cli({"download", "--address", "1", good});
  EXPECT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(r.out, "CDA 1: 3 parameters downloaded, 80-SLOAD = 0: the data set is in the EEPROM\n");
  r = cli({"read", "--address", "1", "CASCY"});
  EXPECT_EQ(r.out, "CDA 1 575-CASCY: 40 ms\n") << r.err;
  std::ifstream back(good);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(back), {}), text);  // never written

  const std::string bad = temp_path("canlust_bad") + ".txt";
  std::ofstream(bad) << "CASCY 40\n\nCAWDG 300\n";
  r = cli({"download", "--address", "1", bad});
  EXPECT_EQ(r.rc, 2);
  EXPECT_EQ(r.err, "ibs canlust download: " + bad + ":3: 574-CAWDG: 300 ms is above the maximum 255 ms\n");
  std::ofstream(bad) << "SAVE 1\n";
  r = cli({"download", "--address", "1", bad});
  EXPECT_EQ(r.rc, 2);
  EXPECT_EQ(r.err, "ibs canlust download: " + bad + ":1: 150-SAVE cannot be part of a data set (it is not Card Writeable)\n");
  r = cli({"download", "--address", "1", temp_path("canlust_missing")});
  EXPECT_EQ(r.rc, 2);

  // 570-CAMOD = MASTER is a value of the table the drive does not run: implausible as a whole.
  std::ofstream(bad) << "CASCY 20\nCAMOD MASTER\n";
  r = cli({"download", "--address", "1", bad, "--json"});
  EXPECT_EQ(r.rc, 1);
  EXPECT_EQ(r.err, "ibs canlust download: CDA 1: the drive found the data set implausible: 570-CAMOD (" + bad +
                       ":2), 80-SLOAD = 570; the old data set stays\n");
  EXPECT_NE(r.out.find("\"outcome\":\"rejected\""), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"rejected_parameter\":570"), std::string::npos) << r.out;
  r = cli({"read", "--address", "1", "CASCY"});
  EXPECT_EQ(r.out, "CDA 1 575-CASCY: 40 ms\n") << r.err;
  std::remove(good.c_str());
  std::remove(bad.c_str());
}

// ---- can-utils' ways and the other buses' conventions (issue 27) ----------------------------

// One line per non-empty line of `text`.
std::vector<std::string> lines_in(const std::string& text) {
  std::vector<std::string> v;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) {
    if (!l.empty()) v.push_back(l);
  }
  return v;
}

// `-p BUS -a ADDR -j` as on the other buses (`--bus`, `--address`, `--addr`, `--json` still
// work); `read --repeat N --interval MS`: one line or JSON object a reading, the failures counted
// at the end on standard error (mbpoll -1 / -l; lustbus read does the same).
TEST(CanlustCli, ShortOptionsAndRepeatedReadings) {
  const Ports p;
  Emulator emu({"-p", p.emulator_bus(), "cda3000@1"});
  ASSERT_EQ(emu.first_line().rfind("bus: ", 0), 0U) << emu.first_line();
  const std::string bus = p.client_bus();
  auto r = run_cli({"canlust", "read", "-p", bus, "-a", "1", "360", "--repeat", "3", "--interval", "100"});
  EXPECT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(r.out, "CDA 1 360-DISP: 406\nCDA 1 360-DISP: 406\nCDA 1 360-DISP: 406\n");
  EXPECT_EQ(r.err, "ibs canlust read: 3 readings, 3 ok, 0 failed\n");
  // With --log the readings share one candump log: every reading's request (1103 = 44FH) and
  // reply (1323 = 52BH, 406 = 0196H) in it, where each reading truncated it again before.
  const std::string log = ::testing::TempDir() + "canlust_repeat_" + std::to_string(::getpid()) + ".log";
  r = run_cli({"canlust", "read", "-p", bus, "-a", "1", "360", "--repeat", "3", "--interval", "50", "--log", log});
  EXPECT_EQ(r.rc, 0) << r.err;
  {
    std::ifstream in(log);
    int requests = 0;
    int replies = 0;
    for (std::string line; std::getline(in, line);) {
      if (line.find(" 44F#6801050000000000") != std::string::npos) ++requests;
      if (line.find(" 52B#6801009601000000") != std::string::npos) ++replies;
    }
    EXPECT_EQ(requests, 3);
    EXPECT_EQ(replies, 3);
  }
  std::remove(log.c_str());
  r = run_cli({"canlust", "read", "--bus", bus, "--addr", "1", "DISP", "-j"});
  EXPECT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.out.find("\"value\":406"), std::string::npos) << r.out;
  // Nobody at 9: every reading ends with its timeout, each a JSON object, the summary says so.
  const auto t0 = std::chrono::steady_clock::now();
  r = run_cli({"canlust", "read", "-p", bus, "-a", "9", "360", "--timeout-ms", "50", "--repeat", "2", "--interval",
               "100", "--json"});
  EXPECT_LT(std::chrono::steady_clock::now() - t0, 2s);
  EXPECT_EQ(r.rc, 1);
  const auto objects = lines_in(r.out);
  ASSERT_EQ(objects.size(), 2U) << r.out;
  for (const std::string& o : objects) EXPECT_NE(o.find("\"outcome\":\"timeout\""), std::string::npos) << o;
  const std::string summary = "ibs canlust read: 2 readings, 0 ok, 2 failed (2 timeouts)\n";
  ASSERT_GE(r.err.size(), summary.size()) << r.err;
  EXPECT_EQ(r.err.substr(r.err.size() - summary.size()), summary) << r.err;
  // A refusal is counted as one.
  r = run_cli({"canlust", "read", "-p", bus, "-a", "1", "999", "--repeat", "2", "--interval", "50"});
  EXPECT_EQ(r.rc, 1);
  EXPECT_NE(r.err.find("ibs canlust read: 2 readings, 0 ok, 2 failed (2 refused)\n"), std::string::npos) << r.err;
  // Bad input ends at once, without a summary.
  r = run_cli({"canlust", "read", "-p", bus, "-a", "100", "360", "--repeat", "5"});
  EXPECT_EQ(r.rc, 2);
  EXPECT_EQ(r.err, "ibs canlust read: --address must be 0..99\n");
  EXPECT_EQ(emu.stop(SIGTERM), 0);
}

// `--log -` (candump -L): the candump log of the read's two frames on standard output, the reading
// itself on standard error, so a pipe gets a log and nothing else.
TEST(CanlustCli, LogDashWritesTheFramesToStandardOutput) {
  const Ports p;
  Emulator emu({"-p", p.emulator_bus(), "cda3000@1"});
  ASSERT_EQ(emu.first_line().rfind("bus: ", 0), 0U) << emu.first_line();
  const auto r = run_cli({"canlust", "read", "-p", p.client_bus(), "-a", "1", "360", "--log", "-"});
  EXPECT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(r.err, "CDA 1 360-DISP: 406\n");
  const auto frames = lines_in(r.out);
  ASSERT_GE(frames.size(), 2U) << r.out;
  // The request 44F (1101 + 2 x 1) and the reply 52B (1321 + 2 x 1), as candump -l writes them.
  EXPECT_NE(r.out.find(" 44F#680105"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(" 52B#68010096"), std::string::npos) << r.out;
  for (const std::string& l : frames) EXPECT_EQ(l.front(), '(') << l;
  EXPECT_FALSE(std::filesystem::exists("-"));
  EXPECT_EQ(emu.stop(SIGTERM), 0);
}

// `ibs canlust send` (cansend) starts the drives; `monitor` (candump) shows their status telegrams
// with candump's filters, -n COUNT, -t a|d|z and -T, identifiers in hex and CANLust's words beside.
TEST(CanlustCli, MonitorFiltersCountsAndTimestampsAsCandump) {
  const Ports p;
  Emulator emu({"-p", p.emulator_bus(), "cda3000@1", "cda3000@2"});
  ASSERT_EQ(emu.first_line().rfind("bus: ", 0), 0U) << emu.first_line();
  const std::string bus = p.client_bus();
  const auto cli = [&](std::vector<std::string> args) {
    args.insert(args.begin(), {"canlust"});
    args.insert(args.end(), {"-p", bus});
    return run_cli(args);
  };
  auto r = cli({"send", "0DD#01"});  // System Start (5.5.4): the drives send their status cyclically
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(r.out, "");  // as cansend: nothing to say

  const std::regex z(R"(^\(\d{3}\.\d{6}\)  udp\d+  373   \[6\]  40 02 00 00 00 00        status CDA 1: 0240 START-UP INHIBIT.*)");
  r = cli({"monitor", "-f", "373:7FF", "-n", "3", "-t", "z", "--duration-ms", "5000"});
  EXPECT_EQ(r.rc, 0) << r.err;
  auto lines = lines_in(r.out);
  ASSERT_EQ(lines.size(), 3U) << r.out;
  for (const std::string& l : lines) EXPECT_TRUE(std::regex_match(l, z)) << l;
  EXPECT_EQ(lines[0].rfind("(000.000000)  ", 0), 0U) << lines[0];
  EXPECT_GE(lines[2].substr(0, 12), lines[1].substr(0, 12));  // time since the first frame

  // Delta: the status cycle (575-CASCY, 80 ms by default) between frames of one drive; summed over
  // four cycles, as the frames are stamped when read (a busy machine may read two at once).
  r = cli({"monitor", "-f", "373:7FF", "-n", "5", "-t", "d", "--duration-ms", "5000"});
  lines = lines_in(r.out);
  ASSERT_EQ(lines.size(), 5U) << r.out;
  EXPECT_EQ(lines[0].rfind("(000.000000)  ", 0), 0U) << lines[0];
  double cycles = 0;
  for (std::size_t i = 1; i < lines.size(); ++i) cycles += std::stod(lines[i].substr(1, 10));
  EXPECT_GT(cycles, 0.15) << r.out;
  EXPECT_LT(cycles, 1.5) << r.out;

  // Absolute: the wall clock, as candump -ta.
  r = cli({"monitor", "-n", "1", "-t", "a", "--duration-ms", "5000"});
  lines = lines_in(r.out);
  ASSERT_EQ(lines.size(), 1U) << r.out;
  ASSERT_TRUE(std::regex_match(lines[0], std::regex(R"(^\(\d{10}\.\d{6}\)  udp\d+  [0-9A-F]{3}   \[\d\]  .*)"))) << lines[0];
  EXPECT_LT(std::abs(std::stod(lines[0].substr(1, 17)) - static_cast<double>(std::time(nullptr))), 5.0) << lines[0];

  // Inverted (candump's ID~MASK and the ~ID:MASK form), repeated, comma-separated.
  r = cli({"monitor", "-f", "373~7FF", "-f", "~607:7F0,j", "-n", "4", "--duration-ms", "5000"});
  lines = lines_in(r.out);
  ASSERT_EQ(lines.size(), 4U) << r.out;
  for (const std::string& l : lines) {
    EXPECT_EQ(l.find("  373   ["), std::string::npos) << l;
    EXPECT_EQ(l.find("  60"), std::string::npos) << l;
  }
  // Two filters no frame passes at once: -T ends the wait.
  const auto t0 = std::chrono::steady_clock::now();
  r = cli({"monitor", "-f", "373:7FF,375:7FF,j", "-T", "300"});
  EXPECT_EQ(r.rc, 0);
  EXPECT_EQ(r.out, "");
  EXPECT_LT(std::chrono::steady_clock::now() - t0, 3s);

  r = cli({"monitor", "-f", "375:7FF", "-n", "1", "-j", "--duration-ms", "5000"});
  EXPECT_NE(r.out.find("\"id\":885,\"id_hex\":\"375\""), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"text\":\"status CDA 2: 0240 START-UP INHIBIT"), std::string::npos) << r.out;

  // Bad input: what and where, exit 2.
  r = cli({"monitor", "-f", "373:7FG"});
  EXPECT_EQ(r.rc, 2);
  EXPECT_EQ(r.err, "ibs canlust monitor: --filter '373:7FG', column 7: 'G' is not a hex digit (the MASK) (candump's "
                   "filters: ID:MASK, ID~MASK, j; hex)\n");
  r = cli({"monitor", "-t", "x"});
  EXPECT_EQ(r.rc, 2);
  EXPECT_EQ(r.err, "ibs canlust monitor: -t 'x': expected a (absolute), d (delta) or z (zero at the first frame)\n");
  EXPECT_EQ(emu.stop(SIGTERM), 0);
}

// Frames on a bus the test holds (CAN over UDP): `ibs canlust send|play` as the user runs them.
class TestBus {
 public:
  TestBus() {
    auto o = can::UdpCanTransport::open({"127.0.0.1", 0, "127.0.0.1", 0});
    if (!o) throw std::runtime_error(o.error);
    bus_ = std::move(o.transport);
  }
  std::string peer_bus() const { return "udp:0:127.0.0.1:" + std::to_string(bus_->local_port()); }
  // Frames with their arrival (steady clock) until `n` came or `limit` passed.
  std::vector<std::pair<cl::CanFrame, std::chrono::steady_clock::time_point>> take(std::size_t n, Duration limit) {
    std::vector<std::pair<cl::CanFrame, std::chrono::steady_clock::time_point>> got;
    const auto end = std::chrono::steady_clock::now() + limit;
    while (got.size() < n && std::chrono::steady_clock::now() < end) {
      const auto r = bus_->receive(10ms);
      if (r.status == can::IoStatus::ok) got.emplace_back(r.frame, std::chrono::steady_clock::now());
    }
    return got;
  }

 private:
  std::unique_ptr<can::UdpCanTransport> bus_;
};

TEST(CanlustCli, SendTakesCansendSyntaxAndSaysWhereItIsWrong) {
  TestBus bus;
  const std::string ibs = std::string(IBS_CLI) + " canlust send -p " + bus.peer_bus() + " ";
  auto r = test::run_shell(ibs + "2a5#01.02.0304 2>&1");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_EQ(r.out, "");
  auto got = bus.take(1, 2s);
  ASSERT_EQ(got.size(), 1U);
  EXPECT_EQ(got[0].first, cl::CanFrame::make(0x2A5, {1, 2, 3, 4}));
  r = test::run_shell(ibs + "0DD#01 -j 2>&1");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("\"frame\":\"0DD#01\""), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("System Start"), std::string::npos) << r.out;
  got = bus.take(1, 2s);
  ASSERT_EQ(got.size(), 1U);
  EXPECT_EQ(got[0].first, cl::encode_system(cl::SystemCommand::start));
  r = test::run_shell(ibs + "123#R2 2>&1");
  got = bus.take(1, 2s);
  ASSERT_EQ(got.size(), 1U);
  EXPECT_TRUE(got[0].first.rtr);
  EXPECT_EQ(got[0].first.dlc, 2);

  const std::string rules = " (cansend's ID#DATA: 3 hex digits 000..7FF, '#', 0..8 bytes of 2 hex digits, '.' between "
                            "bytes; ID#R or ID#R0..R8 a remote frame)\n";
  r = test::run_shell(ibs + "2A5#0G 2>&1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "ibs canlust send: '2A5#0G', column 6: 'G' is not a hex digit (the data)" + rules);
  r = test::run_shell(ibs + "12345678#00 2>&1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "ibs canlust send: '12345678#00', column 1: an 8-digit identifier is an extended (29-bit) one: "
                   "CANLust uses 11-bit identifiers, 3 hex digits" + rules);
  r = test::run_shell(ibs + "123#001122334455667788 2>&1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.out.find("column 21: more than 8 data bytes"), std::string::npos) << r.out;
  EXPECT_TRUE(bus.take(1, 200ms).empty()) << "bad input sends nothing";
}

// canplayer: the frames of a candump log, paced by their times; `-` reads standard input; a bad
// line is FILE:LINE: what, exit 2, and nothing is sent; a signal ends it with 130.
TEST(CanlustCli, PlayPacesACandumpLogInRealTime) {
  TestBus bus;
  const std::string log = temp_path("canlust_play") + ".log";
  std::ofstream(log) << "(1795431275.000000) can0 0DD#01\n\n(1795431275.300000) can0 44F#6801050000000000\n"
                        "(1795431275.600000) vcan1 123#R\n";
  const std::string ibs = std::string(IBS_CLI) + " canlust play -p " + bus.peer_bus() + " ";
  for (const std::string& how : {log, "- < " + log}) {
    test::ShellResult r{};
    std::thread player([&] { r = test::run_shell(ibs + how + " 2>&1"); });
    const auto got = bus.take(3, 5s);
    player.join();
    EXPECT_EQ(r.exit_code, 0) << how << ": " << r.out;
    ASSERT_EQ(got.size(), 3U) << how;
    EXPECT_EQ(got[0].first, cl::encode_system(cl::SystemCommand::start));
    EXPECT_EQ(got[1].first, cl::CanFrame::make(0x44F, {0x68, 0x01, 0x05, 0, 0, 0, 0, 0}));
    EXPECT_TRUE(got[2].first.rtr);
    const auto gap = [&](std::size_t i) { return got[i].second - got[i - 1].second; };
    EXPECT_GT(gap(1), 200ms) << how;  // 300 ms in the log
    EXPECT_LT(gap(1), 1000ms) << how;
    EXPECT_GT(gap(2), 200ms) << how;
    EXPECT_LT(gap(2), 1000ms) << how;
  }
  const auto bad = [&](const std::string& text, const std::string& how) {
    std::ofstream(log) << text;
    const auto r = test::run_shell(ibs + how + " 2>&1");
    EXPECT_EQ(r.exit_code, 2) << r.out;
    EXPECT_TRUE(bus.take(1, 100ms).empty()) << "nothing is sent from a bad log";
    return r.out;
  };
  EXPECT_EQ(bad("(1.000000) can0 0DD#01\n(2.000000) can0 zz#00\n", log),
            "ibs canlust play: " + log + ":2: the identifier is not hex (a candump log line: (SECONDS.MICROS) IFACE "
            "ID#DATA): '(2.000000) can0 zz#00'\n");
  EXPECT_EQ(bad("(1.000000) can0 0DD#01\n(2.000000) can0 12345678#00\n", "- < " + log),
            "ibs canlust play: <stdin>:2: an extended-identifier or CAN FD frame: CANLust carries 11-bit classic "
            "frames only\n");
  EXPECT_EQ(bad("(1.1234567) can0 0DD#01\n", log),
            "ibs canlust play: " + log + ":1: the time '1.1234567' is not SECONDS.MICROS (up to 6 digits after the point)\n");
  EXPECT_EQ(bad("\n\n", log), "ibs canlust play: " + log + ": no frame to play\n");
  EXPECT_EQ(bad("", temp_path("canlust_nolog")).rfind("ibs canlust play: " + temp_path("canlust_nolog") + ": ", 0), 0U);

  // A frame 60 s on: SIGINT ends the wait, after the first frame, with 130.
  std::ofstream(log) << "(10.000000) can0 0DD#01\n(70.000000) can0 0DD#00\n";
  const auto t0 = std::chrono::steady_clock::now();
  const auto r = test::run_shell("timeout --preserve-status -s INT 0.5 " + ibs + log + " 2>&1");
  EXPECT_EQ(r.exit_code, 130) << r.out;
  EXPECT_EQ(r.out, "ibs canlust play: " + log + ": interrupted after 1 of 2 frames\n");
  EXPECT_LT(std::chrono::steady_clock::now() - t0, 5s);
  EXPECT_EQ(bus.take(2, 100ms).size(), 1U);
  std::remove(log.c_str());
}

// ---- the test bench (issue 24) ---------------------------------------------------------------

std::string write_file(const std::string& name, const std::string& text) {
  const std::string path = temp_path(name) + ".toml";
  std::ofstream(path) << text;
  return path;
}

const std::string kBenchHead = "name = \"bench\"\nduration = \"3 s\"\n[bus]\nprotocol = \"canlust\"\n";
const std::string kBenchDrive = "[[device]]\nname = \"a\"\ntype = \"cda3000\"\naddress = 1\n";

// `ibs run --realtime` with bus = "udp:...": the first line names the port bound; `ibs canlust
// read` (the client commands in this process) reads a drive's value from it; a device fault of
// the timeline shows in 95-ERR1 and in the status telegram; the summary counts the frames.
TEST(CanlustBench, ServedScenarioAnswersAClientAndShowsAnInjectedFault) {
  const std::uint16_t client = free_udp_port();
  const std::string file =
      write_file("bench_served", kBenchHead + "bus = \"udp:0:127.0.0.1:" + std::to_string(client) + "\"\n" +
                                          kBenchDrive + "[[timeline]]\nat = \"1.5 s\"\ndevice = \"a\"\nfault = "
                                          "\"device\"\ncause = \"E-OTI\"\n");
  test::ChildProcess run({IBS_CLI, "run", "--realtime", file});
  ASSERT_EQ(run.first_line().rfind("canlust udp: ", 0), 0U) << run.first_line();
  const std::string port = run.first_line().substr(std::string("canlust udp: ").size());
  const std::string bus = "udp:" + std::to_string(client) + ":127.0.0.1:" + port;
  auto r = run_cli({"canlust", "read", "--bus", bus, "--address", "1", "360"});
  EXPECT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(r.out, "CDA 1 360-DISP: 406\n");
  r = run_cli({"canlust", "read", "--bus", bus, "--address", "1", "ERR1"});
  EXPECT_EQ(r.out, "CDA 1 95-ERR1: 0 (no error)\n") << r.err;
  std::this_thread::sleep_for(1600ms);  // past the fault at 1.5 s
  r = run_cli({"canlust", "read", "--bus", bus, "--address", "1", "ERR1"});
  EXPECT_EQ(r.out, "CDA 1 95-ERR1: 8 E-OTI at location 0, 0 h\n") << r.err;
  r = run_cli({"canlust", "start", "--bus", bus, "--listen-ms", "200"});
  EXPECT_NE(r.out.find("CDA 1: status "), std::string::npos) << r.out << r.err;
  EXPECT_NE(r.out.find("FAULT"), std::string::npos) << r.out;
  std::string summary;
  EXPECT_EQ(run.wait(summary), 0);
  EXPECT_NE(summary.find("real time: served on udp: " + port + " for your master, "), std::string::npos) << summary;
  EXPECT_NE(summary.find("a (address 1): System Start, FAULT"), std::string::npos) << summary;
  EXPECT_NE(summary.find("  frames: received "), std::string::npos) << summary;
  EXPECT_NE(summary.find("1.500 s  a: device fault E-OTI: 8 E-OTI (drive unit overheating), FAULT"), std::string::npos) << summary;
  std::remove(file.c_str());
}

// What a served bus and --control need, refused with why (exit 2).
TEST(CanlustBench, ServedBusAndControlNeedRealtime) {
  const std::string served = write_file("bench_norealtime", kBenchHead + "bus = \"udp:0:127.0.0.1:0\"\n" + kBenchDrive);
  auto r = test::run_shell(std::string(IBS_CLI) + " run " + served + " 2>&1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, served + ":5: bus = \"udp:0:127.0.0.1:0\" serves the drives to your own master in real time: run it "
                            "with --realtime\n");
  r = test::run_shell(std::string(IBS_CLI) + " run " + std::string(IBS_SOURCE_DIR) +
                      "/examples/canlust/conveyors.toml --control - < /dev/null 2>&1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "--control - needs --realtime: without it the simulation runs faster than real time, so a live entry would have no time to land in\n");
  std::remove(served.c_str());
  // A bus that does not open: exit 2 with the transport's reason (this kernel has no CAN at all,
  // a kernel with CAN has no interface of this name).
  const std::string none = write_file("bench_nocan", kBenchHead + "bus = \"socketcan:ibsnocan0\"\n" + kBenchDrive);
  r = test::run_shell(std::string(IBS_CLI) + " run --realtime " + none + " 2>&1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out.rfind(none + ": bus = \"socketcan:ibsnocan0\": ", 0), 0U) << r.out;
  EXPECT_EQ(r.out.find("canlust socketcan:"), std::string::npos) << r.out;  // nothing served, nothing announced
  std::remove(none.c_str());
}

// `ibs run --realtime --control -`: a good line is applied at once and listed with its time, a bad
// one reported as control:LINE and skipped; the end of input does not end the run.
TEST(CanlustBench, ControlLinesFromStandardInput) {
  const std::string file =
      write_file("bench_control", "name = \"ctl\"\nduration = \"600 ms\"\n[bus]\nprotocol = \"canlust\"\n" +
                                           kBenchDrive + "[[timeline]]\nat = \"10 ms\"\nsystem = \"start\"\n");
  const auto r = test::run_shell("{ sleep 0.2; printf '%s\\n' '{\"device\": \"a\", \"fault\": \"device\", \"cause\": "
                                 "\"E-PAR\"}' '{\"device\": \"a\", \"at\": \"1 s\", \"load\": 5}' 'nonsense'; } | " +
                                 std::string(IBS_CLI) + " run --realtime --control - " + file + " 2>&1");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("control:2: control entries apply at once: no 'at'\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("control:3: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("  a: device fault E-PAR: 10 E-PAR (faulty parameter setting), FAULT"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("a (address 1): System Start, FAULT"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("real time: 601 steps of 1 ms, "), std::string::npos) << r.out;
  std::remove(file.c_str());
}

// `ibs canlust emulate --control unix:PATH`: a fault sent on the socket is seen by `ibs canlust read`.
TEST(CanlustBench, EmulateControlSocketInjectsAFault) {
  const Ports p;
  const std::string socket_path = temp_path("emulate_control") + ".sock";
  std::remove(socket_path.c_str());
  const std::string err_path = temp_path("emulate_control") + ".err";
  // Through bash for its standard error, where the applied events and the bad lines go.
  test::ChildProcess emu({"/bin/bash", "-c",
                          "exec " + std::string(IBS_CLI) + " canlust emulate --bus " + p.emulator_bus() +
                              " --control unix:" + socket_path + " cda3000@1 2> " + err_path});
  ASSERT_EQ(emu.first_line().rfind("bus: ", 0), 0U) << emu.first_line();
  const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
  sockaddr_un a{};
  a.sun_family = AF_UNIX;
  std::snprintf(a.sun_path, sizeof a.sun_path, "%s", socket_path.c_str());
  ASSERT_EQ(::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a), 0) << std::strerror(errno);
  const std::string lines =
      "{\"fault\": \"device\", \"cause\": \"E-PLS\"}\n{\"device\": 1, \"load\": 50}\n{\"at\": \"1 s\", \"load\": 5}\n"
      "{\"device\": \"cda3000@1\", \"fault\": \"device\", \"cause\": \"E-XYZ\"}\n{\"device\": 7, \"mains\": \"off\"}\n";
  ASSERT_EQ(::write(fd, lines.data(), lines.size()), static_cast<ssize_t>(lines.size()));
  std::this_thread::sleep_for(200ms);
  const auto r = run_cli({"canlust", "read", "--bus", p.client_bus(), "--address", "1", "ERR1"});
  EXPECT_EQ(r.out, "CDA 1 95-ERR1: 9 E-PLS at location 0, 0 h\n") << r.err;
  ::close(fd);
  EXPECT_EQ(emu.stop(SIGTERM), 0);
  std::ifstream in(err_path);
  const std::string err((std::istreambuf_iterator<char>(in)), {});
  // A socket's client is named with its number (issue 41): control:CLIENT:LINE.
  EXPECT_EQ(err,
            "control:1: connected (pid " + std::to_string(::getpid()) + ")\n"
            "control:1:1: cda3000@1: fault E-PLS: 9 E-PLS (plausibility error in parameter or program sequence), FAULT, "
            "error telegram sent\n"
            "control:1:2: cda3000@1: load 50.0 %: set: the motor slips 1.50 Hz below the output frequency\n"
            "control:1:3: control entries apply at once: no 'at'\n"
            "control:1:4: cause 'E-XYZ': the CDA3000's errors (CANLust manual, table 5.9) are 8 E-OTI, 9 E-PLS, 10 E-PAR, "
            "11 E-FLT, 12 E-PWR, 16 E-OP2; its warnings (6.3) are 0004H W-I2T, 0008H W-TM, 0010H W-TH\n"
            "control:1:5: device 7 is not served (give its address or NAME@ADDR as on the command line)\n");
  std::remove(err_path.c_str());
}

}  // namespace
}  // namespace ibs::cli
