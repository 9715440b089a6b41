// can-utils' text forms (can_text.hpp): cansend's ID#DATA, candump's filters and its log's time,
// each with the bad input a user types and the column the error names.
#include "ibs/can/can_text.hpp"

#include <gtest/gtest.h>

#include <string>

namespace ibs::can {
namespace {

using canlust::CanFrame;

std::string error_of(std::string_view text) {
  const FrameText r = parse_cansend(text);
  if (r.frame) return "frame";
  return std::to_string(r.error.column) + ": " + r.error.what;
}

TEST(Cansend, ReadsIdHashDataWithDotsAndRemoteFrames) {
  auto r = parse_cansend("373#4002000000000000");
  ASSERT_TRUE(r.frame);
  EXPECT_EQ(*r.frame, CanFrame::make(0x373, {0x40, 0x02, 0, 0, 0, 0, 0, 0}));
  r = parse_cansend("609#");
  ASSERT_TRUE(r.frame);
  EXPECT_EQ(*r.frame, CanFrame::make(0x609, {}));
  r = parse_cansend("7ff#de.ad.BE.ef");
  ASSERT_TRUE(r.frame);
  EXPECT_EQ(*r.frame, CanFrame::make(0x7FF, {0xDE, 0xAD, 0xBE, 0xEF}));
  r = parse_cansend("123#R");
  ASSERT_TRUE(r.frame);
  EXPECT_TRUE(r.frame->rtr);
  EXPECT_EQ(r.frame->dlc, 0);
  r = parse_cansend("123#r8");
  ASSERT_TRUE(r.frame);
  EXPECT_TRUE(r.frame->rtr);
  EXPECT_EQ(r.frame->dlc, 8);
  // Written back as cansend takes it.
  EXPECT_EQ(cansend_text(CanFrame::make(0x21, {0xAB, 0x01})), "021#AB01");
  EXPECT_EQ(cansend_text(*r.frame), "123#R8");
}

TEST(Cansend, BadInputSaysWhatAndWhere) {
  EXPECT_EQ(error_of(""), "1: empty: expected ID#DATA");
  EXPECT_EQ(error_of("373"), "4: no '#' after the identifier");
  EXPECT_EQ(error_of("3G3#00"), "2: 'G' is not a hex digit (the identifier)");
  EXPECT_EQ(error_of("37#00"), "1: the identifier is 3 hex digits (000..7FF), not 2");
  EXPECT_EQ(error_of("0373#00"), "1: the identifier is 3 hex digits (000..7FF), not 4");
  EXPECT_EQ(error_of("12345678#00"),
            "1: an 8-digit identifier is an extended (29-bit) one: CANLust uses 11-bit identifiers, 3 hex digits");
  EXPECT_EQ(error_of("800#00"), "1: identifier 800 is above 7FF (11 bits)");
  EXPECT_EQ(error_of("123##1"), "5: '##' is a CAN FD frame: CANLust uses classic frames only");
  EXPECT_EQ(error_of("123#0"), "5: half a byte: each data byte is 2 hex digits");
  EXPECT_EQ(error_of("123#0.1"), "5: half a byte: each data byte is 2 hex digits");
  EXPECT_EQ(error_of("123#0x12"), "6: 'x' is not a hex digit (the data)");
  EXPECT_EQ(error_of("123#11 22"), "7: ' ' is not a hex digit (the data)");
  EXPECT_EQ(error_of("123#001122334455667788"), "21: more than 8 data bytes");
  EXPECT_EQ(error_of("123#R9"), "6: a remote frame's length is one digit 0..8, not '9'");
  EXPECT_EQ(error_of("123#R12"), "7: '2' after the remote frame's length");
  EXPECT_EQ(error_of(std::string_view("1\x01" "3#", 4)), "2: byte 01H is not a hex digit (the identifier)");
}

TEST(CandumpFilters, MatchAsSocketCanFiltersDo) {
  CanFilterSet s;
  EXPECT_TRUE(s.passes(CanFrame::make(0x123, {})));  // no filter: everything (candump's 0:0)
  ASSERT_FALSE(add_candump_filters("373:7FF", s));
  EXPECT_TRUE(s.passes(CanFrame::make(0x373, {1})));
  EXPECT_FALSE(s.passes(CanFrame::make(0x375, {1})));
  // Repeated: one more filter, either may match.
  ASSERT_FALSE(add_candump_filters("500:700", s));
  EXPECT_TRUE(s.passes(CanFrame::make(0x5AB, {})));
  EXPECT_TRUE(s.passes(CanFrame::make(0x373, {})));
  EXPECT_FALSE(s.passes(CanFrame::make(0x6AB, {})));

  // Inverted, in candump's form and with the '~' first; joined: all must match.
  CanFilterSet inv;
  ASSERT_FALSE(add_candump_filters("300~700,j,~005:00F", inv));
  EXPECT_TRUE(inv.join);
  ASSERT_EQ(inv.filters.size(), 2U);
  EXPECT_TRUE(inv.filters[0].inverted && inv.filters[1].inverted);
  EXPECT_TRUE(inv.passes(CanFrame::make(0x201, {})));
  EXPECT_FALSE(inv.passes(CanFrame::make(0x301, {})));  // 3xx
  EXPECT_FALSE(inv.passes(CanFrame::make(0x205, {})));  // xx5
  CanFilterSet any;
  ASSERT_FALSE(add_candump_filters("300~700,005~00F", any));
  EXPECT_TRUE(any.passes(CanFrame::make(0x301, {})));   // not xx5
  EXPECT_FALSE(any.passes(CanFrame::make(0x305, {})));  // both refuse it

  // The flags: C00007FF wants a standard data frame; an 8-digit ID an extended frame.
  CanFilterSet data_only;
  ASSERT_FALSE(add_candump_filters("123:C00007FF", data_only));
  CanFrame rtr = CanFrame::make(0x123, {});
  rtr.rtr = true;
  EXPECT_TRUE(data_only.passes(CanFrame::make(0x123, {})));
  EXPECT_FALSE(data_only.passes(rtr));
  CanFilterSet ext;
  ASSERT_FALSE(add_candump_filters("00000123:9FFFFFFF", ext));
  EXPECT_EQ(ext.filters[0].id, kCanEffFlag | 0x123U);
  EXPECT_FALSE(ext.passes(CanFrame::make(0x123, {})));
}

std::string filter_error(std::string_view text) {
  CanFilterSet s;
  EXPECT_FALSE(add_candump_filters("100:700", s)) << "the set before";
  const auto e = add_candump_filters(text, s);
  if (!e) return "ok";
  EXPECT_EQ(s.filters.size(), 1U) << "a refused text adds nothing";
  return std::to_string(e->column) + ": " + e->what;
}

TEST(CandumpFilters, BadInputSaysWhatAndWhere) {
  EXPECT_EQ(filter_error(""), "1: an empty filter: expected ID:MASK, ID~MASK or j");
  EXPECT_EQ(filter_error("373:7FF,"), "9: an empty filter: expected ID:MASK, ID~MASK or j");
  EXPECT_EQ(filter_error("373:7FF,,1:1"), "9: an empty filter: expected ID:MASK, ID~MASK or j");
  EXPECT_EQ(filter_error("373"), "4: no ':' or '~' between ID and MASK");
  EXPECT_EQ(filter_error("373:7FF,37G:7FF"), "11: 'G' is not a hex digit (the ID)");
  EXPECT_EQ(filter_error("373:"), "5: the MASK is missing");
  EXPECT_EQ(filter_error(":7FF"), "1: the ID is missing");
  EXPECT_EQ(filter_error("373:7FZ"), "7: 'Z' is not a hex digit (the MASK)");
  EXPECT_EQ(filter_error("123456789:1"), "9: the ID has more than 8 hex digits");
  EXPECT_EQ(filter_error("~1~2"), "3: '~' twice: write ID~MASK (candump's form) or ~ID:MASK");
  EXPECT_EQ(filter_error("#FFFFFFFF"), "1: an error frame filter (#MASK): this bus carries no error frames");
  EXPECT_EQ(filter_error("0x373:7FF"), "2: 'x' is not a hex digit (the ID)");
}

TEST(CandumpTime, SecondsAndUpToSixDigitsOfFraction) {
  EXPECT_EQ(candump_time_us("1795431275.322679"), 1795431275322679LL);
  EXPECT_EQ(candump_time_us("1.5"), 1500000);
  EXPECT_EQ(candump_time_us("0.000001"), 1);
  for (const char* bad : {"", ".5", "1.", "1", "-1.5", "1.5x", "1.1234567", "a.000000", "99999999999999999999.0",
                          "9223372036854.775807"}) {
    EXPECT_FALSE(candump_time_us(bad)) << bad;
  }
}

}  // namespace
}  // namespace ibs::can
