// The virtual CAN bus: exact frame lengths with stuff bits, bit timing 25..500 kbit/s,
// arbitration by identifier, delivery at the end of the frame, bus load.
#include <gtest/gtest.h>

#include <random>
#include <stdexcept>
#include <string>

#include "ibs/can/bit_timing.hpp"
#include "ibs/can/virtual_bus.hpp"

namespace ibs::can {
namespace {

// An independent, naive model of ISO 11898-1 bit stuffing on a string of '0'/'1'.
std::string bits_of(unsigned v, unsigned width) {
  std::string s;
  for (unsigned i = width; i-- > 0;) s += ((v >> i) & 1U) ? '1' : '0';
  return s;
}
unsigned naive_total(const CanFrame& f) {
  std::string s = "0" + bits_of(f.id, 11) + (f.rtr ? "1" : "0") + "00" + bits_of(f.dlc, 4);
  if (!f.rtr) {
    for (unsigned i = 0; i < f.dlc; ++i) s += bits_of(f.data[i], 8);
  }
  // CRC-15 by polynomial division of the message followed by 15 zeros.
  std::string div = s + std::string(15, '0');
  const std::string poly = "1100010110011001";  // x^15 + x^14 + x^10 + x^8 + x^7 + x^4 + x^3 + 1
  for (std::size_t i = 0; i + 15 < div.size(); ++i) {
    if (div[i] == '1') {
      for (std::size_t j = 0; j < poly.size(); ++j) div[i + j] = div[i + j] == poly[j] ? '0' : '1';
    }
  }
  s += div.substr(div.size() - 15);
  std::string stuffed;
  int run = 0;
  char last = 'x';
  for (const char c : s) {
    stuffed += c;
    run = c == last ? run + 1 : 1;
    last = c;
    if (run == 5) {
      last = c == '0' ? '1' : '0';
      stuffed += last;
      run = 1;
    }
  }
  return static_cast<unsigned>(stuffed.size()) + 10;
}

TEST(FrameBits, AllZeroFrameHas6StuffBits) {
  CanFrame f;  // id 0, DLC 0: SOF..CRC are 34 dominant bits
  const auto b = frame_bits(f);
  EXPECT_EQ(b.stuffed_region, 34U);
  EXPECT_EQ(b.crc, 0);
  EXPECT_EQ(b.stuff, 6U);
  EXPECT_EQ(b.total(), 50U);
  EXPECT_EQ(b.on_bus(), 53U);
}

TEST(FrameBits, MatchesANaiveModelOnRandomFrames) {
  std::mt19937 rng(12);
  for (int i = 0; i < 20000; ++i) {
    CanFrame f;
    f.id = static_cast<std::uint16_t>(rng() & 0x7FF);
    f.rtr = (rng() & 7) == 0;
    f.dlc = static_cast<std::uint8_t>(rng() % 9);
    for (auto& d : f.data) d = static_cast<std::uint8_t>(rng() & (rng() & 1 ? 0xFF : 0x00));
    const auto b = frame_bits(f);
    ASSERT_EQ(b.total(), naive_total(f)) << "id " << f.id << " dlc " << int(f.dlc);
    // Worst case for a base frame: floor((34 + 8n - 1) / 4) stuff bits.
    const unsigned n = f.rtr ? 0U : f.dlc;
    EXPECT_LE(b.stuff, (34U + 8U * n - 1U) / 4U);
    EXPECT_LE(b.on_bus(), 135U);
  }
}

TEST(BitTiming, RangeIs25To500Kbits) {
  EXPECT_EQ(bit_time(500'000), 2us);
  EXPECT_EQ(bit_time(25'000), 40us);
  EXPECT_TRUE(valid_bitrate(125'000));
  EXPECT_FALSE(valid_bitrate(1'000'000));
  EXPECT_THROW(VirtualBus({1'000'000, 4, 4}), std::invalid_argument);
  EXPECT_THROW(VirtualBus({20'000, 4, 4}), std::invalid_argument);
}

TEST(VirtualBus, DeliversToEveryOtherNodeAtTheEndOfTheFrame) {
  VirtualBus bus({250'000, 8, 8});
  const auto a = bus.attach("a");
  const auto b = bus.attach("b");
  const auto c = bus.attach("c");
  const auto f = CanFrame::make(0x44D, {0x68, 0x01, 0x05, 0, 0, 0, 0, 0});
  ASSERT_TRUE(bus.send(a, f, Time{1ms}));
  bus.advance(Time{1ms});
  EXPECT_FALSE(bus.receive(b));
  const Time end = Time{1ms} + bus.bit_time() * frame_bits(f).total();
  EXPECT_EQ(bus.next_event(), end);
  bus.advance(end);
  const auto rb = bus.receive(b);
  ASSERT_TRUE(rb);
  EXPECT_EQ(rb->frame, f);
  EXPECT_EQ(rb->time, end);
  EXPECT_EQ(rb->start, Time{1ms});
  EXPECT_TRUE(bus.receive(c));
  EXPECT_FALSE(bus.receive(a));  // no echo to the sender
}

TEST(VirtualBus, LowestIdentifierWinsArbitration) {
  VirtualBus bus({500'000, 8, 32});
  const auto n1 = bus.attach("1"), n2 = bus.attach("2"), n3 = bus.attach("3"), rx = bus.attach("rx");
  bus.send(n1, CanFrame::make(1101, {1}), Time{0});
  bus.send(n2, CanFrame::make(221, {1}), Time{0});
  bus.send(n3, CanFrame::make(661, {1}), Time{0});
  CanFrame remote = CanFrame::make(221, {});
  remote.rtr = true;
  remote.dlc = 1;
  bus.send(n3, remote, Time{0});  // queued behind 661 in node 3
  bus.advance(Time{10ms});
  std::vector<std::uint16_t> order;
  std::vector<Time> starts;
  while (auto d = bus.receive(rx)) {
    order.push_back(d->frame.id);
    starts.push_back(d->start);
  }
  EXPECT_EQ(order, (std::vector<std::uint16_t>{221, 661, 221, 1101}));
  // Back to back: each starts 3 bits (intermission) after the previous ended.
  for (std::size_t i = 1; i < starts.size(); ++i) EXPECT_GT(starts[i], starts[i - 1]);
  EXPECT_GE(bus.stats().arbitration_losses, 3U);
}

TEST(VirtualBus, DataFrameBeatsRemoteFrameOfTheSameId) {
  VirtualBus bus;
  const auto a = bus.attach("a"), b = bus.attach("b"), rx = bus.attach("rx");
  CanFrame r = CanFrame::make(0x100, {});
  r.rtr = true;
  bus.send(a, r, Time{0});
  bus.send(b, CanFrame::make(0x100, {1}), Time{0});
  bus.advance(Time{1ms});
  EXPECT_FALSE(bus.receive(rx)->frame.rtr);
  EXPECT_TRUE(bus.receive(rx)->frame.rtr);
}

TEST(VirtualBus, BusLoadOfAPeriodicFrame) {
  VirtualBus bus({125'000, 8, 256});
  const auto a = bus.attach("a");
  bus.attach("b");
  const auto f = CanFrame::make(0x371, {0x37, 0x02, 0x00, 0x80, 0x14, 0x00});
  const unsigned bits = frame_bits(f).on_bus();
  for (int i = 0; i < 100; ++i) {
    bus.send(a, f, Time{std::chrono::milliseconds(10 * i)});
    bus.advance(Time{std::chrono::milliseconds(10 * i)});
  }
  bus.advance(Time{1000ms});
  EXPECT_EQ(bus.stats().frames, 100U);
  const double expect = (100.0 * bits * 8e-6) / 1.0;  // 8 us per bit at 125 kbit/s
  EXPECT_NEAR(bus.stats().load(), expect, 1e-9);
  EXPECT_EQ(bus.stats().bits, 100U * frame_bits(f).total());
}

TEST(VirtualBus, FullReceiveBufferCountsLostFrames) {
  VirtualBus bus({500'000, 8, 2});
  const auto a = bus.attach("a");
  bus.attach("b");
  for (int i = 0; i < 5; ++i) bus.send(a, CanFrame::make(1, {}), Time{0});
  bus.advance(Time{1s});
  EXPECT_EQ(bus.stats().rx_overflows, 3U);
}

}  // namespace
}  // namespace ibs::can
