// The controller's receiver: which frames it answers, NAK 86 for unknown commands and wrong
// lengths, the turnaround delay before the reply, the global 83 without an answer.
#include <gtest/gtest.h>

#include <vector>

#include "ibs/dfs1/controller.hpp"

namespace ibs::dfs1 {
namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes bytes_of(const Frame& f) {
  const EncodedFrame e = encode(f);
  return {e.span().begin(), e.span().end()};
}

class RecordingHandler final : public RequestHandler {
 public:
  Reply handle(const Frame& request, bool global, Time) override {
    seen.push_back(request);
    globals += global ? 1 : 0;
    return Reply::ack();
  }
  std::vector<Frame> seen;
  int globals = 0;
};

TEST(Dfs1Receiver, AnswersItsUidAfterTheTurnaround) {
  RecordingHandler h;
  ControllerReceiver rx(5, 2ms);
  rx.receive(bytes_of(make_frame(5, 0x81)), 10ms, h);
  ASSERT_EQ(h.seen.size(), 1U);
  EXPECT_TRUE(rx.pending(11ms).empty());
  EXPECT_EQ(rx.next_deadline(), Time(12ms));
  const auto p = rx.pending(12ms);
  EXPECT_EQ(Bytes(p.begin(), p.end()), bytes_of(make_ack(5)));
  rx.consume(3);
  EXPECT_EQ(rx.pending(12ms).size(), p.size() - 3);
  rx.consume(100);
  EXPECT_FALSE(rx.replying());
}

TEST(Dfs1Receiver, UnknownCommandIsNak86WithoutTheHandler) {
  RecordingHandler h;
  ControllerReceiver rx(5, 0ms);
  rx.receive(bytes_of(make_frame(5, 0x90)), 0ms, h);
  EXPECT_TRUE(h.seen.empty());
  const auto p = rx.pending(0ms);
  EXPECT_EQ(Bytes(p.begin(), p.end()), bytes_of(make_nak(5, ErrorCode::illegal_command)));
}

TEST(Dfs1Receiver, WrongDataLengthIsNak86) {
  RecordingHandler h;
  ControllerReceiver rx(5, 0ms);
  rx.receive(bytes_of(make_frame(5, 0x85)), 0ms, h);  // read parameter without its number
  EXPECT_TRUE(h.seen.empty());
  const auto p = rx.pending(0ms);
  EXPECT_EQ(Bytes(p.begin(), p.end()), bytes_of(make_nak(5, ErrorCode::illegal_command)));
}

TEST(Dfs1Receiver, FramesForAnotherUidGetNoAnswer) {
  RecordingHandler h;
  ControllerReceiver rx(5, 0ms);
  rx.receive(bytes_of(make_frame(6, 0x81)), 0ms, h);
  rx.receive(bytes_of(make_frame(6, 0x90)), 0ms, h);
  rx.receive(bytes_of(make_ack(5)), 0ms, h);  // another controller's answer with our UID
  EXPECT_TRUE(h.seen.empty());
  EXPECT_FALSE(rx.replying());
  EXPECT_EQ(rx.counters().foreign, 3U);
}

TEST(Dfs1Receiver, GlobalExecuteSpeedIsHandledWithoutAnswer) {
  RecordingHandler h;
  ControllerReceiver rx(5, 0ms);
  rx.receive(bytes_of(make_frame(0, 0x83)), 0ms, h);
  EXPECT_EQ(h.globals, 1);
  EXPECT_FALSE(rx.replying());
  // UID 0 with any other command is ignored (notes: UID 00 only with 83).
  rx.receive(bytes_of(make_frame(0, 0x81)), 0ms, h);
  rx.receive(bytes_of(make_frame(0, 0x90)), 0ms, h);
  EXPECT_EQ(h.seen.size(), 1U);
  EXPECT_FALSE(rx.replying());
}

TEST(Dfs1Receiver, CorruptFramesAreCountedAndNotAnswered) {
  RecordingHandler h;
  ControllerReceiver rx(5, 0ms);
  Bytes b = bytes_of(make_frame(5, 0x81));
  b.back() ^= 0xFF;
  rx.receive(b, 0ms, h);
  EXPECT_TRUE(h.seen.empty());
  EXPECT_FALSE(rx.replying());
  EXPECT_EQ(rx.counters().decode_errors, 1U);
}

// D13 (issue 23, defect 1): a host sends P6 := 99 (checksum 10H, sent doubled) and dies part-way;
// the next host's request, after a silence, must be answered as it is -- at every cut point -- and
// the dead host's write never taken.
TEST(Dfs1Receiver, AFrameCutAtAnyByteIsDroppedAfterSilence) {
  const Bytes write_p6 = {0x10, 0x02, 0x01, 0x86, 0x06, 0x00, 0x00, 0x00, 0x63, 0x10, 0x03, 0x10, 0x10};
  const Bytes status = bytes_of(make_frame(1, 0x81));
  for (std::size_t cut = 1; cut < write_p6.size(); ++cut) {
    RecordingHandler h;
    ControllerReceiver rx(1, 0ms);
    EXPECT_EQ(rx.fragment_timeout(), 50ms) << "20 characters at 9600 Bd are 20.8 ms: the floor";
    rx.receive(Bytes(write_p6.begin(), write_p6.begin() + static_cast<std::ptrdiff_t>(cut)), 0ms, h);
    rx.receive(status, rx.fragment_timeout() + 1ms, h);
    ASSERT_EQ(h.seen.size(), 1U) << "cut after " << cut << " bytes";
    EXPECT_EQ(h.seen[0].code, 0x81) << "cut after " << cut << " bytes";
    EXPECT_EQ(rx.counters().fragments, 1U) << "cut after " << cut << " bytes";
  }
  // The whole frame in pieces within the timeout is one frame.
  RecordingHandler h;
  ControllerReceiver rx(1, 0ms);
  Time now{0};
  for (const std::uint8_t b : write_p6) {
    rx.receive(Bytes{b}, now, h);
    now += rx.fragment_timeout();
  }
  ASSERT_EQ(h.seen.size(), 1U);
  EXPECT_EQ(h.seen[0].code, 0x86);
  EXPECT_EQ(rx.counters().fragments, 0U);
  EXPECT_EQ(fragment_timeout(1200), 166666667ns) << "20 characters of 10 bits at 1200 Bd";
}

}  // namespace
}  // namespace ibs::dfs1
