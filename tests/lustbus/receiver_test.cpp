// The device's receiver: every answer section 3 lists, addresses 0 / 1..30 / 31 (4.2), EOT, no
// timeout, deferred answers (10.2) and reaction times.
#include <gtest/gtest.h>

#include <cstdio>

#include "ibs/lustbus/receiver.hpp"
#include "test_support.hpp"

namespace ibs::lustbus {
namespace {

using test::Bytes;
using test::feed;
using test::RecordingResponder;

const std::vector<std::uint8_t> kNone{};

std::vector<std::uint8_t> enq(Address a, const char* code) {
  return Bytes{}(kEot)(address_char(a))(code)(kEnq).v;
}
std::vector<std::uint8_t> sel(Address a, unsigned code, const char* value) {
  const Frame f = encode_select(a, make_code(code), make_value(value));
  return {f.bytes.begin(), f.bytes.begin() + f.size};
}
std::vector<std::uint8_t> ack(Address a) { return Bytes{}(address_char(a))(kAck).v; }
std::vector<std::uint8_t> nak(Address a) { return Bytes{}(address_char(a))(kNak).v; }

struct ReceiverTest : ::testing::Test {
  RecordingResponder r;
  Receiver rx{r, 5};
};

// ---- ENQUIRY (3) -------------------------------------------------------------------------------

TEST_F(ReceiverTest, EnquiryValidIsAnsweredWithText) {
  const auto a = feed(rx, enq(5, "00112"));
  EXPECT_EQ(a, (Bytes{}(0x45)(kStx)("00112=03E8")(kEtx)(text_bcc(make_code(112), make_value("03E8"))).v));
  EXPECT_EQ(rx.last_event(), ReceiverEvent::enquiry);
  EXPECT_EQ(r.telegrams, 1);
}

TEST_F(ReceiverTest, EnquiryImproperCodeOrReadProtectedIsNak) {
  r.enquiry_answer = EnquiryAnswer::nak();
  EXPECT_EQ(feed(rx, enq(5, "00199")), nak(5));
}

TEST_F(ReceiverTest, EnquiryImproperConstructionGetsNoAnswer) {
  const std::vector<std::vector<std::uint8_t>> broken = {
      Bytes{}(kEot)(0x45)("0011")(kEnq).v,         // four digits
      Bytes{}(kEot)(0x45)("001123")(kEnq).v,       // six digits
      Bytes{}(kEot)(0x45)("00A12")(kEnq).v,        // not a digit
      Bytes{}(kEot)(0x45)("00112")(kAck).v,        // wrong control character
      Bytes{}(kEot)(0x45)("00112")(kEtx).v,        // wrong control character
      Bytes{}(kEot)(0x45)("001")(kGarbled)("2")(kEnq).v,  // parity error
      Bytes{}(kEot)(0x45)(kEnq).v,                 // no CODE
      Bytes{}(kEot)("00112")(kEnq).v,              // no ADR
      Bytes{}(kEot)(0x45)(0x45)("00112")(kEnq).v,  // ADR twice
  };
  for (const auto& t : broken) {
    EXPECT_EQ(feed(rx, t), kNone) << test::hex(t);
  }
  EXPECT_EQ(r.enquiries, 0);
  EXPECT_EQ(r.telegrams, 0);
}

TEST_F(ReceiverTest, EnquiryToAnotherAddressGetsNoAnswer) {
  EXPECT_EQ(feed(rx, enq(6, "00112")), kNone);
  EXPECT_EQ(rx.state(), ReceiverState::ignoring);
  EXPECT_EQ(r.enquiries, 0);
}

TEST_F(ReceiverTest, EnquiryAtBroadcastGetsNoAnswer) {
  EXPECT_EQ(feed(rx, enq(31, "00112")), kNone);  // 4.2, 9.1
  EXPECT_EQ(r.enquiries, 0);
}

// ---- SELECT (3) --------------------------------------------------------------------------------

TEST_F(ReceiverTest, SelectValidIsAck) {
  EXPECT_EQ(feed(rx, sel(5, 105, "03E8")), ack(5));
  EXPECT_EQ(r.last_value.view(), "03E8");
  EXPECT_EQ(rx.last_event(), ReceiverEvent::select);
}

TEST_F(ReceiverTest, SelectWrongBccIsNakAndReachesOnlyChecksumError) {
  auto t = sel(5, 105, "03E8");
  t.back() ^= 0x10;
  EXPECT_EQ(feed(rx, t), nak(5));
  EXPECT_EQ(r.selects, 0);
  EXPECT_EQ(r.checksum_errors, 1);
  EXPECT_EQ(r.telegrams, 0);
  EXPECT_EQ(rx.last_event(), ReceiverEvent::checksum_error);
}

TEST_F(ReceiverTest, SelectImproperCodeAccessOrValueIsNakFromTheResponder) {
  r.select_answer = SelectAnswer::nak();
  EXPECT_EQ(feed(rx, sel(5, 105, "03E8")), nak(5));
  EXPECT_EQ(r.selects, 1);
}

TEST_F(ReceiverTest, SelectImproperConstructionGetsNoAnswer) {
  const std::vector<std::vector<std::uint8_t>> broken = {
      Bytes{}(kEot)(0x45)(kStx)("0010503E8")(kEtx)(0).v,   // no '='
      Bytes{}(kEot)(0x45)(kStx)("0105=03E8")(kEtx)(0).v,   // four CODE digits
      Bytes{}(kEot)(0x45)(kStx)("00105=03")(kEnq)("E8")(kEtx)(0).v,  // control in VALUE
      Bytes{}(kEot)(0x45)(kStx)("00105=03")(kStx)("E8")(kEtx)(0).v,
      Bytes{}(kEot)(0x45)(kStx)("00105=03")(kGarbled)("E8")(kEtx)(0).v,
      Bytes{}(kEot)(0x45)(kStx)(kStx)("00105=03E8")(kEtx)(0).v,
      Bytes{}(kEot)(0x45)(kStx)("00105=03E8").v,  // no ETX (then EOT below)
  };
  for (const auto& t : broken) {
    EXPECT_EQ(feed(rx, t), kNone) << test::hex(t);
    rx.receive(kEot, Time{0});
  }
  EXPECT_EQ(r.selects, 0);
  EXPECT_EQ(r.checksum_errors, 0);
}

TEST_F(ReceiverTest, ValueOfHundredCharactersIsTakenAndOfHundredAndOneIsDropped) {
  std::string hundred(100, '1');
  EXPECT_EQ(feed(rx, sel(5, 20500, hundred.c_str())), ack(5));
  EXPECT_EQ(r.last_value.size(), 100U);
  rx.receive(kEot, Time{0});
  // 101 characters cannot be built as a Value: write the bytes by hand.
  Bytes t;
  t(kEot)(0x45)(kStx)("20500=")(std::string(101, '1'))(kEtx)(0);
  EXPECT_EQ(feed(rx, t.v), kNone);  // LB-D4
  EXPECT_EQ(r.selects, 1);
}

TEST_F(ReceiverTest, BroadcastSelectIsTakenAndNeverAnswered) {
  EXPECT_EQ(feed(rx, sel(31, 105, "03E8")), kNone);
  EXPECT_EQ(r.selects, 1);
  EXPECT_TRUE(r.last_ctx.broadcast());
  EXPECT_EQ(rx.last_event(), ReceiverEvent::broadcast);
  auto t = sel(31, 105, "03E8");
  t.back() ^= 1;
  rx.receive(kEot, Time{0});
  EXPECT_EQ(feed(rx, t), kNone);
  EXPECT_EQ(r.checksum_errors, 1);
}

// ---- addresses (4.2) ---------------------------------------------------------------------------

TEST(ReceiverAddresses, ZeroReachesEveryDeviceOwnOnlyItself) {
  for (Address own = 1; own <= 30; ++own) {
    RecordingResponder r;
    Receiver rx(r, own);
    EXPECT_EQ(feed(rx, enq(0, "00091")).size(), 14U) << int(own);
    rx.receive(kEot, Time{0});
    for (Address a = 1; a <= 30; ++a) {
      const auto answer = feed(rx, enq(a, "00091"));
      if (a == own) {
        ASSERT_EQ(answer.size(), 14U);
        EXPECT_EQ(answer[0], address_char(a));
      } else {
        EXPECT_TRUE(answer.empty()) << int(own) << " " << int(a);
      }
      rx.receive(kEot, Time{0});
    }
  }
}

TEST(ReceiverAddresses, AnswerCarriesTheAddressItWasCalledWith) {
  RecordingResponder r;
  Receiver rx(r, 9);
  EXPECT_EQ(feed(rx, sel(0, 105, "03E8")), ack(0));  // '@' (6.2.2)
  rx.receive(kEot, Time{0});
  EXPECT_EQ(feed(rx, sel(9, 105, "03E8")), ack(9));
}

TEST(ReceiverAddresses, DeviceWithoutAddressAnswersOnlyZero) {
  RecordingResponder r;
  Receiver rx(r, 0);
  EXPECT_EQ(feed(rx, enq(1, "00091")), kNone);
  rx.receive(kEot, Time{0});
  EXPECT_EQ(feed(rx, enq(0, "00091")).size(), 14U);
}

TEST(ReceiverAddresses, AddressCharactersAre40To5F) {
  EXPECT_EQ(address_from_char(0x3F), std::nullopt);
  EXPECT_EQ(address_from_char(0x40), 0);
  EXPECT_EQ(address_from_char(0x5F), 31);
  EXPECT_EQ(address_from_char(0x60), std::nullopt);
}

// ---- EOT, no timeout, BCC as any byte -----------------------------------------------------------

TEST_F(ReceiverTest, EotResetsAFragmentAtEveryPosition) {
  const auto t = sel(5, 105, "03E8");
  for (std::size_t cut = 1; cut + 1 < t.size(); ++cut) {  // the last byte (BCC) is any byte
    for (std::size_t i = 0; i < cut; ++i) rx.receive(t[i], Time{0});
    EXPECT_EQ(feed(rx, t), ack(5)) << cut;  // t starts with EOT
    rx.receive(kEot, Time{0});
  }
}

// LUSTBUS manual 3: "strictly as a state-machine without timeout monitoring" -- the device as the seed
// describes it, with the fragment timeout off.
TEST_F(ReceiverTest, WithTheFragmentTimeoutOffItWaitsForEver) {
  rx.set_inter_char_timeout(Duration::zero());
  const auto t = enq(5, "00112");
  Time now{0};
  for (const auto b : t) {
    rx.receive(b, now);
    now += 3600s;
  }
  EXPECT_EQ(rx.take_answer(now).size(), 14U);
}

// A SELECT to address 5 whose BCC is 04H (EOT): the case of issue 23, defect 2.
std::vector<std::uint8_t> select_whose_bcc_is_eot() {
  for (unsigned v = 0; v <= 0xFFFF; ++v) {
    char value[8];
    std::snprintf(value, sizeof value, "%04X", v);
    auto t = sel(5, 5, value);
    if (t.back() == kEot) return t;
  }
  return {};
}

// LB-D23 (issue 23, defect 2): a host sends a SELECT without its BCC and dies; the next host opens
// with EOT. Without a timeout that EOT is the BCC (2.2) and completes the dead host's telegram.
TEST_F(ReceiverTest, AFragmentFollowedBySilenceIsDroppedAndCounted) {
  const auto t = select_whose_bcc_is_eot();
  ASSERT_FALSE(t.empty());
  EXPECT_EQ(rx.inter_char_timeout(), inter_char_timeout(9600)) << "the factory rate's until set";
  EXPECT_EQ(inter_char_timeout(9600), 50ms) << "20 characters are 20.8 ms: the 50 ms floor";
  EXPECT_EQ(inter_char_timeout(2400), 83333333ns) << "20 characters of 10 bits at 2400 Bd";
  Time now{0};
  for (std::size_t i = 0; i + 1 < t.size(); ++i) rx.receive(t[i], now);  // all but the BCC
  now += rx.inter_char_timeout() + 1ms;
  EXPECT_EQ(feed(rx, enq(5, "00112"), now).size(), 14U) << "the next host's ENQUIRY is answered";
  EXPECT_EQ(rx.counters().selects, 0U) << "the dead host's SELECT was not taken";
  EXPECT_EQ(r.telegrams, 1);
  EXPECT_EQ(rx.counters().fragments, 1U);
  // Within the timeout the byte after ETX is the BCC, whatever it is (2.2): here the EOT.
  rx.receive(kEot, now);
  for (std::size_t i = 0; i + 1 < t.size(); ++i) rx.receive(t[i], now);
  EXPECT_EQ(feed(rx, {kEot}, now + rx.inter_char_timeout()), ack(5));
  EXPECT_EQ(rx.counters().selects, 1U);
  EXPECT_EQ(rx.counters().fragments, 1U);
}

// The attack of issue 23 at every byte position: a host dies after any byte of a SELECT (here
// the one whose BCC would be EOT) and the next host sends its own after the silence. The next
// host's SELECT is the one taken and answered; the dead host's value never reaches the drive.
TEST(ReceiverCuts, ASelectCutAtAnyByteIsNeverCompletedByTheNextHost) {
  const auto dead = select_whose_bcc_is_eot();
  ASSERT_FALSE(dead.empty());
  for (std::size_t cut = 1; cut < dead.size(); ++cut) {
    RecordingResponder r;
    Receiver rx{r, 5};
    Time now{0};
    for (std::size_t i = 0; i < cut; ++i) rx.receive(dead[i], now);
    now += rx.inter_char_timeout() + 1ms;
    EXPECT_EQ(feed(rx, sel(5, 105, "03E8"), now), ack(5)) << "cut after byte " << cut;
    EXPECT_EQ(r.selects, 1) << "cut after byte " << cut;
    EXPECT_EQ(r.last_value.view(), "03E8") << "cut after byte " << cut;
    // A fragment is a telegram whose ADR came: a lone EOT is none.
    EXPECT_EQ(rx.counters().fragments, cut >= 2 ? 1U : 0U) << "cut after byte " << cut;
  }
}

// Likewise an ENQUIRY cut at any byte: the next host's ENQUIRY is answered, once.
TEST(ReceiverCuts, AnEnquiryCutAtAnyByteLeavesTheNextHostsAnswered) {
  const auto dead = enq(5, "00105");
  for (std::size_t cut = 1; cut < dead.size(); ++cut) {
    RecordingResponder r;
    Receiver rx{r, 5};
    Time now{0};
    for (std::size_t i = 0; i < cut; ++i) rx.receive(dead[i], now);
    now += rx.inter_char_timeout() + 1ms;
    EXPECT_EQ(feed(rx, enq(5, "00112"), now).size(), 14U) << "cut after byte " << cut;
    EXPECT_EQ(r.enquiries, 1) << "cut after byte " << cut;
    EXPECT_EQ(rx.counters().fragments, cut >= 2 ? 1U : 0U) << "cut after byte " << cut;
  }
}

TEST_F(ReceiverTest, SilenceOutsideAFragmentDropsNothing) {
  Time now{0};
  EXPECT_EQ(feed(rx, enq(5, "00112"), now).size(), 14U);
  now += 10s;  // waiting for EOT after the answer
  rx.receive(kEot, now);
  now += 10s;  // idle
  EXPECT_EQ(feed(rx, sel(5, 105, "03E8"), now), ack(5));
  EXPECT_EQ(rx.counters().fragments, 0U);
}

TEST_F(ReceiverTest, ByteAfterEtxIsTheBccEvenWhenItIsEot) {
  const auto t = sel(5, kPosmodCode.number(), "1?");
  ASSERT_EQ(t.back(), kEot);
  EXPECT_EQ(feed(rx, t), ack(5));
  EXPECT_EQ(r.last_value.view(), "1?");
}

TEST_F(ReceiverTest, NothingIsAnsweredUntilEotAfterAnAnswer) {
  EXPECT_EQ(feed(rx, enq(5, "00112")).size(), 14U);
  // Without EOT, a second telegram is not taken.
  EXPECT_EQ(feed(rx, Bytes{}(0x45)("00112")(kEnq).v), kNone);
  EXPECT_EQ(r.enquiries, 1);
}

// ---- timing of the answer (10) and deferred answers (10.2) ---------------------------------------

TEST_F(ReceiverTest, AnswerIsDueAfterTheReactionTime) {
  r.enquiry_answer = EnquiryAnswer::text(make_value("03E8"), 60ms);
  for (const auto b : enq(5, "00112")) rx.receive(b, Time{1s});
  ASSERT_TRUE(rx.answer_due().has_value());
  EXPECT_EQ(*rx.answer_due(), Time{1s} + 60ms);
  EXPECT_TRUE(rx.take_answer(Time{1s} + 59ms).empty());
  EXPECT_EQ(rx.take_answer(Time{1s} + 60ms).size(), 14U);
  EXPECT_FALSE(rx.answer_due().has_value());
}

TEST_F(ReceiverTest, EotBeforeTheAnswerIsSentDropsIt) {
  r.enquiry_answer = EnquiryAnswer::text(make_value("03E8"), 60ms);
  for (const auto b : enq(5, "00112")) rx.receive(b, Time{0});
  rx.receive(kEot, Time{10ms});
  EXPECT_TRUE(rx.take_answer(Time{1s}).empty());
  EXPECT_EQ(rx.counters().cut_answers, 1U);
  EXPECT_EQ(rx.counters().answers, 0U);
  // An answer taken before the EOT is no cut one.
  r.enquiry_answer = EnquiryAnswer::text(make_value("03E8"), 0ms);
  EXPECT_EQ(feed(rx, enq(5, "00112"), Time{2s}).size(), 14U);
  rx.receive(kEot, Time{3s});
  EXPECT_EQ(rx.counters().cut_answers, 1U);
  EXPECT_EQ(rx.counters().answers, 1U);
}

TEST_F(ReceiverTest, DeferredSelectAnswerIsDeliveredLater) {
  r.select_answer = SelectAnswer::deferred();
  for (const auto b : sel(5, 105, "03E8")) rx.receive(b, Time{0});
  EXPECT_EQ(rx.state(), ReceiverState::deferred);
  EXPECT_FALSE(rx.answer_due().has_value());
  EXPECT_FALSE(rx.deliver_enquiry(EnquiryAnswer::nak(), Time{0}));  // wrong kind
  EXPECT_TRUE(rx.deliver_select(SelectAnswer::ack(), Time{120ms}));
  EXPECT_EQ(test::to_vector(rx.take_answer(Time{120ms})), ack(5));
}

TEST_F(ReceiverTest, DeferredAnswerAfterEotIsDropped) {
  r.enquiry_answer = EnquiryAnswer::deferred();
  for (const auto b : enq(5, "00112")) rx.receive(b, Time{0});
  rx.receive(kEot, Time{1ms});
  EXPECT_FALSE(rx.deliver_enquiry(EnquiryAnswer::text(make_value("0001")), Time{2ms}));
  EXPECT_TRUE(rx.take_answer(Time{1s}).empty());
  EXPECT_EQ(rx.counters().cut_answers, 1U);
}

TEST_F(ReceiverTest, PowerOnForgetsEverything) {
  for (const auto b : enq(5, "00112")) rx.receive(b, Time{0});
  rx.power_on();
  EXPECT_EQ(rx.state(), ReceiverState::idle);
  EXPECT_TRUE(rx.take_answer(Time{1s}).empty());
}

}  // namespace
}  // namespace ibs::lustbus
