// ../shared/specs/trace-format.md, "Timing convention", "Gaps", "Replay": the generic engine
// against small fakes whose answers are easy to predict.
#include <gtest/gtest.h>

#include "ibs/interbus/replay.hpp"

namespace ibs::trace {
namespace {

struct HexExplainer final : Explainer {
  std::size_t m2s_words() const override { return 1; }
  std::size_t s2m_words() const override { return 1; }
  std::string explain_m2s(std::span<const Word> w) const override { return "m" + format_words(w); }
  std::string explain_s2m(std::span<const Word> w) const override { return "s" + format_words(w); }
};

// Answers the previous m2s word plus 1: s2m[k] = m2s[k-1] + 1; s2m[0] = 0.
struct EchoDevice final : DeviceSide {
  std::size_t m2s_words() const override { return 1; }
  std::size_t s2m_words() const override { return 1; }
  void initial(std::span<Word> s2m) override { s2m[0] = 0; }
  void step(std::span<const Word> m2s, std::span<Word> s2m) override {
    s2m[0] = static_cast<Word>(m2s[0] + 1);
    ++steps;
  }
  int steps = 0;
};

// Counts its steps and shows the count; ignores its input.
struct CounterDevice final : DeviceSide {
  std::size_t m2s_words() const override { return 1; }
  std::size_t s2m_words() const override { return 1; }
  void initial(std::span<Word> s2m) override { s2m[0] = 0; }
  void step(std::span<const Word> m2s, std::span<Word> s2m) override {
    last_input = m2s[0];
    s2m[0] = ++count;
  }
  Word count = 0;
  Word last_input = 0;
};

// m2s[k] = s2m[k-1] + 2 once the request has arrived; 0 before. Reports ok when it sees 9.
struct PlusTwoMaster final : MasterSide {
  std::size_t m2s_words() const override { return 1; }
  std::size_t s2m_words() const override { return 1; }
  void initial(std::span<Word> m2s) override { m2s[0] = 0; }
  void submit(const Request& r) override {
    submitted = true;
    request = r;
  }
  void step(std::span<const Word> s2m, std::span<const WordPattern>, std::span<Word> m2s) override {
    ++steps;
    m2s[0] = submitted ? static_cast<Word>(s2m[0] + 2) : Word{0};
    if (s2m[0] == 9) done = true;
  }
  std::optional<Outcome> outcome() const override {
    if (!done) return std::nullopt;
    return Outcome{Outcome::Kind::ok, std::nullopt};
  }
  bool submitted = false;
  bool done = false;
  int steps = 0;
  Request request{};
};

Trace make(const std::string& headers, const std::string& rows) {
  return parse("# format: ibs-trace 1\n# device: vf1000\n# words: comm\n" + headers + rows, "t.trace");
}

TEST(ReplayEngine, DeviceAnswersThePreviousRowsM2s) {
  const Trace t = make("", "0, 0005, 0000\n1, 0007, 0006\n2, 0001, 0008\n3, 0000, 0002\n");
  EchoDevice d;
  const auto r = replay_device(t, d, HexExplainer{});
  EXPECT_TRUE(r.matched) << r.message;
  EXPECT_EQ(r.steps_matched, 4U);
  EXPECT_EQ(r.message, "replay: 4 steps matched");
  EXPECT_EQ(d.steps, 3);
}

TEST(ReplayEngine, MismatchNamesStepFileLineExpectedActualAndMeaning) {
  const Trace t = make("", "0, 0005, 0000\n1, 0007, 0006\n2, 0001, 0009, the remark\n");
  EchoDevice d;
  const auto r = replay_device(t, d, HexExplainer{});
  EXPECT_FALSE(r.matched);
  EXPECT_EQ(r.steps_matched, 2U);
  EXPECT_NE(r.message.find("step 2 (t.trace:6) in s2m"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("expected 0009  s0009"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("actual   0008  s0008"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("remark: the remark"), std::string::npos) << r.message;
}

TEST(ReplayEngine, PatternsInExpectedWords) {
  const Trace t = make("", "0, 0005, ????\n1, 0007, 0?0?\n2, 0001, 0008/000F\n");
  EchoDevice d;
  EXPECT_TRUE(replay_device(t, d, HexExplainer{}).matched);
}

TEST(ReplayEngine, GapRunsUntilTheNextRowMatchesWithThePreviousM2s) {
  const Trace t = make("", "0, 0042, 0000\n1, 0043, 0001\n...\n9, 0044, 0007\n10, 0000, 0008\n");
  CounterDevice d;
  const auto r = replay_device(t, d, HexExplainer{});
  EXPECT_TRUE(r.matched) << r.message;
  EXPECT_EQ(d.count, 8);
  EXPECT_EQ(d.last_input, 0x0044);  // the last row answered the m2s of the row before it
}

TEST(ReplayEngine, GapOfZeroStepsIsAllowed) {
  const Trace t = make("", "0, 0000, 0000\n...\n5, 0000, 0001\n");
  CounterDevice d;
  EXPECT_TRUE(replay_device(t, d, HexExplainer{}).matched);
}

TEST(ReplayEngine, GapLongerThanMaxGapFails) {
  const Trace t = make("# max-gap: 3\n", "0, 0000, 0000\n...\n5, 0000, 0006\n");
  CounterDevice d;
  const auto r = replay_device(t, d, HexExplainer{});
  EXPECT_FALSE(r.matched);
  EXPECT_NE(r.message.find("within max-gap 3 steps"), std::string::npos) << r.message;
  const Trace ok = make("# max-gap: 5\n", "0, 0000, 0000\n...\n5, 0000, 0006\n");
  CounterDevice d2;
  EXPECT_TRUE(replay_device(ok, d2, HexExplainer{}).matched);
}

// The mismatch as data (`ibs replay --json`): what the message says, for a program to read.
TEST(ReplayEngine, TheMismatchIsDataToo) {
  EchoDevice d;
  auto r = replay_device(make("", "0, 0005, 0000\n1, 0007, 0006\n2, 0001, 0009/000F\n"), d, HexExplainer{});
  ASSERT_TRUE(r.mismatch.has_value()) << r.message;
  EXPECT_EQ(r.mismatch->kind, Mismatch::Kind::row);
  EXPECT_EQ(r.mismatch->step, 2U);
  EXPECT_EQ(r.mismatch->line, 6U);
  EXPECT_EQ(r.mismatch->column, "s2m");
  ASSERT_EQ(r.mismatch->expected.size(), 1U);
  EXPECT_EQ(r.mismatch->expected[0].to_string(), "???9");  // 0009/000F as the writer writes it
  EXPECT_EQ(r.mismatch->actual, std::vector<Word>{0x0008});
  CounterDevice c;
  r = replay_device(make("# max-gap: 3\n", "0, 0000, 0000\n...\n5, 0000, 0006\n"), c, HexExplainer{});
  ASSERT_TRUE(r.mismatch.has_value()) << r.message;
  EXPECT_EQ(r.mismatch->kind, Mismatch::Kind::gap);
  EXPECT_EQ(r.mismatch->step, 5U);
  EXPECT_EQ(r.mismatch->actual, std::vector<Word>{0x0004});  // the last the device showed in the gap
  PlusTwoMaster m;
  r = replay_master(make("# request: read 1\n# request-at: 0\n", "0, 0000, 0001\n1, 0003, 0001\n...\n7, 0004, 0005\n"),
                    m, HexExplainer{});
  ASSERT_TRUE(r.mismatch.has_value()) << r.message;
  EXPECT_EQ(r.mismatch->kind, Mismatch::Kind::gap);
  EXPECT_EQ(r.mismatch->column, "m2s");
  PlusTwoMaster m2;
  r = replay_master(make("# request: read 5\n# outcome: timeout\n", "0, 0000, 0001\n1, 0003, 0009\n"), m2, HexExplainer{});
  ASSERT_TRUE(r.mismatch.has_value()) << r.message;
  EXPECT_EQ(r.mismatch->kind, Mismatch::Kind::outcome);
  EXPECT_EQ(r.mismatch->expected_outcome, "timeout");
  EXPECT_EQ(r.mismatch->actual_outcome, std::optional<std::string>("ok"));
  EchoDevice ok;
  EXPECT_FALSE(replay_device(make("", "0, 0005, 0000\n1, 0007, 0006\n"), ok, HexExplainer{}).mismatch.has_value());
}

TEST(ReplayEngine, DrivingWordsMustBePlainAndCountsMustFit) {
  EchoDevice d;
  EXPECT_THROW(replay_device(make("", "0, 000?, 0000\n"), d, HexExplainer{}), TraceError);
  try {
    replay_device(make("", "0, 0000 0000, 0000 0000\n"), d, HexExplainer{});
    FAIL();
  } catch (const TraceError& e) {
    EXPECT_NE(std::string(e.what()).find("t.trace:4: this vf1000 with words: comm exchanges 1 m2s and 1 s2m"),
              std::string::npos)
        << e.what();
  }
}

TEST(ReplayEngine, MasterSeesThePreviousS2mAndGetsTheRequestAtItsStep) {
  const Trace t = make("# request: read 5\n# request-at: 2\n# outcome: ok\n",
                       "0, 0000, 0001\n1, 0000, 0003\n2, 0005, 0007\n3, 0009, 0009\n");
  PlusTwoMaster m;
  const auto r = replay_master(t, m, HexExplainer{});
  EXPECT_TRUE(r.matched) << r.message;
  EXPECT_EQ(m.request.parameter, 5);
  EXPECT_EQ(m.steps, 4);  // one more step than rows after the first, to read the last s2m
}

TEST(ReplayEngine, MasterOutcomeIsChecked) {
  const Trace still_running = make("# request: read 5\n# outcome: ok\n", "0, 0000, 0001\n1, 0003, 0004\n");
  PlusTwoMaster m;
  auto r = replay_master(still_running, m, HexExplainer{});
  EXPECT_FALSE(r.matched);
  EXPECT_NE(r.message.find("reports no outcome yet; expected 'ok'"), std::string::npos) << r.message;
  const Trace wrong = make("# request: read 5\n# outcome: timeout\n", "0, 0000, 0001\n1, 0003, 0009\n");
  PlusTwoMaster m2;
  r = replay_master(wrong, m2, HexExplainer{});
  EXPECT_FALSE(r.matched);
  EXPECT_NE(r.message.find("reports 'ok'; expected 'timeout'"), std::string::npos) << r.message;
}

TEST(ReplayEngine, MasterGapHoldsThePreviousWords) {
  // The master keeps seeing 0001 during the gap, so it keeps sending 0003: the row after the gap
  // must be reached by the master's own output.
  const Trace t = make("# request: read 1\n# request-at: 0\n", "0, 0000, 0001\n1, 0003, 0001\n...\n7, 0003, 0005\n8, 0007, 0000\n");
  PlusTwoMaster m;
  EXPECT_TRUE(replay_master(t, m, HexExplainer{}).matched);
  const Trace bad = make("# request: read 1\n# request-at: 0\n", "0, 0000, 0001\n1, 0003, 0001\n...\n7, 0004, 0005\n");
  PlusTwoMaster m2;
  const auto r = replay_master(bad, m2, HexExplainer{});
  EXPECT_FALSE(r.matched);
  EXPECT_NE(r.message.find("gap before step 7"), std::string::npos) << r.message;
}

TEST(ReplayEngine, RequestAtAStepThatIsNotThereIsMalformed) {
  PlusTwoMaster m;
  EXPECT_THROW(replay_master(make("# request: read 1\n# request-at: 9\n", "0, 0000, 0001\n"), m, HexExplainer{}),
               TraceError);
  EXPECT_THROW(replay_master(make("# outcome: ok\n", "0, 0000, 0001\n"), m, HexExplainer{}), TraceError);
}

// Logs what the device is made to do: "d<m2s>" a step with data, "n" one without, "f"/"c" a
// fault present/gone; shows the number of calls so far.
struct LoggingDevice final : DeviceSide {
  std::size_t m2s_words() const override { return 1; }
  std::size_t s2m_words() const override { return 1; }
  void initial(std::span<Word> s2m) override { s2m[0] = 0; }
  void step(std::span<const Word> m2s, std::span<Word> s2m) override {
    log += "d" + std::to_string(m2s[0]) + " ";
    s2m[0] = ++calls;
  }
  void step_without_data(std::span<Word> s2m) override {
    log += "n ";
    s2m[0] = ++calls;
  }
  bool supports(Event::Kind) const override { return true; }
  void apply(const Event& e) override { log += e.kind == Event::Kind::fault ? "f " : "c "; }
  std::string log;
  Word calls = 0;
};

// trace-format.md, "Events": `no-data N` runs N steps without data after the previous row's
// step; the step after the previous row answers its m2s, each later one had no data; an event
// acts before the step that follows it (the timing convention: s2m[k] = D(m2s[k-1])).
TEST(ReplayEngine, StepsWithoutDataRunBetweenTheRowsInTheFilesOrder) {
  const Trace t = make("", "0, 0005, 0000\n! fault\n! no-data 2\n! fault-cleared\n3, 0007, 0003\n"
                           "! no-data 1\n5, 0001, 0005\n6, 0002, 0006\n");
  LoggingDevice d;
  const auto r = replay_device(t, d, HexExplainer{});
  EXPECT_TRUE(r.matched) << r.message;
  EXPECT_EQ(r.steps_matched, 4U);
  // Row 3: the fault before the step answering row 0, two steps (the second without data), the
  // clearing before the last step without data. Row 5: row 3's words, then one without.
  EXPECT_EQ(d.log, "f d5 n c n d7 n d1 ");
  // The master and decode keep the lines and do not act on them: one master step per row.
  PlusTwoMaster m;
  EXPECT_TRUE(replay_master(make("", "0, 0000, 0000\n! no-data 4\n5, 0000, 0001\n"), m, HexExplainer{}).matched);
  EXPECT_EQ(m.steps, 1);
  const Trace decoded = decode(t, HexExplainer{});
  EXPECT_EQ(decoded.rows[1].events_before, t.rows[1].events_before);
}

TEST(ReplayEngine, DecodeExplainsEveryRowAndKeepsTheRemark) {
  const Trace t = make("", "0, 0005, 0000, first\n...\n1, 0007, 00??\n");
  const Trace d = decode(t, HexExplainer{});
  EXPECT_EQ(d.rows[0].remark, "m2s: m0005; s2m: s0000 | first");
  EXPECT_TRUE(d.rows[1].gap);
  EXPECT_EQ(d.rows[2].remark, "m2s: m0007; s2m: s0000 (masked bits shown as 0)");
  // Decoded output is itself a valid trace that replays the same.
  const Trace again = parse(write(d), "again");
  EXPECT_EQ(again.rows.size(), t.rows.size());
}

TEST(ReplayEngine, DecodingADecodedTraceChangesNothing) {
  const Trace t = make("", "0, 0005, 0000, first\n1, 0007, 00??\n2, 0009, 0001\n");
  const std::string once = write(decode(t, HexExplainer{}));
  const std::string twice = write(decode(parse(once, "once"), HexExplainer{}));
  EXPECT_EQ(twice, once);
  // A remark that only looks like a reading of other words is kept after the new one.
  const Trace other = make("", "0, 0005, 0000, m2s: m0006; s2m: s0000\n");
  EXPECT_EQ(decode(other, HexExplainer{}).rows[0].remark,
            "m2s: m0005; s2m: s0000 | m2s: m0006; s2m: s0000");
}

}  // namespace
}  // namespace ibs::trace
