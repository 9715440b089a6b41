// The emulated CDA3000 on the virtual bus against the core's master, byte for byte where seed
// 003 prints the bytes: the DRIVECOM start of 7.1.2, the reference 20.5 Hz = 00 80 14 00, the
// parameter examples of 7.1.3 (CDA 1 on 663 / 883 / 1103 / 1323), string transfers both ways
// with their checksum; the watchdog's reactions, flash and mains reset, 04-PROG, the logon.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "bus.hpp"
#include "ibs/canlust/errors.hpp"
#include "ibs/devices/cda3000/description.hpp"
#include "ibs/devices/cda3000/descriptor.hpp"

namespace ibs::devices::cda3000 {
namespace {

using namespace ibs::canlust;
using test::Bus;
using test::commissioned;
using Bytes = std::vector<std::uint8_t>;

Bytes bytes(const CanFrame& f) { return {f.data.begin(), f.data.begin() + f.dlc}; }

// The status words on `id` from `from` on, each once (the repeats of the cyclic status dropped).
std::vector<ibs::Word> status_words(const Bus<Master>& b, std::uint16_t id, Time from = Time::min()) {
  std::vector<ibs::Word> v;
  for (const auto& s : b.seen_with_id(id, from)) {
    const auto w = static_cast<ibs::Word>(s.frame.data[0] | (s.frame.data[1] << 8U));
    if (v.empty() || v.back() != w) v.push_back(w);
  }
  return v;
}

const Outcome& finish(Bus<Master>& b, Master& m, const Request& r) {
  const auto id = m.parameters().submit(r).id;
  EXPECT_NE(id, 0U);
  b.run_until_true([&] { return m.parameters().poll(id).state == RequestState::done; }, 5s);
  static const Outcome none{};
  const auto p = m.parameters().poll(id);
  return p.outcome != nullptr ? *p.outcome : none;
}

// 5.2: logon 1543 + 2 x address every 100 ms until System Start (D1, D14).
TEST(Cda3000Node, LogonEvery100MsUntilSystemStart) {
  Master m;
  Bus<Master> b(m);
  b.add(commissioned(1));
  b.run_until(Time{550ms});
  const auto logons = b.seen_with_id(1545);
  ASSERT_EQ(logons.size(), 6U);
  for (std::size_t i = 0; i < logons.size(); ++i) {
    EXPECT_EQ(logons[i].start, Time{std::chrono::milliseconds(100 * i)});
    EXPECT_EQ(logons[i].frame.dlc, 0);
  }
  EXPECT_TRUE(b.seen_with_id(883).empty());
  m.system_start();
  b.run_until(Time{1000ms});
  EXPECT_EQ(b.seen_with_id(1545).size(), 6U);
  EXPECT_EQ(b.drive(0).system_state(), SystemState::start);
  EXPECT_FALSE(b.seen_with_id(883).empty());
}

// 7.1.2, DRIVECOM (CACNF 2): control 0000 -> status 0240, 0006 -> 0231, 000F -> 0237 on 663 /
// 883, the reference 10.0 (00 00 0A 00) with the control word; sent with the nominal DLC 6.
TEST(Cda3000Drivecom, StartOf712ByteForByte) {
  Master m;
  Bus<Master> b(m);
  b.add(commissioned(1));
  b.run_until(Time{50ms});
  m.system_start();
  b.run_for(100ms);
  const ibs::Word words[] = {0x0000, 0x0006, 0x000F};
  for (const auto w : words) {
    m.send_control(1, {w, q16_from_double(10.0)});
    b.run_for(100ms);
  }
  const auto controls = b.seen_with_id(663);
  ASSERT_EQ(controls.size(), 3U);
  EXPECT_EQ(bytes(controls[0].frame), (Bytes{0x00, 0x00, 0x00, 0x00, 0x0A, 0x00}));
  EXPECT_EQ(bytes(controls[1].frame), (Bytes{0x06, 0x00, 0x00, 0x00, 0x0A, 0x00}));
  EXPECT_EQ(bytes(controls[2].frame), (Bytes{0x0F, 0x00, 0x00, 0x00, 0x0A, 0x00}));
  // 7.1.2: "40 02 00 00 ..." - START-UP INHIBIT with the remote bit, actual 0.
  const auto st = b.seen_with_id(883);
  ASSERT_FALSE(st.empty());
  EXPECT_EQ(bytes(st.front().frame), (Bytes{0x40, 0x02, 0x00, 0x00, 0x00, 0x00}));
  EXPECT_EQ(status_words(b, 883), (std::vector<ibs::Word>{0x0240, 0x0231, 0x0237}));
  EXPECT_EQ(b.drive(0).state(), drivecom::State::enabled);
  EXPECT_GT(b.drive(0).actual_hz(b.now()), 3.0);  // on its way to 10 Hz
}

// CAN-E9: the ENABLE OPERATION row of 5.4.2 prints x1xx 0111 (bit 6 set) beside the value 37H;
// the drive sends 37H (bit 6 clear, bit 5 set) as DRIVECOM and 7.1.2 have it.
TEST(Cda3000Drivecom, EnabledIs37HNotTheX1xx0111OfTheStateTable) {
  Master m;
  Bus<Master> b(m);
  b.add(commissioned(1));
  m.system_start();
  b.run_for(10ms);
  m.send_control(1, {0x0006, 0});
  b.run_for(100ms);
  m.send_control(1, {0x000F, 0});
  b.run_for(100ms);
  const ibs::Word w = b.drive(0).status_word();
  EXPECT_EQ(w & 0x7FU, 0x37U);
  EXPECT_FALSE(bit(w, 6));
  EXPECT_EQ(drivecom::decode_state(w), drivecom::State::enabled);
  EXPECT_NE(drivecom::decode_state(0x0047), drivecom::State::enabled);  // x1xx 0111 is not ENABLED
}

// 5.5.5: the reference 20.5 Hz = 00 80 14 00; the plant reaches it, status bit 10 then set.
TEST(Cda3000Drivecom, Reference20Point5HzIs00801400AndIsReached) {
  Master m;
  Bus<Master> b(m);
  b.add(commissioned(1));
  m.system_start();
  b.run_for(10ms);
  const auto ref = *wire_from_hz(ValueWidth::int32q16, 20.5);
  m.send_control(1, {0x0006, ref});
  b.run_for(100ms);
  m.send_control(1, {0x000F, ref});
  b.run_for(3s);
  const auto controls = b.seen_with_id(663);
  EXPECT_EQ(bytes(controls.back().frame), (Bytes{0x0F, 0x00, 0x00, 0x80, 0x14, 0x00}));
  const auto st = decode_status(b.seen_with_id(883).back().frame, b.drive(0).layout());
  ASSERT_TRUE(st);
  EXPECT_NEAR(hz_from_wire(ValueWidth::int32q16, st.value.actual), 20.5, 0.01);
  EXPECT_EQ(st.value.word, 0x0637);  // ENABLED, remote, reference reached
  EXPECT_EQ(*b.drive(0).value(kReff), 0x00148000U);  // 406-REFF shows it
}

// CACNF 1: 16-bit whole-Hz values, DLC 4 (5.5.5 Int16Q0, D25).
TEST(Cda3000Drivecom, Cacnf1Carries16BitWholeHz) {
  MasterConfig mc;
  mc.layout = *process_layout_for_cacnf(1);
  Master m(mc);
  Bus<Master> b(m);
  b.add(commissioned(1, 1));
  m.system_start();
  b.run_for(10ms);
  m.send_control(1, {0x0006, 20});
  b.run_for(100ms);
  m.send_control(1, {0x000F, 20});
  b.run_for(3s);
  EXPECT_EQ(bytes(b.seen_with_id(663).back().frame), (Bytes{0x0F, 0x00, 0x14, 0x00}));
  const auto last = b.seen_with_id(883).back().frame;
  EXPECT_EQ(last.dlc, 4);
  EXPECT_EQ(bytes(last), (Bytes{0x37, 0x06, 0x14, 0x00}));
}

// 4.3.2: only with 260-CLSEL = OPTN2 does the control telegram drive the device; the factory
// setting (TERM) leaves it in START-UP INHIBIT and the remote bit clear.
TEST(Cda3000Drivecom, ControlTelegramsNeedClselOptn2) {
  Master m;
  Bus<Master> b(m);
  DeviceConfig c;
  c.connector_address = 2;  // 571-CLADR = 0: the connector's address (2.1)
  b.add(c);
  m.system_start();
  b.run_for(10ms);
  m.send_control(2, {0x0006, 0});
  b.run_for(200ms);
  EXPECT_EQ(b.drive(0).state(), drivecom::State::start_up_inhibit);
  EXPECT_EQ(status_words(b, 885), (std::vector<ibs::Word>{0x0040}));
  EXPECT_EQ(b.drive(0).counters().controls_ignored, 1U);
  // 151-ASTPR = BUS_1 puts control and reference on the bus (D23).
  EXPECT_EQ(finish(b, m, write(2, kAstpr, kDataSetBus1)).kind, OutcomeKind::done);
  EXPECT_EQ(*b.drive(0).value(kClsel), kOptn2Code);
  EXPECT_EQ(*b.drive(0).value(kRssl1), kOptn2Code);
  m.send_control(2, {0x0006, 0});
  b.run_for(200ms);
  EXPECT_EQ(b.drive(0).state(), drivecom::State::ready);
}

// An emergency stop ramps down with the quick-stop time constant and ends by itself in
// START-UP INHIBIT once the motor stands (transition 12, D27).
TEST(Cda3000Drivecom, EmergencyStopEndsInStartUpInhibitOnceStopped) {
  Master m;
  Bus<Master> b(m);
  b.add(commissioned(1));
  m.system_start();
  b.run_for(10ms);
  const auto ref = *wire_from_hz(ValueWidth::int32q16, 30.0);
  m.send_control(1, {0x0006, ref});
  b.run_for(50ms);
  m.send_control(1, {0x000F, ref});
  b.run_for(2s);
  EXPECT_GT(b.drive(0).actual_hz(b.now()), 29.0);
  m.send_control(1, {0x000B, ref});  // bit 2 low: EMERGENCY STOP
  b.run_for(5ms);
  EXPECT_EQ(b.drive(0).state(), drivecom::State::emergency_stop_active);
  b.run_for(1s);
  EXPECT_EQ(b.drive(0).state(), drivecom::State::start_up_inhibit);
  EXPECT_LE(std::fabs(b.drive(0).actual_hz(b.now())), 0.1);
}

// 5.2: commands stored in System Stop are executed at System Start, by all drives together.
TEST(Cda3000SystemStart, StoredCommandsRunOnAllDrivesWithin1Ms) {
  Master m;
  Bus<Master> b(m);
  for (std::uint8_t a = 1; a <= 5; ++a) b.add(commissioned(a), Time{std::chrono::milliseconds(3 * a)});
  b.run_until(Time{200ms});
  for (std::uint8_t a = 1; a <= 5; ++a) m.send_control(a, {0x0006, q16_from_double(5.0 * a)});
  b.run_for(100ms);
  for (std::size_t i = 0; i < 5; ++i) EXPECT_EQ(b.drive(i).state(), drivecom::State::start_up_inhibit);
  m.system_start();
  b.run_for(50ms);
  Time first = Time::max();
  Time last = Time::min();
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(b.drive(i).state(), drivecom::State::ready);
    first = std::min(first, b.drive(i).state_since());
    last = std::max(last, b.drive(i).state_since());
  }
  EXPECT_LE(last - first, 1ms);
  EXPECT_DOUBLE_EQ(b.drive(4).reference_hz(), 25.0);
}

// 7.1.3: read 360-DISP of CDA 1 -> 1323: 68 01 00 96 01 00 00 00 (406, REFF); write 14 ->
// 1103: 68 01 02 0E 00 00 00 (00: CAN-E8), echoed.
TEST(Cda3000Parameters, ExamplesOf713ByteForByte) {
  Master m;
  Bus<Master> b(m);
  b.add(commissioned(1));
  b.run_until(Time{10ms});
  const Time t0 = b.now();
  const auto& r = finish(b, m, read(1, kDisp));
  EXPECT_EQ(r.kind, OutcomeKind::done);
  EXPECT_EQ(r.value, 406U);
  const auto req = b.seen_with_id(1103, t0);
  const auto rep = b.seen_with_id(1323, t0);
  ASSERT_EQ(req.size(), 1U);
  ASSERT_EQ(rep.size(), 1U);
  EXPECT_EQ(bytes(req[0].frame), (Bytes{0x68, 0x01, 0x05, 0x00, 0x00, 0x00, 0x00, 0x00}));
  EXPECT_EQ(bytes(rep[0].frame), (Bytes{0x68, 0x01, 0x00, 0x96, 0x01, 0x00, 0x00, 0x00}));
  const Time t1 = b.now();
  EXPECT_EQ(finish(b, m, write(1, kDisp, 14)).kind, OutcomeKind::done);
  EXPECT_EQ(bytes(b.seen_with_id(1103, t1)[0].frame), (Bytes{0x68, 0x01, 0x02, 0x0E, 0x00, 0x00, 0x00, 0x00}));
  EXPECT_EQ(bytes(b.seen_with_id(1323, t1)[0].frame), (Bytes{0x68, 0x01, 0x00, 0x0E, 0x00, 0x00, 0x00, 0x00}));
  EXPECT_EQ(*b.drive(0).value(kDisp), 14U);
}

TEST(Cda3000Parameters, RefusalsCarryTheStatusBitsOf45) {
  Master m;
  Bus<Master> b(m);
  b.add(commissioned(1));
  const auto refused = [&](const Request& r) { return finish(b, m, r); };
  EXPECT_EQ(refused(read(1, 999)).status, kStatusUnknownParameter);
  EXPECT_EQ(refused(write(1, kReff, 0)).status, kStatusChangeNotPermitted);   // read-only
  EXPECT_EQ(refused(write(1, kCawdg, 256)).status, kStatusImpermissibleValue);  // USIGN8
  EXPECT_EQ(refused(write(1, kCascy, 0)).status, kStatusImpermissibleValue);    // below 1
  EXPECT_EQ(refused(write(1, kClsel, 3)).status, kStatusImpermissibleValue);    // no such code
  EXPECT_EQ(refused(write(1, kCamod, 1)).status, kStatusChangeNotPermitted);    // no CAN master (D26)
  EXPECT_EQ(refused(write(1, kCacnf, 5)).status, kStatusImpermissibleValue);    // 1..4
  EXPECT_EQ(refused(read(1, kOptn2)).status, kStatusReadNotPermitted);          // a STRING (D24)
  EXPECT_EQ(refused(read(1, kDisp, 1)).status, kStatusImpermissibleValue);      // no field
  EXPECT_EQ(*b.drive(0).value(kCawdg), 0U);
  EXPECT_EQ(*b.drive(0).value(kCascy), 80U);
}

// D29: the description items of mode 04.
TEST(Cda3000Parameters, DescribeItems) {
  Master m;
  Bus<Master> b(m);
  b.add(commissioned(1));
  EXPECT_EQ(finish(b, m, describe(1, kCascy, 0)).value, static_cast<std::uint32_t>(DataType::usign16));
  EXPECT_EQ(finish(b, m, describe(1, kCascy, 1)).value, 1U);
  EXPECT_EQ(finish(b, m, describe(1, kCascy, 2)).value, 32000U);
  EXPECT_EQ(finish(b, m, describe(1, kCascy, 3)).value, 80U);
  EXPECT_EQ(finish(b, m, describe(1, kCascy, 4)).value, 0x03U);  // writable, flash
  EXPECT_EQ(finish(b, m, describe(1, kCascy, 5)).value, 0x43534143U);  // "CASC"
  EXPECT_EQ(finish(b, m, describe(1, kCascy, 6)).value, 0x59U);        // "Y"
  EXPECT_EQ(finish(b, m, describe(1, kCascy, 7)).value, 0x736DU);      // "ms"
  const auto& end = finish(b, m, describe(1, kCascy, 8));
  EXPECT_EQ(end.kind, OutcomeKind::refused);
  EXPECT_EQ(end.status, kStatusListEnd);
}

// D29 read back as `ibs canlust describe` reads it: the items the drive answers make the
// parameter's description again.
TEST(Cda3000Parameters, DescriptionItemsReadBack) {
  Master m;
  Bus<Master> b(m);
  b.add(commissioned(1));
  std::vector<std::uint32_t> items;
  for (std::uint8_t item = 0; item < kDescriptionItems; ++item) {
    items.push_back(finish(b, m, describe(1, kCascy, item)).value);
  }
  const auto d = read_description(items);
  ASSERT_TRUE(d);
  EXPECT_EQ(d->type, DataType::usign16);
  EXPECT_EQ(d->min, 1U);
  EXPECT_EQ(d->max, 32000U);
  EXPECT_EQ(d->factory, 80U);
  EXPECT_TRUE(d->writable());
  EXPECT_TRUE(d->flash());
  EXPECT_FALSE(d->after_mains_reset());
  EXPECT_EQ(d->short_name, "CASCY");
  EXPECT_EQ(d->unit, "ms");
  // Not this drive's items: too few, or item 0 no data type.
  EXPECT_FALSE(read_description(std::span(items).first(7)));
  items[0] = 0xFF;
  EXPECT_FALSE(read_description(items));
}

TEST(Cda3000Parameters, FourCharactersAnItemIntelOrder) {
  EXPECT_EQ(pack4("CASCY"), 0x43534143U);  // the fifth is item 6's
  EXPECT_EQ(pack4("Y"), 0x59U);
  EXPECT_EQ(pack4(""), 0U);
  EXPECT_EQ(unpack4(0x43534143U), "CASC");
  EXPECT_EQ(unpack4(0x736DU), "ms");
  EXPECT_EQ(unpack4(0x00590000U), "");  // text ends at the first NUL
}

// 4.5 string read: 578-OPTN2 = "LCAN": block 0 carries the characters, block 1 the terminator,
// block 2 List_End (10H) with the XOR of blocks 0 and 1 (D8, CAN-E7).
TEST(Cda3000Strings, ReadOptn2ByteForByte) {
  Master m;
  Bus<Master> b(m);
  b.add(commissioned(1));
  b.run_until(Time{10ms});
  const Time t0 = b.now();
  const auto& o = finish(b, m, read_string(1, kOptn2));
  ASSERT_EQ(o.kind, OutcomeKind::done) << describe(o);
  EXPECT_EQ(o.text.view(), "LCAN");
  const auto req = b.seen_with_id(1103, t0);
  const auto rep = b.seen_with_id(1323, t0);
  ASSERT_EQ(rep.size(), 3U);
  EXPECT_EQ(bytes(req[0].frame), (Bytes{0x42, 0x02, 0x0B, 0x00, 0x00, 0x00, 0x00, 0x00}));
  EXPECT_EQ(bytes(rep[0].frame), (Bytes{0x42, 0x02, 0x00, 'L', 'C', 'A', 'N', 0x00}));
  EXPECT_EQ(bytes(rep[1].frame), (Bytes{0x42, 0x02, 0x00, 0x00, 0x00, 0x00, 0x00, 0x01}));
  EXPECT_EQ(bytes(rep[2].frame), (Bytes{0x42, 0x02, 0x10, 'L', 'C', 'A', 'N', 0x02}));
}

// 4.5 string write to 90-NAME (D24): handshake, blocks echoed, List_End with the XOR; then read
// back. A wrong checksum is refused with 80H and changes nothing (p. 47, D11).
TEST(Cda3000Strings, WriteNameBothWaysAndAWrongChecksumChangesNothing) {
  Master m;
  Bus<Master> b(m);
  b.add(commissioned(1));
  b.run_until(Time{10ms});
  const Time t0 = b.now();
  ASSERT_EQ(finish(b, m, write_string(1, kName, "Pump 7")).kind, OutcomeKind::done);
  EXPECT_EQ(b.drive(0).text(kName), "Pump 7");
  const auto req = b.seen_with_id(1103, t0);
  ASSERT_EQ(req.size(), 4U);  // handshake, "Pump", " 7\0\0", List_End
  EXPECT_EQ(bytes(req[0].frame), (Bytes{0x5A, 0x00, 0x08, 0x00, 0x00, 0x00, 0x00, 0x00}));
  EXPECT_EQ(bytes(req[1].frame), (Bytes{0x5A, 0x00, 0x08, 'P', 'u', 'm', 'p', 0x01}));
  EXPECT_EQ(bytes(req[2].frame), (Bytes{0x5A, 0x00, 0x08, ' ', '7', 0x00, 0x00, 0x02}));
  const std::uint32_t sum = get_le32(std::span<const std::uint8_t>(req[1].frame.data.data() + 3, 4)) ^
                            get_le32(std::span<const std::uint8_t>(req[2].frame.data.data() + 3, 4));
  EXPECT_EQ(bytes(req[3].frame), (Bytes{0x5A, 0x00, 0x10, static_cast<std::uint8_t>(sum & 0xFF),
                                        static_cast<std::uint8_t>((sum >> 8) & 0xFF),
                                        static_cast<std::uint8_t>((sum >> 16) & 0xFF),
                                        static_cast<std::uint8_t>(sum >> 24), 0x03}));
  EXPECT_EQ(finish(b, m, read_string(1, kName)).text.view(), "Pump 7");

  // The same transfer closed with a wrong checksum, by hand.
  const IdentifierMap ids;
  const auto send = [&](std::uint8_t mode, std::uint32_t data, std::uint8_t block) {
    b.inject(*encode_parameter_request(ids, 1, {kName, mode, data, block}));
    b.run_for(5ms);
  };
  const Time t1 = b.now();
  send(kModeStringWrite, 0, 0);
  send(kModeStringWrite, 0x00006F4EU, 1);  // "No"
  send(kModeListEnd, 0x12345678U, 2);
  const auto rep = b.seen_with_id(1323, t1);
  ASSERT_EQ(rep.size(), 3U);
  EXPECT_EQ(rep[2].frame.data[2], kStatusImpermissibleValue);
  EXPECT_EQ(b.drive(0).text(kName), "Pump 7");
}

// 7.1.1 / 7.1.2 steps 3-5: CLADR acts after a mains reset, and only if saved by 150-SAVE, whose
// reply comes after the backup time (4.3.3: "a few hundred milliseconds").
TEST(Cda3000Flash, AddressActsAfterSaveAndMainsReset) {
  Master m;
  Bus<Master> b(m);
  b.add(commissioned(1));
  b.run_until(Time{10ms});
  ASSERT_EQ(finish(b, m, write(1, kCladr, 5)).kind, OutcomeKind::done);
  EXPECT_EQ(b.drive(0).address(), 1);
  b.mains_reset(0);
  EXPECT_EQ(b.drive(0).address(), 1);  // not saved: the flash still says 1
  EXPECT_EQ(*b.drive(0).value(kCladr), 1U);
  ASSERT_EQ(finish(b, m, write(1, kCladr, 5)).kind, OutcomeKind::done);
  Request save = write(1, kSave, 1);
  save.timeout = 1s;
  const auto& o = finish(b, m, save);
  ASSERT_EQ(o.kind, OutcomeKind::done);
  EXPECT_GE(o.finished - o.started, 300ms);
  EXPECT_EQ(*b.drive(0).saved_value(kCladr), 5U);
  const Time t = b.now();
  b.mains_reset(0);
  b.run_for(250ms);
  EXPECT_EQ(b.drive(0).address(), 5);
  EXPECT_EQ(b.seen_with_id(1553, t).size(), 3U);  // 1543 + 2 x 5 at 0, 100, 200 ms
  EXPECT_TRUE(b.seen_with_id(1545, t).empty());
}

// p. 13: 04-PROG = 1 puts every setting back to its factory value; the reply comes when done.
TEST(Cda3000Flash, ProgRestoresTheFactorySettings) {
  Master m;
  Bus<Master> b(m);
  b.add(commissioned(1));
  ASSERT_EQ(finish(b, m, write(1, kCascy, 20)).kind, OutcomeKind::done);
  Request prog = write(1, kProg, 1);
  prog.timeout = 1s;
  const auto& o = finish(b, m, prog);
  ASSERT_EQ(o.kind, OutcomeKind::done);
  EXPECT_GE(o.finished - o.started, 500ms);
  EXPECT_EQ(*b.drive(0).value(kCascy), 80U);
  EXPECT_EQ(*b.drive(0).value(kClsel), kClselTerm);
  EXPECT_EQ(*b.drive(0).value(kProg), 0U);
  EXPECT_EQ(b.drive(0).text(kName), kNameFactory);
  EXPECT_EQ(b.drive(0).address(), 1);  // CLADR acts after a mains reset only
}

// 574-CAWDG with each programmable reaction (6.1, D7, D15): the error telegram at the watchdog
// time, and the first status after it - at most one 575-CASCY later - shows the reaction.
struct WatchdogCase {
  ErrorReaction reaction;
  drivecom::State state_after;  // in the first status after the trip
  bool warning;
};

class Cda3000Watchdog : public ::testing::TestWithParam<WatchdogCase> {};

TEST_P(Cda3000Watchdog, TripsWithinOneStatusPeriodWithItsReaction) {
  const auto c = GetParam();
  Master m;
  Bus<Master> b(m);
  DeviceConfig dc = commissioned(1);
  dc.saved.emplace_back(kCawdg, 50);
  dc.saved.emplace_back(kCascy, 20);
  dc.saved.emplace_back(kRop2, static_cast<std::uint32_t>(c.reaction));  // 6.1: a parameter (CAN-E16)
  b.add(dc);
  m.system_start();
  b.run_for(5ms);
  const auto ref = *wire_from_hz(ValueWidth::int32q16, 20.0);
  m.send_control(1, {0x0006, ref});
  b.run_for(30ms);
  // Control telegrams every 30 ms keep the watchdog quiet while the drive runs up.
  for (int i = 0; i < 60; ++i) {
    m.send_control(1, {0x000F, ref});
    b.run_for(30ms);
  }
  ASSERT_EQ(b.drive(0).state(), drivecom::State::enabled);
  EXPECT_TRUE(b.seen_with_id(443).empty());
  const Time last_control = b.seen_with_id(663).back().end;
  b.run_for(200ms);
  const auto errors = b.seen_with_id(443);
  ASSERT_EQ(errors.size(), 1U);
  EXPECT_EQ(bytes(errors[0].frame),
            (Bytes{kErrorOp2, kLocationOp2_172, static_cast<std::uint8_t>(c.reaction)}));
  EXPECT_GE(errors[0].start, last_control + 50ms);
  EXPECT_LE(errors[0].start, last_control + 51ms);
  const auto after = b.seen_with_id(883, last_control + 50ms);
  ASSERT_FALSE(after.empty());
  EXPECT_LE(after[0].start, last_control + 50ms + 20ms);
  const auto w = static_cast<ibs::Word>(after[0].frame.data[0] | (after[0].frame.data[1] << 8U));
  EXPECT_EQ(drivecom::decode_state(w), c.state_after) << explain_status_word(w);
  EXPECT_EQ(bit(w, status_bits::kWarning), c.warning);
  if (c.reaction == ErrorReaction::warning) {
    EXPECT_EQ(b.drive(0).state(), drivecom::State::enabled);
    EXPECT_GT(b.drive(0).actual_hz(b.now()), 19.0);
    return;
  }
  // The drive ends in FAULT; a RESET FAULT edge (with control telegrams again) clears it.
  b.run_for(2s);
  EXPECT_EQ(b.drive(0).state(), drivecom::State::fault);
  m.send_control(1, {0x0000, 0});
  b.run_for(10ms);
  m.send_control(1, {0x0080, 0});
  b.run_for(10ms);
  EXPECT_EQ(b.drive(0).state(), drivecom::State::start_up_inhibit);
}

INSTANTIATE_TEST_SUITE_P(
    Reactions, Cda3000Watchdog,
    ::testing::Values(WatchdogCase{ErrorReaction::warning, drivecom::State::enabled, true},
                      WatchdogCase{ErrorReaction::stop, drivecom::State::fault_response_active, false},
                      WatchdogCase{ErrorReaction::quick_stop, drivecom::State::fault_response_active, false},
                      WatchdogCase{ErrorReaction::disable_power, drivecom::State::fault, false}),
    [](const ::testing::TestParamInfo<WatchdogCase>& p) -> std::string {
      switch (p.param.reaction) {
        case ErrorReaction::warning: return "Warning";
        case ErrorReaction::stop: return "Stop";
        case ErrorReaction::quick_stop: return "QuickStop";
        case ErrorReaction::disable_power: return "DisablePower";
      }
      return "Unknown";
    });

// 6.5: the transition SYSTEM START -> SYSTEM STOP acknowledges the error.
TEST(Cda3000Errors, SystemStopAcknowledgesTheWatchdogFault) {
  Master m;
  Bus<Master> b(m);
  DeviceConfig dc = commissioned(1);
  dc.saved.emplace_back(kCawdg, 30);
  b.add(dc);
  m.system_start();
  b.run_for(5ms);
  m.send_control(1, {0x0006, 0});
  b.run_for(100ms);
  EXPECT_EQ(b.drive(0).state(), drivecom::State::fault);
  m.system_stop();
  b.run_for(5ms);
  EXPECT_EQ(b.drive(0).state(), drivecom::State::start_up_inhibit);
  EXPECT_FALSE(b.drive(0).fault());
}

TEST(Cda3000Config, BadSettingsAreRefusedWithWhereAndWhat) {
  DeviceConfig c;
  c.connector_address = 8;
  EXPECT_THROW({ Cda3000 d(c); }, std::invalid_argument);
  c.connector_address = 0;
  c.saved = {{kCascy, 0}};
  try {
    Cda3000 d(c);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "CDA3000: 575-CASCY: 0 ms is below the minimum 1 ms");
  }
  c.saved = {{kCamod, 1}};  // D26: only the CANLust slave is emulated
  EXPECT_THROW({ Cda3000 d(c); }, std::invalid_argument);
  c.saved = {{kCacnf, 4}};  // EasyDrive is
  EXPECT_NO_THROW({ Cda3000 d(c); });
}

}  // namespace
}  // namespace ibs::devices::cda3000
