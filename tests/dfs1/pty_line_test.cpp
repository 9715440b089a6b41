// Host against emulated DFS-1 controllers over a real pseudo-terminal pair, through the serial
// transport and the loops of `ibs dfs1` (serial::serve, serial::transact of dfs1_host.hpp), in real
// time.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <thread>
#include <vector>

#include "ibs/devices/dfs1/served_controller.hpp"
#include "ibs/serial/dfs1_host.hpp"
#include "ibs/serial/pty.hpp"
#include "ibs/serial/serve.hpp"

namespace ibs::cli {
namespace {

namespace proto = ::ibs::dfs1;
namespace dev = ::ibs::devices::dfs1;
namespace request = proto::request;

class PtyLine : public ::testing::Test {
 protected:
  void SetUp() override {
    for (std::uint8_t uid : std::vector<std::uint8_t>{1, 2, 3}) {
      controllers_.push_back(std::make_unique<dev::Controller>(dev::ControllerConfig{uid}));
      served_.push_back(std::make_unique<dev::ServedController>(*controllers_.back()));
      raw_.push_back(served_.back().get());
    }
    pair_ = std::make_unique<serial::PtyPair>(serial::PtyPair::open());
    server_ =
        std::thread([this] { serial::serve(pair_->master(), raw_, [this] { return stop_.load(); }); });
    host_ = std::make_unique<serial::SerialPort>(serial::SerialPort::open(pair_->slave_path(), {}));
  }
  void TearDown() override {
    stop_ = true;
    server_.join();
  }
  // Generous timeouts: a loaded machine may not schedule the serving thread for a while.
  proto::HostResult transact(const proto::Frame& f, Duration timeout = 2s) {
    return serial::transact(*host_, f, {timeout, 500ms});
  }

  std::vector<std::unique_ptr<dev::Controller>> controllers_;
  std::vector<std::unique_ptr<dev::ServedController>> served_;
  std::vector<base::LineDevice*> raw_;
  std::unique_ptr<serial::PtyPair> pair_;
  std::atomic<bool> stop_{false};
  std::thread server_;
  std::unique_ptr<serial::SerialPort> host_;
};

TEST_F(PtyLine, StatusOfEachController) {
  for (std::uint8_t uid : std::vector<std::uint8_t>{1, 2, 3}) {
    const auto r = transact(request::status(uid));
    ASSERT_EQ(r.outcome, proto::Outcome::ack) << int(uid);
    EXPECT_EQ(r.response.uid, uid);
    EXPECT_EQ(r.response.size, 16U);
  }
}

TEST_F(PtyLine, ParameterOutsideTheTableIsNak82) {
  const auto r = transact(request::read_parameter(2, 99));
  ASSERT_EQ(r.outcome, proto::Outcome::nak);
  EXPECT_EQ(r.error, 0x82);
}

TEST_F(PtyLine, UnknownCommandIsNak86) {
  // The host refuses to send an unknown command, so the bytes go out by hand.
  const proto::EncodedFrame e = proto::encode(proto::make_frame(3, 0x9A));
  host_->write(e.span());
  proto::FrameDecoder d;
  std::array<std::uint8_t, 64> buf{};
  std::optional<proto::Frame> got;
  for (int i = 0; i < 200 && !got; ++i) {
    const std::size_t n = host_->read(buf, 20ms);
    for (std::size_t k = 0; k < n; ++k) {
      if (d.push(buf[k]).status == proto::DecodeStatus::frame) got = d.frame();
    }
  }
  ASSERT_TRUE(got);
  EXPECT_TRUE(got->is_nak());
  EXPECT_EQ(got->uid, 3);
  EXPECT_EQ(got->data[0], 0x86);
}

TEST_F(PtyLine, AFrameForAnAbsentUidGetsNoAnswer) {
  const auto r = transact(request::status(9), 200ms);
  EXPECT_EQ(r.outcome, proto::Outcome::timeout);
}

TEST_F(PtyLine, GlobalExecuteSpeedReachesEveryControllerWithoutAnswer) {
  for (std::uint8_t uid : std::vector<std::uint8_t>{1, 2, 3}) {
    ASSERT_EQ(
        transact(request::write_parameter(uid, dev::kRemoteFunctions, dev::kRemoteAll)).outcome,
        proto::Outcome::ack);
    ASSERT_EQ(transact(request::set_speed(uid, 100 * uid)).outcome, proto::Outcome::ack);
  }
  EXPECT_EQ(transact(request::execute_speed(0)).outcome, proto::Outcome::sent);
  std::array<std::uint8_t, 64> buf{};
  EXPECT_EQ(host_->read(buf, 200ms), 0U);  // nobody answers
  for (std::uint8_t uid : std::vector<std::uint8_t>{1, 2, 3}) {
    const auto r = transact(request::status(uid));
    ASSERT_EQ(r.outcome, proto::Outcome::ack);
    EXPECT_EQ(proto::to_signed(r.response.value_at(0)), 100 * uid);
  }
}

TEST_F(PtyLine, TheEmulatorHonoursTheTurnaroundDelay) {
  ASSERT_EQ(transact(request::write_parameter(1, dev::kTurnaroundDelay, 60)).outcome,
            proto::Outcome::ack);
  // A lower bound only, and one scheduling cannot break: from before the request is written to
  // after the answer is read, so the emulator heard the request after the first stamp. (The
  // host's own `elapsed` starts after its write returns: a host descheduled there stamps later
  // than the emulator heard, and may see the answer sooner than 60 ms after that.)
  const auto before = std::chrono::steady_clock::now();
  const auto r = transact(request::status(1));
  const auto after = std::chrono::steady_clock::now();
  ASSERT_EQ(r.outcome, proto::Outcome::ack);
  EXPECT_GE(after - before, 60ms);
  ASSERT_EQ(transact(request::write_parameter(1, dev::kTurnaroundDelay, 0)).outcome,
            proto::Outcome::ack);
}

}  // namespace
}  // namespace ibs::cli
