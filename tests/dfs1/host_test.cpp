// The host's transaction machine: outcomes, the response and inter-byte timeouts, UID 0 only for
// 83, frames for other UIDs ignored.
#include "ibs/dfs1/host.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace ibs::dfs1 {
namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes bytes_of(const Frame& f) {
  const EncodedFrame e = encode(f);
  return {e.span().begin(), e.span().end()};
}

HostTransaction started(const Frame& request, Time at = 0ms) {
  HostTransaction t({100ms, 10ms});
  EXPECT_EQ(t.start(request, at), StartStatus::accepted);
  t.transmitted(at);
  return t;
}

TEST(Dfs1Host, RequestBytesAreTheEncodedFrame) {
  HostTransaction t;
  ASSERT_EQ(t.start(request::set_speed(1, 4096), 0ms), StartStatus::accepted);
  // The seed's example (DFS-1 manual, note 2) is Set Speed 4096 to UID 1.
  const Bytes want = {0x10, 0x02, 0x01, 0x82, 0x00, 0x00, 0x10, 0x10, 0x00, 0x10, 0x03, 0x6D};
  EXPECT_EQ(Bytes(t.tx().begin(), t.tx().end()), want);
  EXPECT_EQ(t.state(), HostTransaction::State::sending);
  EXPECT_EQ(t.start(request::status(1), 0ms), StartStatus::busy);
}

TEST(Dfs1Host, AckWithTheValueEndsTheTransaction) {
  HostTransaction t = started(request::read_parameter(3, 56));
  std::array<std::uint8_t, 4> v{};
  put_u32(v, 2);
  t.receive(bytes_of(make_ack(3, v)), 5ms);
  auto r = t.take_result();
  ASSERT_TRUE(r);
  EXPECT_EQ(r->outcome, Outcome::ack);
  EXPECT_EQ(r->value(), 2U);
  EXPECT_EQ(r->elapsed, 5ms);
  EXPECT_EQ(t.state(), HostTransaction::State::idle);
}

TEST(Dfs1Host, NakCarriesEveryErrorCode) {
  for (ErrorCode e : kAllErrorCodes) {
    HostTransaction t = started(request::status(9));
    t.receive(bytes_of(make_nak(9, e)), 1ms);
    auto r = t.take_result();
    ASSERT_TRUE(r);
    EXPECT_EQ(r->outcome, Outcome::nak);
    EXPECT_EQ(r->error, static_cast<std::uint8_t>(e));
  }
}

TEST(Dfs1Host, NoAnswerTimesOutAtTheResponseTimeout) {
  HostTransaction t = started(request::status(1), 10ms);
  EXPECT_EQ(t.next_deadline(), Time(110ms));
  t.poll(109ms);
  EXPECT_FALSE(t.done());
  t.poll(110ms);
  auto r = t.take_result();
  ASSERT_TRUE(r);
  EXPECT_EQ(r->outcome, Outcome::timeout);
  EXPECT_EQ(r->elapsed, 100ms);
}

TEST(Dfs1Host, AResponseThatStopsIsAnInterByteTimeout) {
  HostTransaction t = started(request::status(1));
  const Bytes b = bytes_of(make_ack(1, Bytes(16, 0)));
  t.receive(std::span(b).first(5), 20ms);
  EXPECT_EQ(t.next_deadline(), Time(30ms));  // the inter-byte timeout replaces the response one
  t.poll(30ms);
  auto r = t.take_result();
  ASSERT_TRUE(r);
  EXPECT_EQ(r->outcome, Outcome::inter_byte_timeout);
}

// Issue 23, defect 7: a device that answers with an endless trickle of bytes held the host for
// ever (each byte restarted the inter-byte timer). The overall deadline ends it, and the result
// says what the line carried.
TEST(Dfs1Host, ADeviceThatKeepsSendingEndsAtTheOverallDeadline) {
  const HostTimeouts timeouts{100ms, 10ms};
  EXPECT_EQ(timeouts.overall(), 100ms + 42 * 10ms) << "the response time and the longest frame, byte by byte";
  HostTransaction t = started(request::status(1));
  // A byte every 5 ms, each inside a frame: DLE STX, eight body bytes, DLE STX again (which
  // drops the frame begun and begins another: `interrupted`), and so on.
  const Bytes babble = {0x10, 0x02, 0x01, 0x06, 0x55, 0x55, 0x55, 0x55, 0x55, 0x55, 0x55, 0x55};
  Time now = 1ms;
  for (int i = 0; i < 10000 && !t.done(); ++i) {
    t.receive(babble[static_cast<std::size_t>(i) % babble.size()], now);
    now += 5ms;
    t.poll(now);
  }
  ASSERT_TRUE(t.done()) << "still waiting after " << now.count() / 1'000'000 << " ms";
  const auto r = t.take_result();
  EXPECT_EQ(r->outcome, Outcome::line_busy);
  EXPECT_EQ(to_string(r->outcome), "line busy");
  EXPECT_GE(r->elapsed, timeouts.overall());
  EXPECT_LE(r->elapsed, timeouts.overall() + 5ms);
  EXPECT_GT(r->bytes_heard, 100U);
  EXPECT_GT(r->corrupt_frames, 0U) << "the interrupted frames";
  // Garbage outside any frame does not extend the wait: the response timeout ends it.
  HostTransaction g = started(request::status(1));
  now = 0ms;
  while (!g.done()) {
    g.receive(std::uint8_t{0x55}, now);
    now += 5ms;
    g.poll(now);
  }
  const auto rg = g.take_result();
  EXPECT_EQ(rg->outcome, Outcome::timeout);
  EXPECT_EQ(rg->elapsed, 100ms);
}

TEST(Dfs1Host, FramesForAnotherUidAreIgnored) {
  HostTransaction t = started(request::status(2));
  t.receive(bytes_of(make_ack(3, Bytes(16, 0))), 1ms);
  EXPECT_FALSE(t.done());
  EXPECT_EQ(t.foreign_frames(), 1U);
  t.receive(bytes_of(make_ack(2, Bytes(16, 0))), 2ms);
  auto r = t.take_result();
  ASSERT_TRUE(r);
  EXPECT_EQ(r->outcome, Outcome::ack);
  EXPECT_EQ(r->response.uid, 2);
}

TEST(Dfs1Host, AnAckOfTheWrongLengthIsABadResponse) {
  HostTransaction t = started(request::status(1));
  t.receive(bytes_of(make_ack(1, Bytes(4, 0))), 1ms);
  auto r = t.take_result();
  ASSERT_TRUE(r);
  EXPECT_EQ(r->outcome, Outcome::bad_response);
}

TEST(Dfs1Host, ACorruptResponseIsNamedWhenTheTransactionTimesOut) {
  HostTransaction t = started(request::status(1));
  Bytes b = bytes_of(make_ack(1, Bytes(16, 0)));
  b.back() ^= 0x01;
  t.receive(b, 1ms);
  EXPECT_FALSE(t.done());
  t.poll(100ms);
  auto r = t.take_result();
  ASSERT_TRUE(r);
  EXPECT_EQ(r->outcome, Outcome::timeout);
  ASSERT_TRUE(r->last_decode_error);
  EXPECT_EQ(*r->last_decode_error, DecodeError::bad_checksum);
}

TEST(Dfs1Host, UidZeroIsOnlyForExecuteSpeedAndExpectsNoAnswer) {
  HostTransaction t;
  EXPECT_EQ(t.start(request::set_speed(0, 100), 0ms), StartStatus::rejected);
  EXPECT_EQ(t.start(request::status(0), 0ms), StartStatus::rejected);
  EXPECT_EQ(check_request(request::set_and_execute_speed(0, 1)), RequestCheck::global_not_83);
  ASSERT_EQ(t.start(request::execute_speed(0), 0ms), StartStatus::accepted);
  t.transmitted(3ms);
  auto r = t.take_result();
  ASSERT_TRUE(r);
  EXPECT_EQ(r->outcome, Outcome::sent);
}

TEST(Dfs1Host, MalformedRequestsAreRejected) {
  HostTransaction t;
  EXPECT_EQ(t.start(make_frame(1, 0x90), 0ms), StartStatus::rejected);
  EXPECT_EQ(t.start(make_frame(1, 0x81, Bytes{1}), 0ms), StartStatus::rejected);
  EXPECT_EQ(check_request(make_frame(1, 0x85)), RequestCheck::bad_size);
}

TEST(Dfs1Host, EveryRequestBuilderFitsItsCommand) {
  const std::vector<Frame> all = {
      request::status(1),
      request::set_speed(1, -5),
      request::execute_speed(1),
      request::set_and_execute_speed(1, 5),
      request::read_parameter(1, 1),
      request::write_parameter(1, 1, 2),
      request::read_analog_input(1, 1),
      request::read_analog_output(1, 1),
      request::write_analog_output(1, 1, 2),
      request::read_digital_input(1, 1),
      request::read_digital_output(1, 1),
      request::write_digital_output(1, 1, 1),
      request::set_operational_mode(1, 0x0006),
      request::read_operational_mode(1),
      request::application_mode(1, 1, 0),
  };
  ASSERT_EQ(all.size(), kAllCommands.size());
  for (std::size_t i = 0; i < all.size(); ++i) {
    EXPECT_EQ(all[i].code, static_cast<std::uint8_t>(kAllCommands[i]));
    EXPECT_EQ(check_request(all[i]), RequestCheck::ok) << to_string(kAllCommands[i]);
  }
}

}  // namespace
}  // namespace ibs::dfs1
