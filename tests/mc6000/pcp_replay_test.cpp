// `ibs replay` with the PCP adapters: every tests/data/mc6000_pcp_*.trace replays against the
// emulated servo and against the emulated master (trace-format.md, "Replay").
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "ibs/interbus/replay.hpp"
#include "ibs/interbus/trace.hpp"
#include "ibs/devices/mc6000/pcp_trace.hpp"

namespace ibs::devices::mc6000 {
namespace {

const char* const kTraces[] = {
    "mc6000_pcp_read_4words.trace",
    "mc6000_pcp_read_1word.trace",
    "mc6000_pcp_write_2words.trace",
    "mc6000_pcp_power_on_refusal_4words.trace",
    "mc6000_pcp_read_serr_power_on_2words.trace",
    "mc6000_pcp_describe_4words.trace",
    "mc6000_pcp_read_missing_1word.trace",
};

std::string path(const std::string& name) {
  return std::string(IBS_TEST_DATA_DIR) + "/" + name;
}

class PcpTrace : public ::testing::TestWithParam<const char*> {};

TEST_P(PcpTrace, ReplaysAgainstTheEmulatedServo) {
  const trace::Trace t = trace::load(path(GetParam()));
  auto device = make_pcp_device_side(t.header);
  auto explain = make_pcp_explainer(t.header);
  const trace::ReplayResult r = trace::replay_device(t, *device, *explain);
  EXPECT_TRUE(r.matched) << r.message;
  EXPECT_EQ(r.steps_matched, t.rows.size());
}

TEST_P(PcpTrace, ReplaysAgainstTheEmulatedMaster) {
  const trace::Trace t = trace::load(path(GetParam()));
  ASSERT_TRUE(t.header.request.has_value());
  ASSERT_TRUE(t.header.outcome.has_value()) << "every PCP trace pins the master's report";
  auto master = make_pcp_master_side(t.header);
  auto explain = make_pcp_explainer(t.header);
  const trace::ReplayResult r = trace::replay_master(t, *master, *explain);
  EXPECT_TRUE(r.matched) << r.message;
}

// What the two adapters record in lock-step for a trace's header (the servo and the master of
// pcp/, LatencyModel::immediate, docs/pcp.md "Replay"): rows until the master, reading the last
// row's s2m, has its report; each remark is the explainer's reading of both columns, and a comment
// marks where each side starts a message. The header and the comments before the first row are
// the file's.
trace::Trace record(const trace::Trace& file) {
  trace::Trace out;
  out.file = file.file;
  out.header = file.header;
  out.trailing_comments = file.trailing_comments;
  auto device = make_pcp_device_side(file.header);
  auto master = make_pcp_master_side(file.header);
  auto explain = make_pcp_explainer(file.header);
  std::vector<Word> m2s(master->m2s_words());
  std::vector<Word> s2m(device->s2m_words());
  std::vector<Word> next_m2s(m2s.size());
  std::vector<Word> next_s2m(s2m.size());
  std::vector<trace::WordPattern> row_m2s;
  const auto starts = [](Word before, Word now) {
    // A data frame (TYPE 01 FIRST, or 11 LAST alone) after a control frame (TYPE 00).
    return ((before >> 13U) & 3U) == 0 && ((now >> 13U) & 1U) == 1;
  };
  int master_messages = 0;
  int servo_messages = 0;
  Word last_m = 0;
  Word last_s = 0;
  for (std::uint64_t k = 0; k < 20000; ++k) {
    if (file.header.request && k == file.header.request_at) master->submit(*file.header.request);
    if (k == 0) {
      master->initial(m2s);
      device->initial(s2m);
    } else {
      master->step(s2m, row_m2s, next_m2s);
      device->step(m2s, next_s2m);
      if (master->outcome()) break;  // the master read the previous row's s2m: the file ends there
      m2s = next_m2s;
      s2m = next_s2m;
    }
    trace::Row r;
    r.step = k;
    for (const Word w : m2s) r.m2s.push_back(trace::WordPattern::exact(w));
    for (const Word w : s2m) r.s2m.push_back(trace::WordPattern::exact(w));
    r.remark = explain->explain_m2s(m2s) + "; " + explain->explain_s2m(s2m);
    if (k == 0 && !file.rows.empty()) r.comments_before = file.rows.front().comments_before;
    if (k > 0 && starts(last_m, m2s[0])) {
      r.comments_before.push_back(master_messages++ == 0 ? "# master starts the Initiate request" : "# master starts the request");
    }
    if (k > 0 && starts(last_s, s2m[0])) {
      r.comments_before.push_back(servo_messages++ == 0 ? "# servo starts the Initiate confirmation" : "# servo starts the confirmation");
    }
    last_m = m2s[0];
    last_s = s2m[0];
    row_m2s = r.m2s;
    out.rows.push_back(std::move(r));
  }
  return out;
}

// The golden files are exactly what the adapters record: a change of the link or the servo's
// timing shows here first. `IBS_RECORD_PCP_TRACES=1` writes the recordings over the files (the
// one way to regenerate them, docs/pcp.md "Replay").
TEST_P(PcpTrace, IsWhatTheAdaptersRecord) {
  const trace::Trace t = trace::load(path(GetParam()));
  const trace::Trace r = record(t);
  if (std::getenv("IBS_RECORD_PCP_TRACES") != nullptr) {
    std::ofstream(path(GetParam())) << trace::write(r);
    GTEST_SKIP() << "recorded " << GetParam();
  }
  ASSERT_EQ(r.rows.size(), t.rows.size()) << "rows recorded";
  const auto words = [](const trace::Row& row) {
    std::string w;
    for (const auto& p : row.m2s) w += p.to_string() + " ";
    w += ",";
    for (const auto& p : row.s2m) w += " " + p.to_string();
    return w + ", " + row.remark;
  };
  for (std::size_t k = 0; k < r.rows.size(); ++k) {
    ASSERT_EQ(words(r.rows[k]), words(t.rows[k])) << "row " << k;
  }
}

INSTANTIATE_TEST_SUITE_P(Files, PcpTrace, ::testing::ValuesIn(kTraces), [](const auto& i) {
  std::string n = i.param;
  n = n.substr(0, n.find('.'));
  for (char& c : n) {
    if (c == '_') c = 'X';
  }
  return n;
});

TEST(PcpTraceOutcomes, PinTheMastersReports) {
  EXPECT_EQ(trace::to_string(*trace::load(path("mc6000_pcp_read_4words.trace")).header.outcome),
            "ok 2");
  EXPECT_EQ(trace::load(path("mc6000_pcp_read_1word.trace")).header.outcome->value, 0x2580);
  EXPECT_EQ(trace::load(path("mc6000_pcp_read_serr_power_on_2words.trace")).header.outcome->value,
            0x01);
  EXPECT_EQ(trace::load(path("mc6000_pcp_power_on_refusal_4words.trace")).header.outcome->kind,
            trace::Outcome::Kind::nak);
  EXPECT_EQ(trace::load(path("mc6000_pcp_read_missing_1word.trace")).header.outcome->kind,
            trace::Outcome::Kind::nak);
}

TEST(PcpTraceReplay, ADifferentServoWordIsReportedWithItsMeaning) {
  trace::Trace t = trace::load(path("mc6000_pcp_read_4words.trace"));
  // Row 5 carries the servo's first fragment of the Initiate confirmation; make it claim SEQ 1.
  ASSERT_GT(t.rows.size(), 5U);
  t.rows[5].s2m[0] = trace::WordPattern::exact(0xAD80);
  auto device = make_pcp_device_side(t.header);
  auto explain = make_pcp_explainer(t.header);
  const trace::ReplayResult r = trace::replay_device(t, *device, *explain);
  EXPECT_FALSE(r.matched);
  EXPECT_EQ(r.steps_matched, 5U);
  EXPECT_NE(r.message.find("S>M FIRST s0 a2: 80 8B 00 07 00 02 00 (Initiate.conf)"),
            std::string::npos)
      << r.message;
  EXPECT_NE(r.message.find("S>M FIRST s1 a2"), std::string::npos) << r.message;
}

TEST(PcpTraceReplay, AMasterThatWouldReadAnotherParameterIsCaught) {
  trace::Trace t = trace::load(path("mc6000_pcp_read_4words.trace"));
  t.header.request->parameter = 405;  // the file's words ask for 406
  auto master = make_pcp_master_side(t.header);
  auto explain = make_pcp_explainer(t.header);
  EXPECT_FALSE(trace::replay_master(t, *master, *explain).matched);
}

TEST(PcpTraceAdapters, RefuseHeadersTheyCannotServe) {
  trace::Header h;
  h.device = "mc6000";
  h.words = trace::WordsKind::pd;
  EXPECT_THROW(make_pcp_device_side(h), std::invalid_argument);
  h.words = trace::WordsKind::pcp;
  h.set_setting("supi", 4);  // 1 process-data word, no PCP
  EXPECT_THROW(make_pcp_master_side(h), std::invalid_argument);
  h.set_setting("supi", 12);
  EXPECT_THROW(make_pcp_device_side(h), std::invalid_argument);
  h.set_setting("supi", 9);
  EXPECT_EQ(trace_channel_words(h), 2);
  h.set_setting("supi", 3);
  EXPECT_EQ(trace_channel_words(h), 4);
  h.set_setting("supi", 11);
  EXPECT_EQ(trace_channel_words(h), 1);
  auto master = make_pcp_master_side(h);
  trace::Request state;
  state.kind = trace::Request::Kind::state;
  EXPECT_THROW(master->submit(state), std::invalid_argument);
  // Which drive has a PCP channel is the registry's (Registry.TracesOfAChannelAnotherDriveHasAreRefused).
  h.words = trace::WordsKind::comm;
  EXPECT_THROW(make_pcp_explainer(h), std::invalid_argument);
}

TEST(PcpTraceExplainer, ReadsEveryFrameKind) {
  trace::Header h;
  h.device = "mc6000";
  h.words = trace::WordsKind::pcp;
  h.set_setting("supi", 3);
  auto e = make_pcp_explainer(h);
  const std::array<Word, 4> abort{0x0E00, 0, 0, 0};
  EXPECT_EQ(e->explain_m2s(abort), "M>S ABORT (resynchronise)");
  const std::array<Word, 4> first{0x2600, 0x8100, 0x0301, 0x025D};
  EXPECT_EQ(e->explain_m2s(first), "M>S FIRST s0 a3: 00 81 00 03 01 02 5D (Read.req)");
  const std::array<Word, 4> zero{0, 0, 0, 0};
  EXPECT_EQ(e->explain_s2m(zero), "S>M invalid administrative byte 00H (parity or code)");
  EXPECT_EQ(e->explain_s2m(abort), "S>M wrong direction (master->servo) ABORT (resynchronise)");
}

TEST(PcpTraceDecode, WritesTheExplanationIntoTheRemarks) {
  const trace::Trace t = trace::load(path("mc6000_pcp_read_4words.trace"));
  auto explain = make_pcp_explainer(t.header);
  const trace::Trace d = trace::decode(t, *explain);
  ASSERT_GT(d.rows.size(), 9U);
  EXPECT_NE(d.rows[9].remark.find("m2s: M>S FIRST s3 a2: 00 81 00 03 01 02 5D (Read.req)"),
            std::string::npos)
      << d.rows[9].remark;
}

}  // namespace
}  // namespace ibs::devices::mc6000
