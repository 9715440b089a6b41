// The serial transport over a pseudo-terminal pair: bytes both ways, read timeouts, what a pty
// refuses (7 data bits, TIOCSRS485) noted and ignored, errors that name the port, the byte log.
#include "ibs/serial/serial_port.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <vector>

#include "ibs/serial/byte_log.hpp"
#include "ibs/serial/pty.hpp"

namespace ibs::serial {
namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes read_n(SerialPort& p, std::size_t n) {
  Bytes out;
  std::array<std::uint8_t, 64> buf{};
  for (int i = 0; i < 50 && out.size() < n; ++i) {
    const std::size_t got = p.read(buf, std::chrono::milliseconds(20));
    out.insert(out.end(), buf.begin(), buf.begin() + static_cast<long>(got));
  }
  return out;
}

TEST(SerialPty, CarriesBytesBothWaysUnchanged) {
  PtyPair pair = PtyPair::open();
  SerialPort slave = SerialPort::open(pair.slave_path(), {19200, k8N1, false});
  EXPECT_TRUE(slave.is_pty());
  EXPECT_TRUE(pair.master().is_pty());
  // Every byte value, including CR, LF, XON/XOFF and 10H: the line is raw.
  Bytes all(256);
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<std::uint8_t>(i);
  slave.write(all);
  EXPECT_EQ(read_n(pair.master(), all.size()), all);
  pair.master().write(all);
  EXPECT_EQ(read_n(slave, all.size()), all);
}

TEST(SerialPty, ReadTimesOutWithNothing) {
  PtyPair pair = PtyPair::open();
  std::array<std::uint8_t, 8> buf{};
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_EQ(pair.master().read(buf, std::chrono::milliseconds(30)), 0U);
  EXPECT_GE(std::chrono::steady_clock::now() - t0, std::chrono::milliseconds(25));
}

TEST(SerialPty, SevenDataBitsAndRs485AreNotedAndIgnored) {
  PtyPair pair = PtyPair::open();
  SerialPort p = SerialPort::open(pair.slave_path(), {9600, k7E1, true});
  EXPECT_EQ(p.rs485(), Rs485Status::not_supported);
  bool bits = false;
  bool rs485 = false;
  for (const std::string& n : p.notes()) {
    bits = bits || n.find("7 data bits not supported (pty)") != std::string::npos;
    rs485 = rs485 || n.find("TIOCSRS485") != std::string::npos;
  }
  EXPECT_TRUE(bits);
  EXPECT_TRUE(rs485);
  const Bytes b = {0x10, 0x02, 0xFF};
  p.write(b);
  EXPECT_EQ(read_n(pair.master(), 3), b);
}

TEST(SerialPort, AMissingPortNamesThePath) {
  try {
    (void)SerialPort::open("/dev/ibs-no-such-port", {});
    FAIL() << "opened";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("serial port /dev/ibs-no-such-port: cannot open"),
              std::string::npos)
        << e.what();
  }
}

TEST(SerialPort, FramingText) {
  EXPECT_EQ(parse_framing("8N1"), k8N1);
  EXPECT_EQ(parse_framing("7E1"), k7E1);
  EXPECT_EQ(to_string(parse_framing("7o2")), "7O2");
  EXPECT_THROW((void)parse_framing("9N1"), std::invalid_argument);
  EXPECT_THROW((void)parse_framing("8X1"), std::invalid_argument);
  EXPECT_THROW((void)parse_framing("8N"), std::invalid_argument);
}

TEST(SerialPort, ByteLogWritesTimeDirectionPortAndHex) {
  const std::string path = ::testing::TempDir() + "dfs1_byte_log.txt";
  {
    PtyPair pair = PtyPair::open();
    ByteLog log(path);
    pair.master().set_log(&log);
    SerialPort slave = SerialPort::open(pair.slave_path(), {});
    const Bytes b = {0x10, 0x02, 0x01, 0x81, 0x10, 0x03, 0x7E};
    slave.write(b);
    EXPECT_EQ(read_n(pair.master(), b.size()), b);
    pair.master().write(Bytes{0xAB});
  }
  std::ifstream in(path);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, "ibs-serial-log 1");
  std::string t;
  std::string dir;
  std::string port;
  in >> t >> dir >> port;
  EXPECT_EQ(dir, "rx");
  EXPECT_EQ(port, "pty-master");
  EXPECT_NE(t.find('.'), std::string::npos);
  std::string rest;
  std::getline(in, rest);
  EXPECT_EQ(rest.substr(0, 3), " 10");  // the first bytes read (may arrive in pieces)
  std::string line;
  std::string last;
  while (std::getline(in, line)) last = line;
  EXPECT_NE(last.find(" tx pty-master AB"), std::string::npos) << last;
  std::remove(path.c_str());
}

}  // namespace
}  // namespace ibs::serial
