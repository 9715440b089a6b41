// Master driver and emulated controllers on one simulated RS-485 line in simulated time: the
// global 83 reaches every controller without an answer, a frame for another UID gets none,
// timeouts, character timing and the turnaround delay.
#include "ibs/devices/dfs1/line.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "ibs/dfs1/host.hpp"

namespace ibs::devices::dfs1 {
namespace {

namespace proto = ::ibs::dfs1;
namespace request = proto::request;

struct Bench {
  explicit Bench(std::vector<std::uint8_t> uids, std::uint32_t baud = 9600)
      : master({100ms, 10ms}) {
    std::vector<Controller*> raw;
    for (std::uint8_t uid : uids) {
      controllers.push_back(std::make_unique<Controller>(ControllerConfig{uid}));
      raw.push_back(controllers.back().get());
    }
    line = std::make_unique<SimulatedLine>(master, raw, baud);
    line->set_observer([this](Time, std::size_t sender, std::uint8_t) {
      if (sender != 0) ++answered_bytes;
    });
  }
  // Submits `r`, runs until done, returns the completion.
  Completion transact(const proto::Frame& r) {
    const auto t = master.submit(r);
    EXPECT_TRUE(t);
    line->run_until_idle(line->now() + 10s);
    auto c = master.take_completion();
    EXPECT_TRUE(c);
    EXPECT_EQ(c->ticket, *t);
    return *c;
  }
  Master master;
  std::vector<std::unique_ptr<Controller>> controllers;
  std::unique_ptr<SimulatedLine> line;
  std::uint64_t answered_bytes = 0;
};

TEST(Dfs1Line, CharacterTimeIsTenBitsAtTheBaudRate) {
  EXPECT_EQ(character_time(9600), Duration(1041667));
  EXPECT_EQ(character_time(19200), Duration(520833));
  EXPECT_EQ(character_time(38400), Duration(260417));
}

TEST(Dfs1Line, StatusTransactionTakesItsCharactersAndTheTurnaround) {
  Bench b({1, 2, 3});
  const Completion c = b.transact(request::status(2));
  ASSERT_EQ(c.result.outcome, proto::Outcome::ack);
  EXPECT_EQ(c.result.response.uid, 2);
  const std::size_t req = proto::encode(request::status(2)).size;
  const std::size_t resp = proto::encode(c.result.response).size;
  // The response timer starts when the request's last character has ended.
  EXPECT_EQ(c.result.elapsed, 2ms + static_cast<long>(resp) * character_time(9600));
  EXPECT_EQ(b.line->bytes(), req + resp);
  EXPECT_EQ(b.line->collisions(), 0U);
  EXPECT_EQ(b.controllers[0]->counters().foreign, 2U);  // the request and the answer
  EXPECT_EQ(b.controllers[2]->counters().foreign, 2U);
}

TEST(Dfs1Line, GlobalExecuteSpeedReachesEveryControllerWithoutAnswer) {
  Bench b({1, 2, 3, 200});
  for (auto& c : b.controllers) {
    const Completion w = b.transact(request::write_parameter(c->uid(), 3, 15));
    ASSERT_EQ(w.result.outcome, proto::Outcome::ack)
        << int(w.result.error) << " uid " << int(c->uid());
    ASSERT_EQ(
        b.transact(request::set_speed(c->uid(), 5 * static_cast<int>(c->uid()))).result.outcome,
        proto::Outcome::ack);
    EXPECT_EQ(c->commanded_speed(), 0);
  }
  const std::uint64_t answered_before = b.answered_bytes;
  const Completion c = b.transact(request::execute_speed(0));
  EXPECT_EQ(c.result.outcome, proto::Outcome::sent);
  b.line->run_until(b.line->now() + 1s);  // any late answer would show up here
  EXPECT_EQ(b.answered_bytes, answered_before);
  for (auto& ctl : b.controllers) {
    EXPECT_EQ(ctl->commanded_speed(), 5 * static_cast<int>(ctl->uid()));
    EXPECT_EQ(ctl->counters().globals, 1U);
  }
  EXPECT_EQ(b.line->collisions(), 0U);
}

TEST(Dfs1Line, AFrameForAnAbsentUidTimesOut) {
  Bench b({1, 2});
  const Completion c = b.transact(request::status(7));
  EXPECT_EQ(c.result.outcome, proto::Outcome::timeout);
  EXPECT_EQ(c.result.elapsed, 100ms);
  EXPECT_EQ(b.answered_bytes, 0U);
}

TEST(Dfs1Line, QueuedRequestsRunOneAtATimeInOrder) {
  Bench b({1, 2});
  std::vector<Ticket> tickets;
  for (std::uint8_t p : std::vector<std::uint8_t>{1, 2, 3, 4, 6, 48, 56, 62}) {
    tickets.push_back(
        *b.master.submit(request::read_parameter(static_cast<std::uint8_t>(1 + p % 2), p)));
  }
  tickets.push_back(*b.master.submit(request::read_parameter(1, 99)));
  b.line->run_until_idle(10s);
  for (std::size_t i = 0; i < tickets.size(); ++i) {
    auto c = b.master.take_completion();
    ASSERT_TRUE(c);
    EXPECT_EQ(c->ticket, tickets[i]);
    if (i + 1 < tickets.size()) {
      EXPECT_EQ(c->result.outcome, proto::Outcome::ack);
    } else {
      EXPECT_EQ(c->result.outcome, proto::Outcome::nak);
      EXPECT_EQ(c->result.error, 0x82);
    }
  }
  EXPECT_EQ(b.line->collisions(), 0U);
}

TEST(Dfs1Line, TheQueueHasAFixedCapacity) {
  Bench b({1});
  for (std::size_t i = 0; i < Master::kCapacity; ++i) {
    EXPECT_TRUE(b.master.submit(request::status(1)));
  }
  EXPECT_FALSE(b.master.submit(request::status(1)));
  EXPECT_FALSE(b.master.submit(request::status(0)));  // refused anyway: UID 0 only for 83
}

TEST(Dfs1Line, ATurnaroundLongerThanTheResponseTimeoutTimesOut) {
  Bench b({1});
  ASSERT_EQ(b.transact(request::write_parameter(1, 56, 150)).result.outcome, proto::Outcome::ack);
  const Completion c = b.transact(request::status(1));
  EXPECT_EQ(c.result.outcome, proto::Outcome::timeout);
  // The late answer goes out on an idle line. The write of a shorter delay times out as well,
  // but is applied.
  EXPECT_EQ(b.transact(request::write_parameter(1, 56, 2)).result.outcome, proto::Outcome::timeout);
  EXPECT_EQ(b.transact(request::status(1)).result.outcome, proto::Outcome::ack);
  EXPECT_EQ(b.line->collisions(), 0U);
}

TEST(Dfs1Line, SpeedRunsUpInSimulatedTime) {
  Bench b({4}, 38400);
  ASSERT_EQ(b.transact(request::write_parameter(4, 3, 15)).result.outcome, proto::Outcome::ack);
  ASSERT_EQ(b.transact(request::set_and_execute_speed(4, 1200)).result.outcome,
            proto::Outcome::ack);
  b.line->run_until(b.line->now() + 4s);
  const Completion c = b.transact(request::status(4));
  ASSERT_EQ(c.result.outcome, proto::Outcome::ack);
  EXPECT_EQ(proto::to_signed(c.result.response.value_at(0)), 1200);
  EXPECT_NEAR(proto::to_signed(c.result.response.value_at(4)), 1200, 1);
  EXPECT_NE(c.result.response.data[14] & kSt2AtSpeed, 0);
}

}  // namespace
}  // namespace ibs::devices::dfs1
