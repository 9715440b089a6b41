// tshark with tools/wireshark/lustbus.lua and dfs1.lua over captures of the manuals' worked
// examples (LUSTBUS manual's ENQUIRY, SELECT and PosMOD1 exchanges corrected as docs/errata.md decides;
// DFS-1 manual's set-speed frame and its ACK), every field a user filters on checked, and a wrong BCC
// and a wrong CSM flagged as the manuals' errors would make them (skipped where tshark is missing).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "ibs/devices/dfs1/status.hpp"
#include "ibs/dfs1/capture_framer.hpp"
#include "ibs/dfs1/frame.hpp"
#include "ibs/lustbus/capture_framer.hpp"
#include "ibs/pcap/pcap_file.hpp"
#include "ibs/serial/capture.hpp"
#include "../support/seed_telegrams.hpp"

namespace ibs::serial {
namespace {

using base::LineSide;
using Bytes = std::vector<std::uint8_t>;

std::string temp_path(const std::string& name) {
  return ::testing::TempDir() + "/" + name + "_" + std::to_string(::getpid()) + ".pcap";
}

// `seed` recorded into a file, 10 ms apart; returns its path.
std::string write_capture(const std::string& name, LineProtocol protocol, const std::vector<test::SeedTelegram>& seed) {
  lustbus::CaptureFramer lb;
  dfs1::CaptureFramer df;
  base::TelegramFramer& framer = protocol == LineProtocol::lustbus ? static_cast<base::TelegramFramer&>(lb) : df;
  const std::string path = temp_path(name);
  std::ofstream out(path, std::ios::binary);
  LineCapture cap(out, protocol, framer, Direction::tx);
  Time t{0};
  for (const auto& s : seed) {
    cap.record(s.from, s.bytes, t);
    t += 10ms;
  }
  cap.finish();
  return path;
}

std::string run(const std::string& cmd) {
  std::string out;
  FILE* p = ::popen(cmd.c_str(), "r");
  if (p == nullptr) return out;
  char buf[4096];
  std::size_t n = 0;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  ::pclose(p);
  return out;
}

std::vector<std::string> lines_of(const std::string& s) {
  std::vector<std::string> v;
  std::istringstream in(s);
  for (std::string l; std::getline(in, l);) v.push_back(l);
  return v;
}

bool have_tshark() { return std::system("command -v tshark >/dev/null 2>&1") == 0 && pcap::available(); }

std::string tshark(const std::string& lua, const std::string& path) {
  return "tshark -X lua_script:" + std::string(IBS_SOURCE_DIR) + "/tools/wireshark/" + lua + " -r " + path;
}

TEST(WiresharkDissector, TsharkDecodesTheLustbusExamplesOfSeed000) {
  if (!have_tshark()) GTEST_SKIP() << "tshark is not installed (Debian package tshark), or no libpcap";
  const std::string path = write_capture("lustbus_seed", LineProtocol::lustbus, test::lustbus_seed_exchanges());
  const auto rows = lines_of(run(tshark("lustbus.lua", path) +
                                 " -T fields -E separator=';' -e lustbus.direction -e lustbus.kind -e lustbus.address"
                                 " -e lustbus.code -e lustbus.code.family -e lustbus.code.parameter -e lustbus.value"
                                 " -e lustbus.value.raw -e lustbus.bcc -e lustbus.bcc.ok -e lustbus.request_in"
                                 " 2>/dev/null"));
  const std::vector<std::string> want = {
      "0;ENQUIRY;0;00112;VF1000 (2.4.1);12;;;;;",
      "1;answer;0;00112;VF1000 (2.4.1);12;03E8;0x000003e8;0x72;1;1",
      "0;EOT;;;;;;;;;",
      "0;ENQUIRY;0;20077;MC6000 (2.4.2);77;;;;;",
      "1;answer;0;20077;MC6000 (2.4.2);77;04FA4000;0x04fa4000;0x0b;1;4",
      "0;EOT;;;;;;;;;",
      "0;SELECT;0;00105;VF1000 (2.4.1);5;03E8;0x000003e8;0x74;1;",
      "1;ACK;0;;;;;;;;7",
      "0;EOT;;;;;;;;;",
      "0;SELECT;0;20428;MC6000 (2.4.2);428;14D4106;0x014d4106;0x40;1;",
      "1;ACK;0;;;;;;;;10",
      "0;EOT;;;;;;;;;",
      "0;SELECT;0;49999;PosMOD1 (MC6000, 11.6);;8GOA0V1000;;0x1c;1;",
      "1;ACK;0;;;;;;;;13",
      "0;EOT;;;;;;;;;",
  };
  ASSERT_EQ(rows.size(), want.size()) << run(tshark("lustbus.lua", path) + " 2>&1");
  for (std::size_t i = 0; i < want.size(); ++i) EXPECT_EQ(rows[i], want[i]) << "frame " << i + 1;
  // The tree names every control character, the ADR and the parts of the CODE.
  const std::string verbose = run(tshark("lustbus.lua", path) + " -V -c 2 2>/dev/null");
  for (const char* s : {"LUSTBUS (LUSTBUS manual), host to device", "Control character: EOT (0x04)",
                        "ADR: '@' (40H): address 0", "CODE: 00112 (VF1000 parameter 12, value)",
                        "Control character: ENQ (0x05)", "Control character: STX (0x02)",
                        "VALUE: 03E8", "Control character: ETX (0x03)", "BCC: 0x72 [correct]",
                        "Request in frame: 1"}) {
    EXPECT_NE(verbose.find(s), std::string::npos) << s << "\n" << verbose;
  }
  const std::string info = run(tshark("lustbus.lua", path) + " 2>/dev/null");
  EXPECT_NE(info.find("host   SELECT @ 00105=03E8 BCC ok"), std::string::npos) << info;
  EXPECT_NE(info.find("device answer @ 20077=04FA4000 BCC ok"), std::string::npos) << info;
  std::remove(path.c_str());
}

// LB-E4: 6.1.1.2's answer read as the 7-character 4FA4000 has BCC 3BH; sent with the 8 characters
// 04FA4000 it must be 0BH. A capture of the mix shows the error as a recording of a broken device
// would: the BCC field, the recorder's flag and an expert error.
TEST(WiresharkDissector, AWrongLustbusBccIsFlagged) {
  if (!have_tshark()) GTEST_SKIP() << "tshark is not installed (Debian package tshark), or no libpcap";
  auto seed = test::lustbus_seed_exchanges();
  std::vector<test::SeedTelegram> exchange(seed.begin() + 3, seed.begin() + 6);
  exchange[1].bytes.back() = 0x3B;
  const std::string path = write_capture("lustbus_bad_bcc", LineProtocol::lustbus, exchange);
  const auto rows = lines_of(run(tshark("lustbus.lua", path) +
                                 " -Y 'lustbus.bcc.ok == 0' -T fields -E separator=';' -e frame.number"
                                 " -e lustbus.bcc -e lustbus.bcc.computed -e lustbus.flags.check_bad 2>/dev/null"));
  ASSERT_EQ(rows.size(), 1U);
  EXPECT_EQ(rows[0], "2;0x3b;0x0b;1");
  const std::string info = run(tshark("lustbus.lua", path) + " 2>/dev/null");
  EXPECT_NE(info.find("answer @ 20077=04FA4000 BCC WRONG (3BH, should be 0BH)"), std::string::npos) << info;
  const std::string experts = run(tshark("lustbus.lua", path) + " -q -z expert,error 2>/dev/null");
  EXPECT_NE(experts.find("BCC 3BH wrong: should be 0BH (2.2)"), std::string::npos) << experts;
  std::remove(path.c_str());
}

TEST(WiresharkDissector, TsharkDecodesTheDfs1ExampleOfSeed004) {
  if (!have_tshark()) GTEST_SKIP() << "tshark is not installed (Debian package tshark), or no libpcap";
  const std::string path = write_capture("dfs1_seed", LineProtocol::dfs1, test::dfs1_seed_exchange());
  // Two passes (-2): a request shows the frame of its response, which the first pass has not met yet.
  const auto rows = lines_of(run(tshark("dfs1.lua", path) +
                                 " -2 -T fields -E separator=';' -e dfs1.direction -e dfs1.uid -e dfs1.kind"
                                 " -e dfs1.command -e dfs1.response -e dfs1.speed -e dfs1.data -e dfs1.checksum"
                                 " -e dfs1.checksum.ok -e dfs1.request_in -e dfs1.response_in 2>/dev/null"));
  ASSERT_EQ(rows.size(), 2U) << run(tshark("dfs1.lua", path) + " 2>&1");
  // The 10H datum counts once (note 2): data 00 00 10 00, 4096 rpm, CSM 6DH.
  EXPECT_EQ(rows[0], "0;1;request;0x82;;4096;00001000;0x6d;1;;2");
  EXPECT_EQ(rows[1], "1;1;ACK;;0x06;;;0xf9;1;1;");
  const std::string verbose = run(tshark("dfs1.lua", path) + " -V 2>/dev/null");
  for (const char* s : {"DFS-1 (DFS-1 manual), host to controller", "DLE STX: 0x1002", "Command: set speed (0x82)",
                        "Speed (rpm): 4096", "DLE ETX: 0x1003", "CSM: 0x6d [correct]", "Response: ACK (0x06)"}) {
    EXPECT_NE(verbose.find(s), std::string::npos) << s << "\n" << verbose;
  }
  // The unstuffed bytes are a data source of their own: UID, CMD and the data, the 10H once.
  const std::string hex = run(tshark("dfs1.lua", path) + " -x -c 1 2>/dev/null");
  EXPECT_NE(hex.find("Unstuffed DFS-1 frame (6 bytes):\n0000  01 82 00 00 10 00"), std::string::npos) << hex;
  const std::string info = run(tshark("dfs1.lua", path) + " 2>/dev/null");
  EXPECT_NE(info.find("host       UID 1 set speed 4096 rpm"), std::string::npos) << info;
  EXPECT_NE(info.find("controller UID 1 ACK"), std::string::npos) << info;
  std::remove(path.c_str());
}

// DFS1-E1: summing the data "between STX and ETX" as sent, the doubled 10H twice, gives 5DH; the
// seed's note 2 counts it once (6DH). A frame sent with 5DH is what the dissector flags.
TEST(WiresharkDissector, AWrongDfs1ChecksumIsFlagged) {
  if (!have_tshark()) GTEST_SKIP() << "tshark is not installed (Debian package tshark), or no libpcap";
  auto seed = test::dfs1_seed_exchange();
  seed[0].bytes.back() = 0x5D;
  seed.pop_back();
  const std::string path = write_capture("dfs1_bad_csm", LineProtocol::dfs1, seed);
  const auto rows = lines_of(run(tshark("dfs1.lua", path) +
                                 " -T fields -E separator=';' -e dfs1.checksum -e dfs1.checksum.computed"
                                 " -e dfs1.checksum.ok -e dfs1.flags.check_bad 2>/dev/null"));
  ASSERT_EQ(rows.size(), 1U);
  EXPECT_EQ(rows[0], "0x5d;0x6d;0;1");
  const std::string experts = run(tshark("dfs1.lua", path) + " -q -z expert,error 2>/dev/null");
  EXPECT_NE(experts.find("CSM 5DH wrong: should be 6DH"), std::string::npos) << experts;
  std::remove(path.c_str());
}

// A status response (decision D3: commanded, actual, load %, 00 00 ST2 ST1) and a NAK read by the
// command they answer, the status bits by the controller's own names (devices/dfs1/status.hpp).
TEST(WiresharkDissector, Dfs1StatusBitsAreTheControllersAndANakItsError) {
  if (!have_tshark()) GTEST_SKIP() << "tshark is not installed (Debian package tshark), or no libpcap";
  const auto enc = [](const dfs1::Frame& f) {
    const auto e = dfs1::encode(f);
    return Bytes(e.span().begin(), e.span().end());
  };
  std::vector<test::SeedTelegram> seq;
  const std::vector<std::pair<std::uint8_t, std::uint8_t>> statuses = {{0xA5, 0x5A}, {0x5A, 0xA5}};
  for (const auto& [st2, st1] : statuses) {
    const Bytes data = {0x00, 0x00, 0x05, 0xDC, 0xFF, 0xFF, 0xFF, 0x9C, 0x00, 0x00, 0x00, 0x2A, 0x00, 0x00, st2, st1};
    seq.push_back({LineSide::host, enc(dfs1::make_frame(7, 0x81))});
    seq.push_back({LineSide::device, enc(dfs1::make_ack(7, data))});
  }
  seq.push_back({LineSide::host, enc(dfs1::make_frame(7, 0x85, Bytes{200}))});
  seq.push_back({LineSide::device, enc(dfs1::make_nak(7, dfs1::ErrorCode::illegal_parameter_number))});
  const std::string path = write_capture("dfs1_status", LineProtocol::dfs1, seq);
  const auto rows = lines_of(run(tshark("dfs1.lua", path) +
                                 " -Y 'dfs1.response == 0x06' -T fields -E separator=';' -e dfs1.status.commanded"
                                 " -e dfs1.status.actual -e dfs1.status.load -e dfs1.st2.flags -e dfs1.st1.flags"
                                 " 2>/dev/null"));
  ASSERT_EQ(rows.size(), 2U);
  for (std::size_t i = 0; i < 2; ++i) {
    const auto join = [](const std::vector<std::string_view>& v) {
      std::string s;
      for (const auto x : v) s += (s.empty() ? "" : " ") + std::string(x);
      return s.empty() ? std::string("none") : s;
    };
    EXPECT_EQ(rows[i], "1500;-100;42;" + join(devices::dfs1::st2_flags(statuses[i].first)) + ";" +
                           join(devices::dfs1::st1_flags(statuses[i].second)));
  }
  const auto nak = lines_of(run(tshark("dfs1.lua", path) +
                                " -Y 'dfs1.response == 0x15' -T fields -E separator=';' -e dfs1.error"
                                " -e _ws.col.Info 2>/dev/null"));
  ASSERT_EQ(nak.size(), 1U);
  EXPECT_EQ(nak[0], "0x82;controller UID 7 NAK 82 illegal parameter number");
  std::remove(path.c_str());
}

}  // namespace
}  // namespace ibs::serial
