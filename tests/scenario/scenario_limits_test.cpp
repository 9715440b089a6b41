// The INTERBUS limits (public-facts.md, INTERBUS Club FAQ; checked by make_bus_config) reported on
// the line of the first device that breaks one, in both formats.
#include <gtest/gtest.h>

#include <string>

#include "ibs/sim/scenario.hpp"
#include "scenario_errors.hpp"

namespace ibs::sim::test {
namespace {

// `n` devices named d0, d1, ... in both formats. TOML: device k's header is on line 2 + 6k;
// JSON: device k is on line 3 + k.
struct Ring {
  std::string toml;
  std::string json;
};
Ring ring(int n, const std::string& type, int supi, int ibcnf, const std::string& bus) {
  Ring r{"duration = \"1 s\"\n", "{\"duration\": \"1 s\",\n \"device\": [\n"};
  for (int k = 0; k < n; ++k) {
    const std::string name = "d" + std::to_string(k);
    r.toml += "[[device]]\nname = \"" + name + "\"\ntype = \"" + type + "\"\n";
    r.json += "{\"name\": \"" + name + "\", \"type\": \"" + type + "\"";
    if (type == "mc6000") {
      r.toml += "supi = " + std::to_string(supi) + "\nibcnf = " + std::to_string(ibcnf) + "\n";
      r.json += ", \"supi\": " + std::to_string(supi) + ", \"ibcnf\": " + std::to_string(ibcnf);
    } else {
      r.toml += "# no supi\n# no ibcnf\n";  // keep six lines per device
    }
    r.toml += "bus = \"" + bus + "\"\n";
    r.json += ", \"bus\": \"" + bus + "\"}" + (k + 1 < n ? ",\n" : "\n");
  }
  r.json += "]}";
  return r;
}

TEST(ScenarioLimits, RingLayoutOfTheHelper) {
  const Ring r = ring(3, "vf1000", 0, 0, "remote");
  const Scenario t = parse_scenario_toml(r.toml, "r.toml");
  const Scenario j = parse_scenario_json(r.json, "r.json");
  EXPECT_EQ(t, j);
  EXPECT_EQ(t.devices.size(), 3U);
}

TEST(ScenarioLimits, RemoteBusDevices) {
  // SUPI 0 devices occupy one word each, so 255 of them stay within the 256 words.
  EXPECT_NO_THROW((void)parse_scenario_toml(ring(254, "mc6000", 0, 0, "remote").toml, "r.toml"));
  const Ring r = ring(255, "mc6000", 0, 0, "remote");
  const std::string what =
      "bus configuration: device 'd254' (ring position 254): remote bus device number 255 "
      "exceeds the limit of 254 remote bus devices";
  EXPECT_TRUE(refused(r.toml, 2 + 6 * 254, r.json, 3 + 254, what));
}

TEST(ScenarioLimits, LocalBusSegment) {
  EXPECT_NO_THROW((void)parse_scenario_json(ring(63, "mc6000", 0, 0, "local").json, "r.json"));
  const Ring r = ring(64, "mc6000", 0, 0, "local");
  const std::string what =
      "bus configuration: device 'd63' (ring position 63): local bus segment after the master "
      "would hold 64 devices, the limit is 63 per local bus segment";
  EXPECT_TRUE(refused(r.toml, 2 + 6 * 63, r.json, 3 + 63, what));
}

TEST(ScenarioLimits, PcpDevices) {
  // SUPI 1: one PCP word, no process data (INTERBUS manual 3.2.2).
  EXPECT_NO_THROW((void)parse_scenario_toml(ring(62, "mc6000", 1, 0, "remote").toml, "r.toml"));
  const Ring r = ring(63, "mc6000", 1, 0, "remote");
  const std::string what =
      "bus configuration: device 'd62' (ring position 62): PCP device number 63 exceeds the "
      "limit of 62 PCP devices";
  EXPECT_TRUE(refused(r.toml, 2 + 6 * 62, r.json, 3 + 62, what));
}

TEST(ScenarioLimits, ProcessDataWords) {
  // Three words per VF1000: 85 of them use 255 words, the 86th would end at word 258.
  EXPECT_NO_THROW((void)parse_scenario_json(ring(85, "vf1000", 0, 0, "remote").json, "r.json"));
  const Ring r = ring(86, "vf1000", 0, 0, "remote");
  const std::string what =
      "bus configuration: device 'd85' (ring position 85): its 3 words of input data would end "
      "at word 258, the limit is 256 input words (4096 bits)";
  EXPECT_TRUE(refused(r.toml, 2 + 6 * 85, r.json, 3 + 85, what));
}

}  // namespace
}  // namespace ibs::sim::test
