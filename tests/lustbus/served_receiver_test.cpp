// The receiver as a serving loop sees it (base::LineDevice): an answer comes out only once its
// reaction time (10) has passed, time reaches the drive whether or not it hears, and the drive's
// line rate (11.5) is what it says.
#include <gtest/gtest.h>

#include "ibs/lustbus/served_receiver.hpp"
#include "test_support.hpp"

namespace ibs::lustbus {
namespace {

using test::Bytes;
using test::RecordingResponder;
using test::to_vector;

std::vector<std::uint8_t> enq(Address a, const char* code) {
  return Bytes{}(kEot)(address_char(a))(code)(kEnq).v;
}

TEST(ServedReceiver, AnswerComesOutAtItsReactionTimeAndOnlyOnce) {
  RecordingResponder r;
  r.enquiry_answer = EnquiryAnswer::text(make_value("03E8"), 25ms);
  Receiver rx{r, 5};
  ServedReceiver d{&rx};
  EXPECT_FALSE(d.next_due());
  d.receive(enq(5, "00112"), Time{1ms});
  ASSERT_TRUE(d.next_due());
  EXPECT_EQ(*d.next_due(), Time{26ms});
  EXPECT_TRUE(d.output(Time{25ms}).empty());  // not before its time
  const auto a = to_vector(d.output(Time{26ms}));
  EXPECT_EQ(a, (Bytes{}(0x45)(kStx)("00112=03E8")(kEtx)(text_bcc(make_code(112), make_value("03E8"))).v));
  d.written(a.size());
  EXPECT_FALSE(d.next_due());
  EXPECT_TRUE(d.output(Time{100ms}).empty());
}

TEST(ServedReceiver, NoBytesIsNoTelegram) {
  RecordingResponder r;
  Receiver rx{r, 5};
  ServedReceiver d{&rx};
  d.receive({}, Time{1ms});
  EXPECT_EQ(rx.state(), ReceiverState::idle);
  EXPECT_EQ(r.telegrams, 0);
}

TEST(ServedReceiver, TimeAndRateComeFromTheDrive) {
  RecordingResponder r;
  Receiver rx{r, 5};
  Time seen{};
  std::uint32_t rate = 9600;
  ServedReceiver d{&rx, [&](Time t) { seen = t; }, [&] { return rate; }};
  d.advance(Time{7ms});
  EXPECT_EQ(seen, Time{7ms});
  EXPECT_EQ(d.line_baud(), 9600U);
  rate = 19200;  // 4-PROG = 111 (11.5)
  EXPECT_EQ(d.line_baud(), 19200U);
  ServedReceiver plain{&rx};
  plain.advance(Time{9ms});  // no drive hook: nothing happens
  EXPECT_EQ(plain.line_baud(), 0U);  // the port's rate
}

}  // namespace
}  // namespace ibs::lustbus
