// Every scenario in examples/ loads, and the three the documentation walks through say what the
// documentation says they do.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>

#include "ibs/devices/registry.hpp"
#include "ibs/sim/scenario.hpp"

namespace ibs::sim {
namespace {

// A device's own setting as its drive reads it: the value given, or its kind's default.
std::int64_t setting_of(const ibs::sim::DeviceConfig& d, std::string_view name) {
  return d.settings.value(*(*ibs::devices::find_drive_kind(d.kind))->setting(name));
}

const std::string kExamples = std::string(IBS_SOURCE_DIR) + "/examples";

std::size_t count(const Scenario& s, Action a) {
  return static_cast<std::size_t>(std::count_if(
      s.timeline.begin(), s.timeline.end(), [&](const TimelineEntry& e) { return e.action == a; }));
}

TEST(ScenarioExamples, EveryExampleLoads) {
  int files = 0;
  for (const auto& f : std::filesystem::directory_iterator(kExamples)) {
    const std::string ext = f.path().extension().string();
    if (ext != ".toml" && ext != ".json") continue;  // e.g. a README
    EXPECT_NO_THROW((void)load_scenario(f.path().string())) << f.path();
    ++files;
  }
  EXPECT_GE(files, 3);
}

TEST(ScenarioExamples, FullBusIsTheBusOfThePerformanceFigures) {
  // 64 MC6000 with four process-data words each: 256 words each way (docs/performance.md).
  const Scenario s = load_scenario(kExamples + "/full_bus.toml");
  ASSERT_EQ(s.devices.size(), 64U);
  for (const auto& d : s.devices) {
    EXPECT_EQ(d.kind, "mc6000") << d.name;
    EXPECT_EQ(setting_of(d, "supi"), 12) << d.name;
    EXPECT_EQ(setting_of(d, "ibcnf"), 2) << d.name;
  }
  EXPECT_EQ(count(s, Action::speed), 64U);
}

TEST(ScenarioExamples, DefaultTomlIsTheBuiltInScenario) {
  EXPECT_EQ(load_scenario(kExamples + "/default.toml"), default_scenario());
}

TEST(ScenarioExamples, FaultsCoversEveryFault) {
  const Scenario s = load_scenario(kExamples + "/faults.toml");
  EXPECT_EQ(s.name, "faults");
  EXPECT_GE(count(s, Action::fault_corrupt), 1U);
  EXPECT_GE(count(s, Action::fault_power_cycle), 1U);
  EXPECT_GE(count(s, Action::fault_device), 1U);
  EXPECT_GE(count(s, Action::fault_lost), 1U);
  EXPECT_GE(count(s, Action::master_restart), 1U);
  EXPECT_GE(count(s, Action::wait_state), 1U);
  EXPECT_NE(s.random, RandomFaults{});
  EXPECT_EQ(s.random.seed, 42U);
  // The power cycle hits a VF1000; the device fault is reset by a later state request.
  const auto power = std::find_if(s.timeline.begin(), s.timeline.end(), [](const TimelineEntry& e) {
    return e.action == Action::fault_power_cycle;
  });
  ASSERT_NE(power, s.timeline.end());
  const auto dev = std::find_if(s.devices.begin(), s.devices.end(),
                                [&](const DeviceConfig& d) { return d.name == power->device; });
  ASSERT_NE(dev, s.devices.end());
  EXPECT_EQ(dev->kind, "vf1000");
  const auto fault = std::find_if(s.timeline.begin(), s.timeline.end(), [](const TimelineEntry& e) {
    return e.action == Action::fault_device;
  });
  ASSERT_NE(fault, s.timeline.end());
  EXPECT_TRUE(std::any_of(fault, s.timeline.end(), [&](const TimelineEntry& e) {
    return e.action == Action::state && e.device == fault->device && e.at > fault->at;
  }));
}

TEST(ScenarioExamples, EstopStopsWhileRunning) {
  const Scenario s = load_scenario(kExamples + "/estop.json");
  EXPECT_EQ(s.name, "estop");
  ASSERT_EQ(count(s, Action::emergency_stop), 2U);
  for (const TimelineEntry& e : s.timeline) {
    if (e.action != Action::emergency_stop) continue;
    // Running: a nonzero reference was set for that device before the stop.
    EXPECT_TRUE(std::any_of(s.timeline.begin(), s.timeline.end(), [&](const TimelineEntry& r) {
      return r.device == e.device && r.at < e.at &&
             (r.action == Action::speed || r.action == Action::frequency) && r.number != 0.0;
    })) << e.device;
  }
}

TEST(ScenarioExamples, LoadRefusesOtherExtensionsAndMissingFiles) {
  try {
    (void)load_scenario("scenario.yaml");
    FAIL();
  } catch (const ScenarioError& e) {
    EXPECT_STREQ(e.what(),
                 "scenario.yaml:0: unknown scenario format: the file name must end in .toml or "
                 ".json");
    EXPECT_EQ(e.line(), 0U);
  }
  try {
    (void)load_scenario(kExamples + "/no-such-file.toml");
    FAIL();
  } catch (const ScenarioError& e) {
    EXPECT_EQ(std::string(e.what()),
              kExamples + "/no-such-file.toml:0: cannot read the file: it does not exist");
  }
  try {
    (void)load_scenario(kExamples + "/.toml");
    FAIL();
  } catch (const ScenarioError& e) {
    EXPECT_EQ(e.line(), 0U);
  }
  const std::string dir = ::testing::TempDir() + "ibs_scenario_dir.toml";
  std::filesystem::create_directories(dir);
  try {
    (void)load_scenario(dir);
    FAIL();
  } catch (const ScenarioError& e) {
    EXPECT_EQ(std::string(e.what()), dir + ":0: cannot read the file: it is a directory");
  }
  std::filesystem::remove(dir);
}

TEST(ScenarioExamples, LoadPicksTheParserByExtension) {
  // The same JSON text in a .toml file is a TOML syntax error; upper-case extensions count.
  const std::string base = ::testing::TempDir() + "ibs_scenario_ext";
  const std::string json = R"({"duration": "1 s", "device": [{"name": "m", "type": "mc6000"}]})";
  for (const std::string ext : {".json", ".JSON", ".toml"}) {
    const std::string path = base + ext;
    {
      std::FILE* f = std::fopen(path.c_str(), "wb");
      ASSERT_NE(f, nullptr);
      std::fputs(json.c_str(), f);
      std::fclose(f);
    }
    if (ext == ".toml") {
      try {
        (void)load_scenario(path);
        FAIL();
      } catch (const ScenarioError& e) {
        EXPECT_EQ(e.line(), 1U);
        EXPECT_NE(std::string(e.what()).find("TOML syntax error"), std::string::npos);
      }
    } else {
      EXPECT_EQ(load_scenario(path).devices.size(), 1U) << ext;
    }
    std::filesystem::remove(path);
  }
}

}  // namespace
}  // namespace ibs::sim
