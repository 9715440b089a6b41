// Every telegram example of the LUSTBUS manual (6.1.1, 6.2.2, 6.2.3, 7.1.1, 7.2.1, 11.6.4) byte for byte
// on both sides, with the BCC filled in by the rule of 2.2, and the errata decisions pinned
// (docs/errata.md, "LUSTBUS (LUSTBUS manual)").
#include <gtest/gtest.h>

#include "ibs/lustbus/telegram.hpp"
#include "test_support.hpp"

namespace ibs::lustbus {
namespace {

using test::Bytes;
using test::feed;
using test::RecordingResponder;
using test::to_vector;

std::vector<std::uint8_t> v(const Frame& f) { return to_vector(f.span()); }

// The host's decoder takes `answer` as the answer to (a, c).
AnswerDecoder decode(Address a, const Code& c, AnswerDecoder::Expect e,
                     const std::vector<std::uint8_t>& answer) {
  AnswerDecoder d;
  d.start(a, c, e);
  for (const auto b : answer) d.feed(b);
  return d;
}

TEST(Bcc, IsTheXorOfEverythingAfterStxThroughEtx) {
  const auto t = Bytes{}("00112=03E8")(kEtx).v;
  EXPECT_EQ(bcc(t), 0x72);
  EXPECT_EQ(text_bcc(make_code(112), make_value("03E8")), 0x72);
}

TEST(ControlCharacters, AreThoseOf22WithNakAs15H) {
  EXPECT_EQ(kStx, 0x02);
  EXPECT_EQ(kEtx, 0x03);
  EXPECT_EQ(kEot, 0x04);
  EXPECT_EQ(kEnq, 0x05);
  EXPECT_EQ(kAck, 0x06);
  EXPECT_EQ(kNak, 21);  // LB-E2: 15H, not the table's decimal 15
  EXPECT_EQ(kEquals, '=');
  EXPECT_EQ(address_char(0), '@');
  EXPECT_EQ(address_char(1), 'A');
  EXPECT_EQ(address_char(30), '^');
  EXPECT_EQ(address_char(31), 0x5F);  // LB-E2: '_', the broadcast address
}

// 6.1.1.1: parameter 12 via address 0. LB-E1: the answer's ADR is 64 ('@'), not 0. LB-E3: the
// CODE is the character row's 00112 (the number rows' 48 48 48 49 50 drop the device digit).
TEST(SeedExamples, Enquiry6111Vf1000) {
  const auto host = Bytes{}(4)(64)(48)(48)(49)(49)(50)(5).v;
  EXPECT_EQ(v(encode_enquiry(0, make_code(112))), host);
  const auto answer = Bytes{}(64)(2)("00112=03E8")(3)(0x72).v;
  EXPECT_EQ(v(encode_text_answer(0, make_code(112), make_value("03E8"))), answer);

  RecordingResponder r;
  r.enquiry_answer = EnquiryAnswer::text(make_value("03E8"));
  Receiver rx(r, 5);
  EXPECT_EQ(feed(rx, host), answer);
  EXPECT_EQ(r.last_code, make_code(112));
  EXPECT_EQ(r.last_ctx.address, 0);

  const auto d = decode(0, make_code(112), AnswerDecoder::Expect::text_or_nak, answer);
  ASSERT_EQ(d.status(), AnswerDecoder::Status::done);
  EXPECT_EQ(d.value().view(), "03E8");
  EXPECT_DOUBLE_EQ(decode(Family::standard, DataType::fixpoint16, d.value().view()).value, 50.0);
}

// 6.1.1.2: 77-SPEED via address 0. LB-E4: ETX is 3 (the row shows 2) and the VALUE is the
// character row's 04FA4000 (eight characters, as 10.1.1 counts 18 bytes); its number row's
// first 52 ('4') is a typo. The value is 4FA4000H = 1274.25 1/min.
TEST(SeedExamples, Enquiry6112Mc6000) {
  const auto host = Bytes{}(4)(64)(50)(48)(48)(55)(55)(5).v;
  EXPECT_EQ(v(encode_enquiry(0, make_code(20077))), host);
  const auto answer = Bytes{}(64)(2)("20077=04FA4000")(3)(0x0B).v;
  EXPECT_EQ(v(encode_text_answer(0, make_code(20077), make_value("04FA4000"))), answer);
  EXPECT_EQ(answer.size(), 18U);

  const auto d = decode(0, make_code(20077), AnswerDecoder::Expect::text_or_nak, answer);
  ASSERT_EQ(d.status(), AnswerDecoder::Status::done);
  EXPECT_DOUBLE_EQ(decode(Family::enhanced, DataType::int32q16, d.value().view()).value, 1274.25);
  // Leading zeros are optional (2.3): the seven-character form, BCC 3BH, is the same value.
  const auto short_form = Bytes{}(64)(2)("20077=4FA4000")(3)(0x3B).v;
  const auto d2 = decode(0, make_code(20077), AnswerDecoder::Expect::text_or_nak, short_form);
  ASSERT_EQ(d2.status(), AnswerDecoder::Status::done);
  EXPECT_DOUBLE_EQ(decode(Family::enhanced, DataType::int32q16, d2.value().view()).value, 1274.25);
  // The printed bytes as they stand: ETX 2 and BCC missing -> not an answer.
  const auto printed = Bytes{}(64)(2)(50)(48)(48)(55)(55)(61)(52)(52)(70)(65)(52)(48)(48)(48)(2).v;
  const auto d3 = decode(0, make_code(20077), AnswerDecoder::Expect::text_or_nak, printed);
  EXPECT_EQ(d3.status(), AnswerDecoder::Status::error);
  EXPECT_EQ(d3.error(), AnswerError::unexpected);
}

// 6.2.2: 05-FSSIO = 50.00 Hz = 03E8H via address 0; BCC 74H.
TEST(SeedExamples, Select622Vf1000) {
  const auto host = Bytes{}(4)(64)(2)("00105=03E8")(3)(0x74).v;
  EXPECT_EQ(v(encode_select(0, make_code(105), make_value("03E8"))), host);
  EXPECT_EQ(host.size(), 15U);  // 10.1.2
  EXPECT_EQ(v(encode_ack(0)), (Bytes{}(64)(6).v));
  EXPECT_EQ(encode(Family::standard, DataType::fixpoint16, 50.0).value.view(), "03E8");

  RecordingResponder r;
  Receiver rx(r, 7);
  EXPECT_EQ(feed(rx, host), (Bytes{}(64)(6).v));
  EXPECT_EQ(r.last_code, make_code(105));
  EXPECT_EQ(r.last_value.view(), "03E8");
  const auto d = decode(0, make_code(105), AnswerDecoder::Expect::ack_or_nak, Bytes{}(64)(6).v);
  EXPECT_EQ(d.kind(), AnswerKind::ack);
}

// 6.2.3: 333.254 1/min as INT32Q16 = 14D4106H. LB-E5: the number row (03E8...) does not match
// the VALUE; the VALUE is right. CODE 00005 is no MC6000 CODE (2.4.2): the corrected telegram
// writes 428-RSIO (7.2.1) as 20428. Both pinned, each with its own BCC.
TEST(SeedExamples, Select623Mc6000AsPrintedAndCorrected) {
  EXPECT_EQ(encode(Family::enhanced, DataType::int32q16, 333.254).value.view(), "14D4106");
  const auto printed = Bytes{}(4)(64)(2)("00005=14D4106")(3)(0x49).v;
  EXPECT_EQ(v(encode_select(0, make_code(5), make_value("14D4106"))), printed);
  EXPECT_FALSE(as_mc_code(make_code(5)).has_value());
  const auto corrected = Bytes{}(4)(64)(2)("20428=14D4106")(3)(0x40).v;
  EXPECT_EQ(v(encode_select(0, make_code(20428), make_value("14D4106"))), corrected);
  EXPECT_EQ(corrected.size(), 18U);

  // Against the fake servo: the printed CODE is refused (20H), the corrected one taken.
  auto servo = test::make_mc6000();
  servo.siof = 0;
  Receiver rx(servo, 1);
  EXPECT_EQ(feed(rx, printed), (Bytes{}(64)(kNak).v));
  EXPECT_EQ(servo.siof, 0x20);
  servo.siof = 0;
  rx.receive(kEot, Time{0});
  EXPECT_EQ(feed(rx, corrected), (Bytes{}(64)(kAck).v));
  EXPECT_EQ(servo.value_of(428), 0x14D4106U);
}

// 7.1.1: MODE 0, CSEL 3, FSSEL 8, FSSIO 23.15 Hz = 463 = 01CFH, CNTL 128 = 0080H. LB-E11: the
// printed list shifts the values against the parameters; corrected, with CNTL (the start) last.
// 6.2.3's number row as printed: "4 64 2 48 48 48 48 53 = 48 51 69 56 49 48 54 3 ?". Its VALUE
// numbers are the characters "03E8106" -- the first four 6.2.2's "03E8" (48 51 69 56), a copy --
// not the character row's "14D4106" that the text computes ("333.254 · 65536 = 21840134 =
// 14D4106H"); 03E8106H is 62.5 1/min (LB-E5). The VALUE the text computes is the one the encoder
// gives, and the numbers of the corrected telegram are pinned; the telegram of the printed numbers
// is refused by a servo as the character row's is (CODE 00005 is no MC6000 CODE, 2.4.2: 20H).
TEST(SeedExamples, Select623NumberRowAsPrintedIsACopyOf622AndRefused) {
  const std::vector<std::uint8_t> printed_numbers = {4,  64, 2,  48, 48, 48, 48, 53, 61,
                                                     48, 51, 69, 56, 49, 48, 54, 3};
  const std::string printed_value(printed_numbers.begin() + 9, printed_numbers.end() - 1);
  EXPECT_EQ(printed_value, "03E8106");
  EXPECT_EQ(printed_value.substr(0, 4), "03E8");  // 6.2.2's 50.00 Hz
  const auto as_printed = decode(Family::enhanced, DataType::int32q16, printed_value);
  ASSERT_TRUE(as_printed.ok());
  EXPECT_NEAR(as_printed.value, 62.5, 0.01);  // not the example's 333.254
  const auto computed = encode(Family::enhanced, DataType::int32q16, 333.254).value;
  EXPECT_EQ(computed.view(), "14D4106");
  EXPECT_EQ(21840134U, 0x14D4106U);
  // The corrected telegram's numbers, BCC by the rule of 2.2: 20428 as 7.2.1 writes 428-RSIO.
  EXPECT_EQ(v(encode_select(0, make_code(20428), computed)),
            (std::vector<std::uint8_t>{4, 64, 2, 50, 48, 52, 50, 56, 61, 49, 52, 68, 52, 49, 48, 54, 3, 0x40}));
  // The printed numbers as a telegram (their BCC by 2.2) reach a servo: refused, 20H.
  std::vector<std::uint8_t> t = printed_numbers;
  t.push_back(bcc(std::span<const std::uint8_t>(t).subspan(3)));
  EXPECT_EQ(t, v(encode_select(0, make_code(5), make_value("03E8106"))));
  auto servo = test::make_mc6000();
  servo.siof = 0;
  Receiver rx(servo, 1);
  EXPECT_EQ(feed(rx, t), (Bytes{}(64)(kNak).v));
  EXPECT_EQ(servo.siof, 0x20);
}

TEST(SeedExamples, ControlSequence711Corrected) {
  struct Row {
    unsigned code;
    const char* value;
    std::uint8_t bcc;
  };
  const Row rows[] = {{1, "0000", 0x0F}, {2, "0003", 0x0F}, {4, "0008", 0x02},
                      {5, "01CF", 0x0F}, {3, "0080", 0x05}};
  EXPECT_EQ(encode(Family::standard, DataType::fixpoint16, 23.15).value.view(), "01CF");
  EXPECT_EQ(format_raw(Family::standard, 128).value.view(), "0080");
  auto vf = test::make_vf1000();
  vf.siof = 0;
  Receiver rx(vf, 1);
  for (const Row& r : rows) {
    const auto t = v(encode_select(0, make_code(r.code), make_value(r.value)));
    EXPECT_EQ(t.back(), r.bcc) << r.code;
    EXPECT_EQ(feed(rx, t), (Bytes{}(64)(kAck).v)) << r.code;
    rx.receive(kEot, Time{0});
  }
  // CNTL = 0080 has BCC 05H (ENQ) and came last: the start command after the set-up.
  EXPECT_EQ(vf.history.back().number, 3U);
  EXPECT_EQ(vf.value_of(1), 0U);
  EXPECT_EQ(vf.value_of(2), 3U);
  EXPECT_EQ(vf.value_of(4), 8U);
  EXPECT_EQ(vf.value_of(5), 463U);
  EXPECT_EQ(vf.value_of(3), 128U);
}

// 7.2.1: the servo's sequence; 132.15 * 65536 = 8660582 = 842666H (hex, LB-E5).
TEST(SeedExamples, ControlSequence721) {
  struct Row {
    unsigned code;
    const char* value;
    std::uint8_t bcc;
  };
  const Row rows[] = {{20300, "2", 0x3D}, {20416, "0", 0x3F}, {20402, "2", 0x38},
                      {20418, "0", 0x31}, {20419, "0", 0x30}, {20420, "0", 0x3A},
                      {20417, "3", 0x3D}, {20428, "842666", 0x0A}, {20416, "1", 0x3E}};
  EXPECT_EQ(encode(Family::enhanced, DataType::int32q16, 132.15).value.view(), "842666");
  auto mc = test::make_mc6000();
  mc.siof = 0;
  mc.mc_eeprom_per_byte = 0ms;
  Receiver rx(mc, 3);
  for (const Row& r : rows) {
    const auto t = v(encode_select(3, make_code(r.code), make_value(r.value)));
    EXPECT_EQ(t.back(), r.bcc) << r.code;
    EXPECT_EQ(feed(rx, t), (Bytes{}(0x43)(kAck).v)) << r.code;
    rx.receive(kEot, Time{0});
  }
  EXPECT_EQ(mc.value_of(428), 8660582U);
  EXPECT_EQ(mc.value_of(416), 1U);
}

// 11.6.4: the PosMOD1 telegrams, user data = status byte + text. "49999=1?" has BCC 04H = EOT:
// the byte after ETX is the BCC whatever its value (2.2).
TEST(SeedExamples, Posmod1164) {
  struct Row {
    const char* data;
    std::uint8_t bcc;
  };
  const Row selects[] = {{"8GOA0V1000", 0x1C}, {"<%P10 (RPF)", 0x27}, {"<N10 GO 0", 0x41},
                         {"8END", 0x7D},       {"1?", 0x04},          {"1%RDP10", 0x59}};
  const Row answers[] = {{"0G10H10", 0x35}, {"4%P10 (RPF)", 0x2F}, {"4N10 GO 0", 0x49},
                         {"0END", 0x75}};
  EXPECT_EQ(posmod_status_char({false, false}), '0');
  EXPECT_EQ(posmod_status_char({true, false}), '1');
  EXPECT_EQ(posmod_status_char({false, true}), '4');
  EXPECT_EQ(parse_posmod_status('<'), (PosmodStatus{false, true}));
  EXPECT_EQ(parse_posmod_status('8'), (PosmodStatus{false, false}));
  auto mc = test::make_mc6000();
  Receiver rx(mc, 2);
  for (const Row& r : selects) {
    const auto t = v(encode_select(0, kPosmodCode, make_value(r.data)));
    EXPECT_EQ(t.back(), r.bcc) << r.data;
    EXPECT_EQ(feed(rx, t), (Bytes{}(64)(kAck).v)) << r.data;
    EXPECT_EQ(mc.posmod_last.view(), r.data);
    rx.receive(kEot, Time{0});
  }
  EXPECT_EQ(v(encode_enquiry(0, kPosmodCode)), (Bytes{}(4)(64)("49999")(5).v));
  for (const Row& r : answers) {
    const auto t = v(encode_text_answer(0, kPosmodCode, make_value(r.data)));
    EXPECT_EQ(t.back(), r.bcc) << r.data;
    const auto d = decode(0, kPosmodCode, AnswerDecoder::Expect::text_or_nak, t);
    ASSERT_EQ(d.status(), AnswerDecoder::Status::done) << r.data;
    EXPECT_EQ(d.value().view(), r.data);
  }
}

TEST(AnswerDecoder, ChecksTheAnswerAsSection3Says) {
  using E = AnswerDecoder::Expect;
  const Code c = make_code(112);
  const auto good = Bytes{}(0x41)(2)("00112=03E8")(3)(0x72).v;
  EXPECT_EQ(decode(1, c, E::text_or_nak, good).status(), AnswerDecoder::Status::done);
  EXPECT_EQ(decode(2, c, E::text_or_nak, good).error(), AnswerError::wrong_address);
  EXPECT_EQ(decode(1, make_code(113), E::text_or_nak, good).error(), AnswerError::wrong_code);
  auto bad = good;
  bad.back() ^= 1;
  EXPECT_EQ(decode(1, c, E::text_or_nak, bad).error(), AnswerError::bad_bcc);
  EXPECT_EQ(decode(1, c, E::ack_or_nak, good).error(), AnswerError::wrong_kind);
  EXPECT_EQ(decode(1, c, E::text_or_nak, Bytes{}(0x41)(kAck).v).error(), AnswerError::wrong_kind);
  EXPECT_EQ(decode(1, c, E::text_or_nak, Bytes{}(0x41)(kNak).v).kind(), AnswerKind::nak);
  EXPECT_EQ(decode(1, c, E::ack_or_nak, Bytes{}(0x41)(kNak).v).kind(), AnswerKind::nak);
  EXPECT_EQ(decode(1, c, E::text_or_nak, Bytes{}(0x41)(kGarbled).v).error(), AnswerError::garbled);
  // A BCC that is a control character is still the BCC.
  const auto t = v(encode_text_answer(0, kPosmodCode, make_value("1?")));
  EXPECT_EQ(t.back(), kEot);
  EXPECT_EQ(decode(0, kPosmodCode, E::text_or_nak, t).status(), AnswerDecoder::Status::done);
  // 101 VALUE characters are too many.
  Bytes longer;
  longer(0x41)(2)("00112=");
  for (int i = 0; i < 101; ++i) longer("1");
  EXPECT_EQ(decode(1, c, E::text_or_nak, longer.v).error(), AnswerError::value_too_long);
}

TEST(Frames, LongestTelegramFits) {
  Value v100;
  for (int i = 0; i < 100; ++i) ASSERT_TRUE(v100.push_back('F'));
  EXPECT_FALSE(v100.push_back('F'));
  const Frame f = encode_select(1, make_code(20500), v100);
  EXPECT_EQ(f.size, kMaxTelegramLength);
}

// LB-D10: an 11.2 description's binary elements may be frame characters; the decoder takes a
// known number of VALUE bytes as they come, and only then looks for ETX.
TEST(AnswerDecoderBinary, TakesAKnownPrefixWithFrameCharacters) {
  auto answer = Bytes{}(0x43)(kStx)("30084=")(kEtx)(kEot)(kAck)("AB")(kEtx).v;
  std::uint8_t sum = 0;
  for (std::size_t i = 2; i < answer.size(); ++i) sum ^= answer[i];
  answer.push_back(sum);
  AnswerDecoder d;
  d.start(3, make_code(30084), AnswerDecoder::Expect::text_or_nak, 3);
  for (const auto b : answer) d.feed(b);
  ASSERT_EQ(d.status(), AnswerDecoder::Status::done) << to_string(d.error());
  EXPECT_EQ(d.value().view(), std::string_view("\x03\x04\x06" "AB"));
  // Without the prefix, the first ETX ends the VALUE and the rest is no BCC.
  const auto plain = decode(3, make_code(30084), AnswerDecoder::Expect::text_or_nak, answer);
  EXPECT_EQ(plain.status(), AnswerDecoder::Status::error);
  // A byte >= 80H inside the prefix is still a garbled character.
  AnswerDecoder g;
  g.start(3, make_code(30084), AnswerDecoder::Expect::text_or_nak, 3);
  const auto garbled = Bytes{}(0x43)(kStx)("30084=")(0x83).v;
  for (const auto b : garbled) g.feed(b);
  EXPECT_EQ(g.error(), AnswerError::garbled);
}

}  // namespace
}  // namespace ibs::lustbus
