// `--pcap FILE` of `ibs dfs1` (issue 36, docs/pcap.md "Serial lines"): the host's and the
// emulator's captures of the same frames, a NAK and a global frame nobody answers among them, and
// `ibs decode` reading the capture back with the status and the error named.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "dfs1_cmd.hpp"
#include "ibs/dfs1/frame.hpp"
#include "ibs/pcap/pcap_file.hpp"
#include "ibs/serial/capture.hpp"
#include "serial_decode.hpp"

#include "../support/cli_harness.hpp"

namespace ibs::cli {
namespace {

using base::LineSide;
using Bytes = std::vector<std::uint8_t>;
using test::CliRun;

CliRun run_cli(std::vector<std::string> args) {
  return test::run_cli_group<Dfs1CommandState>(std::move(args), kExitDfs1BadInput, add_dfs1_commands,
                                               run_dfs1_commands);
}

serial::LineCaptureReading read_capture(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return serial::read_line_capture(Bytes((std::istreambuf_iterator<char>(in)), {}));
}

Bytes frame(const dfs1::Frame& f) {
  const auto e = dfs1::encode(f);
  return Bytes(e.span().begin(), e.span().end());
}

TEST(Dfs1Pcap, TheHostAndTheEmulatorCaptureTheSameFramesAndDecodeReadsThem) {
  const std::string dir = ::testing::TempDir() + "dfs1_pcap_" + std::to_string(::getpid());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string emu_pcap = dir + "/emulator.pcap";
  test::ChildProcess emu({IBS_DFS1_CLI, "dfs1", "emulate", "--pty", "--pcap", emu_pcap, "dfs1@1"});
  ASSERT_EQ(emu.first_line().rfind("pty: ", 0), 0U) << emu.first_line();
  const std::string port = emu.pty();
  const std::string status_pcap = dir + "/status.pcap";
  CliRun r = run_cli({"dfs1", "status", "--port", port, "--uid", "1", "--timeout-ms", "3000", "--pcap", status_pcap});
  ASSERT_EQ(r.rc, 0) << r.err;
  const auto host = read_capture(status_pcap);
  ASSERT_FALSE(host.error) << host.error->what;
  EXPECT_EQ(host.protocol, serial::LineProtocol::dfs1);
  ASSERT_EQ(host.packets.size(), 2U);
  EXPECT_EQ(host.packets[0].from, LineSide::host);
  EXPECT_EQ(host.packets[0].bytes, frame(dfs1::make_frame(1, 0x81)));
  EXPECT_EQ(host.packets[0].address, 1);
  EXPECT_EQ(host.packets[1].from, LineSide::device);
  EXPECT_EQ(host.packets[1].flags, 0);
  EXPECT_EQ(host.packets[1].address, 1);
  // A NAK is a device's answer like any other: captured, and the command exits 1.
  r = run_cli({"dfs1", "read", "--port", port, "--uid", "1", "99", "--timeout-ms", "3000", "--pcap", dir + "/nak.pcap"});
  EXPECT_EQ(r.rc, kExitDfs1Device);
  const auto nak = read_capture(dir + "/nak.pcap");
  ASSERT_EQ(nak.packets.size(), 2U);
  EXPECT_EQ(nak.packets[1].bytes, frame(dfs1::make_nak(1, dfs1::ErrorCode::illegal_parameter_number)));
  // UID 0, command 83: nobody answers (DFS-1 manual); the capture holds the one frame.
  r = run_cli({"dfs1", "speed", "--port", port, "--uid", "0", "--execute", "--pcap", dir + "/global.pcap"});
  EXPECT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(read_capture(dir + "/global.pcap").packets.size(), 1U);
  EXPECT_FALSE(std::filesystem::exists(emu_pcap)) << "written when the emulator stops, not before";
  ASSERT_EQ(emu.stop(SIGINT), 0);
  const auto served = read_capture(emu_pcap);
  ASSERT_FALSE(served.error) << served.error->what;
  ASSERT_EQ(served.packets.size(), 5U);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(served.packets[i].from, host.packets[i].from);
    EXPECT_EQ(served.packets[i].bytes, host.packets[i].bytes);
  }
  std::ostringstream out;
  std::ostringstream err;
  ASSERT_EQ(decode_line_capture(emu_pcap, out, err), 0) << err.str();
  const std::string text = out.str();
  EXPECT_NE(text.find(emu_pcap + ": DFS-1 capture (pcap, link type 149), 5 packet(s) from "), std::string::npos) << text;
  EXPECT_NE(text.find(" host       UID 1 status\n"), std::string::npos) << text;
  EXPECT_NE(text.find(" controller UID 1 ACK status: commanded 0 rpm, actual 0 rpm, load 0 %, ST2 31H "
                      "(at-speed forward zero-speed), ST1 00H (none)\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find(" host       UID 1 read parameter 99\n"), std::string::npos) << text;
  EXPECT_NE(text.find(" controller UID 1 NAK 82H illegal parameter number\n"), std::string::npos) << text;
  EXPECT_NE(text.find(" host       UID 0 (every controller) execute speed\n"), std::string::npos) << text;
  std::filesystem::remove_all(dir);
}

// `ibs decode` of a pcap file that is no serial line's capture, and of one with a broken packet.
TEST(Dfs1Pcap, DecodeRefusesAnotherLinkTypeAndABrokenPacketByNumber) {
  const std::string dir = ::testing::TempDir() + "dfs1_pcap_bad_" + std::to_string(::getpid());
  std::filesystem::create_directories(dir);
  std::ostringstream other;
  {
    pcap::PcapFile f(other, 147);
    f.write(Time{0}, Bytes{0x49, 0x42, 1, 1});
    f.close();
  }
  std::ofstream(dir + "/interbus.pcap", std::ios::binary) << other.str();
  std::ostringstream out;
  std::ostringstream err;
  EXPECT_EQ(decode_line_capture(dir + "/interbus.pcap", out, err), 2);
  EXPECT_EQ(err.str(), "ibs decode: " + dir + "/interbus.pcap: link type 147 is no serial line's (148 LUSTBUS, 149 DFS-1)\n");
  EXPECT_EQ(out.str(), "");
  std::ostringstream broken;
  {
    pcap::PcapFile f(broken, serial::kLinktypeDfs1);
    f.write(Time{0}, Bytes{1, 0, 0, 0, 0, 0, 0, 0, 0x10, 0x02});
    f.write(Time{1ms}, Bytes{9, 0, 0, 0, 0, 0, 0, 0});
    f.close();
  }
  std::ofstream(dir + "/broken.pcap", std::ios::binary) << broken.str();
  err.str("");
  EXPECT_EQ(decode_line_capture(dir + "/broken.pcap", out, err), 2);
  EXPECT_EQ(err.str(), "ibs decode: " + dir + "/broken.pcap: packet 2: header version 9 (this ibs reads version 1)\n");
  // Anything that is no pcap file is another reader's.
  std::ofstream(dir + "/text.log") << "ibs-serial-log 1\n";
  EXPECT_FALSE(decode_line_capture(dir + "/text.log", out, err));
  EXPECT_FALSE(decode_line_capture(dir + "/missing", out, err));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace ibs::cli
