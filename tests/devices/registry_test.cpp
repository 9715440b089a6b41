// The registry of drive kinds (devices/registry.hpp): every kind builds its emulator and its
// master driver from its descriptor alone, and the drive-neutral parts -- trace adapters, the
// trace reader's vocabulary -- find the drives through it.
#include "ibs/devices/registry.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include "ibs/devices/trace_adapters.hpp"
#include "ibs/drivecom/sequencer.hpp"

namespace ibs::devices {
namespace {

TEST(Registry, ListsEveryDriveKindOnceSortedByName) {
  const auto kinds = drive_kinds();
  ASSERT_FALSE(kinds.empty());
  std::vector<std::string_view> names;
  for (const DriveKind& k : kinds) {
    ASSERT_NE(k.descriptor, nullptr);
    ASSERT_NE(k.make_emulator, nullptr);
    names.push_back(k->name());
    EXPECT_EQ(find_drive_kind(k->name()), &k);
  }
  EXPECT_TRUE(std::is_sorted(names.begin(), names.end()));
  EXPECT_EQ(std::adjacent_find(names.begin(), names.end()), names.end());
  EXPECT_EQ(find_drive_kind("mc7000"), nullptr);
  EXPECT_EQ(drive_kind_names(", ", " or ", "\""), "\"mc6000\" or \"vf1000\"");
}

// Every kind, with the settings its descriptor takes by default: a configuration the bus takes,
// an emulator that samples, a driver that cycles, both with the words the configuration gives.
TEST(Registry, EveryKindBuildsItsEmulatorAndDriverFromItsDescriptor) {
  for (const DriveKind& k : drive_kinds()) {
    SCOPED_TRACE(std::string(k->name()));
    const DriveFacts& f = k->facts();
    EXPECT_FALSE(f.title.empty());
    EXPECT_FALSE(f.unit.empty());
    EXPECT_GT(f.sample_period, Duration{0});
    const Configuration c = k->configure(DeviceSettings{});
    EXPECT_TRUE(c.id_code.decodable());
    EXPECT_EQ(c.id_code.pd_words(), static_cast<int>(c.pd_words));
    EXPECT_EQ(c.id_code.pcp_words(), static_cast<int>(c.pcp_words));

    auto emulator = k.make_emulator(c, DeviceStart::operational, Time{0});
    ASSERT_NE(emulator, nullptr);
    EXPECT_EQ(emulator->state(), drivecom::State::start_up_inhibit);
    std::array<Word, 4> m2s{0x0006, 0, 0, 0};  // SHUTDOWN
    std::array<Word, 4> s2m{};
    std::array<Word, 4> pcp_m2s{};
    std::array<Word, 4> pcp_s2m{};
    emulator->bus_cycle(f.sample_period);
    emulator->sample({std::span<const Word>(m2s.data(), c.pd_words), std::span<Word>(s2m.data(), c.pd_words),
                      std::span<const Word>(pcp_m2s.data(), c.pcp_words), std::span<Word>(pcp_s2m.data(), c.pcp_words)},
                     f.sample_period);
    EXPECT_EQ(emulator->state(), drivecom::State::ready);
    EXPECT_EQ(drivecom::decode_state(s2m[0]), drivecom::State::ready) << std::hex << s2m[0];
    const auto copy = emulator->clone();
    EXPECT_EQ(copy->state(), drivecom::State::ready);
    EXPECT_FALSE(emulator->error_number().has_value());

    auto driver = k->make_driver(c);
    ASSERT_NE(driver, nullptr);
    EXPECT_EQ(driver->unit(), f.unit);
    std::array<Word, 4> out{};
    std::array<Word, 4> pcp_out{};
    const DriverIo io{std::span<const Word>(s2m.data(), c.pd_words), std::span<Word>(out.data(), c.pd_words),
                      std::span<const Word>(pcp_s2m.data(), c.pcp_words), std::span<Word>(pcp_out.data(), c.pcp_words)};
    driver->initial(io);
    driver->sequencer().request(drivecom::Target::on, Time{0});
    driver->cycle(io, f.sample_period);
    EXPECT_EQ(out[0] & drivecom::cw::kDrivecomMask, 0x0007) << "POWER-ON from READY";
    EXPECT_FALSE(k->explain_status(s2m[0]).empty());
  }
}

TEST(Registry, EveryKindRefusesASettingWithTheSettingNamed) {
  for (const DriveKind& k : drive_kinds()) {
    SCOPED_TRACE(std::string(k->name()));
    DeviceSettings s;
    s.watchdog_ms = -1;
    try {
      k->check_watchdog(s);
      ADD_FAILURE() << "a negative watchdog time was taken";
    } catch (const SettingsError& e) {
      EXPECT_EQ(e.setting(), "watchdog_ms") << e.what();
    }
  }
}

TEST(Registry, TheTraceVocabularyIsTheKindsAndDrivecomsTargets) {
  const trace::Vocabulary v = trace_vocabulary();
  ASSERT_EQ(v.devices.size(), drive_kinds().size());
  for (std::size_t i = 0; i < v.devices.size(); ++i) EXPECT_EQ(v.devices[i], drive_kinds()[i]->name());
  EXPECT_EQ(std::vector<std::string_view>(v.targets.begin(), v.targets.end()),
            (std::vector<std::string_view>{"start-up-inhibit", "ready", "on", "enabled"}));
  try {
    (void)parse_trace("# format: ibs-trace 1\n# device: mc7000\n", "x.trace");
    ADD_FAILURE();
  } catch (const trace::TraceError& e) {
    EXPECT_STREQ(e.what(), "x.trace:2: device: 'mc7000' is not one of mc6000, vf1000");
  }
}

// A trace read without the vocabulary still meets the registry before anything runs.
TEST(Registry, AdaptersRefuseAnUnknownDriveOrTargetOnItsHeaderLine) {
  const trace::Trace unknown =
      trace::parse("# format: ibs-trace 1\n# device: cda3000\n# words: pd\n0, 0000, 0240\n", "u.trace");
  try {
    (void)make_device_side(unknown);
    ADD_FAILURE();
  } catch (const trace::TraceError& e) {
    EXPECT_STREQ(e.what(), "u.trace:2: device: 'cda3000' is not one of mc6000, vf1000");
  }
  const trace::Trace target = trace::parse(
      "# format: ibs-trace 1\n# device: vf1000\n# words: pd\n# request: state running\n0, 0000 0000 0000, 0240 0000 0000\n",
      "t.trace");
  try {
    (void)make_master_side(target);
    ADD_FAILURE();
  } catch (const trace::TraceError& e) {
    EXPECT_STREQ(e.what(), "t.trace:4: request: state target 'running' is not one of start-up-inhibit, ready, on, enabled");
  }
}

TEST(Registry, TracesOfAChannelAnotherDriveHasAreRefused) {
  const trace::Trace t =
      trace::parse("# format: ibs-trace 1\n# device: vf1000\n# words: pcp\n0, 0000, 0000\n", "p.trace");
  try {
    (void)make_explainer(t);
    ADD_FAILURE();
  } catch (const trace::TraceError& e) {
    EXPECT_STREQ(e.what(), "p.trace:3: words: pcp is not served for device vf1000 (PCP is the MC6000's)");
  }
}

}  // namespace
}  // namespace ibs::devices
