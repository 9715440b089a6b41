// The channel segmentation (docs/pcp.md, "Segmentation"): administrative byte, go-back-N with a
// window of two, message check, resynchronisation.
#include "ibs/pcp/link.hpp"

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <vector>


namespace ibs::pcp {
namespace {

std::vector<std::uint8_t> pdu_of_size(std::size_t size, std::uint8_t seed) {
  std::vector<std::uint8_t> p(size);
  p[0] = 0x00;
  p[1] = 0x81;
  const auto count = static_cast<std::uint16_t>((size - 4) / 2);
  p[2] = high_byte(count);
  p[3] = low_byte(count);
  for (std::size_t i = 4; i < size; ++i) p[i] = static_cast<std::uint8_t>(seed + i * 7U);
  return p;
}

// Two links in the trace's lock-step timing: each reads what the other showed the step before.
struct Pair {
  explicit Pair(int words, Duration timeout = 100ms)
      : a({words, Direction::to_server, timeout}), b({words, Direction::to_client, timeout}) {}
  void step() {
    now += 1ms;
    const auto a_in = b_out;
    const auto b_in = a_out;
    ea = a.receive(now, a_in);
    a.transmit(now, a_out);
    eb = b.receive(now, b_in);
    b.transmit(now, b_out);
  }
  Link a;
  Link b;
  Time now{};
  std::array<Word, 4> a_out{};
  std::array<Word, 4> b_out{};
  LinkEvents ea;
  LinkEvents eb;
};

TEST(AdminByte, RoundTripsEveryFieldCombinationWithOddParity) {
  for (unsigned dir = 0; dir < 2; ++dir) {
    for (unsigned type = 0; type < 4; ++type) {
      for (std::uint8_t seq = 0; seq < 4; ++seq) {
        for (std::uint8_t ack = 0; ack < 4; ++ack) {
          if (type == 0 && seq == 3) continue;  // the invalid control code
          const AdminByte a{static_cast<Direction>(dir), static_cast<FrameType>(type), seq, ack};
          const std::uint8_t b = encode_admin(a);
          EXPECT_EQ(std::popcount(static_cast<unsigned>(b)) % 2, 1) << int(b);
          const auto d = decode_admin(b);
          ASSERT_TRUE(d.has_value()) << int(b);
          EXPECT_EQ(*d, a);
        }
      }
    }
  }
}

TEST(AdminByte, DecodesExactlyTheOddParityBytesWithoutControlCode3) {
  int valid = 0;
  for (unsigned b = 0; b < 256; ++b) {
    const bool odd = std::popcount(b) % 2 == 1;
    const bool control3 = ((b >> 5U) & 3U) == 0 && ((b >> 3U) & 3U) == 3;
    EXPECT_EQ(decode_admin(static_cast<std::uint8_t>(b)).has_value(), odd && !control3) << b;
    valid += decode_admin(static_cast<std::uint8_t>(b)).has_value() ? 1 : 0;
  }
  EXPECT_EQ(valid, 128 - 8);
  // A zeroed or all-ones process image is never a frame.
  EXPECT_FALSE(decode_admin(0x00).has_value());
  EXPECT_FALSE(decode_admin(0xFF).has_value());
}

TEST(AdminByte, HandComputedValuesOfTheDocumentedLayout) {
  // docs/pcp.md example: master ABORT 0EH, servo ABORT-ACK 97H, master IDLE a3 07H,
  // master FIRST s0 a3 26H, servo IDLE a0 80H, master NEXT s1 a3 4FH, servo ABORT 8FH.
  EXPECT_EQ(encode_admin({Direction::to_server, FrameType::control, 1, 3}), 0x0E);
  EXPECT_EQ(encode_admin({Direction::to_client, FrameType::control, 2, 3}), 0x97);
  EXPECT_EQ(encode_admin({Direction::to_server, FrameType::control, 0, 3}), 0x07);
  EXPECT_EQ(encode_admin({Direction::to_server, FrameType::first, 0, 3}), 0x26);
  EXPECT_EQ(encode_admin({Direction::to_client, FrameType::control, 0, 0}), 0x80);
  EXPECT_EQ(encode_admin({Direction::to_server, FrameType::middle, 1, 3}), 0x4F);
  EXPECT_EQ(encode_admin({Direction::to_client, FrameType::control, 1, 3}), 0x8F);
}

TEST(Link, RefusesWidthsOtherThan124) {
  EXPECT_THROW(Link({3, Direction::to_server, 100ms}), std::invalid_argument);
  EXPECT_THROW(Link({0, Direction::to_server, 100ms}), std::invalid_argument);
  EXPECT_NO_THROW(Link({4, Direction::to_server, 100ms}));
}

TEST(Link, OneWordReadRequestCycleByCycle) {
  Pair p(1);
  // Step 0 outputs: both sides start by announcing a reset.
  p.a.transmit(p.now, p.a_out);
  p.b.transmit(p.now, p.b_out);
  EXPECT_EQ(p.a_out[0], 0x0E00);  // master ABORT, abort number 3
  EXPECT_EQ(p.b_out[0], 0x8F00);  // servo ABORT, abort number 3
  p.step();  // both abort: the master's goes first; the servo answers it, the master waits
  EXPECT_EQ(p.a_out[0], 0x0E00);
  EXPECT_EQ(p.b_out[0], 0x9700);  // ABORT-ACK of the master's abort 3
  p.step();  // the master has its answer and answers the servo's abort it noted
  EXPECT_EQ(p.a_out[0], 0x1600);  // ABORT-ACK of the servo's abort 3
  EXPECT_EQ(p.b_out[0], 0x9700);
  p.step();  // the servo has its answer too: ready
  EXPECT_EQ(p.b.state(), LinkState::ready);
  EXPECT_EQ(p.a_out[0], 0x1600);
  EXPECT_EQ(p.b_out[0], 0x8600);
  p.step();  // the master sees IDLE: ready
  EXPECT_EQ(p.a.state(), LinkState::ready);
  EXPECT_EQ(p.b.state(), LinkState::ready);
  EXPECT_EQ(p.a_out[0], 0x0700);
  EXPECT_EQ(p.b_out[0], 0x8600);
  EXPECT_EQ(p.a.stats().aborts_peer, 1U);
  EXPECT_EQ(p.b.stats().aborts_peer, 1U);

  const std::vector<std::uint8_t> read{0x00, 0x81, 0x00, 0x03, 0x07, 0x02, 0x5D, 0x97, 0x00, 0x00};
  ASSERT_TRUE(p.a.send(read));
  std::vector<std::uint8_t> wire;
  std::vector<Word> frames;
  while (!p.eb.message_received) {
    p.step();
    frames.push_back(p.a_out[0]);
    ASSERT_LT(frames.size(), 100U);
  }
  // 10 PDU bytes (no link CRC: INTERBUS checks each cycle) = 10 fragments, one a step: the next
  // fragment goes out before the acknowledgement of the one before comes back (window two).
  // (The receiver reads each frame a step after it was shown: 11 steps.)
  ASSERT_EQ(frames.size(), 11U);
  EXPECT_EQ(frames[0], 0x2600);  // FIRST s0 a3, 00
  EXPECT_EQ(frames[1], 0x4F81);  // NEXT s1 a3, 81
  for (std::size_t i = 0; i < read.size(); ++i) {
    EXPECT_EQ(low_byte(frames[i]), read[i]) << i;
    EXPECT_EQ((high_byte(frames[i]) >> 3U) & 3U, i % 4) << "SEQ of fragment " << i;
  }
  EXPECT_EQ(high_byte(frames[9]) & 0x60, 0x60);  // LAST
  ASSERT_TRUE(p.b.has_message());
  const auto m = p.b.message();
  EXPECT_EQ(std::vector<std::uint8_t>(m.begin(), m.end()), read);
}

TEST(Link, EveryMessageSizeArrivesIntactOverEveryWidth) {
  for (const int words : {1, 2, 4}) {
    Pair p(words);
    for (std::size_t size = kMinPduSize; size <= kMaxPduSize; size += 2) {
      const auto pdu = pdu_of_size(size, static_cast<std::uint8_t>(size));
      while (!p.a.can_send()) p.step();
      ASSERT_TRUE(p.a.send(pdu));
      int steps = 0;
      while (!p.eb.message_received) {
        p.step();
        ASSERT_LT(++steps, 1000) << "width " << words << " size " << size;
      }
      const auto m = p.b.message();
      ASSERT_EQ(std::vector<std::uint8_t>(m.begin(), m.end()), pdu) << "width " << words;
      p.b.release_message();
      // One step per fragment: the window of two covers the round trip of the acknowledgement.
      const std::size_t fragments = (size + frame_data_size(words) - 1) / frame_data_size(words);
      EXPECT_LE(static_cast<std::size_t>(steps), fragments + 2);
    }
    EXPECT_EQ(p.b.stats().messages_dropped, 0U);
  }
}

TEST(Link, RefusesPdusWhoseCountWordIsWrongOrSizeOutOfRange) {
  Pair p(2);
  while (!p.a.can_send()) p.step();
  auto pdu = pdu_of_size(10, 1);
  pdu[3] = 4;  // says 12 bytes
  EXPECT_FALSE(p.a.send(pdu));
  EXPECT_FALSE(p.a.send(pdu_of_size(4, 1)));
  std::vector<std::uint8_t> big(kMaxPduSize + 2, 0);
  EXPECT_FALSE(p.a.send(big));
  EXPECT_TRUE(p.a.send(pdu_of_size(10, 1)));
  EXPECT_FALSE(p.a.send(pdu_of_size(10, 1))) << "one message at a time";
}

// Drives a receiving link with hand-made frames: the peer side of a malformed sender.
struct Injector {
  explicit Injector(int w) : words(w), rx({w, Direction::to_client, 100ms, true}) {}
  LinkEvents frame(FrameType type, std::uint8_t s, std::span<const std::uint8_t> data,
                   std::uint8_t ack = 3) {
    std::array<std::uint8_t, 8> b{};
    b[0] = encode_admin({Direction::to_server, type, s, ack});
    for (std::size_t i = 0; i < data.size() && i + 1 < b.size(); ++i) b[i + 1] = data[i];
    std::array<Word, 4> w{};
    for (std::size_t i = 0; i < 4; ++i) w[i] = make_word(b[2 * i], b[2 * i + 1]);
    now += 1ms;
    return rx.receive(now, w);
  }
  // Sends `bytes` as fragments with consecutive SEQ, the last typed `last_type`.
  LinkEvents message(std::span<const std::uint8_t> bytes, FrameType last_type = FrameType::last) {
    const std::size_t n = frame_data_size(words);
    LinkEvents ev;
    for (std::size_t off = 0; off < bytes.size(); off += n) {
      const std::size_t len = std::min(n, bytes.size() - off);
      const FrameType t =
          off + len == bytes.size() ? last_type : (off == 0 ? FrameType::first : FrameType::middle);
      ev = frame(t, seq, bytes.subspan(off, len));
      seq = static_cast<std::uint8_t>((seq + 1) & 3);
    }
    return ev;
  }
  int words;
  Link rx;
  Time now{};
  std::uint8_t seq = 0;
};

TEST(Link, DeliversAHandMadeMessage) {
  Injector in(2);
  const auto bytes = pdu_of_size(10, 3);
  const LinkEvents ev = in.message(bytes);
  EXPECT_TRUE(ev.message_received);
  EXPECT_EQ(in.rx.stats().messages_received, 1U);
}

// The 6-byte Identify and Status requests fit one 4-word frame: a LAST frame alone carries them.
// Over 1 and 2 words no message fits a frame, and a LAST outside a message is an orphan.
TEST(Link, AMessageOfOneFrameIsALastFrameAloneOverFourWords) {
  const auto pdu = pdu_of_size(6, 9);
  Injector in(4);
  EXPECT_TRUE(in.message(pdu).message_received);
  const auto m = in.rx.message();
  EXPECT_EQ(std::vector<std::uint8_t>(m.begin(), m.end()), pdu);
  Injector narrow(2);
  EXPECT_FALSE(narrow.frame(FrameType::last, 0, std::span<const std::uint8_t>(pdu.data(), 3)).message_received);
  EXPECT_EQ(narrow.rx.stats().fragments_orphaned, 1U);
  // And the sender shows it so.
  Pair p(4);
  while (!p.a.can_send() || p.b.state() != LinkState::ready) p.step();
  ASSERT_TRUE(p.a.send(pdu));
  p.step();
  EXPECT_EQ(high_byte(p.a_out[0]) & 0x60, 0x60);
  while (!p.eb.message_received) p.step();
  EXPECT_EQ(p.b.message().size(), 6U);
}

TEST(Link, DropsAMessageWhoseLastFragmentComesTooEarlyOrTooLate) {
  {
    Injector in(1);
    auto bytes = pdu_of_size(10, 3);
    bytes.pop_back();  // LAST one byte early
    EXPECT_FALSE(in.message(bytes).message_received);
    EXPECT_EQ(in.rx.stats().messages_dropped, 1U);
  }
  {
    Injector in(1);
    auto bytes = pdu_of_size(10, 3);
    bytes.push_back(0);  // LAST one byte late
    EXPECT_FALSE(in.message(bytes).message_received);
    EXPECT_EQ(in.rx.stats().messages_dropped, 1U);
  }
  {
    Injector in(1);
    const auto bytes = pdu_of_size(10, 3);
    in.message(bytes, FrameType::middle);  // never says LAST
    EXPECT_FALSE(in.rx.has_message());
    EXPECT_EQ(in.rx.stats().messages_dropped, 1U);
  }
}

TEST(Link, DropsAMessageWithNonZeroPadding) {
  Injector in(4);  // 10 bytes over 7-byte frames: the last frame has 4 padding bytes
  auto bytes = pdu_of_size(10, 3);
  std::array<std::uint8_t, 7> last{};
  std::copy(bytes.begin() + 7, bytes.end(), last.begin());
  last[6] = 0x55;
  in.frame(FrameType::first, 0, std::span<const std::uint8_t>(bytes.data(), 7));
  EXPECT_FALSE(in.frame(FrameType::last, 1, last).message_received);
  EXPECT_EQ(in.rx.stats().messages_dropped, 1U);
}

TEST(Link, DropsACountWordBeyondTheKblSize) {
  Injector in(2);
  const std::array<std::uint8_t, 3> first{0x00, 0x81, 0x00};
  const std::array<std::uint8_t, 3> next{66, 0x01, 0x02};  // count 66: 136 bytes > 134
  in.frame(FrameType::first, 0, first);
  in.frame(FrameType::middle, 1, next);
  EXPECT_EQ(in.rx.stats().messages_dropped, 1U);
}

TEST(Link, IgnoresRepeatedFramesAndOrphanFragments) {
  Injector in(2);
  const auto bytes = pdu_of_size(10, 3);
  const std::span<const std::uint8_t> s(bytes);
  in.frame(FrameType::first, 0, s.subspan(0, 3));
  in.frame(FrameType::first, 0, s.subspan(0, 3));  // the same frame again: a stale cycle
  in.frame(FrameType::middle, 1, s.subspan(3, 3));
  in.frame(FrameType::middle, 1, s.subspan(3, 3));
  in.frame(FrameType::middle, 2, s.subspan(6, 3));
  in.frame(FrameType::middle, 1, s.subspan(3, 3));  // an older one again
  const LinkEvents ev = in.frame(FrameType::last, 3, s.subspan(9, 1));
  EXPECT_TRUE(ev.message_received);
  EXPECT_EQ(in.rx.stats().frames_repeated, 3U);
  in.rx.release_message();
  // A continuation without a first fragment is never the start of a message.
  in.frame(FrameType::middle, 0, s.subspan(3, 3));
  EXPECT_FALSE(in.frame(FrameType::last, 1, s.subspan(9, 1)).message_received);
  EXPECT_EQ(in.rx.stats().fragments_orphaned, 2U);
}

// Window two: the receiver that missed fragment s sees s + 1 first; it takes nothing out of
// order and waits for the sender to show s again.
TEST(Link, AFrameBeyondTheNextWaitsUntilTheMissedOneComes) {
  Injector in(2);
  const auto bytes = pdu_of_size(10, 3);
  const std::span<const std::uint8_t> s(bytes);
  in.frame(FrameType::first, 0, s.subspan(0, 3));
  EXPECT_FALSE(in.frame(FrameType::middle, 2, s.subspan(6, 3)).reset);
  EXPECT_EQ(in.rx.stats().frames_ahead, 1U);
  in.frame(FrameType::middle, 1, s.subspan(3, 3));
  in.frame(FrameType::middle, 2, s.subspan(6, 3));
  EXPECT_TRUE(in.frame(FrameType::last, 3, s.subspan(9, 1)).message_received);
  const auto m = in.rx.message();
  EXPECT_EQ(std::vector<std::uint8_t>(m.begin(), m.end()), bytes);
}

// An ACK can name only the predecessor of the oldest unacknowledged fragment or one shown since:
// any other is a peer whose state is not ours. Resynchronise.
TEST(Link, AnAckOfAFragmentNeverShownResynchronises) {
  Injector in(2);
  const auto bytes = pdu_of_size(10, 3);
  const LinkEvents ev = in.frame(FrameType::first, 0, std::span<const std::uint8_t>(bytes.data(), 3), 1);
  EXPECT_TRUE(ev.reset);
  EXPECT_EQ(in.rx.state(), LinkState::aborting);
  EXPECT_EQ(in.rx.stats().sequence_errors, 1U);
}

// A sender whose fragment was missed shows it again: the peer sees the window's second fragment
// without the first, and the message still arrives whole, in order, once.
TEST(Link, AMissedFragmentIsShownAgain) {
  Pair p(1);
  while (!p.a.can_send() || p.b.state() != LinkState::ready) p.step();
  const auto pdu = pdu_of_size(10, 4);
  ASSERT_TRUE(p.a.send(pdu));
  p.step();  // FIRST s0 on the channel
  p.step();  // NEXT s1; the servo saw s0
  const auto s1 = p.a_out;
  p.step();
  // The servo's view of the master stood still for a cycle: it sees s1 again, not s2.
  p.a_out = s1;
  int steps = 0;
  while (!p.eb.message_received) {
    p.step();
    ASSERT_LT(++steps, 40);
  }
  const auto m = p.b.message();
  EXPECT_EQ(std::vector<std::uint8_t>(m.begin(), m.end()), pdu);
  EXPECT_EQ(p.b.stats().messages_received, 1U);
}

TEST(Link, RejectsFramesOfTheWrongDirectionAndControlFramesWithData) {
  Link rx({1, Direction::to_client, 100ms, true});
  const std::array<Word, 1> own{
      make_word(encode_admin({Direction::to_client, FrameType::first, 0, 3}), 0)};
  rx.receive(1ms, own);
  const std::array<Word, 1> dirty_idle{
      make_word(encode_admin({Direction::to_server, FrameType::control, 0, 3}), 1)};
  rx.receive(2ms, dirty_idle);
  EXPECT_EQ(rx.stats().frames_invalid, 2U);
  const std::array<Word, 1> zero{0x0000};
  rx.receive(3ms, zero);
  EXPECT_EQ(rx.stats().frames_invalid, 3U);
  EXPECT_EQ(rx.state(), LinkState::ready);
}

TEST(Link, HoldsANewMessageBackUntilTheLastIsReleased) {
  Pair p(4);
  while (!p.a.can_send()) p.step();
  ASSERT_TRUE(p.a.send(pdu_of_size(10, 1)));
  while (!p.ea.message_sent) p.step();
  ASSERT_TRUE(p.b.has_message());
  ASSERT_TRUE(p.a.send(pdu_of_size(12, 2)));
  for (int i = 0; i < 10; ++i) p.step();
  EXPECT_TRUE(p.a.sending()) << "the receiver has not taken the first message yet";
  EXPECT_GT(p.b.stats().frames_refused, 0U);
  EXPECT_EQ(p.b.message().size(), 10U);
  p.b.release_message();
  while (!p.eb.message_received) p.step();
  EXPECT_EQ(p.b.message().size(), 12U);
}

TEST(Link, AnUnacknowledgedFragmentTimesOutIntoAnAbort) {
  Link a({2, Direction::to_server, 50ms, true});
  std::array<Word, 2> out{};
  const std::array<Word, 2> silent{
      make_word(encode_admin({Direction::to_client, FrameType::control, 0, 3}), 0), 0};
  ASSERT_TRUE(a.send(pdu_of_size(10, 1)));
  Time t{};
  a.transmit(t, out);
  LinkEvents ev;
  while (!ev.reset) {
    t += 1ms;
    ev = a.receive(t, silent);
    a.transmit(t, out);
    ASSERT_LE(t, 60ms);
  }
  EXPECT_GE(t, 50ms);
  EXPECT_EQ(a.state(), LinkState::aborting);
  EXPECT_EQ(a.stats().ack_timeouts, 1U);
  // Showing ABORT with abort number 0, the first after the one of the start (3).
  EXPECT_EQ(high_byte(out[0]), 0x08);
  EXPECT_EQ(high_byte(out[0]),
            encode_admin({Direction::to_server, FrameType::control, 1, 0}));
}

TEST(Link, APeerRestartMidMessageResetsTheOtherSide) {
  Pair p(1);
  while (!p.a.can_send() || p.b.state() != LinkState::ready) p.step();
  ASSERT_TRUE(p.a.send(pdu_of_size(20, 5)));
  for (int i = 0; i < 9; ++i) p.step();
  p.b.abort();  // the servo restarts
  bool a_reset = false;
  for (int i = 0; i < 6; ++i) {
    p.step();
    a_reset = a_reset || p.ea.reset;
  }
  EXPECT_TRUE(a_reset);
  EXPECT_FALSE(p.a.sending());
  EXPECT_EQ(p.a.state(), LinkState::ready);
  EXPECT_EQ(p.b.state(), LinkState::ready);
  EXPECT_FALSE(p.b.has_message());
  // And the channel works again.
  ASSERT_TRUE(p.a.send(pdu_of_size(8, 6)));
  while (!p.eb.message_received) p.step();
  EXPECT_EQ(p.b.message().size(), 8U);
}

TEST(Link, SimultaneousAbortsConverge) {
  Pair p(2);
  // The start: nothing on the channel yet, then the same five frames as below.
  for (int i = 0; i < 5; ++i) p.step();
  ASSERT_EQ(p.a.state(), LinkState::ready);
  p.a.abort();
  p.b.abort();
  // The last frames before the aborts, ABORT both ways, the servo's ABORT-ACK, the master's
  // ABORT-ACK, the servo's IDLE.
  for (int i = 0; i < 5; ++i) p.step();
  EXPECT_EQ(p.a.state(), LinkState::ready);
  EXPECT_EQ(p.b.state(), LinkState::ready);
  EXPECT_EQ(p.a.stats().aborts_peer, 2U);  // the start and this one: each side answered both
  EXPECT_EQ(p.b.stats().aborts_peer, 2U);
  ASSERT_TRUE(p.a.send(pdu_of_size(8, 6)));
  while (!p.eb.message_received) p.step();
  EXPECT_EQ(p.b.message().size(), 8U);
}

// The frames a side shows, written out (docs/pcp.md, "Link").
Word master_frame(FrameType type, std::uint8_t seq, std::uint8_t ack, std::uint8_t data = 0) {
  return make_word(encode_admin({Direction::to_server, type, seq, ack}), data);
}
Word servo_frame(FrameType type, std::uint8_t seq, std::uint8_t ack, std::uint8_t data = 0) {
  return make_word(encode_admin({Direction::to_client, type, seq, ack}), data);
}
constexpr std::uint8_t kAbort = static_cast<std::uint8_t>(ControlCode::abort);
constexpr std::uint8_t kAbortAck = static_cast<std::uint8_t>(ControlCode::abort_ack);
constexpr std::uint8_t kIdle = static_cast<std::uint8_t>(ControlCode::idle);

// F1 (docs/robustness.md): a repeated cycle shows an ABORT-ACK of an earlier abort.
TEST(Link, AnAbortAckOfAnEarlierAbortDoesNotEndANewerOne) {
  Link a({1, Direction::to_server, 100ms, true});
  std::array<Word, 1> out{};
  a.abort();  // abort number 0
  a.transmit(Time{}, out);
  EXPECT_EQ(out[0], master_frame(FrameType::control, kAbort, 0));
  (void)a.receive(Time{}, std::array<Word, 1>{servo_frame(FrameType::control, kAbortAck, 0)});
  ASSERT_EQ(a.state(), LinkState::ready);
  a.abort();  // abort number 1
  (void)a.receive(Time{}, std::array<Word, 1>{servo_frame(FrameType::control, kAbortAck, 0)});
  EXPECT_EQ(a.state(), LinkState::aborting) << "the answer to abort 0 ended abort 1";
  (void)a.receive(Time{}, std::array<Word, 1>{servo_frame(FrameType::control, kAbortAck, 1)});
  EXPECT_EQ(a.state(), LinkState::ready);
}

// F1 (the 10-minute run after the first repair): a side that aborts again and again while its
// view of the peer stands still on the answer to an earlier abort must not see that answer come
// round again when the abort number wraps. Aborting again before an answer keeps the number.
TEST(Link, AbortingAgainBeforeTheAnswerKeepsTheAbortNumber) {
  Link b({1, Direction::to_client, 100ms, true});
  std::array<Word, 1> out{};
  b.abort();  // abort number 0
  (void)b.receive(Time{}, std::array<Word, 1>{master_frame(FrameType::control, kAbortAck, 0)});
  ASSERT_EQ(b.state(), LinkState::ready);
  // The master's frame stays ABORT-ACK 0 on the servo's side (its view stands still).
  for (int i = 0; i < 6; ++i) {
    b.abort();
    b.transmit(Time{}, out);
    EXPECT_EQ(out[0], servo_frame(FrameType::control, kAbort, 1)) << "abort " << i;
    (void)b.receive(Time{}, std::array<Word, 1>{master_frame(FrameType::control, kAbortAck, 0)});
    EXPECT_EQ(b.state(), LinkState::aborting) << "abort " << i;
  }
  EXPECT_EQ(b.stats().aborts_local, 7U);
  (void)b.receive(Time{}, std::array<Word, 1>{master_frame(FrameType::control, kAbortAck, 1)});
  EXPECT_EQ(b.state(), LinkState::ready);
}

// F1: a fragment shown before the peer's abort but seen after it belongs to the old link.
TEST(Link, AckingEndsOnlyOnIdleOrTheFirstFragmentOfANewMessage) {
  Link b({1, Direction::to_client, 100ms, true});
  std::array<Word, 1> out{};
  (void)b.receive(Time{}, std::array<Word, 1>{master_frame(FrameType::control, kAbort, 2)});
  ASSERT_EQ(b.state(), LinkState::acking);
  b.transmit(Time{}, out);
  EXPECT_EQ(out[0], servo_frame(FrameType::control, kAbortAck, 2));  // names the abort it answers
  for (const Word old : {master_frame(FrameType::middle, 1, 3, 0x81),
                         master_frame(FrameType::last, 2, 3, 0x55),
                         master_frame(FrameType::first, 1, 3, 0x00)}) {
    const LinkEvents ev = b.receive(Time{}, std::array<Word, 1>{old});
    EXPECT_EQ(b.state(), LinkState::acking) << std::hex << old;
    EXPECT_FALSE(ev.message_received);
  }
  (void)b.receive(Time{}, std::array<Word, 1>{master_frame(FrameType::first, 0, 3, 0x00)});
  EXPECT_EQ(b.state(), LinkState::ready);
  EXPECT_EQ(b.stats().frames_repeated + b.stats().sequence_errors, 0U);
}

// F1: the servo aborts and then sees a master ABORT it cannot tell from an old one on a repeated
// cycle; it answers it, and when the master goes on without answering the servo's own abort, the
// servo announces it again.
TEST(Link, AServoWhoseAbortWentUnansweredAbortsAgain) {
  Link b({1, Direction::to_client, 100ms, true});
  std::array<Word, 1> out{};
  b.abort();  // abort number 0
  (void)b.receive(Time{}, std::array<Word, 1>{master_frame(FrameType::control, kAbort, 1)});
  ASSERT_EQ(b.state(), LinkState::acking);
  b.transmit(Time{}, out);
  EXPECT_EQ(out[0], servo_frame(FrameType::control, kAbortAck, 1));
  // The master is already past that abort: it shows a fragment of a message, then IDLE.
  (void)b.receive(Time{}, std::array<Word, 1>{master_frame(FrameType::first, 0, 3, 0x00)});
  EXPECT_EQ(b.state(), LinkState::aborting);
  EXPECT_EQ(b.stats().aborts_local, 2U);
  b.transmit(Time{}, out);
  EXPECT_EQ(out[0], servo_frame(FrameType::control, kAbort, 1));  // abort number 1
  // Answered this time, the servo is ready.
  (void)b.receive(Time{}, std::array<Word, 1>{master_frame(FrameType::control, kAbortAck, 1)});
  EXPECT_EQ(b.state(), LinkState::ready);
}

// Both abort at once: the master's goes first and the servo's is answered after it.
TEST(Link, WhenBothAbortTheMastersIsAnsweredFirstThenTheServos) {
  Link a({1, Direction::to_server, 100ms, true});
  Link b({1, Direction::to_client, 100ms, true});
  std::array<Word, 1> out{};
  a.abort();
  b.abort();
  (void)a.receive(Time{}, std::array<Word, 1>{servo_frame(FrameType::control, kAbort, 0)});
  EXPECT_EQ(a.state(), LinkState::aborting) << "the master keeps its abort first";
  (void)b.receive(Time{}, std::array<Word, 1>{master_frame(FrameType::control, kAbort, 0)});
  EXPECT_EQ(b.state(), LinkState::acking);
  (void)a.receive(Time{}, std::array<Word, 1>{servo_frame(FrameType::control, kAbortAck, 0)});
  EXPECT_EQ(a.state(), LinkState::acking) << "the master answers the servo's abort it noted";
  a.transmit(Time{}, out);
  EXPECT_EQ(out[0], master_frame(FrameType::control, kAbortAck, 0));
  (void)b.receive(Time{}, out);
  EXPECT_EQ(b.state(), LinkState::ready);
  (void)a.receive(Time{}, std::array<Word, 1>{servo_frame(FrameType::control, kIdle, 3)});
  EXPECT_EQ(a.state(), LinkState::ready);
}

}  // namespace
}  // namespace ibs::pcp
