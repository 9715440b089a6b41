// The cycle tables of the INTERBUS manual 4.1.3 (and further comm traces) replayed against both sides, and
// the adapters' mapping between trace requests/outcomes and the channel's.
#include "ibs/vf1000_channel/trace_adapters.hpp"

#include "ibs/devices/vf1000/channel.hpp"
#include "ibs/devices/vf1000/parameters.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "ibs/interbus/replay.hpp"
#include "ibs/interbus/trace.hpp"

namespace {

namespace tr = ibs::trace;
namespace ch = ibs::vf1000_channel;

std::string data_path(const std::string& name) {
  return std::string(IBS_TEST_DATA_DIR) + "/" + name;
}

std::vector<std::string> comm_traces() {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(IBS_TEST_DATA_DIR)) {
    const std::string n = e.path().filename().string();
    if (n.rfind("vf1000_comm_", 0) == 0 && e.path().extension() == ".trace") names.push_back(n);
  }
  std::sort(names.begin(), names.end());
  return names;
}

class CommTrace : public ::testing::TestWithParam<std::string> {};

TEST_P(CommTrace, DeviceSideAnswersEveryRowAsTheFileSays) {
  const tr::Trace t = tr::load(data_path(GetParam()));
  auto device = ch::make_comm_device_side(t.header, ibs::devices::vf1000::parameters(), ibs::devices::vf1000::server_config());
  auto explain = ch::make_comm_explainer();
  const tr::ReplayResult r = tr::replay_device(t, *device, *explain);
  EXPECT_TRUE(r.matched) << r.message;
  EXPECT_EQ(r.steps_matched, t.rows.size()) << r.message;
}

TEST_P(CommTrace, MasterSideSendsEveryRowAsTheFileSaysAndReportsTheOutcome) {
  const tr::Trace t = tr::load(data_path(GetParam()));
  ASSERT_TRUE(t.header.request.has_value()) << GetParam() << " has no request for the master";
  ASSERT_TRUE(t.header.outcome.has_value()) << GetParam() << " has no outcome to check";
  auto master = ch::make_comm_master_side(t.header);
  auto explain = ch::make_comm_explainer();
  const tr::ReplayResult r = tr::replay_master(t, *master, *explain);
  EXPECT_TRUE(r.matched) << r.message;
  EXPECT_EQ(r.steps_matched, t.rows.size()) << r.message;
}

INSTANTIATE_TEST_SUITE_P(AllVf1000CommTraces, CommTrace, ::testing::ValuesIn(comm_traces()),
                         [](const ::testing::TestParamInfo<std::string>& i) {
                           std::string n = i.param.substr(0, i.param.size() - 6);
                           for (char& c : n) {
                             if (c == '.' || c == '-') c = '_';
                           }
                           return n;
                         });

TEST(CommTraceFiles, EveryCycleTableOfSection413IsThere) {
  const auto names = comm_traces();
  for (const char* n : {"vf1000_comm_value_inquiry.trace", "vf1000_comm_value_inquiry_nak.trace",
                        "vf1000_comm_value_transfer.trace", "vf1000_comm_description_scan.trace"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), n), names.end()) << n;
  }
}

// A trace whose inverter word departs from the protocol must fail replay, at the right step.
TEST(CommTraceReplay, DeviceMismatchIsReportedAtItsStep) {
  tr::Trace t = tr::load(data_path("vf1000_comm_value_inquiry.trace"));
  t.rows[4].s2m[0] = tr::WordPattern::exact(0x88E9);  // the manual's value is 3E8H
  auto device = ch::make_comm_device_side(t.header, ibs::devices::vf1000::parameters(), ibs::devices::vf1000::server_config());
  const tr::ReplayResult r = tr::replay_device(t, *device, *ch::make_comm_explainer());
  EXPECT_FALSE(r.matched);
  EXPECT_EQ(r.steps_matched, 4U);
  EXPECT_NE(r.message.find("step 4"), std::string::npos) << r.message;
}

TEST(CommTraceReplay, MasterWithAnotherOutcomeFails) {
  tr::Trace t = tr::load(data_path("vf1000_comm_value_inquiry.trace"));
  t.header.outcome = tr::Outcome{tr::Outcome::Kind::ok, 0x03E9};
  auto master = ch::make_comm_master_side(t.header);
  const tr::ReplayResult r = tr::replay_master(t, *master, *ch::make_comm_explainer());
  EXPECT_FALSE(r.matched) << r.message;
}

TEST(CommTraceReplay, PowerOnInitRefusesWhatOperationalAccepts) {
  tr::Trace t = tr::load(data_path("vf1000_comm_value_transfer.trace"));
  t.header.init = ibs::DeviceStart::initialised;
  auto device = ch::make_comm_device_side(t.header, ibs::devices::vf1000::parameters(), ibs::devices::vf1000::server_config());
  const tr::ReplayResult r = tr::replay_device(t, *device, *ch::make_comm_explainer());
  EXPECT_FALSE(r.matched);
  EXPECT_EQ(r.steps_matched, 2U);  // row 2 shows A000, the power-on inverter B000
}

// Which drive has this channel is the registry's: a `device: mc6000` trace with `words: comm` is
// refused there (PdReplay.RefusedConfigurationsAndRequestsNameTheirHeaderLine).
TEST(CommTraceAdapters, RefuseOtherWordKinds) {
  tr::Header h;
  h.device = "vf1000";
  for (const auto w : {tr::WordsKind::pd, tr::WordsKind::pcp}) {
    h.words = w;
    EXPECT_THROW((void)ch::make_comm_device_side(h, ibs::devices::vf1000::parameters(), ibs::devices::vf1000::server_config()), std::invalid_argument);
    EXPECT_THROW((void)ch::make_comm_master_side(h), std::invalid_argument);
  }
}

TEST(CommTraceAdapters, RefuseStateRequestsAndNumbersAbove3FF) {
  tr::Header h;
  h.device = "vf1000";
  h.words = tr::WordsKind::comm;
  tr::Request state;
  state.kind = tr::Request::Kind::state;
  h.request = state;
  EXPECT_THROW((void)ch::make_comm_master_side(h), std::invalid_argument);
  tr::Request big;
  big.kind = tr::Request::Kind::read;
  big.parameter = 0x400;
  EXPECT_THROW((void)ch::to_channel_request(big), std::invalid_argument);
  tr::Request w;
  w.kind = tr::Request::Kind::write;
  w.parameter = 905;
  w.value = 0x10000;
  EXPECT_THROW((void)ch::to_channel_request(w), std::invalid_argument);
}

TEST(CommTraceAdapters, NegativeWriteValuesAreTwosComplement) {
  tr::Request w;
  w.kind = tr::Request::Kind::write;
  w.parameter = ibs::devices::vf1000::pnr::kFdriv;
  w.value = -20;
  const ch::Request r = ch::to_channel_request(w);
  EXPECT_EQ(r.kind, ch::RequestKind::value_transfer);
  EXPECT_EQ(r.value, 0xFFEC);
}

TEST(CommTraceAdapters, OutcomesMapToTraceOutcomes) {
  ch::Outcome o;
  o.kind = ch::OutcomeKind::value;
  o.value = 0x03E8;
  EXPECT_EQ(ch::to_trace_outcome(o), (tr::Outcome{tr::Outcome::Kind::ok, 0x03E8}));
  o.kind = ch::OutcomeKind::written;
  EXPECT_EQ(ch::to_trace_outcome(o), (tr::Outcome{tr::Outcome::Kind::ok, std::nullopt}));
  o.kind = ch::OutcomeKind::description;
  EXPECT_EQ(ch::to_trace_outcome(o).kind, tr::Outcome::Kind::ok);
  o.kind = ch::OutcomeKind::nak;
  EXPECT_EQ(ch::to_trace_outcome(o).kind, tr::Outcome::Kind::nak);
  for (auto k : {ch::OutcomeKind::timeout, ch::OutcomeKind::inverter_restarted,
                 ch::OutcomeKind::aborted, ch::OutcomeKind::protocol_error}) {
    o.kind = k;
    EXPECT_EQ(ch::to_trace_outcome(o).kind, tr::Outcome::Kind::timeout) << ch::to_string(k);
  }
}

TEST(CommExplainer, ReadsTheManualsWords) {
  auto e = ch::make_comm_explainer();
  const ibs::Word m = 0x2416;
  EXPECT_EQ(e->explain_m2s({&m, 1}), "toggle 1, CODE 1 value inquiry, byte 16H (as PNR: 22)");
  const ibs::Word s = 0xA003;
  EXPECT_EQ(e->explain_s2m({&s, 1}), "ready, toggle 1, data 03H");
  const ibs::Word ack = 0x88E8;
  EXPECT_EQ(e->explain_s2m({&ack, 1}), "ready, toggle 0, ACK, data E8H");
  const ibs::Word nak = 0xB000;
  EXPECT_EQ(e->explain_s2m({&nak, 1}), "ready, toggle 1, NAK, data 00H");
  const ibs::Word init = 0x0000;
  EXPECT_EQ(e->explain_s2m({&init, 1}), "initialising (RESET distinction 0)");
  const ibs::Word idle = 0x0000;
  EXPECT_EQ(e->explain_m2s({&idle, 1}), "starting position (CODE 0)");
  const ibs::Word high = 0x278A;
  EXPECT_EQ(e->explain_m2s({&high, 1}), "toggle 1, CODE 1 value inquiry, byte 8AH (as PNR: 906)");
}

TEST(CommTraceDecode, ExplainsEveryRowAndKeepsTheRemark) {
  const tr::Trace t = tr::load(data_path("vf1000_comm_value_transfer.trace"));
  const tr::Trace d = tr::decode(t, *ch::make_comm_explainer());
  ASSERT_EQ(d.rows.size(), t.rows.size());
  EXPECT_NE(d.rows[6].remark.find("ACK"), std::string::npos) << d.rows[6].remark;
  EXPECT_NE(d.rows[6].remark.find(t.rows[6].remark), std::string::npos) << d.rows[6].remark;
}

}  // namespace
