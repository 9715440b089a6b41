// cannelloni's UDP format v2 byte for byte, and CANLust over UDP on loopback: two sockets in
// one process form one bus, both sides of the parameter channel run over it.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <vector>

#include "fake_drive.hpp"
#include "ibs/can/cannelloni.hpp"
#include "ibs/can/udp.hpp"
#include "ibs/canlust/master.hpp"
#include "ibs/canlust/node.hpp"

namespace ibs::can {
namespace {

using Bytes = std::vector<std::uint8_t>;

TEST(Cannelloni, DatagramOfTheReplyOf713) {
  const CanFrame f = CanFrame::make(1323, {0x68, 0x01, 0x00, 0x96, 0x01, 0x00, 0x00, 0x00});
  std::array<std::uint8_t, 64> buf{};
  const auto n = cannelloni::encode(std::span(&f, 1), 7, buf);
  ASSERT_TRUE(n);
  EXPECT_EQ(Bytes(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(*n)),
            (Bytes{0x02, 0x00, 0x07, 0x00, 0x01,               // version 2, DATA, seq 7, 1 frame
                   0x00, 0x00, 0x05, 0x2B, 0x08,               // can_id 52BH, length 8
                   0x68, 0x01, 0x00, 0x96, 0x01, 0x00, 0x00, 0x00}));
  std::array<CanFrame, 4> out{};
  const auto r = cannelloni::decode(std::span(buf.data(), *n), out);
  EXPECT_EQ(r.status, cannelloni::DecodeStatus::ok);
  EXPECT_EQ(r.sequence, 7);
  ASSERT_EQ(r.frames, 1U);
  EXPECT_EQ(out[0], f);
}

TEST(Cannelloni, RemoteFrameHasItsDlcButNoData) {
  CanFrame r = CanFrame::make(0x607, {});
  r.rtr = true;
  r.dlc = 3;
  std::array<std::uint8_t, 64> buf{};
  const auto n = cannelloni::encode(std::span(&r, 1), 0, buf);
  ASSERT_EQ(*n, 10U);
  EXPECT_EQ(Bytes(buf.begin() + 5, buf.begin() + 10), (Bytes{0x40, 0x00, 0x06, 0x07, 0x03}));
  std::array<CanFrame, 1> out{};
  EXPECT_EQ(cannelloni::decode(std::span(buf.data(), *n), out).frames, 1U);
  EXPECT_EQ(out[0], r);
}

TEST(Cannelloni, SkipsExtendedAndFdFramesAndRejectsBrokenDatagrams) {
  const Bytes d = {0x02, 0x00, 0x01, 0x00, 0x03,
                   0x80, 0x00, 0x01, 0x00, 0x01, 0xAA,          // extended: skipped
                   0x00, 0x00, 0x00, 0xDD, 0x81, 0x00, 0x01,    // CAN FD, 1 byte: skipped
                   0x00, 0x00, 0x00, 0xDD, 0x01, 0x01};         // 221: 01H (System Start)
  std::array<CanFrame, 4> out{};
  const auto r = cannelloni::decode(d, out);
  EXPECT_EQ(r.status, cannelloni::DecodeStatus::ok);
  EXPECT_EQ(r.skipped, 2U);
  ASSERT_EQ(r.frames, 1U);
  EXPECT_EQ(out[0], CanFrame::make(221, {0x01}));
  EXPECT_EQ(cannelloni::decode(Bytes{0x01, 0, 0, 0, 0}, out).status, cannelloni::DecodeStatus::bad_version);
  EXPECT_EQ(cannelloni::decode(Bytes{0x02, 1, 0, 0, 0}, out).status, cannelloni::DecodeStatus::bad_op_code);
  EXPECT_EQ(cannelloni::decode(Bytes{0x02, 0, 0, 0, 1, 0, 0}, out).status, cannelloni::DecodeStatus::truncated);
  EXPECT_EQ(cannelloni::decode(Bytes{0x02, 0, 0, 0, 1, 0, 0, 0, 1, 2, 0xAA}, out).status,
            cannelloni::DecodeStatus::truncated);
  // One frame and a byte the header does not account for.
  EXPECT_EQ(cannelloni::decode(Bytes{0x02, 0, 0, 0, 1, 0, 0, 0, 0xDD, 1, 0x01, 0x55}, out).status,
            cannelloni::DecodeStatus::trailing);
}

// Two UDP sockets on loopback: the master on one, a fake drive's node on the other.
TEST(CanOverUdp, ParameterChannelBothSidesOverTwoLoopbackSockets) {
  auto a = UdpCanTransport::open({"127.0.0.1", 0, "127.0.0.1", 0});
  ASSERT_TRUE(a) << a.error;
  UdpConfig cb{"127.0.0.1", 0, "127.0.0.1", a.transport->local_port()};
  auto b = UdpCanTransport::open(cb);
  ASSERT_TRUE(b) << b.error;

  canlust::test::FakeDrive drive;
  canlust::NodeConfig nc;
  nc.address = 1;
  canlust::Node node(nc, drive, drive);
  canlust::Master master;
  const auto clock0 = std::chrono::steady_clock::now();
  const auto now = [&] { return std::chrono::duration_cast<Time>(std::chrono::steady_clock::now() - clock0); };
  node.power_on(now());  // its logon is the first datagram: the master's socket learns the peer

  auto& c = master.parameters();
  const auto r1 = c.submit(canlust::read(1, canlust::test::kParamDisp)).id;
  const auto w1 = c.submit(canlust::write_string(1, canlust::test::kParamText, "over UDP, 4 by 4")).id;
  const auto r2 = c.submit(canlust::read_string(1, canlust::test::kParamText)).id;
  master.system_start();
  bool started = false;
  for (int i = 0; i < 2000 && !(c.idle() && started); ++i) {
    node.step(now());
    while (auto f = node.take_frame()) ASSERT_EQ(b.transport->send(*f), IoStatus::ok) << b.transport->last_error();
    for (;;) {
      const auto r = a.transport->receive(0ms);
      if (r.status != IoStatus::ok) break;
      master.receive(r.frame, now());
    }
    master.step(now());
    while (auto f = master.take_frame()) ASSERT_EQ(a.transport->send(*f), IoStatus::ok) << a.transport->last_error();
    for (;;) {
      const auto r = b.transport->receive(1ms);
      if (r.status != IoStatus::ok) break;
      node.receive(r.frame, now());
    }
    started = node.state() == canlust::SystemState::start;
  }
  EXPECT_TRUE(started);
  ASSERT_EQ(c.poll(r1).state, canlust::RequestState::done);
  EXPECT_EQ(c.poll(r1).outcome->value, 406U);
  ASSERT_EQ(c.poll(w1).state, canlust::RequestState::done);
  EXPECT_EQ(c.poll(w1).outcome->kind, canlust::OutcomeKind::done);
  ASSERT_EQ(c.poll(r2).state, canlust::RequestState::done);
  EXPECT_EQ(c.poll(r2).outcome->text.view(), "over UDP, 4 by 4");
  EXPECT_TRUE(master.drive(1).logged_on);
  EXPECT_EQ(a.transport->bad_datagrams(), 0U);
}

// Issue 23, defect 3: a datagram whose header disagrees with its content ran the frames it held.
// Each is dropped whole and counted; its sender does not become the peer; a good one still counts.
TEST(CanOverUdp, ADatagramWhoseHeaderDisagreesIsDroppedWholeAndCounted) {
  auto a = UdpCanTransport::open({"127.0.0.1", 0, "127.0.0.1", 0});
  ASSERT_TRUE(a) << a.error;
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  ASSERT_GE(fd, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(a.transport->local_port());
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  const auto send = [&](const Bytes& d) {
    ASSERT_EQ(::sendto(fd, d.data(), d.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof to),
              static_cast<ssize_t>(d.size()));
  };
  const Bytes frame = {0x00, 0x00, 0x00, 0xDD, 0x01, 0x01};  // 221: 01H (System Start)
  const auto datagram = [&](std::uint16_t count, const Bytes& body) {
    Bytes d = {0x02, 0x00, 0x00, static_cast<std::uint8_t>(count >> 8U), static_cast<std::uint8_t>(count & 0xFFU)};
    d.insert(d.end(), body.begin(), body.end());
    return d;
  };
  Bytes trailing = frame;
  trailing.push_back(0x00);
  send(datagram(2, frame));                                // count 2, one frame
  send(datagram(65535, frame));                            // count 65535, one frame
  send(datagram(1, trailing));                             // a byte after the frame
  Bytes cut = frame;
  cut.insert(cut.end(), {0x00, 0x00, 0x00, 0xDD});
  send(datagram(2, cut));                                  // the second frame cut after its id
  EXPECT_EQ(a.transport->receive(50ms).status, IoStatus::timeout) << "no frame of a broken datagram";
  EXPECT_EQ(a.transport->bad_datagrams(), 4U);
  EXPECT_EQ(a.transport->send(CanFrame::make(221, {1})), IoStatus::error) << "a broken datagram names no peer";
  send(datagram(1, frame));
  const auto r = a.transport->receive(500ms);
  ASSERT_EQ(r.status, IoStatus::ok);
  EXPECT_EQ(r.frame, CanFrame::make(221, {0x01}));
  EXPECT_EQ(a.transport->receive(20ms).status, IoStatus::timeout);
  EXPECT_EQ(a.transport->bad_datagrams(), 4U);
  EXPECT_EQ(a.transport->send(CanFrame::make(221, {1})), IoStatus::ok) << "the good datagram's sender is the peer";
  ::close(fd);
}

TEST(CanOverUdp, ReceiveTimesOutAndSendWithoutPeerSaysWhy) {
  auto a = UdpCanTransport::open({"127.0.0.1", 0, "127.0.0.1", 0});
  ASSERT_TRUE(a) << a.error;
  EXPECT_EQ(a.transport->receive(5ms).status, IoStatus::timeout);
  EXPECT_EQ(a.transport->send(CanFrame::make(221, {1})), IoStatus::error);
  EXPECT_NE(a.transport->last_error().find("no peer"), std::string_view::npos);
  EXPECT_FALSE(UdpCanTransport::open({"not-an-ip", 0, "127.0.0.1", 1}));
}

}  // namespace
}  // namespace ibs::can
