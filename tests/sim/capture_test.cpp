// Captures for Wireshark (docs/pcap.md): the packet layouts byte by byte, a simulated run written
// through libpcap, and the Lua dissector tools/wireshark/interbus.lua run by tshark over it
// (skipped, saying why, where tshark is missing).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "ibs/sim/pcap_recorder.hpp"
#include "ibs/sim/simulator.hpp"

namespace ibs::sim {
namespace {

using Bytes = std::vector<std::uint8_t>;

capture::Configuration two_devices() {
  capture::Configuration c;
  c.cycle_time = 726us;
  c.in_words = 6;
  c.out_words = 6;
  c.pcp_words = 1;
  capture::Device mc;
  mc.name = "servo";
  mc.kind = 2;  // MC6000 (docs/pcap.md, "Configuration")
  mc.id_code = 0x4DB;
  mc.in = {0, 3};
  mc.out = {0, 3};
  mc.pcp = {0, 1};
  mc.values = capture::Values::q16;
  mc.layout = {11, 2};  // 405-SUPI, 406-IBCNF
  mc.unit = "rpm";
  capture::Device vf;
  vf.name = "fan";
  vf.kind = 1;  // VF1000
  vf.id_code = 0x33B;
  vf.in = {3, 3};
  vf.out = {3, 3};
  vf.pcp = {1, 0};
  vf.values = capture::Values::hz_005;
  vf.unit = "Hz";
  c.devices = {mc, vf};
  return c;
}

TEST(Capture, ConfigurationPacketLayout) {
  const Bytes b = capture::encode_configuration(two_devices());
  const Bytes header{0x49, 0x42, 1, 1, 0, 2, 0, 6, 0, 6, 0, 1, 0x00, 0x0B, 0x13, 0xF0, 0, 0, 0, 0};
  ASSERT_GE(b.size(), header.size());
  EXPECT_EQ(Bytes(b.begin(), b.begin() + 20), header);
  const Bytes servo{2, 1, 0x04, 0xDB, 0, 0, 0, 3, 0, 0, 0, 3, 0, 0, 0, 1, 2, 11, 2,
                    5, 's', 'e', 'r', 'v', 'o', 3, 'r', 'p', 'm'};
  EXPECT_EQ(Bytes(b.begin() + 20, b.begin() + 20 + static_cast<long>(servo.size())), servo);
  const Bytes fan{1, 1, 0x03, 0x3B, 0, 3, 0, 3, 0, 3, 0, 3, 0, 1, 0, 0, 4, 0, 0, 3, 'f', 'a', 'n', 2, 'H', 'z'};
  EXPECT_EQ(Bytes(b.begin() + 20 + static_cast<long>(servo.size()), b.end()), fan);
}

TEST(Capture, ConfigurationRefusesWhatTheLayoutCannotCarry) {
  capture::Configuration c = two_devices();
  c.devices[1].in = {4, 3};
  EXPECT_THROW(capture::encode_configuration(c), std::invalid_argument);
  c = two_devices();
  c.devices[0].name = std::string(256, 'x');
  EXPECT_THROW(capture::encode_configuration(c), std::invalid_argument);
}

TEST(Capture, CyclePacketLayout) {
  interbus::ProcessImage image;
  const Word out[] = {0x000F, 0x09C4, 0x4000, 0x807F, 0x03E8, 0x2416};
  const Word in[] = {0x0637, 0x09C4, 0x4000, 0x0237, 0x03E8, 0xA003};
  std::copy(std::begin(out), std::end(out), image.out.begin());
  std::copy(std::begin(in), std::end(in), image.in.begin());
  image.pcp_out[0] = 0x0700;
  image.pcp_in[0] = 0x8300;
  image.out[6] = 0xFFFF;  // beyond the used part: not in the packet
  Bytes b;
  capture::encode_cycle(two_devices(), 0x01020304, false, image, b);
  const Bytes want{0x49, 0x42, 1, 2, 1, 2, 3, 4, 0, 0, 0, 6, 0, 6, 0, 1,
                   0x00, 0x0F, 0x09, 0xC4, 0x40, 0x00, 0x80, 0x7F, 0x03, 0xE8, 0x24, 0x16,
                   0x06, 0x37, 0x09, 0xC4, 0x40, 0x00, 0x02, 0x37, 0x03, 0xE8, 0xA0, 0x03,
                   0x07, 0x00, 0x83, 0x00};
  EXPECT_EQ(b, want);
  capture::encode_cycle(two_devices(), 1, true, image, b);
  EXPECT_EQ(b[8], 1);
}

std::string temp_path(const std::string& name) {
  return ::testing::TempDir() + "/" + name + "_" + std::to_string(::getpid()) + ".pcap";
}

Bytes read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

std::uint32_t le32(const Bytes& b, std::size_t at) {
  return static_cast<std::uint32_t>(b[at] | (b[at + 1] << 8U) | (b[at + 2] << 16U)) |
         (static_cast<std::uint32_t>(b[at + 3]) << 24U);
}

// The default scenario for 1.5 s with a burst of corrupted cycles: parameter traffic on both
// channels, both drives brought up.
Scenario short_run() {
  Scenario s = default_scenario();
  s.duration = 1500ms;
  TimelineEntry corrupt;
  corrupt.at = 1s;
  corrupt.action = Action::fault_corrupt;
  corrupt.count = 2;
  s.timeline.push_back(corrupt);
  std::stable_sort(s.timeline.begin(), s.timeline.end(),
                   [](const TimelineEntry& a, const TimelineEntry& b) { return a.at < b.at; });
  return s;
}

std::string write_run(const std::string& name, std::uint64_t* cycles = nullptr) {
  const std::string path = temp_path(name);
  const Scenario s = short_run();
  Simulator sim(s);
  std::ofstream out(path, std::ios::binary);
  PcapRecorder rec(sim, s, out);
  sim.add_observer(&rec);
  sim.run();
  rec.finish();
  if (cycles != nullptr) *cycles = sim.summary().cycles;
  EXPECT_EQ(rec.packets(), sim.summary().cycles + 1);
  return path;
}

TEST(Capture, ASimulatedRunIsAPcapFileOfUser0WithNanosecondTimes) {
  if (!pcap_available()) GTEST_SKIP() << "this build has no libpcap (Debian package libpcap-dev)";
  std::uint64_t cycles = 0;
  const std::string path = write_run("capture_file", &cycles);
  const Bytes f = read_file(path);
  ASSERT_GE(f.size(), 24U + 16U);
  EXPECT_EQ(le32(f, 0), 0xA1B23C4DU);  // nanosecond pcap, this (little-endian) host's order
  EXPECT_EQ(le32(f, 20), static_cast<std::uint32_t>(kLinktypeInterbus));
  // First record: the configuration at time 0.
  EXPECT_EQ(le32(f, 24), 0U);
  EXPECT_EQ(le32(f, 28), 0U);
  const std::uint32_t len = le32(f, 32);
  EXPECT_EQ(f[40 + 3], capture::kTypeConfiguration);
  // Second record: cycle 1 at one cycle time (726 us).
  const std::size_t r1 = 40 + len;
  EXPECT_EQ(le32(f, r1), 0U);
  EXPECT_EQ(le32(f, r1 + 4), 726000U);
  EXPECT_EQ(f[r1 + 16 + 3], capture::kTypeCycle);
  EXPECT_EQ(Bytes(f.begin() + static_cast<long>(r1 + 16 + 4), f.begin() + static_cast<long>(r1 + 16 + 8)),
            (Bytes{0, 0, 0, 1}));  // cycle 1, big-endian
  EXPECT_GT(cycles, 2000U);
  std::remove(path.c_str());
}

TEST(Capture, AFailedStreamIsReportedAtTheEnd) {
  if (!pcap_available()) GTEST_SKIP() << "this build has no libpcap (Debian package libpcap-dev)";
  std::ostringstream out;
  PcapFile file(out, kLinktypeInterbus);
  file.write(Time{0}, Bytes{1, 2, 3});
  out.setstate(std::ios::badbit);
  file.write(Time{1}, Bytes(100000, 0));
  EXPECT_THROW(file.close(), PcapError);
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

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

bool contains(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }

TEST(WiresharkDissector, TsharkDecodesEveryDevicesWords) {
  if (!pcap_available()) GTEST_SKIP() << "this build has no libpcap (Debian package libpcap-dev)";
  if (std::system("command -v tshark >/dev/null 2>&1") != 0) {
    GTEST_SKIP() << "tshark is not installed (Debian package tshark)";
  }
  const std::string path = write_run("capture_tshark");
  const std::string tshark =
      "tshark -X lua_script:" + std::string(IBS_SOURCE_DIR) + "/tools/wireshark/interbus.lua -r " + path;

  // The configuration packet names both devices with their slices.
  const auto config = lines_of(run(tshark + " -c 1 -T fields -E separator=';' -e interbus.type -e interbus.device"
                                             " -e interbus.device.kind -e interbus.device.id_code"
                                             " -e interbus.device.in_offset -e interbus.device.values 2>/dev/null"));
  ASSERT_EQ(config.size(), 1U);
  EXPECT_EQ(config[0], "1;mc6000,vf1000;2,1;0x04db,0x033b;0,3;2,4");

  // Cycle by cycle: states, commands, references and actual values in engineering units.
  const auto rows = lines_of(run(tshark + " -T fields -E separator=';' -e interbus.cycle -e interbus.valid"
                                          " -e interbus.state -e interbus.command -e interbus.reference"
                                          " -e interbus.actual 2>/dev/null"));
  ASSERT_GT(rows.size(), 2000U);
  std::size_t enabled = 0, invalid = 0, running = 0;
  for (const auto& r : rows) {
    if (contains(r, "ENABLED,ENABLED")) ++enabled;
    if (contains(r, ";0;")) ++invalid;  // valid = 0
    if (contains(r, ";2500.25,50;")) ++running;  // both references as the master sends them
  }
  EXPECT_GT(enabled, 100U);
  EXPECT_GE(invalid, 2U);  // the corrupted cycles and the recovery after them
  EXPECT_GT(running, 10U);
  EXPECT_EQ(rows[1].substr(0, 4), "1;1;") << rows[1];
  EXPECT_TRUE(contains(rows[1], "START-UP INHIBIT,START-UP INHIBIT;BLOCK POWER,BLOCK POWER")) << rows[1];

  // The VF1000 communication word: a value inquiry (CODE 1) and the inverter's ACK.
  bool inquiry = false, ack = false;
  for (const auto& l : lines_of(run(tshark + " -T fields -e interbus.comm.code -e interbus.comm.ack 2>/dev/null"))) {
    inquiry = inquiry || l.rfind("1\t", 0) == 0;
    ack = ack || (l.size() >= 2 && l.substr(l.size() - 2) == "\t1");
  }
  EXPECT_TRUE(inquiry) << "no value inquiry (CODE 1) from the master";
  EXPECT_TRUE(ack) << "no ACK from the inverter";

  // PCP: fragments reassembled into messages with their services, each of the length its count
  // word gives (docs/pcp.md: the link adds no CRC).
  const auto msgs = lines_of(run(tshark + " -Y interbus.pcp.message -T fields -E separator=';'"
                                          " -e interbus.pcp.message.service -e interbus.pcp.message.parameter"
                                          " -e interbus.pcp.message.count -e interbus.pcp.message.device 2>/dev/null"));
  ASSERT_GE(msgs.size(), 4U);
  EXPECT_EQ(msgs[0], "Initiate.req;;8;mc6000");
  EXPECT_EQ(msgs[1], "Initiate.conf;;7;mc6000");
  EXPECT_EQ(msgs[2], "Read.req;85;3;mc6000");
  EXPECT_EQ(msgs[3], "Read.conf;;4;mc6000");

  // The verbose tree, as `tshark -V` shows it.
  const std::string verbose = run(tshark + " -V -c 3000 2>/dev/null");
  for (const char* what : {"INTERBUS (ibs capture), configuration", "Device mc6000: MC6000, ID code 4DBH",
                           "Control word: 0x000f POWER-ON/ENABLE", "Status word: 0x0637 ENABLED, remote, reference reached",
                           "Reference: 2500.25 rpm (Q16)", "Reference: 50 Hz", "Communication word (inverter): 0x8000",
                           "PCP master -> servo: FIRST s", "PCP message master -> servo (mc6000): Read.req"}) {
    EXPECT_TRUE(contains(verbose, what)) << what;
  }
  std::remove(path.c_str());
}

}  // namespace
}  // namespace ibs::sim
