// The serial lines' capture format (serial/capture.hpp, docs/pcap.md "Serial lines"): the 8-byte
// header byte for byte, the pcap file (link types 148 and 149, nanosecond times) read back packet
// by packet, a port's bytes recorded through its tap, and every way a file can be refused.
#include <gtest/gtest.h>

#include <sstream>

#include "ibs/dfs1/capture_framer.hpp"
#include "ibs/lustbus/capture_framer.hpp"
#include "ibs/pcap/pcap_file.hpp"
#include "ibs/serial/capture.hpp"
#include "ibs/serial/pty.hpp"
#include "../support/seed_telegrams.hpp"

namespace ibs::serial {
namespace {

using base::LineSide;
using Bytes = std::vector<std::uint8_t>;

Bytes bytes_of(const std::string& s) { return Bytes(s.begin(), s.end()); }

// The seed's telegrams recorded as a capture, 10 ms apart from `epoch`.
std::string record(LineProtocol protocol, const std::vector<test::SeedTelegram>& seed, Time epoch = Time{0}) {
  lustbus::CaptureFramer lb;
  dfs1::CaptureFramer df;
  base::TelegramFramer& framer = protocol == LineProtocol::lustbus ? static_cast<base::TelegramFramer&>(lb) : df;
  std::ostringstream out;
  LineCapture cap(out, protocol, framer, Direction::tx, epoch);
  Time t{0};
  for (const auto& s : seed) {
    cap.record(s.from, s.bytes, t);
    t += 10ms;
  }
  cap.finish();
  return out.str();
}

TEST(CaptureFormat, TheHeaderIsVersionDirectionFlagsAddressAndDuration) {
  base::LineTelegram t;
  t.from = LineSide::device;
  t.bytes = {0x40, 0x06};
  t.first = Time{1ms};
  t.last = Time{3ms + 250us};
  t.flags = base::kTelegramCheckBad | base::kTelegramCut;
  t.address = 30;
  Bytes out;
  capture::encode(t, out);
  EXPECT_EQ(out, (Bytes{1, 1, 0x83, 30, 0x00, 0x00, 0x08, 0xCA, 0x40, 0x06}));  // 2250 us
  std::string why;
  const auto p = capture::decode(out, Time{5s}, why);
  ASSERT_TRUE(p) << why;
  EXPECT_EQ(p->from, LineSide::device);
  EXPECT_EQ(p->flags, base::kTelegramCheckBad | base::kTelegramCut);
  EXPECT_EQ(p->address, 30);
  EXPECT_EQ(p->duration, 2250us);
  EXPECT_EQ(p->bytes, (Bytes{0x40, 0x06}));
  EXPECT_EQ(p->at, Time{5s});
  // No address: bit 7 clear, byte 3 zero.
  t.address.reset();
  t.flags = 0;
  t.from = LineSide::host;
  capture::encode(t, out);
  EXPECT_EQ(Bytes(out.begin(), out.begin() + 4), (Bytes{1, 0, 0x00, 0}));
  EXPECT_FALSE(capture::decode(out, Time{0}, why)->address);
}

TEST(CaptureFormat, APacketThisFormatCannotBeIsRefusedWithWhy) {
  std::string why;
  EXPECT_FALSE(capture::decode(Bytes{1, 0, 0, 0, 0, 0, 0}, Time{0}, why));
  EXPECT_EQ(why, "7 bytes, shorter than the 8-byte header");
  EXPECT_FALSE(capture::decode(Bytes{2, 0, 0, 0, 0, 0, 0, 0}, Time{0}, why));
  EXPECT_EQ(why, "header version 2 (this ibs reads version 1)");
  EXPECT_FALSE(capture::decode(Bytes{1, 2, 0, 0, 0, 0, 0, 0}, Time{0}, why));
  EXPECT_EQ(why, "direction 2 (0 from the host, 1 from a device)");
}

TEST(CaptureFile, LustbusSeedExamplesReadBackAsWritten) {
  if (!pcap::available()) GTEST_SKIP() << "this build has no libpcap (Debian package libpcap-dev)";
  const Time epoch{1'700'000'000'123'456'789};
  const auto seed = test::lustbus_seed_exchanges();
  const std::string file = record(LineProtocol::lustbus, seed, epoch);
  // A pcap file, nanosecond magic, link type 148 (read in this little-endian host's order).
  ASSERT_GE(file.size(), 24U);
  EXPECT_EQ(Bytes(file.begin(), file.begin() + 4), (Bytes{0x4D, 0x3C, 0xB2, 0xA1}));
  EXPECT_EQ(static_cast<unsigned char>(file[20]) | (static_cast<unsigned char>(file[21]) << 8), kLinktypeLustbus);
  const LineCaptureReading r = read_line_capture(Bytes(file.begin(), file.end()));
  ASSERT_FALSE(r.error) << r.error->what;
  EXPECT_EQ(r.protocol, LineProtocol::lustbus);
  ASSERT_EQ(r.packets.size(), seed.size());
  for (std::size_t i = 0; i < seed.size(); ++i) {
    EXPECT_EQ(r.packets[i].from, seed[i].from);
    EXPECT_EQ(r.packets[i].bytes, seed[i].bytes);
    EXPECT_EQ(r.packets[i].flags, 0);
    EXPECT_EQ(r.packets[i].at, epoch + Time{10ms} * static_cast<int>(i)) << "nanoseconds kept";
  }
}

TEST(CaptureFile, Dfs1SeedExampleReadsBackUnderLinktype149) {
  if (!pcap::available()) GTEST_SKIP() << "this build has no libpcap (Debian package libpcap-dev)";
  const std::string file = record(LineProtocol::dfs1, test::dfs1_seed_exchange());
  const LineCaptureReading r = read_line_capture(Bytes(file.begin(), file.end()));
  ASSERT_FALSE(r.error) << r.error->what;
  EXPECT_EQ(r.protocol, LineProtocol::dfs1);
  ASSERT_EQ(r.packets.size(), 2U);
  EXPECT_EQ(r.packets[0].address, 1);
  EXPECT_EQ(r.packets[1].from, LineSide::device);
}

TEST(CaptureFile, AFileThatIsNoLineCaptureIsRefusedNamingThePacket) {
  if (!pcap::available()) GTEST_SKIP() << "this build has no libpcap (Debian package libpcap-dev)";
  EXPECT_EQ(read_line_capture({}).error->what, "not a pcap file: an empty file");
  const auto text = bytes_of("ibs-serial-log 1\n");
  const auto r0 = read_line_capture(text);
  ASSERT_TRUE(r0.error);
  EXPECT_EQ(r0.error->packet, 0U);
  EXPECT_EQ(r0.error->what.rfind("not a pcap file: ", 0), 0U) << r0.error->what;
  // Another link type: an INTERBUS capture's 147.
  std::ostringstream other;
  pcap::PcapFile f(other, 147);
  f.write(Time{0}, Bytes{0x49, 0x42, 1, 1});
  f.close();
  const auto r1 = read_line_capture(bytes_of(other.str()));
  ASSERT_TRUE(r1.error);
  EXPECT_EQ(r1.error->what, "link type 147 is no serial line's (148 LUSTBUS, 149 DFS-1)");
  // A packet too short for the header, and a file cut inside a record.
  std::ostringstream shortp;
  pcap::PcapFile g(shortp, kLinktypeDfs1);
  g.write(Time{0}, Bytes{1, 0, 0, 0, 0, 0, 0, 0, 0x10});
  g.write(Time{1ms}, Bytes{1, 0, 0});
  g.close();
  const auto r2 = read_line_capture(bytes_of(shortp.str()));
  ASSERT_TRUE(r2.error);
  EXPECT_EQ(r2.error->packet, 2U);
  EXPECT_EQ(r2.error->what, "3 bytes, shorter than the 8-byte header");
  EXPECT_EQ(r2.packets.size(), 1U) << "the packets before it are kept";
  const std::string whole = record(LineProtocol::dfs1, test::dfs1_seed_exchange());
  const auto r3 = read_line_capture(bytes_of(whole.substr(0, whole.size() - 3)));
  ASSERT_TRUE(r3.error);
  EXPECT_EQ(r3.error->packet, 2U);
  EXPECT_NE(r3.error->what.find("truncated"), std::string::npos) << r3.error->what;
  EXPECT_EQ(r3.packets.size(), 1U);
}

// A port's tap sees every byte both ways: a host writes an ENQUIRY through a pty, the "device"
// answers from the other end; the capture of the host's port holds both telegrams, each its way.
TEST(CaptureFile, APortsTapRecordsBothDirections) {
  if (!pcap::available()) GTEST_SKIP() << "this build has no libpcap (Debian package libpcap-dev)";
  PtyPair pair = PtyPair::open();
  SerialPort device = SerialPort::open(pair.slave_path(), {});
  std::ostringstream out;
  lustbus::CaptureFramer framer;
  LineCapture cap(out, LineProtocol::lustbus, framer, Direction::rx);  // an emulator: the host's bytes come in
  pair.master().set_tap(&cap);
  const auto seed = test::lustbus_seed_exchanges();
  device.write(seed[0].bytes);  // the host, on the other end
  std::array<std::uint8_t, 64> buf{};
  std::size_t got = 0;
  for (int i = 0; i < 50 && got < seed[0].bytes.size(); ++i) got += pair.master().read(buf, 20ms);
  ASSERT_EQ(got, seed[0].bytes.size());
  pair.master().write(seed[1].bytes);  // the answer
  pair.master().set_tap(nullptr);
  cap.finish();
  EXPECT_EQ(cap.packets(), 2U);
  const auto r = read_line_capture(bytes_of(out.str()));
  ASSERT_FALSE(r.error) << r.error->what;
  ASSERT_EQ(r.packets.size(), 2U);
  EXPECT_EQ(r.packets[0].from, LineSide::host);
  EXPECT_EQ(r.packets[0].bytes, seed[0].bytes);
  EXPECT_EQ(r.packets[1].from, LineSide::device);
  EXPECT_EQ(r.packets[1].bytes, seed[1].bytes);
  EXPECT_LE(r.packets[0].at, r.packets[1].at);
}

}  // namespace
}  // namespace ibs::serial
