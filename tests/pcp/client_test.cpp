// The PCP client: submissions, the KBL check, timeouts, aborts, restarts of either side.
#include "ibs/pcp/client.hpp"
#include "ibs/devices/mc6000/channel.hpp"
#include "ibs/devices/mc6000/parameters.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "pcp_harness.hpp"
#include "peers.hpp"

namespace ibs::pcp {
namespace {

using namespace ibs::devices::mc6000;

using test::FakeServer;
using test::pdu_bytes;
using test::Session;

TEST(Client, SubmissionsAreCheckedBeforeAnythingIsSent) {
  Session s(1);
  const Time t = s.bus.now();
  EXPECT_EQ(s.client.read(t, ParameterRef::number(83)), SubmitStatus::not_initiated);
  EXPECT_EQ(s.client.status(t), SubmitStatus::not_initiated);
  EXPECT_EQ(s.client.initiate(t), SubmitStatus::accepted);
  EXPECT_EQ(s.client.initiate(t), SubmitStatus::busy);
  ASSERT_TRUE(s.bus.await()->ok());
  EXPECT_EQ(s.client.write(t, ParameterRef::number(82), DataType::usign8, 300.0),
            SubmitStatus::invalid_argument);
  std::vector<std::uint8_t> big(kMaxDataSize + 1, 0);
  EXPECT_EQ(s.client.write_bytes(t, ParameterRef::number(83), big), SubmitStatus::invalid_argument);
  EXPECT_FALSE(s.client.busy());
  EXPECT_THROW(Client(test::client_config(3)), std::invalid_argument);
  ClientConfig bad;
  bad.kbl.max_pdu_sending = 200;
  EXPECT_THROW(Client{bad}, std::invalid_argument);
}

TEST(Client, ARequestBiggerThanTheKblSendingSizeIsRefused) {
  ClientConfig cc;
  cc.kbl.max_pdu_sending = 20;  // just the Initiate request
  Session s(2, Session::running_server(), cc);
  ASSERT_TRUE(s.initiate().ok());
  const std::array<std::uint8_t, 12> twelve{};
  EXPECT_EQ(s.client.write_bytes(s.bus.now(), ParameterRef::number(428), twelve),
            SubmitStatus::invalid_argument);
  EXPECT_EQ(s.client.read(s.bus.now(), ParameterRef::number(428)), SubmitStatus::accepted);
  // Below the Initiate's own 20 bytes (either way) a client could never open an association.
  ClientConfig tiny;
  tiny.kbl.max_pdu_sending = 18;
  EXPECT_THROW(Client{tiny}, std::invalid_argument);
  tiny.kbl.max_pdu_sending = 134;
  tiny.kbl.max_pdu_receiving = 18;
  EXPECT_THROW(Client{tiny}, std::invalid_argument);
}

TEST(Client, TypedReadReportsALengthThatIsNotTheTypes) {
  Session s(4);
  ASSERT_TRUE(s.initiate().ok());
  const Result r = s.run(
      [](Client& c, Time t) { return c.read(t, ParameterRef::number(83), DataType::int32q16); });
  EXPECT_EQ(r.kind, ResultKind::type_mismatch);
  EXPECT_EQ(r.data.size, 2U);
  EXPECT_TRUE(s.client.associated());
}

TEST(Client, ServerRefusesAnIncompatibleKbl) {
  ClientConfig small;
  small.kbl.max_pdu_receiving = 64;  // the servo may send 134
  Session a(2, Session::running_server(), small);
  Result r = a.initiate();
  EXPECT_EQ(r.kind, ResultKind::negative);
  EXPECT_EQ(r.error, errors::kServiceNotExecutable);
  EXPECT_EQ(r.peer_kbl, ibs::devices::mc6000::kKbl) << "the negative confirmation tells why";
  EXPECT_FALSE(a.client.associated());

  ClientConfig put;
  put.kbl.services.client(kSvcPutOv);  // the MC6000 serves no Put-OV
  Session b(2, Session::running_server(), put);
  EXPECT_EQ(b.initiate().error, errors::kServiceNotExecutable);

  ServerConfig locked = Session::running_server();
  locked.password = 0x1234;
  Session c(2, locked);
  EXPECT_EQ(c.initiate().error, errors::kNoAccess);
  ClientConfig key;
  key.password = 0x1234;
  Session d(2, locked, key);
  EXPECT_TRUE(d.initiate().ok());
}

TEST(Client, ClientRefusesAServerKblThatDoesNotServeIt) {
  Client client(test::client_config(2));
  FakeServer fake(
      client, [](const std::vector<std::uint8_t>& m) -> std::optional<std::vector<std::uint8_t>> {
        if (m[1] != 0x8B) return std::nullopt;
        // Positive, but the server part offers only Get-OV long: no Read, no Write.
        return pdu_bytes({0x808B, 0x0007, static_cast<Word>(m[4] << 8 | m[5]), 0x0000, 134, 134,
                          0x0000, 0x0004, 0x0000});
      });
  ASSERT_EQ(client.initiate(fake.now()), SubmitStatus::accepted);
  const auto r = fake.await();
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->kind, ResultKind::incompatible);
  EXPECT_EQ(r->mismatch, KblMismatch::service_not_supported);
  EXPECT_FALSE(client.associated());
  fake.run(50);
  ASSERT_EQ(fake.received().size(), 2U);
  EXPECT_EQ(fake.received()[1],
            pdu_bytes({0x088D, 0x0002, 0x0002, static_cast<Word>(AbortReason::kbl_mismatch)}));
}

TEST(Client, AConfirmationThatDoesNotAnswerTheRequestIsAProtocolError) {
  Client client(test::client_config(4));
  FakeServer fake(
      client, [](const std::vector<std::uint8_t>& m) -> std::optional<std::vector<std::uint8_t>> {
        const Word iid_cr = static_cast<Word>(m[4] << 8 | m[5]);
        if (m[1] == 0x8B)
          return pdu_bytes({0x808B, 0x0007, iid_cr, 0x0000, 134, 134, 0x0000, 0x0004, 0x0304});
        // Answers a Read with another InvokeID.
        return pdu_bytes(
            {0x8081, 0x0004, static_cast<Word>(iid_cr + 0x0100), 0x0000, 0x0002, 0x1234});
      });
  ASSERT_EQ(client.initiate(fake.now()), SubmitStatus::accepted);
  ASSERT_TRUE(fake.await()->ok());
  ASSERT_EQ(client.read(fake.now(), ParameterRef::number(83)), SubmitStatus::accepted);
  const auto r = fake.await();
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->kind, ResultKind::protocol_error);
  EXPECT_FALSE(client.associated());
  EXPECT_EQ(client.link().state(), LinkState::aborting) << "the channel is resynchronised";
}

TEST(Client, EveryReadRequestHasTheBytesOfAFreshOne) {
  // The client builds its Read requests in one reused member: between Writes with data, plain,
  // typed and subindex Reads, each Read's PDU must be encode() of a fresh RequestPdu.
  Client client(test::client_config(4));
  FakeServer fake(
      client, [](const std::vector<std::uint8_t>& m) -> std::optional<std::vector<std::uint8_t>> {
        const Word iid_cr = static_cast<Word>(m[4] << 8 | m[5]);
        if (m[1] == 0x8B)
          return pdu_bytes({0x808B, 0x0007, iid_cr, 0x0000, 134, 134, 0x0000, 0x0004, 0x0304});
        if (m[1] == 0x82) return pdu_bytes({0x8082, 0x0002, iid_cr, 0x0000});
        return pdu_bytes({0x8081, 0x0004, iid_cr, 0x0000, 0x0002, 0x1234});
      });
  ASSERT_EQ(client.initiate(fake.now()), SubmitStatus::accepted);
  ASSERT_TRUE(fake.await()->ok());
  std::mt19937 rng(26);
  for (int k = 0; k < 200; ++k) {
    const auto index = static_cast<std::uint16_t>(rng());
    const auto subindex = static_cast<std::uint8_t>(rng());
    const unsigned how = rng() % 4;
    SubmitStatus st{};
    if (how == 0) {
      std::vector<std::uint8_t> data(1 + rng() % 16);
      for (auto& b : data) b = static_cast<std::uint8_t>(rng());
      st = client.write_bytes(fake.now(), ParameterRef{index}, data, subindex);
    } else if (how == 1) {
      st = client.read(fake.now(), ParameterRef{index});
    } else if (how == 2) {
      st = client.read(fake.now(), ParameterRef{index}, DataType::usign16);
    } else {
      st = client.read_subindex(fake.now(), ParameterRef{index}, subindex);
    }
    ASSERT_EQ(st, SubmitStatus::accepted);
    ASSERT_TRUE(fake.await().has_value());
    if (how == 0) continue;
    const std::vector<std::uint8_t>& m = fake.received().back();
    RequestPdu fresh;
    fresh.service = ServiceCode::read;
    fresh.index = index;
    fresh.subindex = how == 3 ? subindex : 0;
    fresh.invoke_id = m.size() > 4 ? m[4] : 0;
    fresh.cr = client.config().communication_reference;
    Pdu expected;
    ASSERT_TRUE(encode(fresh, expected));
    ASSERT_TRUE(std::equal(m.begin(), m.end(), expected.view().begin(), expected.view().end()))
        << "request " << k;
    EXPECT_EQ(fresh.invoke_id, static_cast<std::uint8_t>(k + 1)) << "the InvokeIDs count on";
  }
}

TEST(Client, EveryReadResultIsAFreshResultWithTheReadsFields) {
  // After a Read the client resets only what a Read's completion writes (reset_result): every
  // Read's result, between Writes and Reads that end positive with values of every length,
  // typed (matching or not), or negative, must be a fresh Result but for the fields a Read sets,
  // and hold no byte of an earlier value past its size.
  Client client(test::client_config(4));
  std::mt19937 rng(2626);
  std::vector<std::uint8_t> value;
  bool negative = false;
  FakeServer fake(
      client, [&](const std::vector<std::uint8_t>& m) -> std::optional<std::vector<std::uint8_t>> {
        const Word iid_cr = static_cast<Word>(m[4] << 8 | m[5]);
        if (m[1] == 0x8B)
          return pdu_bytes({0x808B, 0x0007, iid_cr, 0x0000, 134, 134, 0x0000, 0x0004, 0x0304});
        if (m[1] == 0x82) return pdu_bytes({0x8082, 0x0002, iid_cr, 0x0000});
        if (negative) return pdu_bytes({0x8081, 0x0003, iid_cr, 0x0607, 0x0001});
        std::vector<std::uint8_t> b{0x80, 0x81, 0, 0, m[4], m[5], 0, 0, 0,
                                    static_cast<std::uint8_t>(value.size())};
        b.insert(b.end(), value.begin(), value.end());
        if (b.size() % 2 != 0) b.push_back(0);
        b[3] = static_cast<std::uint8_t>((b.size() - 4) / 2);
        return b;
      });
  ASSERT_EQ(client.initiate(fake.now()), SubmitStatus::accepted);
  ASSERT_TRUE(fake.await()->ok());
  for (int k = 0; k < 300; ++k) {
    const auto index = static_cast<std::uint16_t>(rng());
    const unsigned how = rng() % 4;  // 0: Write, 1: Read, 2: typed Read, 3: negative Read
    negative = how == 3;
    value.resize(rng() % 4 == 0 ? 2 : rng() % (kMaxDataSize + 1));
    for (auto& b : value) b = static_cast<std::uint8_t>(rng() | 1U);
    SubmitStatus st{};
    if (how == 0) {
      st = client.write_bytes(fake.now(), ParameterRef{index}, value, 0);
    } else if (how == 2) {
      st = client.read(fake.now(), ParameterRef{index}, DataType::usign16);
    } else {
      st = client.read(fake.now(), ParameterRef{index});
    }
    ASSERT_EQ(st, SubmitStatus::accepted);
    const std::optional<Result> r = fake.await();
    ASSERT_TRUE(r.has_value());
    if (how == 0) {
      ASSERT_TRUE(r->ok());
      continue;
    }
    const Result fresh{};
    EXPECT_EQ(r->service, ServiceCode::read);
    EXPECT_EQ(r->index, index);
    if (how == 3) {
      EXPECT_EQ(r->kind, ResultKind::negative);
      EXPECT_EQ(r->error.error_class, 6);
      EXPECT_EQ(r->error.error_code, 7);
      EXPECT_EQ(r->data.size, 0U);
      EXPECT_FALSE(r->value.has_value());
    } else {
      EXPECT_EQ(r->error, fresh.error) << k;
      ASSERT_EQ(r->data.size, value.size()) << k;
      EXPECT_TRUE(std::equal(value.begin(), value.end(), r->data.data.begin())) << k;
      if (how == 2 && value.size() == 2) {
        EXPECT_EQ(r->kind, ResultKind::ok) << k;
        EXPECT_TRUE(r->value.has_value()) << k;
      } else if (how == 2) {
        EXPECT_EQ(r->kind, ResultKind::type_mismatch) << k;
        EXPECT_FALSE(r->value.has_value()) << k;
      } else {
        EXPECT_EQ(r->kind, ResultKind::ok) << k;
        EXPECT_FALSE(r->value.has_value()) << k;
      }
    }
    // Everything past the value, and every field a Read does not set, as in a fresh Result.
    EXPECT_TRUE(std::all_of(r->data.data.begin() + static_cast<std::ptrdiff_t>(r->data.size),
                            r->data.data.end(), [](std::uint8_t b) { return b == 0; }))
        << "read " << k;
    EXPECT_EQ(r->abort_reason, fresh.abort_reason);
    EXPECT_EQ(r->mismatch, fresh.mismatch);
    EXPECT_EQ(r->description, fresh.description);
    EXPECT_EQ(r->identity, fresh.identity);
    EXPECT_EQ(r->status, fresh.status);
    EXPECT_EQ(r->peer_kbl, fresh.peer_kbl);
    EXPECT_LT(r->submitted_at, r->completed_at);
  }
}

TEST(Client, AServerAbortEndsTheRequest) {
  Client client(test::client_config(1));
  FakeServer fake(
      client, [](const std::vector<std::uint8_t>& m) -> std::optional<std::vector<std::uint8_t>> {
        const Word iid_cr = static_cast<Word>(m[4] << 8 | m[5]);
        if (m[1] == 0x8B)
          return pdu_bytes({0x808B, 0x0007, iid_cr, 0x0000, 134, 134, 0x0000, 0x0004, 0x0304});
        return pdu_bytes({0x088D, 0x0002, 0x0002, static_cast<Word>(AbortReason::not_initiated)});
      });
  ASSERT_EQ(client.initiate(fake.now()), SubmitStatus::accepted);
  ASSERT_TRUE(fake.await()->ok());
  ASSERT_EQ(client.status(fake.now()), SubmitStatus::accepted);
  const auto r = fake.await();
  EXPECT_EQ(r->kind, ResultKind::aborted);
  EXPECT_EQ(r->abort_reason, AbortReason::not_initiated);
  EXPECT_FALSE(client.associated());
}

TEST(Client, TakeResultViewIsTakeResultWithoutACopy) {
  // Two sessions alike: one takes its results with take_result(), the other with
  // take_result_view(); the same results in the same cycles, each taken once.
  Session a(4);
  Session b(4);
  const auto take = [](Session& s, bool view) -> std::optional<Result> {
    if (!view) return s.client.take_result();
    const Result* r = s.client.take_result_view();
    if (r == nullptr) return std::nullopt;
    EXPECT_EQ(s.client.take_result_view(), nullptr) << "taken once";
    EXPECT_FALSE(s.client.take_result().has_value()) << "taken once";
    return *r;
  };
  const std::array<std::uint16_t, 3> numbers{kSerr, kIbstu, 999};  // 999: no such parameter
  for (int k = 0; k < 4; ++k) {
    for (Session* s : {&a, &b}) {
      const Time t = s->bus.now();
      ASSERT_EQ(k == 0 ? s->client.initiate(t)
                       : s->client.read(t, ParameterRef::number(numbers[static_cast<std::size_t>(k - 1)])),
                SubmitStatus::accepted);
    }
    std::optional<Result> ra;
    std::optional<Result> rb;
    for (int c = 0; c < 1000 && !ra; ++c) {
      a.bus.cycle();
      b.bus.cycle();
      ra = take(a, false);
      rb = take(b, true);
      ASSERT_EQ(ra.has_value(), rb.has_value()) << "cycle " << c;
    }
    ASSERT_TRUE(ra && rb);
    EXPECT_EQ(ra->service, rb->service);
    EXPECT_EQ(ra->kind, rb->kind);
    EXPECT_EQ(ra->index, rb->index);
    EXPECT_EQ(ra->invoke_id, rb->invoke_id);
    EXPECT_EQ(ra->error, rb->error);
    EXPECT_EQ(ra->data, rb->data);
    EXPECT_EQ(ra->peer_kbl, rb->peer_kbl);
    EXPECT_EQ(ra->submitted_at, rb->submitted_at);
    EXPECT_EQ(ra->completed_at, rb->completed_at);
  }
}

TEST(Client, ASilentServoEndsInATimeout) {
  Client client(test::client_config(2));
  std::array<Word, 2> zero{};
  std::array<Word, 2> out{};
  ASSERT_EQ(client.initiate(0ms), SubmitStatus::accepted);
  std::optional<Result> r;
  Time t{};
  while (!r) {
    t += 1ms;
    client.step(t, zero, out);
    r = client.take_result();
    ASSERT_LE(t, 600ms);
  }
  EXPECT_EQ(r->kind, ResultKind::timeout);
  EXPECT_EQ(t, 500ms);
  EXPECT_EQ(client.link().state(), LinkState::aborting);
  EXPECT_GT(client.link().stats().frames_invalid, 0U) << "a zero channel is never a frame";
}

TEST(Client, AStuckServoTimesOutAndTheAbortEndsItsAssociation) {
  ServerConfig sc = Session::running_server();
  LatencyModel stuck;
  stuck.processing_min = stuck.processing_max = 5s;
  sc.latency = stuck;
  Session s(2, sc);
  // Initiate itself is executed after 5 s: give it a long timeout.
  const Result init = s.run([](Client& c, Time t) { return c.initiate(t, 6s); });
  ASSERT_TRUE(init.ok()) << to_string(init.kind);
  ASSERT_TRUE(s.server.associated());
  const Result r = s.read(83);
  EXPECT_EQ(r.kind, ResultKind::timeout);
  EXPECT_EQ(r.completed_at - r.submitted_at, 500ms);
  s.idle(20ms);
  EXPECT_FALSE(s.server.associated()) << "the link abort ended it";
  EXPECT_FALSE(s.server.busy()) << "and dropped the stuck job";
  EXPECT_EQ(s.client.read(s.bus.now(), ParameterRef::number(83)), SubmitStatus::not_initiated);
}

TEST(Client, UserAbortWithARequestOutstanding) {
  Session s(1);
  ASSERT_TRUE(s.initiate().ok());
  ASSERT_EQ(s.client.read(s.bus.now(), ParameterRef::number(83)), SubmitStatus::accepted);
  for (int i = 0; i < 7; ++i) s.bus.cycle();  // half-way through the request's fragments
  s.client.abort(s.bus.now());
  const auto r = s.client.take_result();
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->kind, ResultKind::aborted);
  EXPECT_EQ(r->abort_reason, AbortReason::user);
  s.idle(20ms);
  EXPECT_FALSE(s.server.associated());
  EXPECT_FALSE(s.client.take_result().has_value()) << "exactly one result per request";
  EXPECT_TRUE(s.initiate().ok());
  EXPECT_TRUE(s.read(83).ok());
}

TEST(Client, UserAbortWhenIdleSendsTheAbortMessage) {
  Session s(2);
  ASSERT_TRUE(s.initiate().ok());
  s.client.abort(s.bus.now());
  EXPECT_FALSE(s.client.associated());
  s.idle(30ms);
  EXPECT_FALSE(s.server.associated());
  EXPECT_EQ(s.server.stats().aborts_received, 1U);
  EXPECT_FALSE(s.client.take_result().has_value()) << "Abort is unconfirmed";
}

TEST(Client, ServoRestartEndsTheOutstandingRequestWithALinkReset) {
  Session s(1);
  ASSERT_TRUE(s.initiate().ok());
  ASSERT_EQ(s.client.read(s.bus.now(), ParameterRef::number(83)), SubmitStatus::accepted);
  for (int i = 0; i < 8; ++i) s.bus.cycle();  // the request half-way on the channel
  s.power_on();
  const auto r = s.bus.await(100ms);
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->kind, ResultKind::link_reset);
  EXPECT_LT(r->completed_at - s.bus.now(), 10ms) << "no waiting for the timeout";
  EXPECT_TRUE(s.initiate().ok());
  EXPECT_EQ(s.read_serr(), kSerrPowerOn);
}

TEST(Client, ARestartedMasterNeverSeesTheOldConfirmation) {
  for (const int words : {1, 2, 4}) {
    Session s(words);
    ASSERT_TRUE(s.initiate().ok());
    s.drive().set_reading(83, 1111);
    s.drive().set_reading(kIbstu, 2222);
    ASSERT_EQ(s.client.read(s.bus.now(), ParameterRef::number(83)), SubmitStatus::accepted);
    // Run until the servo is half-way through sending the Read's confirmation.
    ASSERT_TRUE(s.bus.run_until(
        [&] { return s.server.stats().requests == 2 && !s.server.busy() && s.server.link().sending(); },
        1s));
    s.bus.cycle();
    s.bus.cycle();
    ASSERT_TRUE(s.server.link().sending()) << "still on the wire when the master restarts";
    Client fresh(test::client_config(words));  // the master program restarts
    s.bus.set_client(fresh);
    ASSERT_EQ(fresh.initiate(s.bus.now()), SubmitStatus::accepted);
    auto r = s.bus.await();
    ASSERT_TRUE(r.has_value() && r->ok()) << words;
    ASSERT_EQ(fresh.read(s.bus.now(), ParameterRef::number(kIbstu)), SubmitStatus::accepted);
    r = s.bus.await();
    ASSERT_TRUE(r->ok());
    EXPECT_EQ(r->index, index_of(kIbstu));
    EXPECT_EQ(make_word(r->data.data[0], r->data.data[1]), 2222);
    EXPECT_EQ(fresh.stats().protocol_errors, 0U);
    s.bus.set_client(s.client);  // the session's destructor order needs nothing more
  }
}

}  // namespace
}  // namespace ibs::pcp
