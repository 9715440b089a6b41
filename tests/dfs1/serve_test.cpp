// The one serving loop of every serial emulator (serial::serve) over a pseudo-terminal pair, with
// a fake device: bytes reach the device with their time, its answer goes out no earlier than it
// is due, a device at another rate hears nothing but still sees time pass, a lone device's new
// rate takes the port along, the byte log sees both ways, and the loop stops when asked.
#include "ibs/serial/serve.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <fstream>
#include <sstream>
#include <thread>
#include <vector>

#include "ibs/serial/byte_log.hpp"
#include "ibs/serial/pty.hpp"

namespace ibs::serial {
namespace {

using Bytes = std::vector<std::uint8_t>;
using Clock = std::chrono::steady_clock;

// Answers what it heard, each byte + 1, `delay` after the bytes came.
class EchoDevice final : public base::LineDevice {
 public:
  explicit EchoDevice(Duration delay, std::uint32_t baud = 0) : delay_(delay), baud_(baud) {}
  [[nodiscard]] std::optional<Time> next_due() const override {
    if (answer_.empty()) return std::nullopt;
    return due_;
  }
  void advance(Time now) override { last_advance_ = now; }
  void receive(std::span<const std::uint8_t> bytes, Time now) override {
    for (const auto b : bytes) {
      heard_.push_back(b);
      answer_.push_back(static_cast<std::uint8_t>(b + 1));
      due_ = now + delay_;
    }
  }
  std::span<const std::uint8_t> output(Time now) override {
    if (answer_.empty() || now < due_) return {};
    return answer_;
  }
  void written(std::size_t n) override { answer_.erase(answer_.begin(), answer_.begin() + static_cast<long>(n)); }
  [[nodiscard]] std::uint32_t line_baud() const override { return baud_; }

  const Bytes& heard() const { return heard_; }
  Time last_advance() const { return last_advance_; }
  void set_baud(std::uint32_t b) { baud_ = b; }

 private:
  Duration delay_;
  std::atomic<std::uint32_t> baud_;
  Bytes heard_;
  Bytes answer_;
  Time due_{};
  Time last_advance_{};
};

Bytes read_n(SerialPort& p, std::size_t n, std::chrono::milliseconds within = std::chrono::milliseconds(2000)) {
  Bytes out;
  std::array<std::uint8_t, 64> buf{};
  const auto end = Clock::now() + within;
  while (out.size() < n && Clock::now() < end) {
    const std::size_t got = p.read(buf, std::chrono::milliseconds(10));
    out.insert(out.end(), buf.begin(), buf.begin() + static_cast<long>(got));
  }
  return out;
}

struct Served {
  PtyPair pair = PtyPair::open({9600, k8N1, false});
  std::vector<base::LineDevice*> devices;
  std::atomic<bool> stop{false};
  std::thread loop;
  void start() {
    loop = std::thread([this] { serve(pair.master(), devices, [this] { return stop.load(); }); });
  }
  void finish() {
    stop = true;
    loop.join();
  }
};

TEST(SerialServe, AnswerGoesOutWhenDueNotBefore) {
  EchoDevice d(60ms);
  Served s;
  s.devices = {&d};
  s.start();
  SerialPort host = SerialPort::open(s.pair.slave_path(), {});
  const auto t0 = Clock::now();
  host.write(Bytes{0x10, 0x20});
  EXPECT_EQ(read_n(host, 2), (Bytes{0x11, 0x21}));
  EXPECT_GE(Clock::now() - t0, 60ms);  // the device's time counts from when the loop read them
  s.finish();
  EXPECT_EQ(d.heard(), (Bytes{0x10, 0x20}));
}

TEST(SerialServe, StopsWithinAPollWhenAsked) {
  EchoDevice d(0ms);
  Served s;
  s.devices = {&d};
  s.start();
  std::this_thread::sleep_for(30ms);
  const auto t0 = Clock::now();
  s.finish();
  EXPECT_LT(Clock::now() - t0, 500ms);  // kServePoll is 20 ms; slack for a loaded machine
  EXPECT_GT(d.last_advance(), Time{0});  // time passed for it without a byte
}

TEST(SerialServe, DeviceAtAnotherRateHearsNothingButTimePasses) {
  EchoDevice here(0ms);
  EchoDevice elsewhere(0ms, 19200);  // the port runs at 9600
  Served s;
  s.devices = {&here, &elsewhere};
  s.start();
  SerialPort host = SerialPort::open(s.pair.slave_path(), {});
  host.write(Bytes{0x41});
  EXPECT_EQ(read_n(host, 1), Bytes{0x42});
  EXPECT_EQ(read_n(host, 1, std::chrono::milliseconds(100)), Bytes{});  // one answer only
  s.finish();
  EXPECT_EQ(elsewhere.heard(), Bytes{});
  EXPECT_GT(elsewhere.last_advance(), Time{0});
  EXPECT_EQ(s.pair.master().baud(), 9600U);  // two devices: the port keeps its rate
}

TEST(SerialServe, LoneDeviceTakesThePortToItsRateOnceItsAnswerIsOut) {
  EchoDevice d(0ms, 9600);
  Served s;
  s.devices = {&d};
  s.start();
  SerialPort host = SerialPort::open(s.pair.slave_path(), {});
  host.write(Bytes{0x01});
  EXPECT_EQ(read_n(host, 1), Bytes{0x02});
  d.set_baud(38400);
  const auto end = Clock::now() + 2s;
  while (s.pair.master().baud() != 38400U && Clock::now() < end) std::this_thread::sleep_for(5ms);
  s.finish();
  EXPECT_EQ(s.pair.master().baud(), 38400U);
}

TEST(SerialServe, ByteLogSeesBothWays) {
  const std::string path = ::testing::TempDir() + "serve_byte_log.txt";
  EchoDevice d(0ms);
  Served s;
  ByteLog log(path);
  s.pair.master().set_log(&log);
  s.devices = {&d};
  s.start();
  SerialPort host = SerialPort::open(s.pair.slave_path(), {});
  host.write(Bytes{0x30});
  EXPECT_EQ(read_n(host, 1), Bytes{0x31});
  s.finish();
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find(" rx " + s.pair.master().name() + " 30\n"), std::string::npos) << text.str();
  EXPECT_NE(text.str().find(" tx " + s.pair.master().name() + " 31\n"), std::string::npos) << text.str();
}

}  // namespace
}  // namespace ibs::serial
