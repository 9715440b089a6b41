// The master side of the parameter channel, fed scripted inverter words: the cycle tables of
// INTERBUS manual 4.1.3 from the master's column, the 85-SIOF read after a refused transfer (4.1.4),
// timeouts, inverter and master restarts, the request queue and polling.
#include "ibs/vf1000_channel/client.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace ibs::vf1000_channel;
using namespace ibs::drive;
using ibs::Error;
using ibs::ErrorCode;
using ibs::Time;
using ibs::Word;
using namespace std::chrono_literals;

ClientConfig synchronised() {
  ClientConfig c;
  c.start_synchronised = true;
  return c;
}

struct Master {
  explicit Master(const ClientConfig& config = synchronised()) : c(config) {}
  Client c;
  Time now{0};
  ibs::Duration period = 10ms;

  Word step(Word from_inverter) {
    now += period;
    return c.step(from_inverter, now);
  }
  // Feeds the s2m column of rows 0..n-1; returns the master's words of rows 1..n.
  std::vector<Word> sends(const std::vector<Word>& s2m) {
    std::vector<Word> out;
    for (Word s : s2m) out.push_back(step(s));
    return out;
  }
  Outcome outcome(RequestId id) const {
    const Poll p = c.poll(id);
    EXPECT_EQ(p.state, RequestState::done);
    return p.outcome;
  }
};

TEST(ClientCycleTables, ValueInquirySendsTheRowsOf41311) {
  Master m;
  EXPECT_EQ(Client::initial_word(), 0x0000);
  const RequestId id = m.c.submit(value_inquiry(0x16)).id;
  EXPECT_EQ(m.sends({0x8000, 0x8000, 0xA003, 0xA003, 0x88E8, 0x88E8}),
            (std::vector<Word>{0x2416, 0x2416, 0x0400, 0x0400, 0x0000, 0x0000}));
  const Outcome o = m.outcome(id);
  EXPECT_EQ(o.kind, OutcomeKind::value);
  EXPECT_EQ(o.value, 0x03E8);
  EXPECT_EQ(describe(o), "value 03E8H");
  EXPECT_EQ(m.step(0x8000), 0x0000);
  EXPECT_EQ(m.c.state(), ClientState::idle);
  ASSERT_NE(m.c.outcome(id), nullptr);
  EXPECT_EQ(m.c.outcome(id)->value, 0x03E8);
  EXPECT_EQ(m.c.outcome(id + 1), nullptr);
}

TEST(ClientCycleTables, ValueInquiryNakReportsNoParameterWithoutReadingSiof) {
  Master m;
  const RequestId id = m.c.submit(value_inquiry(40)).id;
  EXPECT_EQ(m.sends({0x8000, 0x8000, 0xB000, 0xB000, 0x8000, 0x8000}),
            (std::vector<Word>{0x2428, 0x2428, 0x0000, 0x0000, 0x0000, 0x0000}));
  const Outcome o = m.outcome(id);
  EXPECT_EQ(o.kind, OutcomeKind::nak);
  EXPECT_EQ(o.nak_cause, NakCause::no_parameter);
}

TEST(ClientCycleTables, ValueTransferSendsTheRowsOf41321) {
  Master m;
  const RequestId id = m.c.submit(value_transfer(0x16, 0x01F4)).id;
  EXPECT_EQ(m.sends({0x8000, 0x8000, 0xA000, 0xA000, 0x8000, 0x8000, 0xA800, 0xA800}),
            (std::vector<Word>{0x2816, 0x2816, 0x0801, 0x0801, 0x28F4, 0x28F4, 0x0000, 0x0000}));
  const Outcome o = m.outcome(id);
  EXPECT_EQ(o.kind, OutcomeKind::written);
  EXPECT_EQ(o.value, 0x01F4);
}

TEST(ClientCycleTables, DescriptionScanCollectsTheEighteenBytes) {
  Master m;
  const RequestId id = m.c.submit(description_scan(45)).id;
  const std::vector<std::uint8_t> bytes = {'V', 'B', '2', ' ',  ' ',  '%',  ' ',  ' ',  ' ',
                                           ' ', '2', '2', 0x00, 0x00, 0x01, 0xF4, 0x00, 0xA0};
  std::vector<Word> s2m = {0x8000, 0x8000};
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    const Word flags = i == 17 ? 0x8800 : (i % 2 == 0 ? 0xA000 : 0x8000);
    s2m.push_back(static_cast<Word>(flags | bytes[i]));
    s2m.push_back(static_cast<Word>(flags | bytes[i]));
  }
  const std::vector<Word> m2s = m.sends(s2m);
  ASSERT_EQ(m2s.size(), 38U);
  EXPECT_EQ(m2s[0], 0x2C2D);
  EXPECT_EQ(m2s[1], 0x2C2D);
  for (std::size_t row = 3; row <= 36; ++row) {
    const Word expected = ((row - 3) / 2) % 2 == 0 ? 0x0C00 : 0x2C00;
    EXPECT_EQ(m2s[row - 1], expected) << "row " << row;
  }
  EXPECT_EQ(m2s[36], 0x0000);  // row 37
  EXPECT_EQ(m2s[37], 0x0000);  // row 38
  const Outcome o = m.outcome(id);
  ASSERT_EQ(o.kind, OutcomeKind::description);
  const Description d = decode_description(o.description);
  EXPECT_EQ(d.name, "VB2");
  EXPECT_EQ(d.unit, "%");
  EXPECT_EQ(d.category, Category::eeprom);
  EXPECT_EQ(d.type, DataType::fixpoint16);
  EXPECT_EQ(d.max, 0x01F4);
  EXPECT_EQ(d.default_value, 0x00A0);
  EXPECT_EQ(describe(o), "description VB2 [%] category 2 type 2 min 0000H max 01F4H default 00A0H");
}

TEST(ClientNak, InquiryRefusedAfterItsNumberReportsControlBits) {
  Master m;
  const RequestId id = m.c.submit(value_inquiry(0x16)).id;
  EXPECT_EQ(m.sends({0x8000, 0x8000, 0xA003, 0xA003, 0x9000}),
            (std::vector<Word>{0x2416, 0x2416, 0x0400, 0x0400, 0x0000}));
  const Outcome o = m.outcome(id);
  EXPECT_EQ(o.kind, OutcomeKind::nak);
  EXPECT_EQ(o.nak_cause, NakCause::control_bits);
  EXPECT_EQ(describe(o), "NAK: unintended control bits");
}

TEST(ClientNak, RefusedTransferReads85AndReportsTheDecodedCause) {
  Master m;
  const RequestId id = m.c.submit(value_transfer(0x16, 0x5000)).id;
  EXPECT_EQ(m.sends({0x8000, 0x8000, 0xA000, 0xA000, 0x8000, 0x8000, 0xB000, 0xB000, 0x8000, 0x8000,
                     0xA000, 0xA000, 0x8880, 0x8880}),
            (std::vector<Word>{0x2816, 0x2816, 0x0850, 0x0850, 0x2800, 0x2800, 0x0000, 0x0000,
                               0x2455, 0x2455, 0x0400, 0x0400, 0x0000, 0x0000}));
  const Outcome o = m.outcome(id);
  EXPECT_EQ(o.kind, OutcomeKind::nak);
  EXPECT_EQ(o.nak_cause, NakCause::siof);
  EXPECT_EQ(o.siof, 0x80);
  EXPECT_EQ(describe(o), "NAK: 85-SIOF 80H: invalid value");
  EXPECT_EQ(m.c.last_siof(), 0x80);
  EXPECT_FALSE(m.c.siof_unread());
}

TEST(ClientNak, TheOutcomeWaitsFor85) {
  Master m;
  const RequestId id = m.c.submit(value_transfer(40, 1)).id;
  m.sends({0x8000, 0x8000, 0xB000});
  EXPECT_EQ(m.c.poll(id).state, RequestState::active);
}

TEST(ClientNak, A85ReadThatFailsLeavesTheCauseUnreadAndIsRepeatedBeforeTheNextTransfer) {
  Master m;
  const RequestId id = m.c.submit(value_transfer(0x16, 0x5000)).id;
  // Transfer refused at once, then the 85-SIOF read is refused too (not what a VF1000 does).
  EXPECT_EQ(
      m.sends({0x8000, 0x8000, 0xB000, 0xB000, 0x8000, 0x8000, 0xB000, 0xB000, 0x8000}),
      (std::vector<Word>{0x2816, 0x2816, 0x0000, 0x0000, 0x2455, 0x2455, 0x0000, 0x0000, 0x0000}));
  const Outcome o = m.outcome(id);
  EXPECT_EQ(o.kind, OutcomeKind::nak);
  EXPECT_EQ(o.nak_cause, NakCause::siof_unread);
  EXPECT_TRUE(m.c.siof_unread());
  m.c.submit(value_transfer(0x16, 0x01F4));
  EXPECT_EQ(m.step(0x8000), 0x2455);  // 85-SIOF first
}

TEST(ClientTimeout, NoAnswerEndsTheTransactionAndResyncs) {
  ClientConfig cfg = synchronised();
  cfg.timeout = 100ms;
  cfg.resync_hold = 50ms;
  Master m(cfg);
  const RequestId id = m.c.submit(value_inquiry(0x16)).id;
  const RequestId next = m.c.submit(value_inquiry(0x16)).id;
  Word w = 0;
  int steps = 0;
  while (m.c.poll(id).state != RequestState::done) {
    w = m.step(0x8000);
    ASSERT_LT(++steps, 100);
  }
  EXPECT_EQ(steps, 11);  // active from the first cycle at 10 ms: deadline 110 ms
  EXPECT_EQ(w, 0x0000);
  const Outcome o = m.outcome(id);
  EXPECT_EQ(o.kind, OutcomeKind::timeout);
  EXPECT_EQ(o.answers, 0);
  EXPECT_EQ(describe(o), "timeout after 0 answers of the inverter");
  EXPECT_EQ(m.c.state(), ClientState::resync);
  // CODE 0 held for resync_hold (from 110 ms) before the next telegram goes out at 160 ms.
  for (int i = 0; i < 4; ++i) EXPECT_EQ(m.step(0x8000), 0x0000) << i;
  EXPECT_EQ(m.step(0x8000), 0x2416);
  EXPECT_EQ(m.c.poll(next).state, RequestState::active);
}

TEST(ClientTimeout, EachRequestCanCarryItsOwnTimeout) {
  ClientConfig cfg = synchronised();
  cfg.timeout = 10s;
  Master m(cfg);
  Request r = value_inquiry(0x16);
  r.timeout = 30ms;
  const RequestId id = m.c.submit(r).id;
  m.sends({0x8000, 0x8000, 0xA003});
  EXPECT_EQ(m.c.poll(id).state, RequestState::active);
  m.step(0xA003);  // 40 ms: 30 ms after it started
  EXPECT_EQ(m.c.poll(id).state, RequestState::done);
  EXPECT_EQ(m.outcome(id).kind, OutcomeKind::timeout);
  EXPECT_EQ(m.outcome(id).answers, 1);
}

TEST(ClientTimeout, AnInverterThatStaysInitialisingTimesOut) {
  ClientConfig cfg = synchronised();
  cfg.timeout = 1s;
  Master m(cfg);
  const RequestId id = m.c.submit(value_inquiry(0x16)).id;
  for (int i = 0; i < 100; ++i) EXPECT_EQ(m.step(0x0000), 0x0000);
  EXPECT_EQ(m.c.poll(id).state, RequestState::active);
  EXPECT_EQ(m.step(0x0000), 0x0000);  // 1010 ms
  EXPECT_EQ(m.outcome(id).kind, OutcomeKind::timeout);
}

TEST(ClientRestarts, InverterRestartMidTransactionIsReportedAndSiofReadBeforeTheNextTransfer) {
  ClientConfig cfg = synchronised();
  cfg.resync_hold = 20ms;
  Master m(cfg);
  const RequestId id = m.c.submit(value_transfer(0x16, 0x01F4)).id;
  m.sends({0x8000, 0x8000, 0xA000, 0xA000});
  EXPECT_EQ(m.step(0x0000), 0x0000);  // RESET distinction 0
  const Outcome o = m.outcome(id);
  EXPECT_EQ(o.kind, OutcomeKind::inverter_restarted);
  EXPECT_EQ(o.answers, 1);
  EXPECT_TRUE(m.c.siof_unread());
  const RequestId again = m.c.submit(value_transfer(0x16, 0x01F4)).id;
  for (int i = 0; i < 20; ++i) EXPECT_EQ(m.step(0x0000), 0x0000);
  EXPECT_EQ(m.step(0x8000), 0x0000);  // ready again; resync_hold counts from the last RESET word
  EXPECT_EQ(m.step(0x8000), 0x2455);  // 85-SIOF read first (LUSTBUS manual 8.1.1)
  EXPECT_EQ(m.sends({0x8000, 0xA000, 0xA000, 0x8801, 0x8801, 0x8000}),
            (std::vector<Word>{0x2455, 0x0400, 0x0400, 0x0000, 0x0000, 0x2816}));
  EXPECT_EQ(m.c.last_siof(), 0x01);
  EXPECT_FALSE(m.c.siof_unread());
  EXPECT_EQ(m.c.poll(again).state, RequestState::active);
}

// Found by the fault campaign (docs/robustness.md, defect B): a master restart during a data
// outage let the resync hold run out while no CODE 0 reached the inverter, and the next telegram
// completed the inverter's old one. The hold counts only cycles that delivered data.
TEST(ClientRestarts, TheResyncHoldCountsOnlyCyclesWithValidData) {
  ClientConfig cfg = synchronised();
  cfg.resync_hold = 50ms;
  Master m(cfg);
  m.c.restart(m.now);
  const RequestId id = m.c.submit(value_inquiry(0x16)).id;
  // 300 ms without valid data: the words are old, the hold must not run out.
  for (int i = 0; i < 30; ++i) {
    m.now += m.period;
    EXPECT_EQ(m.c.step(0x8000, m.now, false), 0x0000) << i;
  }
  EXPECT_EQ(m.c.state(), ClientState::resync);
  // Data flows again: CODE 0 for the whole hold, counted from the first valid cycle.
  for (int i = 0; i < 5; ++i) EXPECT_EQ(m.step(0x8000), 0x0000) << i;
  EXPECT_EQ(m.step(0x8000), 0x2416);
  EXPECT_EQ(m.c.poll(id).state, RequestState::active);
}

TEST(ClientTimeout, ADeadlineRunsOutWithoutValidDataToo) {
  ClientConfig cfg = synchronised();
  cfg.timeout = 100ms;
  Master m(cfg);
  const RequestId id = m.c.submit(value_inquiry(0x16)).id;
  EXPECT_EQ(m.step(0x8000), 0x2416);
  for (int i = 0; i < 10; ++i) {
    m.now += m.period;
    m.c.step(0xA003, m.now, false);  // an answer that never arrived: not read
  }
  EXPECT_EQ(m.c.poll(id).state, RequestState::done);
  EXPECT_EQ(m.outcome(id).kind, OutcomeKind::timeout);
  EXPECT_EQ(m.outcome(id).answers, 0) << "the invalid cycles' words are not taken as answers";
}

TEST(ClientRestarts, InverterRestartWhileIdleOnlyMarks85Unread) {
  ClientConfig cfg = synchronised();
  cfg.resync_hold = 0ms;
  Master m(cfg);
  EXPECT_EQ(m.step(0x0000), 0x0000);
  EXPECT_TRUE(m.c.siof_unread());
  const RequestId id = m.c.submit(value_inquiry(0x16)).id;
  EXPECT_EQ(m.step(0x8000), 0x2416);  // inquiries need no 85-SIOF read
  EXPECT_EQ(m.c.poll(id).state, RequestState::active);
}

TEST(ClientRestarts, MasterRestartAbortsActiveAndQueuedAndHoldsCode0) {
  ClientConfig cfg = synchronised();
  cfg.resync_hold = 30ms;
  Master m(cfg);
  const RequestId a = m.c.submit(value_transfer(0x16, 0x01F4)).id;
  const RequestId b = m.c.submit(value_inquiry(0x16)).id;
  m.sends({0x8000, 0x8000, 0xA000});
  EXPECT_EQ(m.c.poll(a).state, RequestState::active);
  m.c.restart(m.now);
  EXPECT_EQ(m.outcome(a).kind, OutcomeKind::aborted);
  EXPECT_EQ(m.outcome(b).kind, OutcomeKind::aborted);
  EXPECT_FALSE(m.c.busy());
  const RequestId c = m.c.submit(value_inquiry(0x16)).id;
  EXPECT_EQ(m.step(0xA000), 0x0000);  // 40 ms
  EXPECT_EQ(m.step(0x8000), 0x0000);  // 50 ms
  EXPECT_EQ(m.step(0x8000), 0x2416);  // 60 ms: 30 ms after the restart
  EXPECT_EQ(m.c.poll(c).state, RequestState::active);
}

TEST(ClientRestarts, AFreshMasterHoldsCode0BeforeItsFirstTelegram) {
  ClientConfig cfg;
  cfg.resync_hold = 50ms;
  Master m(cfg);
  EXPECT_EQ(m.c.state(), ClientState::resync);
  m.c.submit(value_inquiry(0x16));
  // The inverter may be mid-telegram (8000 looks like wait mode): CODE 0 first, for 50 ms.
  for (int i = 0; i < 5; ++i) EXPECT_EQ(m.step(0x8000), 0x0000) << i;
  EXPECT_EQ(m.step(0x8000), 0x2416);
}

TEST(ClientRestarts, ResyncWaitsForTheAckToDrop) {
  ClientConfig cfg;
  cfg.resync_hold = 0ms;
  Master m(cfg);
  m.c.submit(value_inquiry(0x16));
  EXPECT_EQ(m.step(0x88E8), 0x0000);
  EXPECT_EQ(m.step(0xA000), 0x0000);
  EXPECT_EQ(m.step(0x8000), 0x2416);
}

TEST(ClientProtocol, AnAckOutOfPlaceIsAProtocolError) {
  ClientConfig cfg = synchronised();
  cfg.resync_hold = 0ms;
  Master m(cfg);
  const RequestId id = m.c.submit(value_transfer(0x16, 0x01F4)).id;
  EXPECT_EQ(m.sends({0x8000, 0x8000, 0xA800}), (std::vector<Word>{0x2816, 0x2816, 0x0000}));
  EXPECT_EQ(m.outcome(id).kind, OutcomeKind::protocol_error);
  EXPECT_EQ(m.outcome(id).answers, 1);
  EXPECT_EQ(m.c.state(), ClientState::resync);
  const RequestId id2 = m.c.submit(value_inquiry(0x16)).id;
  EXPECT_EQ(m.sends({0x8000, 0x8000, 0xA003, 0xA003, 0x8003}),  // last byte without ACK
            (std::vector<Word>{0x2416, 0x2416, 0x0400, 0x0400, 0x0000}));
  EXPECT_EQ(m.outcome(id2).kind, OutcomeKind::protocol_error);
  EXPECT_EQ(m.outcome(id2).answers, 2);
}

TEST(ClientQueue, OneTransactionAtATimeInSubmissionOrder) {
  Master m;
  const RequestId a = m.c.submit(value_inquiry(0x16)).id;
  const RequestId b = m.c.submit(value_inquiry(906)).id;
  EXPECT_EQ(a, 1U);
  EXPECT_EQ(b, 2U);
  EXPECT_EQ(m.c.queued(), 2U);
  EXPECT_EQ(m.c.poll(b).state, RequestState::queued);
  EXPECT_EQ(m.sends({0x8000, 0x8000, 0xA003, 0xA003, 0x88E8, 0x88E8, 0x8000}),
            (std::vector<Word>{0x2416, 0x2416, 0x0400, 0x0400, 0x0000, 0x0000, 0x278A}));
  EXPECT_EQ(m.c.poll(a).state, RequestState::done);
  EXPECT_EQ(m.c.poll(b).state, RequestState::active);
  EXPECT_EQ(m.c.queued(), 0U);
  EXPECT_TRUE(m.c.busy());
}

TEST(ClientQueue, RefusesWhenFullAndNumbersAbove3FF) {
  ClientConfig cfg = synchronised();
  cfg.queue_capacity = 2;
  Master m(cfg);
  EXPECT_TRUE(m.c.submit(value_inquiry(1)));
  EXPECT_TRUE(m.c.submit(value_inquiry(2)));
  const Submitted full = m.c.submit(value_inquiry(3));
  EXPECT_FALSE(full);
  EXPECT_EQ(full.error, SubmitError::queue_full);
  EXPECT_EQ(to_string(full.error), "request queue full");
  Master n;
  const Submitted big = n.c.submit(value_inquiry(0x400));
  EXPECT_EQ(big.error, SubmitError::invalid_number);
  EXPECT_EQ(big.id, 0U);
  EXPECT_TRUE(n.c.submit(value_inquiry(0x3FF)));
}

TEST(ClientQueue, PollKnowsOnlyRecentOutcomes) {
  ClientConfig cfg = synchronised();
  cfg.completed_capacity = 2;
  cfg.timeout = 10ms;
  cfg.resync_hold = 0ms;
  Master m(cfg);
  std::vector<RequestId> ids;
  for (int i = 0; i < 3; ++i) ids.push_back(m.c.submit(value_inquiry(0x16)).id);
  for (int i = 0; i < 20; ++i) m.step(0x8000);
  EXPECT_EQ(m.c.poll(ids[0]).state, RequestState::unknown);
  EXPECT_EQ(m.c.poll(ids[1]).state, RequestState::done);
  EXPECT_EQ(m.c.poll(ids[2]).state, RequestState::done);
  EXPECT_EQ(m.c.poll(0).state, RequestState::unknown);
  EXPECT_EQ(m.c.poll(99).state, RequestState::unknown);
}

TEST(ClientConstruction, RejectsEmptyQueuesAndNonPositiveTimeouts) {
  ClientConfig cfg;
  cfg.queue_capacity = 0;
  EXPECT_THROW(Client{cfg}, std::invalid_argument);
  cfg = ClientConfig{};
  cfg.timeout = 0ms;
  EXPECT_THROW(Client{cfg}, std::invalid_argument);
}

// Client::validate, the check the constructor throws by (docs/embedding.md, "An embedded build").
TEST(ClientConstruction, ValidateGivesTheCodeAndTheConstructorsMessage) {
  const auto thrown = [](const ClientConfig& c) -> std::string {
    try {
      const Client client(c);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  ClientConfig cfg;
  EXPECT_FALSE(Client::validate(cfg));
  EXPECT_EQ(thrown(cfg), "");
  cfg.queue_capacity = 0;
  Error e = Client::validate(cfg);
  EXPECT_EQ(e.code, ErrorCode::channel_capacity_zero);
  EXPECT_EQ(e.message,
            "vf1000_channel::Client: queue_capacity and completed_capacity must be at least 1");
  EXPECT_EQ(e.message, thrown(cfg));
  cfg = ClientConfig{};
  cfg.completed_capacity = 0;
  EXPECT_EQ(Client::validate(cfg).code, ErrorCode::channel_capacity_zero);
  EXPECT_EQ(Client::validate(cfg).message, thrown(cfg));
  for (const ibs::Duration t : {ibs::Duration{0}, ibs::Duration{-1}}) {
    cfg = ClientConfig{};
    cfg.timeout = t;
    e = Client::validate(cfg);
    EXPECT_EQ(e.code, ErrorCode::channel_timeout_not_positive);
    EXPECT_EQ(e.message, "vf1000_channel::Client: timeout must be positive");
    EXPECT_EQ(e.message, thrown(cfg));
  }
  // An accepted configuration makes the client it describes.
  cfg = ClientConfig{};
  cfg.start_synchronised = true;
  cfg.queue_capacity = 1;
  ASSERT_FALSE(Client::validate(cfg));
  Client c(cfg);
  EXPECT_EQ(c.state(), ClientState::idle);
  EXPECT_TRUE(c.submit(value_inquiry(0x16)));
  EXPECT_EQ(c.submit(value_inquiry(0x16)).error, SubmitError::queue_full);
}

}  // namespace
