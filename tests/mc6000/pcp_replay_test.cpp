// `ibs replay` with the PCP adapters: every tests/data/mc6000_pcp_*.trace replays against the
// emulated servo and against the emulated master (trace-format.md, "Replay").
#include <gtest/gtest.h>

#include <string>

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
  // Row 9 carries the servo's first fragment of the Initiate confirmation; make it claim SEQ 1.
  ASSERT_GT(t.rows.size(), 9U);
  t.rows[9].s2m[0] = trace::WordPattern::exact(0xAE80);
  auto device = make_pcp_device_side(t.header);
  auto explain = make_pcp_explainer(t.header);
  const trace::ReplayResult r = trace::replay_device(t, *device, *explain);
  EXPECT_FALSE(r.matched);
  EXPECT_EQ(r.steps_matched, 9U);
  EXPECT_NE(r.message.find("S>M FIRST s0 a3: 80 8B 00 07 00 02 00 (Initiate.conf)"),
            std::string::npos)
      << r.message;
  EXPECT_NE(r.message.find("S>M FIRST s1 a3"), std::string::npos) << r.message;
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
  EXPECT_NE(d.rows[15].remark.find("m2s: M>S FIRST s0 a2: 00 81 00 03 01 02 5D (Read.req)"),
            std::string::npos)
      << d.rows[15].remark;
}

}  // namespace
}  // namespace ibs::devices::mc6000
