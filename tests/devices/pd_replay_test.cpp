// The process-data traces in tests/data, replayed against the device models and the master
// drivers (INTERBUS manual 5.3.4 and the project's own VF1000 traces).
#include <gtest/gtest.h>

#include "ibs/devices/trace_adapters.hpp"

namespace ibs::devices {
namespace {

trace::Trace load(const std::string& name) { return trace::load(std::string(IBS_TEST_DATA_DIR) + "/" + name); }

trace::ReplayResult as_device(const trace::Trace& t) {
  const auto d = make_device_side(t);
  return trace::replay_device(t, *d, *make_explainer(t));
}
trace::ReplayResult as_master(const trace::Trace& t) {
  const auto m = make_master_side(t);
  return trace::replay_master(t, *m, *make_explainer(t));
}

TEST(PdReplay, StartUpTableOf534BothWays) {
  const auto t = load("mc6000_pd_startup_5_3_4.trace");
  const auto d = as_device(t);
  EXPECT_TRUE(d.matched) << d.message;
  EXPECT_EQ(d.steps_matched, 6U);
  const auto m = as_master(t);
  EXPECT_TRUE(m.matched) << m.message;
}

TEST(PdReplay, ManualsLastStatusWord0437IsRefusedByTheDevice) {
  // Erratum E1: 5.3.4 prints 0437H for the last row, without the remote bit 9 that every
  // earlier row shows. The device keeps bit 9; replaying the manual's value must fail there.
  auto t = load("mc6000_pd_startup_5_3_4.trace");
  t.rows.back().s2m[0] = trace::WordPattern::exact(0x0437);
  const auto r = as_device(t);
  EXPECT_FALSE(r.matched);
  EXPECT_NE(r.message.find("cannot reach 0437 09C4 4000"), std::string::npos) << r.message;
}

TEST(PdReplay, FaultResetTraceBothWays) {
  const auto t = load("mc6000_pd_fault_reset.trace");
  EXPECT_TRUE(as_device(t).matched) << as_device(t).message;
  EXPECT_TRUE(as_master(t).matched) << as_master(t).message;
}

TEST(PdReplay, Vf1000StartUpBothWays) {
  const auto t = load("vf1000_pd_startup.trace");
  EXPECT_TRUE(as_device(t).matched) << as_device(t).message;
  EXPECT_TRUE(as_master(t).matched) << as_master(t).message;
}

TEST(PdReplay, Vf1000EmergencyStopRampsDownThenStartUpInhibit) {
  const auto t = load("vf1000_pd_emergency_stop.trace");
  const auto r = as_device(t);
  EXPECT_TRUE(r.matched) << r.message;
}

TEST(PdReplay, MasterThatSkipsShutdownWouldBeCaught) {
  // A hand-edited trace where the master is expected to send ENABLE straight from START-UP
  // INHIBIT: the sequencer sends SHUTDOWN and the replay says so.
  auto t = load("mc6000_pd_startup_5_3_4.trace");
  t.rows[1].m2s[0] = trace::WordPattern::exact(0x000F);
  const auto r = as_master(t);
  EXPECT_FALSE(r.matched);
  EXPECT_NE(r.message.find("actual   0006 09C4 4000  control 0006 SHUTDOWN"), std::string::npos) << r.message;
}

TEST(PdReplay, RefusedConfigurationsAndRequestsNameTheirHeaderLine) {
  const std::string base = "# format: ibs-trace 1\n# device: mc6000\n# words: pd\n";
  try {
    make_device_side(trace::parse(base + "# supi: 7\n# ibcnf: 2\n0, 0000 0000, 0240 0000\n", "s.trace"));
    FAIL();
  } catch (const trace::TraceError& e) {
    // The message is about 406-IBCNF: reported on the ibcnf line (docs/replay.md).
    EXPECT_STREQ(e.what(), "s.trace:5: 406-IBCNF = 2 needs 405-SUPI 10..12, not 7 (INTERBUS manual 3.2.3)");
  }
  try {
    make_master_side(trace::parse(base + "# request: read 405\n0, 0000 0000 0000, 0240 0000 0000\n", "r.trace"));
    FAIL();
  } catch (const trace::TraceError& e) {
    EXPECT_NE(std::string(e.what()).find("r.trace:4: request: 'read 405' is a parameter request"), std::string::npos)
        << e.what();
  }
  try {
    make_device_side(trace::parse("# format: ibs-trace 1\n# device: mc6000\n# words: comm\n0, 0000, 8000\n", "c.trace"));
    FAIL();
  } catch (const trace::TraceError& e) {
    EXPECT_NE(std::string(e.what()).find("c.trace:3: words: comm is not served for device mc6000"), std::string::npos)
        << e.what();
  }
}

TEST(PdReplay, DecodeExplainsTheStartUpTable) {
  const auto t = load("mc6000_pd_startup_5_3_4.trace");
  const auto d = trace::decode(t, *make_explainer(t));
  EXPECT_EQ(d.rows[1].remark,
            "m2s: control 0006 SHUTDOWN; reference 2500.25 rpm; s2m: status 0240 START-UP INHIBIT, "
            "block-power request, e-stop request, remote; actual 0 rpm | command SHUTDOWN");
  EXPECT_NE(d.rows.back().remark.find("status 0637 ENABLED, remote, reference reached; actual 2500.25 rpm"),
            std::string::npos);
}

}  // namespace
}  // namespace ibs::devices
