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

// The fault campaign finds each kind's part through the registry (campaign_profile.hpp): a ring
// its descriptor takes, and a model whose start is what the kind's emulator holds and whose
// writes keep to (or, where meant to, leave) the documented ranges.
TEST(Registry, EveryKindHasACampaignProfileTheEmulatorAgreesWith) {
  for (const DriveKind& k : drive_kinds()) {
    SCOPED_TRACE(std::string(k->name()));
    ASSERT_NE(k.campaign, nullptr);
    EXPECT_EQ(k.campaign->kind(), k->name());
    CampaignRandom rng(1);
    const std::vector<CampaignRingDevice> ring = k.campaign->ring(rng);
    ASSERT_FALSE(ring.empty());
    for (const CampaignRingDevice& r : ring) {
      SCOPED_TRACE(r.name);
      EXPECT_NO_THROW(k->check_watchdog(r.settings));
      const Configuration c = k->configure(r.settings);
      EXPECT_LT(r.phase, k->facts().sample_period);
      auto emulator = k.make_emulator(c, DeviceStart::operational, Time{0});
      const CampaignDevice d = k.campaign->device(r, *emulator, rng);
      EXPECT_EQ(d.period, k->facts().sample_period);
      EXPECT_FALSE(d.description.empty());
      EXPECT_EQ(k.campaign->software_resets(*emulator), 0U);
      EXPECT_FALSE(k.campaign->layout_mismatch(*emulator));
      std::vector<CampaignStoreEntry> store;
      k.campaign->read_store(*emulator, store);
      if (!d.has_channel) {
        EXPECT_TRUE(d.params.empty());
        EXPECT_TRUE(store.empty());
        EXPECT_GT(d.watchdog_fixed_ms, 0);
        continue;
      }
      ASSERT_FALSE(d.params.empty());
      EXPECT_FALSE(d.writes.empty());
      const auto watchdog = std::find_if(d.params.begin(), d.params.end(),
                                         [&d](const CampaignParam& p) { return p.number == d.watchdog_parameter; });
      ASSERT_NE(watchdog, d.params.end());
      EXPECT_EQ(watchdog->initial, *r.settings.watchdog_ms);
      for (const CampaignParam& p : d.params) {
        if (p.role == CampaignRole::device_owned) continue;
        SCOPED_TRACE(p.number);
        const auto e = std::find_if(store.begin(), store.end(),
                                    [&p](const CampaignStoreEntry& x) { return x.number == p.number; });
        ASSERT_NE(e, store.end());
        EXPECT_EQ(e->ram, p.initial);
        if (p.eeprom && e->eeprom) {
          EXPECT_EQ(*e->eeprom, p.initial);
        }
        EXPECT_GE(p.factory, p.min);
        EXPECT_LE(p.factory, p.max);
      }
      for (const CampaignWrites& w : d.writes) {
        SCOPED_TRACE(w.number);
        const auto p = std::find_if(d.params.begin(), d.params.end(),
                                    [&w](const CampaignParam& x) { return x.number == w.number; });
        ASSERT_NE(p, d.params.end());
        EXPECT_EQ(p->role, CampaignRole::normal);
        for (const std::int64_t v : w.in_range) EXPECT_TRUE(v >= p->min && v <= p->max) << v;
        for (const std::int64_t v : w.out_of_range) EXPECT_TRUE(v < p->min || v > p->max) << v;
      }
    }
  }
}

// The watchdog's raw value and the channel's timeouts, as the manuals give them.
TEST(Registry, CampaignProfilesTurnWatchdogValuesAndRequestsIntoTimes) {
  const CampaignProfile& vf = *find_drive_kind("vf1000")->campaign;
  EXPECT_EQ(vf.watchdog_ms(65), 100);  // seed 001, 4.1.1: 50 ms steps, rounded up
  EXPECT_EQ(vf.watchdog_ms(100), 100);
  EXPECT_LE(vf.watchdog_ms(65535), 0);  // off
  EXPECT_EQ(vf.request_timeout(ParamOp::write, 71, 1), 2s);
  const CampaignProfile& mc = *find_drive_kind("mc6000")->campaign;
  EXPECT_EQ(mc.watchdog_ms(30), 30);  // 409-BUTWD in ms
  EXPECT_LE(mc.watchdog_ms(0), 0);    // off
  EXPECT_EQ(mc.request_timeout(ParamOp::read, 4, 0), 1s);  // Initiate + request, 500 ms each
  EXPECT_EQ(mc.request_timeout(ParamOp::write, 4, 1), 500ms + 10500ms);  // factory defaults
  ASSERT_TRUE(mc.download().has_value());
  EXPECT_EQ(mc.download()->parameter, 80);
  EXPECT_FALSE(vf.download().has_value());
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
