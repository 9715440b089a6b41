// Downloading a parameter data set into the emulated CDA3000 with the core's DataSetDownload
// (CANLust manual 4.x "Downloading parameter data sets", p. 48-49; docs/canlust.md D39):
//   "... transferred to the drive controller without individual checking of the parameter
//   values. When the upload is finished the drive controller checks the now complete new data
//   set for plausibility. If the data set is valid the parameters are accepted with the attribute
//   Card Writeable into the EEPROM. The drive is enabled again ..."
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "bus.hpp"
#include "ibs/canlust/data_set.hpp"
#include "ibs/devices/cda3000/bus_face.hpp"
#include "ibs/devices/cda3000/descriptor.hpp"

namespace ibs::devices::cda3000 {
namespace {

using namespace ibs::canlust;
using test::Bus;
using test::commissioned;

const DownloadHandshake& handshake() { return *bus_face().download; }

DownloadResult run(Bus<Master>& b, Master& m, std::vector<DataSetRecord> records) {
  DataSetDownload d(handshake(), 1, std::move(records));
  EXPECT_TRUE(b.run_until_true([&] {
    d.step(m.parameters());
    return d.finished();
  }, 10s));
  return d.result();
}

const Outcome& finish(Bus<Master>& b, Master& m, const Request& r) {
  const auto id = m.parameters().submit(r).id;
  b.run_until_true([&] { return m.parameters().poll(id).state == RequestState::done; }, 5s);
  static const Outcome none{};
  const auto p = m.parameters().poll(id);
  return p.outcome != nullptr ? *p.outcome : none;
}

struct DownloadRow {
  const char* name;
  std::vector<DataSetRecord> records;
  DownloadState state;
  std::size_t step;                // refused / failed: the step
  std::uint8_t status;             // refused: the status bits
  std::uint16_t rejected;          // rejected: the parameter 80-SLOAD names
  std::uint32_t cawdg_after;       // 574-CAWDG, settings and flash
  std::uint32_t cascy_after;       // 575-CASCY
};

const DownloadRow kRows[] = {
    // Valid: both values into the settings and the flash (EEPROM), 80-SLOAD 0.
    {"ValidSetIsTakenIntoTheEeprom", {{kCawdg, 0, 1}, {kCascy, 40, 2}}, DownloadState::downloaded, 0, 0, 0, 0, 40},
    // A value outside its row is taken "without individual checking" and found at the end: the
    // first implausible parameter in 80-SLOAD, nothing taken.
    {"ImplausibleValueRejectsTheWholeSet", {{kCascy, 40, 1}, {kCawdg, 300, 2}}, DownloadState::rejected, 0, 0, kCawdg, 0, 80},
    {"ZeroCascyIsImplausible", {{kCascy, 0, 1}}, DownloadState::rejected, 0, 0, kCascy, 0, 80},
    // 570-CAMOD = MASTER is a value of the row the emulator does not model (D26): implausible.
    {"CamodMasterIsImplausible", {{kCamod, kCamodMaster, 1}}, DownloadState::rejected, 0, 0, kCamod, 0, 80},
    // Not Card Writeable (a command in RAM): refused at its step with 40H; the client drops the
    // download, the old set stays.
    {"SaveIsNoPartOfADataSet", {{kCawdg, 100, 1}, {kSave, 1, 2}}, DownloadState::refused, 2, kStatusChangeNotPermitted, 0, 0, 80},
    {"UnknownParameterIsRefused", {{999, 1, 1}}, DownloadState::refused, 1, kStatusUnknownParameter, 0, 0, 80},
};

class Cda3000Download : public ::testing::TestWithParam<DownloadRow> {};

TEST_P(Cda3000Download, TheWholeSetIsCheckedAtTheEnd) {
  const DownloadRow row = GetParam();
  Master m;
  Bus<Master> b(m);
  b.add(commissioned(1));
  m.system_start();
  b.run_for(5ms);
  const DownloadResult r = run(b, m, row.records);
  EXPECT_EQ(r.state, row.state) << to_string(r.state) << " " << describe(r.outcome);
  if (row.state == DownloadState::refused) {
    EXPECT_EQ(r.step, row.step);
    EXPECT_EQ(r.outcome.status, row.status);
  }
  EXPECT_EQ(r.rejected_parameter, row.rejected);
  EXPECT_FALSE(b.drive(0).downloading());
  EXPECT_EQ(*b.drive(0).value(kCawdg), row.cawdg_after);
  EXPECT_EQ(*b.drive(0).saved_value(kCawdg), row.cawdg_after);
  EXPECT_EQ(*b.drive(0).value(kCascy), row.cascy_after);
  EXPECT_EQ(*b.drive(0).saved_value(kCascy), row.cascy_after);
  // 80-SLOAD as the master reads it afterwards: 0, or the implausible parameter.
  EXPECT_EQ(finish(b, m, read(1, kSload)).value, static_cast<std::uint32_t>(row.rejected));
  // "The drive is enabled again": DRIVECOM walks up.
  const auto ref = *wire_from_hz(ValueWidth::int32q16, 10.0);
  m.send_control(1, {0x0006, ref});
  b.run_for(10ms);
  m.send_control(1, {0x000F, ref});
  b.run_for(10ms);
  EXPECT_EQ(b.drive(0).state(), drivecom::State::enabled);
}

INSTANTIATE_TEST_SUITE_P(DownloadingDataSets, Cda3000Download, ::testing::ValuesIn(kRows),
                         [](const ::testing::TestParamInfo<DownloadRow>& p) { return std::string(p.param.name); });

// The drive is disabled while the set travels: no start before -1 is accepted with the power
// stage on, no enable during the download; a mains reset loses the download and keeps the old set.
TEST(Cda3000Download, TheDriveIsDisabledDuringTheDownload) {
  Master m;
  Bus<Master> b(m);
  b.add(commissioned(1));
  m.system_start();
  b.run_for(5ms);
  const auto ref = *wire_from_hz(ValueWidth::int32q16, 10.0);
  m.send_control(1, {0x0006, ref});
  b.run_for(10ms);
  m.send_control(1, {0x000F, ref});
  b.run_for(10ms);
  ASSERT_EQ(b.drive(0).state(), drivecom::State::enabled);
  const DownloadResult running = run(b, m, {{kCawdg, 100, 1}});
  EXPECT_EQ(running.state, DownloadState::refused);
  EXPECT_EQ(running.step, 0U);
  EXPECT_EQ(running.outcome.status, kStatusChangeNotPermitted);
  m.send_control(1, {0x0002, ref});  // quick stop: at rest, then START-UP INHIBIT
  b.run_for(1s);
  ASSERT_EQ(finish(b, m, write(1, kSload, kSloadStart)).kind, OutcomeKind::done);
  EXPECT_TRUE(b.drive(0).downloading());
  EXPECT_EQ(finish(b, m, read(1, kSload)).value, kSloadStart);
  ASSERT_EQ(finish(b, m, write(1, kCascy, 40)).kind, OutcomeKind::done);
  EXPECT_EQ(*b.drive(0).value(kCascy), 80U);  // nothing acts before the end
  m.send_control(1, {0x0006, ref});
  b.run_for(10ms);
  m.send_control(1, {0x000F, ref});
  b.run_for(10ms);
  EXPECT_EQ(b.drive(0).state(), drivecom::State::start_up_inhibit);
  b.mains_reset(0);
  EXPECT_FALSE(b.drive(0).downloading());
  EXPECT_EQ(*b.drive(0).value(kCascy), 80U);
  EXPECT_EQ(*b.drive(0).value(kSload), 0U);
}

// The end is answered once the set is checked: the reply to -2 comes download_check_time later.
TEST(Cda3000Download, TheEndIsAnsweredAfterTheCheck) {
  Master m;
  Bus<Master> b(m);
  b.add(commissioned(1));
  ASSERT_EQ(finish(b, m, write(1, kSload, kSloadStart)).kind, OutcomeKind::done);
  ASSERT_EQ(finish(b, m, write(1, kCawdg, 20)).kind, OutcomeKind::done);
  Request end = write(1, kSload, kSloadEnd);
  end.timeout = 1s;
  const Outcome& o = finish(b, m, end);
  ASSERT_EQ(o.kind, OutcomeKind::done);
  EXPECT_GE(o.finished - o.started, 200ms);
  EXPECT_EQ(*b.drive(0).saved_value(kCawdg), 20U);
  // -2 without an open download, and codes other than -2, -1, 0, are impermissible.
  EXPECT_EQ(finish(b, m, write(1, kSload, kSloadEnd)).status, kStatusImpermissibleValue);
  EXPECT_EQ(finish(b, m, write(1, kSload, 5)).status, kStatusImpermissibleValue);
}

// Issue 41, canlust_fuzz's "the flash changed without 150-SAVE"
// (fuzz/corpus/canlust_fuzz/drive_rejected_download_then_save): a 150-SAVE after a rejected data
// set. 4.3.3: SAVE backs up the settings; 80-SLOAD is a RAM handshake (D39) that still names the
// implausible parameter, so after the SAVE the flash holds every flash setting but no 80-SLOAD:
// it reads the parameter until a mains reset, then 0. The drive was right; the fuzz oracle
// compared RAM values with the flash.
TEST(Cda3000Download, SaveAfterARejectedSetStoresTheSettingsNotTheHandshake) {
  Master m;
  Bus<Master> b(m);
  b.add(commissioned(1));
  m.system_start();
  b.run_for(5ms);
  ASSERT_EQ(finish(b, m, write(1, kCawdg, 30)).kind, OutcomeKind::done);  // a setting, not yet saved
  const DownloadResult r = run(b, m, {{kCascy, 40, 1}, {kCawmk, 0x10000, 2}});
  ASSERT_EQ(r.state, DownloadState::rejected);
  EXPECT_EQ(r.rejected_parameter, kCawmk);
  EXPECT_EQ(*b.drive(0).value(kCascy), 80U);  // nothing of the rejected set taken
  EXPECT_EQ(*b.drive(0).saved_value(kCascy), 80U);
  EXPECT_EQ(*b.drive(0).saved_value(kCawdg), 0U);
  Request save = write(1, kSave, 1);
  save.timeout = 1s;
  ASSERT_EQ(finish(b, m, save).kind, OutcomeKind::done);
  EXPECT_EQ(*b.drive(0).saved_value(kCawdg), 30U);  // the setting is in flash
  EXPECT_EQ(*b.drive(0).saved_value(kCascy), 80U);
  EXPECT_FALSE(b.drive(0).saved_value(kSload).has_value());  // RAM: no flash copy
  EXPECT_EQ(finish(b, m, read(1, kSload)).value, static_cast<std::uint32_t>(kCawmk));
  b.mains_reset(0);
  EXPECT_EQ(*b.drive(0).value(kCawdg), 30U);
  EXPECT_EQ(*b.drive(0).value(kCascy), 80U);
  EXPECT_EQ(*b.drive(0).value(kSload), 0U);
  for (const auto& p : kParameters) {
    if (p.memory == Memory::flash && !p.is_string()) {
      EXPECT_EQ(b.drive(0).saved_value(p.number), b.drive(0).value(p.number)) << display_name(p);
    }
  }
}

}  // namespace
}  // namespace ibs::devices::cda3000
