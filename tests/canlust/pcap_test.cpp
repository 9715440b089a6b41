// A capture of CANLust frames as LINKTYPE_CAN_SOCKETCAN (227) through libpcap, and the Lua
// dissector tools/wireshark/canlust.lua run by tshark over it (skipped where tshark is missing).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <unistd.h>
#include <vector>

#include "ibs/can/pcap_writer.hpp"
#include "ibs/canlust/errors.hpp"
#include "ibs/canlust/parameter_channel.hpp"
#include "ibs/canlust/telegrams.hpp"

namespace ibs::can {
namespace {

using namespace ibs::canlust;

std::string temp_path(const char* name) {
  return ::testing::TempDir() + "/" + name + "_" + std::to_string(::getpid()) + ".pcap";
}

std::vector<CanFrame> sample_frames() {
  const IdentifierMap ids;
  const auto l = *process_layout_for_cacnf(2);
  return {
      encode_logon(ids, 1),
      encode_system(SystemCommand::start),
      *encode_control(ids, 1, l, {0x000F, q16_from_double(20.5)}),
      *encode_status(ids, 1, l, {0x0237, q16_from_double(20.5)}),
      *encode_parameter_request(ids, 1, {360, kModeRead, 0, 0}),
      CanFrame::make(1323, {0x68, 0x01, 0x00, 0x96, 0x01, 0x00, 0x00, 0x00}),
      *encode_parameter_reply(ids, 1, {7, kStatusUnknownParameter | kStatusImpermissibleValue, 0, 3}),
      *encode_error(ids, 1, {kErrorOp2, 170, 1}),
  };
}

std::string write_capture(const char* name) {
  const auto path = temp_path(name);
  auto w = PcapWriter::open(path);
  EXPECT_TRUE(w) << w.error;
  Time t{1s};
  for (const auto& f : sample_frames()) {
    w.transport->write(f, t);
    t += 1ms;
  }
  w.transport.reset();  // closes the file
  return path;
}

TEST(PcapWriter, RecordsAreSocketcanLayoutWithLinktype227) {
  const auto path = write_capture("canlust_layout");
  std::ifstream in(path, std::ios::binary);
  const std::vector<std::uint8_t> file((std::istreambuf_iterator<char>(in)), {});
  ASSERT_GE(file.size(), 24U);
  std::uint32_t magic = 0;
  for (int i = 3; i >= 0; --i) magic = (magic << 8U) | file[static_cast<std::size_t>(i)];
  ASSERT_EQ(magic, 0xA1B2C3D4U);  // written in this (little-endian) host's order
  EXPECT_EQ(file[20] | (file[21] << 8), kLinktypeCanSocketcan);
  // First record: the logon of CDA 1, id 1545 = 609H big-endian, length 0.
  const std::size_t r0 = 24 + 16;
  EXPECT_EQ(std::vector<std::uint8_t>(file.begin() + r0, file.begin() + r0 + 8),
            (std::vector<std::uint8_t>{0x00, 0x00, 0x06, 0x09, 0x00, 0x00, 0x00, 0x00}));
  std::uint8_t rec[16];
  EXPECT_EQ(socketcan_record(CanFrame::make(663, {0x0F, 0x00, 0x00, 0x80, 0x14, 0x00}), rec), 14U);
  EXPECT_EQ(std::vector<std::uint8_t>(rec, rec + 14),
            (std::vector<std::uint8_t>{0x00, 0x00, 0x02, 0x97, 0x06, 0, 0, 0, 0x0F, 0x00, 0x00, 0x80, 0x14, 0x00}));
  std::remove(path.c_str());
}

std::string run(const std::string& cmd) {
  std::string out;
  FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) return out;
  char buf[4096];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  ::pclose(p);
  return out;
}

TEST(WiresharkDissector, TsharkDecodesTheCanlustFields) {
  if (std::system("command -v tshark >/dev/null 2>&1") != 0) {
    GTEST_SKIP() << "tshark is not installed (Debian package tshark)";
  }
  const auto path = write_capture("canlust_tshark");
  const std::string lua = std::string(IBS_SOURCE_DIR) + "/tools/wireshark/canlust.lua";
  const std::string fields =
      "tshark -X lua_script:" + lua + " -r " + path +
      " -T fields -E separator=';' -e can.id -e canlust.kind -e canlust.address -e canlust.system"
      " -e canlust.control -e canlust.status_word -e canlust.q16 -e canlust.parameter -e canlust.mode"
      " -e canlust.status -e canlust.data -e canlust.block -e canlust.error.number"
      " -e canlust.error.location 2>/dev/null";
  const std::string out = run(fields);
  std::vector<std::string> lines;
  std::size_t pos = 0;
  while (pos < out.size()) {
    const auto e = out.find('\n', pos);
    lines.push_back(out.substr(pos, e - pos));
    if (e == std::string::npos) break;
    pos = e + 1;
  }
  ASSERT_EQ(lines.size(), 8U) << out;
  EXPECT_EQ(lines[0], "1545;1;1;;;;;;;;;;;");
  EXPECT_EQ(lines[1], "221;6;;0x01;;;;;;;;;;");
  EXPECT_EQ(lines[2], "663;2;1;;0x000f;;20.5;;;;;;;");
  EXPECT_EQ(lines[3], "883;3;1;;;0x0237;20.5;;;;;;;");
  EXPECT_EQ(lines[4], "1103;4;1;;;;;360;5;;0x00000000;0;;");
  EXPECT_EQ(lines[5], "1323;5;1;;;;;360;;0x00;0x00000196;0;;");
  EXPECT_EQ(lines[6], "1323;5;1;;;;;7;;0xa0;0x00000000;3;;");
  EXPECT_EQ(lines[7], "443;0;1;;;;;;;;;;16;170");
  const std::string verbose = run("tshark -X lua_script:" + lua + " -r " + path + " -V 2>/dev/null");
  EXPECT_NE(verbose.find("CANLust (LUST CM-CAN1)"), std::string::npos);
  EXPECT_NE(verbose.find("Error number: E-OP2 (16)"), std::string::npos) << verbose;
  EXPECT_NE(verbose.find("Mode: ENQ (read) (5)"), std::string::npos);
  std::remove(path.c_str());
}

}  // namespace
}  // namespace ibs::can
