// `--pcap FILE` of `ibs lustbus` (issue 36, docs/pcap.md "Serial lines"): the host's and the
// emulator's captures of the same exchange, each telegram its way; a device that does not answer
// still gives a capture; `-` is standard output; and the output rules of docs/robustness.md: no
// file under its name before the command ends, none after bad input or an interrupt, nothing
// replaced that is not a regular file. `ibs decode` reads the capture back.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <thread>

#include "ibs/serial/capture.hpp"
#include "ibs/serial/pty.hpp"
#include "lustbus_cmd.hpp"
#include "serial_decode.hpp"

#include "../support/cli_harness.hpp"

namespace ibs::cli {
namespace {

using base::LineSide;
using Bytes = std::vector<std::uint8_t>;
using test::CliRun;

CliRun run_cli(std::vector<std::string> args) {
  return test::run_cli_group<LustbusCommandState>(std::move(args), kExitLustbusBadInput, add_lustbus_commands,
                                                  run_lustbus_commands);
}

std::vector<std::string> cmd(std::vector<std::string> a, const std::string& port) {
  std::vector<std::string> v = {"lustbus"};
  v.insert(v.end(), a.begin(), a.end());
  v.insert(v.end(), {"--port", port, "--timeout-ms", "2000"});
  return v;
}

Bytes file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return Bytes((std::istreambuf_iterator<char>(in)), {});
}

serial::LineCaptureReading read_capture(const std::string& path) { return serial::read_line_capture(file_bytes(path)); }

Bytes text(Bytes head, std::string_view s, Bytes tail) {
  head.insert(head.end(), s.begin(), s.end());
  head.insert(head.end(), tail.begin(), tail.end());
  return head;
}

// No file under `path`, and no temporary of it beside.
bool nothing_written(const std::string& path) {
  const std::filesystem::path p(path);
  if (std::filesystem::exists(p)) return false;
  for (const auto& e : std::filesystem::directory_iterator(p.parent_path())) {
    if (e.path().filename().string().rfind(p.filename().string() + ".ibs-partial-", 0) == 0) return false;
  }
  return true;
}

std::string temp_dir(const std::string& name) {
  const std::string dir = ::testing::TempDir() + name + "_" + std::to_string(::getpid());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

TEST(LustbusPcap, TheHostAndTheEmulatorCaptureTheSameTelegramsEachItsWay) {
  const std::string dir = temp_dir("lustbus_pcap");
  const std::string emu_pcap = dir + "/emulator.pcap";
  test::ChildProcess emu({IBS_CLI, "lustbus", "emulate", "--pty", "--pcap", emu_pcap, "vf1000@1"});
  ASSERT_EQ(emu.first_line().rfind("pty: ", 0), 0U) << emu.first_line();
  const std::string host_pcap = dir + "/host.pcap";
  CliRun r = run_cli(cmd({"write", "--addr", "1", "--device", "vf1000", "FSSIO", "23.15", "--pcap", host_pcap}, emu.pty()));
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(r.out, "vf1000@1 5-FSSIO := 23.15 Hz (01CFH)\n");
  // The host's capture: its SELECT, refused at first (NAK: the power-on bit of 85-SIOF, 6), the
  // ENQUIRY of SIOF that clears it, the SELECT again and the drive's ACK, each closed by EOT.
  const auto host = read_capture(host_pcap);
  ASSERT_FALSE(host.error) << host.error->what;
  EXPECT_EQ(host.protocol, serial::LineProtocol::lustbus);
  const Bytes select = text({0x04, 0x41, 0x02}, "00105=01CF", {0x03, 0x0E});
  const std::vector<std::pair<LineSide, Bytes>> want = {
      {LineSide::host, select},          {LineSide::device, {0x41, 0x15}}, {LineSide::host, {0x04}},
      {LineSide::host, text({0x04, 0x41}, "00085", {0x05})},
      {LineSide::device, text({0x41, 0x02}, "00085=0001", {0x03, 0x02})},
      {LineSide::host, {0x04}},          {LineSide::host, select},         {LineSide::device, {0x41, 0x06}},
      {LineSide::host, {0x04}}};
  ASSERT_EQ(host.packets.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    EXPECT_EQ(host.packets[i].from, want[i].first) << i;
    EXPECT_EQ(host.packets[i].bytes, want[i].second) << i;
    EXPECT_EQ(host.packets[i].flags, 0) << i;
    if (i > 0) {
      EXPECT_LE(host.packets[i - 1].at, host.packets[i].at) << i;
    }
  }
  EXPECT_EQ(host.packets[0].address, 1);
  EXPECT_EQ(host.packets[1].address, 1);
  EXPECT_FALSE(host.packets[2].address) << "a lone EOT names no device";
  // The emulator's capture is written when it stops, all or nothing: nothing under its name before.
  r = run_cli(cmd({"read", "--addr", "1", "--device", "vf1000", "FSSIO"}, emu.pty()));
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_FALSE(std::filesystem::exists(emu_pcap));
  ASSERT_EQ(emu.stop(SIGTERM), 0);
  const auto served = read_capture(emu_pcap);
  ASSERT_FALSE(served.error) << served.error->what;
  ASSERT_EQ(served.packets.size(), want.size() + 3);
  for (std::size_t i = 0; i < want.size(); ++i) {
    EXPECT_EQ(served.packets[i].from, want[i].first) << i;
    EXPECT_EQ(served.packets[i].bytes, want[i].second) << i;
  }
  EXPECT_EQ(served.packets[want.size() + 1].bytes, text({0x41, 0x02}, "00105=01CF", {0x03, 0x0E}));
  // `ibs decode` reads it back, telegram by telegram.
  std::ostringstream out;
  std::ostringstream err;
  ASSERT_EQ(decode_line_capture(emu_pcap, out, err), 0) << err.str();
  const std::string decoded = out.str();
  EXPECT_NE(decoded.find(emu_pcap + ": LUSTBUS capture (pcap, link type 148), 12 packet(s) from "), std::string::npos)
      << decoded;
  EXPECT_NE(decoded.find(" host  SELECT A (address 1) 00105=01CF BCC ok: VF1000 5-FSSIO := 23.15 Hz"),
            std::string::npos)
      << decoded;
  EXPECT_NE(decoded.find(" drive A 00105=01CF BCC ok: VF1000 5-FSSIO = 23.15 Hz"), std::string::npos) << decoded;
  std::filesystem::remove_all(dir);
}

// What a capture is for: a device that does not answer. The command fails (exit 1); its capture
// holds the ENQUIRY that went unanswered and the EOT after the timeout.
TEST(LustbusPcap, ACaptureOfADeviceThatDoesNotAnswerIsKept) {
  const std::string dir = temp_dir("lustbus_pcap_silent");
  test::ChildProcess emu({IBS_CLI, "lustbus", "emulate", "--pty", "vf1000@1"});
  const std::string pcap = dir + "/silent.pcap";
  const CliRun r = run_cli({"lustbus", "read", "--port", emu.pty(), "--addr", "5", "--device", "vf1000", "FSSIO",
                            "--timeout-ms", "100", "--pcap", pcap});
  EXPECT_EQ(r.rc, kExitLustbusDevice) << r.err;
  const auto c = read_capture(pcap);
  ASSERT_FALSE(c.error) << c.error->what;
  ASSERT_GE(c.packets.size(), 1U);
  EXPECT_EQ(c.packets[0].bytes, text({0x04, 0x45}, "00105", {0x05}));
  EXPECT_EQ(c.packets[0].address, 5);
  for (const auto& p : c.packets) EXPECT_EQ(p.from, LineSide::host) << "nobody answered";
  EXPECT_EQ(emu.stop(SIGTERM), 0);
  std::filesystem::remove_all(dir);
}

TEST(LustbusPcap, DashIsStandardOutputAndTheReportGoesToStandardError) {
  test::ChildProcess emu({IBS_CLI, "lustbus", "emulate", "--pty", "vf1000@1"});
  CliRun r = run_cli(cmd({"read", "--addr", "1", "--device", "vf1000", "FSSIO", "--pcap", "-"}, emu.pty()));
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(r.err, "vf1000@1 5-FSSIO = 0.00 Hz (0000H)\n");
  const auto c = serial::read_line_capture(Bytes(r.out.begin(), r.out.end()));
  ASSERT_FALSE(c.error) << c.error->what;
  EXPECT_EQ(c.packets.size(), 3U);
  // One standard output for two outputs is refused before anything runs.
  r = run_cli(cmd({"read", "--addr", "1", "--device", "vf1000", "FSSIO", "--pcap", "-", "--log", "-"}, emu.pty()));
  EXPECT_EQ(r.rc, kExitLustbusBadInput);
  EXPECT_EQ(r.err, "ibs lustbus read: --log - and --pcap - both ask for standard output; give one of them a file\n");
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(emu.stop(SIGTERM), 0);
}

TEST(LustbusPcap, APathThatCannotTakeTheCaptureFailsBeforeAnythingIsSent) {
  const std::string dir = temp_dir("lustbus_pcap_bad");
  test::ChildProcess emu({IBS_CLI, "lustbus", "emulate", "--pty", "--json", "vf1000@1"});
  // A missing folder, a directory, the byte log's own file: each refused, exit 2, nothing made.
  CliRun r = run_cli(cmd({"read", "--addr", "1", "--device", "vf1000", "FSSIO", "--pcap", dir + "/no/such/x.pcap"},
                         emu.pty()));
  EXPECT_EQ(r.rc, kExitLustbusBadInput);
  EXPECT_NE(r.err.find("ibs lustbus read: --pcap " + dir + "/no/such/x.pcap: "), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/no"));
  r = run_cli(cmd({"read", "--addr", "1", "--device", "vf1000", "FSSIO", "--pcap", dir}, emu.pty()));
  EXPECT_EQ(r.rc, kExitLustbusBadInput);
  EXPECT_NE(r.err.find("is a directory"), std::string::npos) << r.err;
  r = run_cli(cmd({"read", "--addr", "1", "--device", "vf1000", "FSSIO", "--pcap", dir + "/same", "--log",
                   dir + "/./same"},
                  emu.pty()));
  EXPECT_EQ(r.rc, kExitLustbusBadInput);
  EXPECT_NE(r.err.find("are the same file"), std::string::npos) << r.err;
  EXPECT_TRUE(nothing_written(dir + "/same"));
  // Bad input found after the capture was opened (an unknown parameter): no file either.
  r = run_cli(cmd({"read", "--addr", "1", "--device", "vf1000", "NOSUCH", "--pcap", dir + "/bad.pcap"}, emu.pty()));
  EXPECT_EQ(r.rc, kExitLustbusBadInput);
  EXPECT_TRUE(nothing_written(dir + "/bad.pcap"));
  // The emulator heard none of it: its first line is `serving`, the next its summary.
  ASSERT_EQ(emu.stop(SIGTERM), 0);
  EXPECT_EQ(emu.rest().find("\"event\":\"telegram\""), std::string::npos);
  std::filesystem::remove_all(dir);
}

// SIGINT while a single request waits: the request ends (its timeout bounds it), the command says
// it was interrupted and exits 130, and no capture is left, neither under its name nor a temporary.
TEST(LustbusPcap, AnInterruptedCommandLeavesNoCapture) {
  const std::string dir = temp_dir("lustbus_pcap_sigint");
  serial::PtyPair silent = serial::PtyPair::open();  // a line nobody answers on
  const std::string pcap = dir + "/interrupted.pcap";
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::execl(IBS_CLI, IBS_CLI, "lustbus", "read", "--port", silent.slave_path().c_str(), "--addr", "1", "--device",
            "vf1000", "FSSIO", "--timeout-ms", "1500", "--pcap", pcap.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  std::array<std::uint8_t, 64> buf{};
  ASSERT_GT(silent.master().read(buf, std::chrono::seconds(5)), 0U) << "the request went out";
  ::kill(pid, SIGINT);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130);
  EXPECT_TRUE(nothing_written(pcap));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace ibs::cli
