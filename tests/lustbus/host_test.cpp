// The host client on a simulated line: EOT framing, timeouts, the 85-SIOF read after a NAK on a
// SELECT and the repetitions 9.2 allows, broadcast, address 0, the network scan of 5.2, the baud
// scan of 5.1, the download handshake of 11.4, substitution texts (11.3), the queue.
#include <gtest/gtest.h>

#include "test_support.hpp"

namespace ibs::lustbus {
namespace {

using test::Bus;
using test::Bytes;
using test::FakeDrive;
using test::make_mc6000;
using test::make_vf1000;

// Records who sent what on the line.
struct Recorder {
  std::vector<std::uint8_t> host;
  std::vector<std::uint8_t> devices;
  std::vector<std::uint8_t> all;
  void attach(Line& line) {
    line.set_tap([this](const LineChar& c) {
      (c.node == kHostNode ? host : devices).push_back(c.byte);
      all.push_back(c.byte);
    });
  }
};

TEST(HostFraming, EnquiryIsEotTelegramAnswerEot) {
  auto vf = make_vf1000();
  Bus bus;
  bus.add(vf, 1);
  Recorder rec;
  rec.attach(bus.line);
  const Outcome o = bus.run(enquiry(1, make_code(112)));
  EXPECT_EQ(o.kind, OutcomeKind::value);
  EXPECT_EQ(o.value.view(), "03E8");
  EXPECT_EQ(rec.all, (Bytes{}(kEot)(0x41)("00112")(kEnq)(0x41)(kStx)("00112=03E8")(kEtx)(
                          text_bcc(make_code(112), make_value("03E8")))(kEot).v));
}

TEST(HostFraming, SelectIsEotTelegramAckEot) {
  auto vf = make_vf1000();
  vf.siof = 0;
  Bus bus;
  bus.add(vf, 1);
  Recorder rec;
  rec.attach(bus.line);
  const Outcome o = bus.run(select(1, make_code(105), make_value("03E8")));
  EXPECT_EQ(o.kind, OutcomeKind::acknowledged);
  EXPECT_EQ(rec.host, (Bytes{}(kEot)(0x41)(kStx)("00105=03E8")(kEtx)(0x74)(kEot).v));
  EXPECT_EQ(rec.devices, (Bytes{}(0x41)(kAck).v));
}

// 6.2 note, 9.2: after the NAK, the host reads 85 before anything else and reports the cause.
TEST(HostSiof, NakOnSelectReadsSiofAndReportsTheCause) {
  auto vf = make_vf1000();
  vf.siof = 0;
  Bus bus;
  bus.add(vf, 1);
  Recorder rec;
  rec.attach(bus.line);
  const Outcome o = bus.run(select(1, make_code(105), make_value("FFFF")));  // > max
  EXPECT_EQ(o.kind, OutcomeKind::nak);
  ASSERT_TRUE(o.siof.has_value());
  EXPECT_EQ(*o.siof, 0x80);
  EXPECT_EQ(o.attempts, 1);
  EXPECT_EQ(describe(o), "nak, 85-SIOF 80H: invalid value");
  EXPECT_EQ(rec.host, (Bytes{}(kEot)(0x41)(kStx)("00105=FFFF")(kEtx)(
                          text_bcc(make_code(105), make_value("FFFF")))(kEot)(kEot)(0x41)("00085")(
                          kEnq)(kEot).v));
  EXPECT_EQ(vf.siof, 0);  // the read cleared it: further SELECTs are possible
  EXPECT_EQ(bus.run(select(1, make_code(105), make_value("03E8"))).kind, OutcomeKind::acknowledged);
}

TEST(HostSiof, NoChangeAndNoParameterAreReportedNotRepeated) {
  auto vf = make_vf1000();
  vf.siof = 0;
  Bus bus;
  bus.add(vf, 1);
  Outcome o = bus.run(select(1, make_code(112), make_value("0001")));  // actual value
  EXPECT_EQ(o.kind, OutcomeKind::nak);
  EXPECT_EQ(o.siof, 0x40);
  o = bus.run(select(1, make_code(140), make_value("0001")));
  EXPECT_EQ(o.kind, OutcomeKind::nak);
  EXPECT_EQ(o.siof, 0x20);
  EXPECT_EQ(o.attempts, 1);
}

// 6 / 8.1: after power-on the latch refuses; the read clears it and the SELECT may go again.
TEST(HostSiof, PowerOnRefusalIsRepeatedAfterTheRead) {
  auto vf = make_vf1000();  // siof = 01H
  Bus bus;
  bus.add(vf, 1);
  const Outcome o = bus.run(select(1, make_code(105), make_value("03E8")));
  EXPECT_EQ(o.kind, OutcomeKind::acknowledged);
  EXPECT_EQ(o.attempts, 2);
  EXPECT_EQ(vf.value_of(5), 0x3E8U);
}

// 3, 9.2: EEPROM busy -> wait (> 60 ms) and repeat.
TEST(HostSiof, EepromBusyIsRepeatedAfterTheWait) {
  auto mc = make_mc6000();
  mc.siof = 0;
  mc.mc_eeprom_per_byte = 40ms;  // 4 bytes: busy for 160 ms
  HostConfig cfg;
  cfg.select_retries = 5;
  Bus bus(cfg);
  bus.add(mc, 4);
  ASSERT_EQ(bus.run(select(4, make_code(20500), make_value("1"))).kind, OutcomeKind::acknowledged);
  const Outcome o = bus.run(select(4, make_code(20500), make_value("2")));
  EXPECT_EQ(o.kind, OutcomeKind::acknowledged);
  EXPECT_GE(o.attempts, 2);
  EXPECT_EQ(mc.value_of(500), 2U);
  EXPECT_GE(o.finished - o.started, cfg.eeprom_busy_wait);
}

// 10.2.2's example, row by row: "Minimum telegram duration time = 22 ms" (10.1.2, example 2, the
// servo's minimum: the host's 19 bytes 16 ms, reaction 1 ms, the answer's 2 bytes 2 ms, the host's
// reaction 2 ms, its EOT 1 ms), "memory time is: 4 bytes · 3 · 5 ms/byte = 60 ms", "wait time =
// memory time - telegram duration time = 60 ms - 22 ms = 38 ms". The host is driven with the
// table's own times (its 8-bit characters, LB-E10): the second EEPROM SELECT goes out 38 ms after
// the first sequence's EOT, 60 ms after its first byte, and is acknowledged at once (no 04H, no
// repetition after it).
TEST(Timing1022, TheHostWaitsTheWaitTimeOfTheExampleBeforeTheNextEepromSelect) {
  HostConfig cfg;
  cfg.turnaround = 2ms;  // 10.1: "Reaction time of the Host computer e.g., 2 ms"
  Host host(cfg);
  Request first = select(1, make_code(20409), make_value("0000EA60"));  // 4 bytes (8 characters)
  first.eeprom_width = 4;
  Request second = first;
  second.value = make_value("0000EA61");
  const auto id1 = host.submit(first).id;
  const auto id2 = host.submit(second).id;
  const Time t0{0};
  host.step(t0);
  EXPECT_EQ(host.take_output().size(), 19U);  // "Host computer sends telegram 19 Byte"
  host.output_done(t0 + 16ms);                // "... / 9600 bps = 16 ms"
  host.receive(0x41, t0 + 17ms);              // "Reaction time of the servocontroller Min. 1 ms"
  host.receive(kAck, t0 + 19ms);              // "Servocontroller answer 2 Byte ... = 2 ms"
  host.step(t0 + 21ms);                       // "Reaction time of the Host computer e.g., 2 ms"
  EXPECT_EQ(host.take_output().size(), 1U);   // EOT
  host.output_done(t0 + 22ms);                // "Host computer sends EOT 1 ... = 1 ms": total 22 ms
  ASSERT_NE(host.outcome(id1), nullptr);
  EXPECT_EQ(host.outcome(id1)->kind, OutcomeKind::acknowledged);
  EXPECT_EQ(host.outcome(id1)->finished, t0 + 22ms);
  // "wait time = 60 ms - 22 ms = 38 ms": nothing on the line until then.
  host.step(t0 + 22ms);
  EXPECT_TRUE(host.take_output().empty());
  EXPECT_EQ(host.next_deadline(), t0 + 60ms);
  host.step(t0 + 59ms);
  EXPECT_TRUE(host.take_output().empty());
  host.step(t0 + 60ms);
  EXPECT_EQ(host.take_output().size(), 19U);
  host.output_done(t0 + 76ms);
  host.receive(0x41, t0 + 77ms);
  host.receive(kAck, t0 + 79ms);
  host.step(t0 + 81ms);
  EXPECT_EQ(host.take_output().size(), 1U);
  host.output_done(t0 + 82ms);
  const Outcome* o = host.outcome(id2);
  ASSERT_NE(o, nullptr);
  EXPECT_EQ(o->kind, OutcomeKind::acknowledged);
  EXPECT_EQ(o->attempts, 1);
  EXPECT_EQ(o->eeprom_wait, 38ms);
  EXPECT_EQ(eeprom_wait(4, cfg.eeprom_write_time, 22ms), 38ms);  // the formula of 10.2.2
}

// 10.2.2: "For ENQUIRY-telegrams and SELECT-telegrams to RAM parameters, no wait time is
// necessary", and the wait is the device's: another address, an ENQUIRY or a RAM SELECT go out at
// once; a SELECT after the memory time has passed waits nothing.
TEST(Timing1022, OnlyAnEepromSelectToTheSavingDeviceWaits) {
  auto mc = make_mc6000();
  mc.siof = 0;
  mc.mc_eeprom_per_byte = 15ms;  // LUSTBUS manual 3: 15 ms a byte
  auto other = make_mc6000();
  other.siof = 0;
  other.mc_eeprom_per_byte = 15ms;
  Bus bus;
  bus.add(mc, 4);
  bus.add(other, 5);
  Request eeprom = select(4, make_code(20500), make_value("1"));
  eeprom.eeprom_width = 4;
  ASSERT_EQ(bus.run(eeprom).kind, OutcomeKind::acknowledged);
  Request elsewhere = eeprom;
  elsewhere.address = 5;
  const Outcome o5 = bus.run(elsewhere);
  EXPECT_EQ(o5.kind, OutcomeKind::acknowledged);
  EXPECT_EQ(o5.eeprom_wait, Duration{0});
  const Outcome ram = bus.run(select(4, make_code(20500), make_value("3")));  // eeprom_width 0
  EXPECT_EQ(ram.eeprom_wait, Duration{0});
  bus.line.run_until(bus.line.now() + 100ms);
  const Outcome later = bus.run(eeprom);
  EXPECT_EQ(later.kind, OutcomeKind::acknowledged);
  EXPECT_EQ(later.eeprom_wait, Duration{0});
  EXPECT_EQ(later.attempts, 1);
}

// 10.2.2 against a servo that saves 15 ms a byte (3): EEPROM SELECTs in series each wait the
// computed time and are acknowledged at the first attempt; without the wait the second one meets
// "EEPROM busy" (04H) and is only repeated after 9.2's "> 60 ms" -- the host keeps that repetition
// for a drive slower than the manual.
TEST(Timing1022, EepromSelectsInSeriesAreNeverRefusedAsBusy) {
  for (const bool declared : {true, false}) {
    auto mc = make_mc6000();
    mc.siof = 0;
    mc.mc_eeprom_per_byte = 15ms;
    Bus bus;
    bus.add(mc, 4);
    for (int i = 1; i <= 3; ++i) {
      Request r = select(4, make_code(20500), make_value(std::to_string(i)));
      r.eeprom_width = declared ? 4 : 0;
      const Outcome o = bus.run(r);
      ASSERT_EQ(o.kind, OutcomeKind::acknowledged) << i;
      if (declared) {
        EXPECT_EQ(o.attempts, 1) << i;
        if (i > 1) {
          EXPECT_GT(o.eeprom_wait, Duration{0}) << i;
        }
      } else if (i > 1) {
        EXPECT_EQ(o.attempts, 2) << "undeclared, the servo refuses with 04H first: " << i;
      }
    }
    EXPECT_EQ(mc.value_of(500), 3U);
  }
}

// 9.2 bit 3: a SELECT corrupted on the way is refused with a checksum error and repeated.
TEST(HostSiof, ChecksumErrorIsRepeated) {
  auto vf = make_vf1000();
  vf.siof = 0;
  Bus bus;
  bus.add(vf, 1);
  int seen = 0;
  bus.line.set_filter([&seen](const LineChar& c) -> std::optional<std::uint8_t> {
    // The first SELECT's first VALUE character '0' arrives as '1' (a parity error would be a
    // framing error; this one the parity did not catch).
    if (c.node == kHostNode && c.byte == '=' ) ++seen;
    if (c.node == kHostNode && seen == 1 && c.byte == '0') {
      ++seen;
      return '1';
    }
    return c.byte;
  });
  const Outcome o = bus.run(select(1, make_code(105), make_value("03E8")));
  EXPECT_EQ(o.kind, OutcomeKind::acknowledged);
  EXPECT_EQ(o.attempts, 2);
  EXPECT_EQ(o.siof, 0x08);
  EXPECT_EQ(vf.checksum_errors, 1);
  EXPECT_EQ(vf.value_of(5), 0x3E8U);
}

TEST(HostTimeouts, NoDeviceMeansNoAnswerAfterTheResponseTimeout) {
  HostConfig cfg;
  cfg.response_timeout = 50ms;
  cfg.enquiry_retries = 2;
  Bus bus(cfg);
  Recorder rec;
  rec.attach(bus.line);
  Outcome o = bus.run(enquiry(7, make_code(112)));
  EXPECT_EQ(o.kind, OutcomeKind::no_answer);
  EXPECT_EQ(o.answer_error, AnswerError::no_answer);
  EXPECT_EQ(o.attempts, 3);
  // Three times: 8 characters, 50 ms, EOT.
  const Duration one = 9 * character_time(9600) + 50ms;
  EXPECT_EQ(o.finished - o.started, 3 * one);
  EXPECT_EQ(rec.host.size(), 27U);
  // A SELECT is not repeated after no answer (the device may have taken it).
  o = bus.run(select(7, make_code(105), make_value("03E8")));
  EXPECT_EQ(o.kind, OutcomeKind::no_answer);
  EXPECT_EQ(o.attempts, 1);
}

TEST(HostTimeouts, InterCharacterTimeoutEndsAnIncompleteAnswer) {
  auto vf = make_vf1000();
  HostConfig cfg;
  cfg.inter_char_timeout = 5ms;
  Bus bus(cfg);
  bus.add(vf, 1);
  int answer_bytes = 0;
  bus.line.set_filter([&answer_bytes](const LineChar& c) -> std::optional<std::uint8_t> {
    if (c.node != kHostNode && ++answer_bytes > 5 && answer_bytes <= 14) return std::nullopt;
    return c.byte;
  });
  const Outcome o = bus.run(enquiry(1, make_code(112)));
  EXPECT_EQ(o.kind, OutcomeKind::value);  // a repetition got through
  // The lost characters still occupied the line: the host's EOT after 5 ms of silence may
  // collide with them, and the device then misses the next EOT too.
  EXPECT_GE(o.attempts, 2);
  EXPECT_EQ(o.value.view(), "03E8");
}

// Issue 23, defect 7 (LB-D24): against a device that answers with an endless trickle of
// characters (each restarting the inter-character timer) `ibs lustbus read` did not end. Each
// exchange ends by its overall deadline, and the outcome says why.
TEST(HostTimeouts, ADeviceThatKeepsSendingEndsEachExchangeAtItsLimit) {
  HostConfig cfg;
  cfg.response_timeout = 100ms;
  const Duration limit = cfg.exchange_limit(cfg.response_timeout);
  EXPECT_EQ(limit, 100ms + 111 * 20ms) << "the response time and the longest telegram, character by character";
  for (const std::uint8_t babble : {std::uint8_t{'A'}, std::uint8_t{'0'}}) {  // broken at once, or a long ADR...
    Host h(cfg);
    const Submitted sub = h.submit(enquiry(1, make_code(112)));
    ASSERT_TRUE(sub);
    const RequestId id = sub.id;
    Time now{0};
    Time exchange_start{0};
    int exchanges = 0;
    while (!h.idle() && now < 60s) {
      h.step(now);
      if (!h.take_output().empty()) {
        h.output_done(now);
        if (h.state() == HostState::awaiting) {
          ++exchanges;
          exchange_start = now;
        }
      }
      if (h.state() == HostState::awaiting || h.state() == HostState::receiving || h.state() == HostState::draining) {
        h.receive(babble, now);
        EXPECT_LE(now - exchange_start, limit) << "an exchange past its limit";
      }
      now += 5ms;
    }
    ASSERT_TRUE(h.idle()) << "still busy after 60 s";
    const Outcome* o = h.outcome(id);
    ASSERT_NE(o, nullptr);
    EXPECT_EQ(o->kind, OutcomeKind::bad_answer);
    EXPECT_EQ(o->answer_error, AnswerError::line_busy);
    EXPECT_EQ(to_string(o->answer_error), "the line never fell quiet");
    EXPECT_EQ(exchanges, 1 + cfg.enquiry_retries);
    EXPECT_LE(now, (1 + cfg.enquiry_retries) * (limit + 10ms));
  }
}

TEST(HostTimeouts, SiofIsNotReadTwice) {
  auto vf = make_vf1000();
  vf.siof = 0x80;
  Bus bus;
  bus.add(vf, 1);
  int answer_bytes = 0;
  bus.line.set_filter([&answer_bytes](const LineChar& c) -> std::optional<std::uint8_t> {
    if (c.node != kHostNode && ++answer_bytes == 8) return kGarbled;
    return c.byte;
  });
  const Outcome o = bus.run(enquiry(1, kSiofCode));
  EXPECT_EQ(o.kind, OutcomeKind::bad_answer);  // the bits are gone: reading again shows 00
  EXPECT_EQ(o.attempts, 1);
  EXPECT_EQ(vf.siof, 0);
}

// 10, exception 4: a VF1000 answers an EEPROM write only when the value is stored.
TEST(HostTimeouts, DelayedEepromAckAndATimeoutThatDoesNotUndoTheWrite) {
  auto vf = make_vf1000(1ms);
  vf.siof = 0;
  Bus bus;
  bus.add(vf, 1);
  Outcome o = bus.run(select(1, make_code(122), make_value("0190")));
  EXPECT_EQ(o.kind, OutcomeKind::acknowledged);
  EXPECT_GT(o.finished - o.started, 120ms);
  Request r = select(1, make_code(122), make_value("01F4"));
  r.response_timeout = 50ms;
  o = bus.run(r);
  EXPECT_EQ(o.kind, OutcomeKind::no_answer);  // the host's EOT came before the ACK
  EXPECT_EQ(vf.value_of(22), 0x1F4U);         // the drive took it whole all the same
}

TEST(HostBroadcast, EveryDeviceTakesItNoneAnswers) {
  auto a = make_vf1000();
  auto b = make_mc6000();
  a.siof = 0;
  b.siof = 0;
  Bus bus;
  bus.add(a, 1);
  bus.add(b, 2);
  Recorder rec;
  rec.attach(bus.line);
  const Outcome o = bus.run(broadcast(shared_code(kParamDummy), make_value("0042")));
  EXPECT_EQ(o.kind, OutcomeKind::sent);
  EXPECT_TRUE(rec.devices.empty());
  EXPECT_EQ(rec.host.front(), kEot);
  EXPECT_EQ(rec.host[1], 0x5F);
  EXPECT_EQ(rec.host.back(), kEot);
  EXPECT_EQ(a.value_of(83), 0x42U);
  EXPECT_EQ(b.value_of(83), 0x42U);
  EXPECT_EQ(bus.host.submit(enquiry(31, kTypeCode)).error, SubmitError::invalid_address);
}

TEST(HostAddressZero, StandAloneDeviceAnswersOnZero) {
  auto vf = make_vf1000();
  Bus bus;
  bus.add(vf, 17);
  const Outcome o = bus.run(enquiry(0, kTypeCode));
  EXPECT_EQ(o.kind, OutcomeKind::value);
  EXPECT_EQ(o.value.view(), "03E8");
}

// 9.1: on a bus of several, every device answers address 0 at once: no valid answer.
TEST(HostAddressZero, SeveralDevicesGarbleEachOther) {
  auto a = make_vf1000(2ms);
  auto b = make_vf1000(2ms);
  HostConfig cfg;
  cfg.enquiry_retries = 0;
  Bus bus(cfg);
  bus.add(a, 1);
  bus.add(b, 2);
  const Outcome o = bus.run(enquiry(0, kTypeCode));
  EXPECT_EQ(o.kind, OutcomeKind::bad_answer);
  EXPECT_EQ(o.answer_error, AnswerError::garbled);
  EXPECT_GT(bus.line.stats().collisions, 0U);
}

TEST(HostScan, FindsInvertersAndServosOnOneToThirty) {
  auto vf = make_vf1000();
  auto mc = make_mc6000();
  HostConfig cfg;
  cfg.scan_response_timeout = 40ms;
  Bus bus(cfg);
  bus.add(vf, 3);
  bus.add(mc, 30);
  Recorder rec;
  rec.attach(bus.line);
  const Outcome o = bus.run(network_scan());
  ASSERT_EQ(o.kind, OutcomeKind::scan);
  ASSERT_EQ(o.scan.count, 2);
  EXPECT_EQ(o.scan.devices[0].address, 3);
  EXPECT_EQ(o.scan.devices[0].family, Family::standard);
  EXPECT_EQ(o.scan.devices[0].type, 1000U);
  EXPECT_EQ(o.scan.devices[1].address, 30);
  EXPECT_EQ(o.scan.devices[1].family, Family::enhanced);
  EXPECT_EQ(o.scan.devices[1].type, 6000U);
  // 30 TYPE enquiries + 2 probes, each framed by EOT ... EOT.
  std::size_t enqs = 0;
  for (const auto b : rec.host) enqs += b == kEnq ? 1U : 0U;
  EXPECT_EQ(enqs, 32U);
}

TEST(HostBaudScan, TriesTheFactoryRateFirstThenEveryOther) {
  auto mc = make_mc6000();
  HostConfig cfg;
  cfg.response_timeout = 40ms;
  cfg.enquiry_retries = 0;
  Bus bus(cfg);
  const int dev = bus.line.attach(*bus.receivers.emplace_back(std::make_unique<Receiver>(mc, 1)));
  bus.line.set_device_baud(dev, 38400);
  BaudScan scan;
  std::vector<std::uint32_t> tried;
  while (const auto rate = scan.current()) {
    tried.push_back(*rate);
    bus.line.set_baud(*rate);
    scan.report(bus.run(scan.request()));
  }
  EXPECT_EQ(scan.found(), 38400U);
  EXPECT_EQ(tried, (std::vector<std::uint32_t>{9600, 19200, 38400}));
  BaudScan none(std::span<const std::uint32_t>(kBaudScanOrder).first(2));
  bus.line.set_baud(9600);
  while (none.current()) none.report(bus.run(none.request()));
  EXPECT_FALSE(none.found());
  EXPECT_TRUE(none.finished());
}

TEST(HostDownload, HandshakeOf114AsOneRequest) {
  auto mc = make_mc6000();
  mc.mc_eeprom_per_byte = 0ms;
  Bus bus;
  bus.add(mc, 5);
  const std::vector<Assignment> records = {{make_code(20300), make_value("2")},
                                           {make_code(20428), make_value("842666")},
                                           {make_code(20402), make_value("2")}};
  const auto procedures = mc.procedures();
  const Outcome o = bus.run(download(*procedures.download, 5, records));
  EXPECT_EQ(o.kind, OutcomeKind::downloaded) << describe(o);
  EXPECT_EQ(mc.value_of(300), 2U);
  EXPECT_EQ(mc.value_of(428), 0x842666U);
  EXPECT_EQ(mc.value_of(80), 0U);
  EXPECT_GE(o.finished - o.started, 300ms);  // the fake tests for 300 ms
}

TEST(HostDownload, RejectedDatasetNamesTheFirstInvalidParameter) {
  auto mc = make_mc6000();
  mc.siof = 0;
  Bus bus;
  bus.add(mc, 5);
  const std::vector<Assignment> records = {{make_code(20428), make_value("7FFFFFFF")}};
  const auto procedures = mc.procedures();
  const Outcome o = bus.run(download(*procedures.download, 5, records));
  EXPECT_EQ(o.kind, OutcomeKind::download_rejected);
  EXPECT_EQ(o.rejected_parameter, 428U);
}

TEST(HostDownload, RefusedRecordEndsTheDownloadWithItsStepAndCause) {
  auto mc = make_mc6000();
  mc.siof = 0;
  Bus bus;
  bus.add(mc, 5);
  const std::vector<Assignment> records = {{make_code(20300), make_value("2")},
                                           {make_code(20077), make_value("1")}};  // read-only
  const auto procedures = mc.procedures();
  const Outcome o = bus.run(download(*procedures.download, 5, records));
  EXPECT_EQ(o.kind, OutcomeKind::download_refused);
  EXPECT_EQ(o.failed_step, 1);
  EXPECT_EQ(o.siof, 0x40);
}

TEST(HostDownload, TimesOutWhenSloadStaysBusy) {
  auto mc = make_mc6000();
  mc.siof = 0;
  mc.download_never_ready = true;
  HostConfig cfg;
  cfg.download_timeout = 1s;
  Bus bus(cfg);
  bus.add(mc, 5);
  const std::vector<Assignment> records = {{make_code(20300), make_value("2")}};
  const auto procedures = mc.procedures();
  const Outcome o = bus.run(download(*procedures.download, 5, records));
  EXPECT_EQ(o.kind, OutcomeKind::download_timeout);
  EXPECT_GE(o.finished - o.started, 1s);
}

TEST(HostSubstitutionText, Steps113AsOneRequest) {
  auto mc = make_mc6000();
  mc.siof = 0;
  Bus bus;
  bus.add(mc, 2);
  const auto texts = *mc.procedures().indexed_text;
  Outcome o = bus.run(indexed_text_request(texts, 2, 300, 2));
  EXPECT_EQ(o.kind, OutcomeKind::value);
  EXPECT_EQ(substitution_text(o.value.view()), "SCON");
  o = bus.run(indexed_text_request(texts, 2, 300, 5));  // beyond the texts: NAK
  EXPECT_EQ(o.kind, OutcomeKind::nak);
  o = bus.run(indexed_text_request(texts, 2, 416, 0));  // no texts
  EXPECT_EQ(o.kind, OutcomeKind::nak);
  // 2.4.2's text CODE carries parameters up to 999.
  EXPECT_EQ(bus.host.submit(indexed_text_request(texts, 2, 1000, 0)).error,
            SubmitError::invalid_request);
}

// The host knows no device's parameter numbers: the procedures run through the parameters the
// device's description names (here a servo whose handshake is 79 and whose index is 416).
TEST(HostProcedures, RunThroughTheParametersTheDescriptionNames) {
  auto mc = make_mc6000();
  mc.mc_eeprom_per_byte = 0ms;
  mc.siof = 0;
  mc.params.push_back({79, DataType::integer16, 0, 0xFFFE, 999, true, false, "HSHK"});
  mc.handshake_parameter = 79;
  mc.text_index_parameter = 416;
  Bus bus;
  bus.add(mc, 5);
  const auto procedures = mc.procedures();
  const std::vector<Assignment> records = {{make_code(20300), make_value("2")}};
  const Outcome o = bus.run(download(*procedures.download, 5, records));
  EXPECT_EQ(o.kind, OutcomeKind::downloaded) << describe(o);
  EXPECT_EQ(mc.value_of(300), 2U);
  EXPECT_EQ(mc.value_of(79), 0U);
  EXPECT_EQ(mc.value_of(80), 0U);  // untouched: SLOAD is no handshake here
  EXPECT_EQ(bus.run(indexed_text_request(*procedures.indexed_text, 5, 300, 0)).value.view(),
            "TCON");
  EXPECT_EQ(mc.value_of(416), 0U);
  EXPECT_EQ(bus.run(indexed_text_request(*procedures.indexed_text, 5, 300, 1)).value.view(),
            "VFCON");
  EXPECT_EQ(mc.value_of(416), 1U);
}

// A request without the description its procedure needs, or one whose parameter the family's
// CODEs cannot carry, is refused before a byte goes out.
TEST(HostProcedures, RefusedWithoutADescriptionTheFamilyCanCarry) {
  Host host;
  Request r = download(DownloadProcedure{}, 1, {});
  r.download = nullptr;
  EXPECT_EQ(host.submit(r).error, SubmitError::invalid_request);
  const DownloadProcedure too_high{Family::standard, 100, -1, -2};  // 2.4.1: 00..99
  EXPECT_EQ(host.submit(download(too_high, 1, {})).error, SubmitError::invalid_request);
  const IndexedTextProcedure standard_texts{Family::standard, 5};  // 2.4.1 has no text CODEs
  EXPECT_EQ(host.submit(indexed_text_request(standard_texts, 1, 5, 0)).error,
            SubmitError::invalid_request);
  EXPECT_FALSE(text_code(Family::standard, 5));
  EXPECT_EQ(text_code(Family::enhanced, 300)->text(), "61300");
}

TEST(HostDescriptions, ParsedFromBothFamilies) {
  auto vf = make_vf1000();
  auto mc = make_mc6000();
  Bus bus;
  bus.add(vf, 1);
  bus.add(mc, 2);
  Outcome o = bus.run(enquiry(1, *vf_code(22, VfSpecifier::description)));
  ASSERT_EQ(o.kind, OutcomeKind::value);
  const auto d = parse_vf_description(o.value.view());
  ASSERT_TRUE(d.ok()) << to_string(d.error);
  EXPECT_EQ(d.value.name_view(), "FMAX1");
  EXPECT_EQ(d.value.unit_view(), "Hz");
  EXPECT_EQ(d.value.basis, 1000);
  o = bus.run(enquiry(2, *mc_code(McCodeKind::description, 300)));
  ASSERT_EQ(o.kind, OutcomeKind::value);
  const auto m = parse_mc_description(o.value.view());
  ASSERT_TRUE(m.ok()) << to_string(m.error);
  EXPECT_EQ(m.value.name_view(), "CFCON");
  EXPECT_EQ(m.value.kind, '2');
  EXPECT_EQ(m.value.attribute, kAttrShowText);
}

TEST(HostQueue, OneTransactionAtATimeInOrder) {
  auto vf = make_vf1000();
  HostConfig cfg;
  cfg.queue_capacity = 3;
  Bus bus(cfg);
  bus.add(vf, 1);
  const auto a = bus.host.submit(enquiry(1, make_code(112)));
  const auto b = bus.host.submit(enquiry(1, kTypeCode));
  const auto c = bus.host.submit(enquiry(1, make_code(199)));
  EXPECT_EQ(bus.host.submit(enquiry(1, kTypeCode)).error, SubmitError::queue_full);
  EXPECT_EQ(bus.host.poll(a.id).state, RequestState::queued);
  bus.line.run_until(bus.line.now() + 1ms);
  EXPECT_EQ(bus.host.poll(a.id).state, RequestState::active);
  EXPECT_EQ(bus.host.poll(b.id).state, RequestState::queued);
  ASSERT_TRUE(bus.line.run_until_idle(bus.line.now() + 10s));
  EXPECT_EQ(bus.host.poll(a.id).outcome->value.view(), "03E8");
  EXPECT_EQ(bus.host.poll(b.id).outcome->value.view(), "03E8");  // TYPE 1000
  EXPECT_EQ(bus.host.poll(c.id).outcome->kind, OutcomeKind::nak);
  EXPECT_LT(bus.host.poll(a.id).outcome->finished, bus.host.poll(b.id).outcome->started + 1ns);
  EXPECT_EQ(bus.host.poll(12345).state, RequestState::unknown);
}

TEST(HostQueue, RestartAbortsAndSendsEot) {
  auto vf = make_vf1000(50ms);
  Bus bus;
  bus.add(vf, 1);
  const auto a = bus.host.submit(enquiry(1, make_code(112)));
  const auto b = bus.host.submit(enquiry(1, make_code(112)));
  bus.line.run_until(bus.line.now() + 20ms);
  bus.host.restart(bus.line.now());
  ASSERT_TRUE(bus.line.run_until_idle(bus.line.now() + 1s));
  EXPECT_EQ(bus.host.poll(a.id).outcome->kind, OutcomeKind::aborted);
  EXPECT_EQ(bus.host.poll(b.id).outcome->kind, OutcomeKind::aborted);
  EXPECT_EQ(bus.run(enquiry(1, make_code(112))).kind, OutcomeKind::value);
}

// 2.4.1 / 2.4.2, 11.1 / 11.2: the CODE of a parameter's value and description in each family.
TEST(HostCodes, ParameterCodeOfEitherFamily) {
  EXPECT_EQ(parameter_code(Family::standard, 5), make_code(105));                // 0 0 1 05
  EXPECT_EQ(parameter_code(Family::standard, 5, true), make_code(10105));        // 1 0 1 05
  EXPECT_EQ(parameter_code(Family::enhanced, 77), make_code(20077));             // 2 0 077
  EXPECT_EQ(parameter_code(Family::enhanced, 416, true), make_code(30416));      // 3 0 416
  EXPECT_FALSE(parameter_code(Family::standard, 100));  // two digits only
  EXPECT_FALSE(parameter_code(Family::enhanced, 1000));
  EXPECT_EQ(device_kind(Family::standard), "inverter");
  EXPECT_EQ(device_kind(Family::enhanced), "servo");
}

}  // namespace
}  // namespace ibs::lustbus
