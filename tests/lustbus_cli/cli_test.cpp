// `ibs lustbus ...`: `emulate --pty` as a process (prints `pty: PATH` first, serves, exits 0 on
// SIGTERM and SIGINT), read / write / describe / scan in process against it, JSON, a NAK exiting 1
// with its cause, bad input exiting 2 with the parameter, value and limit, and the byte log.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "lustbus_cmd.hpp"

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

TEST(LustbusCli, EmulatePrintsThePtyFirstAndExitsZeroOnSignals) {
  Emulator a({"vf1000@1"});
  ASSERT_EQ(a.first_line().rfind("pty: /dev/pts/", 0), 0U) << a.first_line();
  EXPECT_EQ(a.stop(SIGTERM), 0);
  Emulator b({"mc6000@2"});
  ASSERT_EQ(b.first_line().rfind("pty: ", 0), 0U);
  EXPECT_EQ(b.stop(SIGINT), 0);
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

TEST(LustbusCli, NakExitsOneWithTheCause) {
  Emulator emu({"vf1000@1"});
  const std::string port = emu.pty();
  // 7.1: control on the serial interface, then the start.
  ASSERT_EQ(run_cli(cmd({"write", "--addr", "1", "--device", "vf1000", "MODE", "0"}, port)).rc, 0);
  ASSERT_EQ(run_cli(cmd({"write", "--addr", "1", "--device", "vf1000", "CSEL", "3"}, port)).rc, 0);
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
