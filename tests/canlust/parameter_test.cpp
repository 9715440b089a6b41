// The parameter channel (4.5): server and client against each other in memory, byte for byte,
// and the server's answers to broken sequences.
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "fake_drive.hpp"
#include "ibs/canlust/parameter_channel.hpp"
#include "ibs/canlust/parameter_client.hpp"

namespace ibs::canlust {
namespace {

using test::FakeDrive;
using Bytes = std::vector<std::uint8_t>;

Bytes bytes(const CanFrame& f) { return {f.data.begin(), f.data.begin() + f.dlc}; }

// Client <-> server of drive `address` in memory; records every frame.
struct Loop {
  FakeDrive drive;
  ParameterServer server{drive};
  ParameterClient client;
  IdentifierMap ids;
  Address address = 1;
  std::vector<CanFrame> frames;
  Time now{0};
  // Frames from the drive are passed through `tamper` (tests of the client's checks).
  std::function<void(CanFrame&)> tamper;

  const Outcome& run(const Request& r) {
    const auto id = client.submit(r).id;
    EXPECT_NE(id, 0U);
    for (int i = 0; i < 100000; ++i) {
      client.step(now);
      while (auto f = client.take_frame()) {
        frames.push_back(*f);
        const auto c = ids.classify(f->id);
        if (c && c->kind == TelegramKind::parameter_request && c->address == address) {
          server.receive(decode_parameter(*f).value, now);
        }
      }
      while (auto t = server.take_reply(now)) {
        auto f = *encode_parameter_reply(ids, address, *t);
        if (tamper) tamper(f);
        frames.push_back(f);
        client.receive(f, now);
      }
      const auto p = client.poll(id);
      if (p.state == RequestState::done) return *p.outcome;
      now += 1ms;
    }
    static Outcome none;
    return none;
  }
};

// 7.1.3 as an exchange: read 360-DISP of CDA 1 -> 1323: 68 01 00 96 01 00 00 00.
TEST(ParameterExchange, Read360OfCda1IsTheReplyOf713) {
  Loop l;
  const auto& o = l.run(read(1, test::kParamDisp));
  EXPECT_EQ(o.kind, OutcomeKind::done);
  EXPECT_EQ(o.value, 406U);
  ASSERT_EQ(l.frames.size(), 2U);
  EXPECT_EQ(l.frames[0].id, 1103);
  EXPECT_EQ(bytes(l.frames[0]), (Bytes{0x68, 0x01, 0x05, 0x00, 0x00, 0x00, 0x00, 0x00}));
  EXPECT_EQ(l.frames[1].id, 1323);
  EXPECT_EQ(bytes(l.frames[1]), (Bytes{0x68, 0x01, 0x00, 0x96, 0x01, 0x00, 0x00, 0x00}));
}

TEST(ParameterExchange, WriteIsEchoedWithStatus0) {
  Loop l;
  const auto& o = l.run(write(1, test::kParamDisp, 14));
  EXPECT_EQ(o.kind, OutcomeKind::done);
  EXPECT_EQ(l.drive.disp, 14U);
  EXPECT_EQ(bytes(l.frames[0]), (Bytes{0x68, 0x01, 0x02, 0x0E, 0x00, 0x00, 0x00, 0x00}));
  EXPECT_EQ(bytes(l.frames[1]), (Bytes{0x68, 0x01, 0x00, 0x0E, 0x00, 0x00, 0x00, 0x00}));
}

TEST(ParameterExchange, RefusalsCarryTheStatusBits) {
  Loop l;
  EXPECT_EQ(l.run(write(1, test::kParamDisp, 5000)).status, kStatusImpermissibleValue);
  EXPECT_EQ(l.run(write(1, test::kParamFixed, 1)).status, kStatusChangeNotPermitted);
  const auto& o = l.run(read(1, 777));
  EXPECT_EQ(o.kind, OutcomeKind::refused);
  EXPECT_EQ(o.status, kStatusUnknownParameter);
  EXPECT_EQ(bytes(l.frames.back()), (Bytes{0x09, 0x03, 0x20, 0x00, 0x00, 0x00, 0x00, 0x00}));
}

TEST(ParameterExchange, SignedAndQ16ValuesTravelAs32BitsIntelOrder) {
  Loop l;
  EXPECT_EQ(l.run(write(1, test::kParamQ16, wire_from_signed(q16_from_double(-20.5)))).kind,
            OutcomeKind::done);
  EXPECT_DOUBLE_EQ(double_from_q16(l.drive.q16), -20.5);
  const auto& o = l.run(read(1, test::kParamSigned));
  EXPECT_EQ(signed_from_wire(o.value), -5);
  EXPECT_EQ(bytes(l.frames.back()), (Bytes{0x15, 0x00, 0x00, 0xFB, 0xFF, 0xFF, 0xFF, 0x00}));
}

TEST(ParameterExchange, DescribeReadsOneItemPerRequest) {
  Loop l;
  EXPECT_EQ(l.run(describe(1, test::kParamDisp, 2)).value, 999U);
  EXPECT_EQ(bytes(l.frames[0]), (Bytes{0x68, 0x01, 0x04, 0x00, 0x00, 0x00, 0x00, 0x02}));
  EXPECT_EQ(l.run(describe(1, test::kParamDisp, 9)).status, kStatusListEnd);
}

TEST(ParameterExchange, UnknownModeIsStatus04) {
  FakeDrive d;
  ParameterServer s(d);
  s.receive({360, 0x33, 0, 0}, Time{0});
  EXPECT_EQ(s.take_reply(Time{0})->code, kStatusUnknownMode);
}

// 4.5.x reading a string: block 0..n-1 carry 4 characters each, the last-but-one holds the 0
// terminator, the last has List_End (10H) and the XOR of the data words before it (D8).
TEST(StringTransfer, ReadHelloByteForByte) {
  Loop l;
  const auto& o = l.run(read_string(1, test::kParamText));
  ASSERT_EQ(o.kind, OutcomeKind::done) << describe(o);
  EXPECT_EQ(o.text.view(), "hello");
  const std::vector<Bytes> expect = {
      {0x07, 0x00, 0x0B, 0x00, 0x00, 0x00, 0x00, 0x00},  // master: ENQ_String, block 0
      {0x07, 0x00, 0x00, 'h', 'e', 'l', 'l', 0x00},      // drive: "hell"
      {0x07, 0x00, 0x0B, 0x00, 0x00, 0x00, 0x00, 0x01},
      {0x07, 0x00, 0x00, 'o', 0x00, 0x00, 0x00, 0x01},   // "o" and the terminator
      {0x07, 0x00, 0x0B, 0x00, 0x00, 0x00, 0x00, 0x02},
      // List_End, checksum 6C6C6568H ^ 0000006FH = 6C6C6507H
      {0x07, 0x00, 0x10, 0x07, 0x65, 0x6C, 0x6C, 0x02},
  };
  ASSERT_EQ(l.frames.size(), expect.size());
  for (std::size_t i = 0; i < expect.size(); ++i) {
    EXPECT_EQ(l.frames[i].id, i % 2 == 0 ? 1103 : 1323);
    EXPECT_EQ(bytes(l.frames[i]), expect[i]) << "frame " << i;
  }
}

// 4.5.x writing a string: block 0 a handshake, blocks 1.. four characters each echoed, then
// List_End with the XOR of the data of blocks 1..n-1.
TEST(StringTransfer, WriteHiByteForByte) {
  Loop l;
  const auto& o = l.run(write_string(1, test::kParamText, "Hi"));
  ASSERT_EQ(o.kind, OutcomeKind::done) << describe(o);
  EXPECT_EQ(l.drive.text_view(), "Hi");
  const std::vector<Bytes> expect = {
      {0x07, 0x00, 0x08, 0x00, 0x00, 0x00, 0x00, 0x00},  // SEL_String, block 0: handshake
      {0x07, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00},
      {0x07, 0x00, 0x08, 'H', 'i', 0x00, 0x00, 0x01},    // "Hi", terminator, padding
      {0x07, 0x00, 0x00, 'H', 'i', 0x00, 0x00, 0x01},    // echoed
      {0x07, 0x00, 0x10, 'H', 'i', 0x00, 0x00, 0x02},    // List_End, checksum 00006948H
      {0x07, 0x00, 0x00, 'H', 'i', 0x00, 0x00, 0x02},
  };
  ASSERT_EQ(l.frames.size(), expect.size());
  for (std::size_t i = 0; i < expect.size(); ++i) EXPECT_EQ(bytes(l.frames[i]), expect[i]) << i;
}

TEST(StringTransfer, BothWaysAtEveryLengthUpTo99) {
  Loop l;
  std::string s;
  for (std::size_t n = 0; n <= kMaxStringChars; ++n) {
    const auto& w = l.run(write_string(1, test::kParamText, s));
    ASSERT_EQ(w.kind, OutcomeKind::done) << n;
    const auto& r = l.run(read_string(1, test::kParamText));
    ASSERT_EQ(r.kind, OutcomeKind::done) << n;
    EXPECT_EQ(r.text.view(), s);
    s.push_back(static_cast<char>('a' + n % 26));
  }
  EXPECT_EQ(l.client.submit(write_string(1, test::kParamText, std::string(100, 'x'))).error,
            SubmitError::text_too_long);
}

TEST(StringTransfer, ReadWithAWrongChecksumIsNeverSuccess) {
  Loop l;
  l.tamper = [](CanFrame& f) {
    if (f.data[2] == kStatusListEnd) f.data[3] ^= 0x01;
  };
  const auto& o = l.run(read_string(1, test::kParamName));
  EXPECT_EQ(o.kind, OutcomeKind::checksum_mismatch);
}

TEST(StringTransfer, ReadOfAReadOnlyStringAndWriteRefused) {
  Loop l;
  EXPECT_EQ(l.run(read_string(1, test::kParamName)).text.view(), "fake drive 1.0");
  const auto& o = l.run(write_string(1, test::kParamName, "x"));
  EXPECT_EQ(o.kind, OutcomeKind::refused);
  EXPECT_EQ(o.status, kStatusChangeNotPermitted);
  EXPECT_EQ(o.telegrams, 1);
}

// A wrong block counter resets the drive's string machine (public-facts; status D11).
TEST(StringServer, WrongBlockCounterResetsWith80) {
  FakeDrive d;
  ParameterServer s(d);
  s.receive({test::kParamText, kModeStringRead, 0, 0}, Time{0});
  EXPECT_EQ(s.take_reply(Time{0})->code, kStatusOk);
  EXPECT_EQ(s.state(), ServerState::string_read);
  s.receive({test::kParamText, kModeStringRead, 0, 2}, Time{0});
  EXPECT_EQ(s.take_reply(Time{0})->code, kStatusImpermissibleValue);
  EXPECT_EQ(s.state(), ServerState::idle);
  s.receive({test::kParamText, kModeStringRead, 0, 1}, Time{0});  // no longer open
  EXPECT_EQ(s.take_reply(Time{0})->code, kStatusImpermissibleValue);
  EXPECT_EQ(s.counters().block_errors, 2U);
}

TEST(StringServer, WriteWithAWrongChecksumIsNotSaved) {
  FakeDrive d;
  ParameterServer s(d);
  s.receive({test::kParamText, kModeStringWrite, 0, 0}, Time{0});
  (void)s.take_reply(Time{0});
  s.receive({test::kParamText, kModeStringWrite, 0x00006948, 1}, Time{0});
  (void)s.take_reply(Time{0});
  s.receive({test::kParamText, kModeListEnd, 0x00006949, 2}, Time{0});
  EXPECT_EQ(s.take_reply(Time{0})->code, kStatusImpermissibleValue);
  EXPECT_EQ(d.text_view(), "hello");
  EXPECT_EQ(s.counters().checksum_errors, 1U);
}

// p. 47: "If the master transmits more than 100 characters for a string the string is not saved
// and the error is entered at the end".
TEST(StringServer, MoreThan100BytesIsRefusedAtTheEnd) {
  FakeDrive d;
  ParameterServer s(d);
  s.receive({test::kParamText, kModeStringWrite, 0, 0}, Time{0});
  (void)s.take_reply(Time{0});
  std::uint32_t sum = 0;
  for (std::uint8_t b = 1; b <= 26; ++b) {  // 104 bytes
    s.receive({test::kParamText, kModeStringWrite, 0x41414141, b}, Time{0});
    const auto r = s.take_reply(Time{0});
    EXPECT_EQ(r->code, kStatusOk);
    EXPECT_EQ(r->data, 0x41414141U);
    sum ^= 0x41414141U;
  }
  s.receive({test::kParamText, kModeListEnd, sum, 27}, Time{0});
  EXPECT_EQ(s.take_reply(Time{0})->code, kStatusImpermissibleValue);
  EXPECT_EQ(d.text_view(), "hello");
  EXPECT_EQ(s.counters().overlong_strings, 1U);
}

TEST(ParameterServerTiming, SlowWriteRepliesAfterTheDrivesDelayAndABusyRequestGetsRepeat) {
  FakeDrive d;
  ParameterServer s(d);
  s.receive({test::kParamSlow, kModeWrite, 1, 0}, Time{0});
  EXPECT_FALSE(s.take_reply(Time{0}));
  EXPECT_EQ(s.next_deadline(), Time{300ms});
  s.receive({test::kParamDisp, kModeRead, 0, 0}, Time{10ms});
  const auto busy = s.take_reply(Time{10ms});
  ASSERT_TRUE(busy);
  EXPECT_EQ(busy->code, kStatusRepeat);
  EXPECT_EQ(busy->parameter, test::kParamDisp);
  EXPECT_FALSE(s.take_reply(Time{299ms}));
  EXPECT_EQ(s.take_reply(Time{300ms})->parameter, test::kParamSlow);
}

TEST(ParameterClientTiming, NoDriveEndsInTimeoutAtTheRequestsTimeout) {
  ParameterClient c;
  auto r = read(5, 1);
  r.timeout = 40ms;
  const auto id = c.submit(r).id;
  c.step(Time{0});
  EXPECT_TRUE(c.take_frame());
  c.step(Time{39ms});
  EXPECT_EQ(c.poll(id).state, RequestState::active);
  EXPECT_EQ(c.next_deadline(), Time{40ms});
  c.step(Time{40ms});
  ASSERT_EQ(c.poll(id).state, RequestState::done);
  EXPECT_EQ(c.poll(id).outcome->kind, OutcomeKind::timeout);
}

TEST(ParameterClientQueue, OneRequestPerDriveAtATimeButDrivesInParallel) {
  ParameterClient c;
  const auto a1 = c.submit(read(1, 1)).id;
  const auto a2 = c.submit(read(1, 2)).id;
  const auto b1 = c.submit(read(2, 1)).id;
  c.step(Time{0});
  EXPECT_EQ(c.poll(a1).state, RequestState::active);
  EXPECT_EQ(c.poll(a2).state, RequestState::queued);
  EXPECT_EQ(c.poll(b1).state, RequestState::active);
  int frames = 0;
  while (c.take_frame()) ++frames;
  EXPECT_EQ(frames, 2);
  // The reply of drive 1 frees it for the next request.
  c.receive(*encode_parameter_reply(IdentifierMap{}, 1, {1, 0, 7, 0}), Time{1ms});
  EXPECT_EQ(c.poll(a1).outcome->value, 7U);
  c.step(Time{1ms});
  EXPECT_EQ(c.poll(a2).state, RequestState::active);
  // A reply for a parameter nobody asked for is ignored.
  c.receive(*encode_parameter_reply(IdentifierMap{}, 1, {99, 0, 7, 0}), Time{2ms});
  EXPECT_EQ(c.counters().stray_replies, 1U);
  c.abort_all(Time{3ms});
  EXPECT_EQ(c.poll(a2).outcome->kind, OutcomeKind::aborted);
  EXPECT_EQ(c.poll(b1).outcome->kind, OutcomeKind::aborted);
}

// The client keeps the drives with a request in a list of its own (issue 26): requests to every
// address at once, answered, timed out and aborted in an order unlike the one they started in,
// each ends exactly once with its own outcome, and the client's deadline and idleness follow.
TEST(ParameterClientQueue, EveryAddressAtOnceEndsEachRequestOnceWhateverTheOrder) {
  ClientConfig cfg;
  cfg.queue_capacity = 128;
  cfg.completed_capacity = 128;
  cfg.outbox_capacity = 128;
  ParameterClient c(cfg);
  const IdentifierMap ids;
  std::vector<RequestId> id(100);
  for (unsigned a = 0; a < 100; ++a) {
    auto r = read(static_cast<Address>(a), static_cast<std::uint16_t>(a + 1));
    r.timeout = std::chrono::milliseconds(10 + (a * 37) % 50);  // deadlines in no address order
    id[a] = c.submit(r).id;
  }
  c.step(Time{0});
  int frames = 0;
  while (c.take_frame()) ++frames;
  EXPECT_EQ(frames, 100);
  // Odd addresses answer, from the highest down; the even ones never do.
  for (unsigned a = 99; a < 100; a -= 2) {
    c.receive(*encode_parameter_reply(ids, static_cast<Address>(a), {static_cast<std::uint16_t>(a + 1), 0, a * 3, 0}), 1ms);
  }
  for (unsigned a = 1; a < 100; a += 2) {
    ASSERT_EQ(c.poll(id[a]).state, RequestState::done) << a;
    EXPECT_EQ(c.poll(id[a]).outcome->value, a * 3) << a;
  }
  // The earliest deadline of the even ones: 10 + (a x 37) % 50 smallest over even a.
  Duration first = Duration::max();
  for (unsigned a = 0; a < 100; a += 2) first = std::min<Duration>(first, std::chrono::milliseconds(10 + (a * 37) % 50));
  EXPECT_EQ(c.next_deadline(), Time{first});
  EXPECT_FALSE(c.idle());
  c.step(Time{35ms});
  for (unsigned a = 0; a < 100; a += 2) {
    const bool due = 10 + (a * 37) % 50 <= 35;
    const Poll p = c.poll(id[a]);
    if (due) {
      ASSERT_EQ(p.state, RequestState::done) << a;
      EXPECT_EQ(p.outcome->kind, OutcomeKind::timeout) << a;
    } else {
      EXPECT_EQ(p.state, RequestState::active) << a;
    }
  }
  c.abort_all(Time{36ms});
  EXPECT_TRUE(c.idle());
  EXPECT_EQ(c.next_deadline(), Time::max());
  for (unsigned a = 0; a < 100; a += 2) {
    const bool due = 10 + (a * 37) % 50 <= 35;
    EXPECT_EQ(c.poll(id[a]).outcome->kind, due ? OutcomeKind::timeout : OutcomeKind::aborted) << a;
  }
  // A slot freed in the middle of the list takes a new request again.
  const auto again = c.submit(read(50, 7)).id;
  c.step(Time{40ms});
  EXPECT_EQ(c.poll(again).state, RequestState::active);
  c.receive(*encode_parameter_reply(ids, 50, {7, 0, 1234, 0}), 41ms);
  EXPECT_EQ(c.poll(again).outcome->value, 1234U);
  EXPECT_TRUE(c.idle());
}

}  // namespace
}  // namespace ibs::canlust
