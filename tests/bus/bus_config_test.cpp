// Bus configuration: placement of devices in the process image and every INTERBUS limit
// (public-facts.md, "Limits").
#include "ibs/interbus/bus_config.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace ibs::interbus {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

constexpr IdCode kMc6000Supi11Remote{0x4DB};  // INTERBUS manual 3.2.2
constexpr IdCode kVf1000{0x33B};              // INTERBUS manual 3.1.2
constexpr IdCode kBusTerminal{0x0008};        // remote bus, no data words
constexpr IdCode kLocalNoData{0x0090};        // local bus (class 9H, type 0), no data words
constexpr IdCode kRemoteIn16{0x1202};         // remote bus, 16 words in (length code 12H)
constexpr IdCode kRemoteOut16{0x1201};        // remote bus, 16 words out
constexpr IdCode kRemotePcp1{0x1DB};          // MC6000 SUPI 1 remote: 1 word PCP only

std::string config_error(const std::vector<DeviceSpec>& ring) {
  try {
    (void)make_bus_config(ring);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(accepted)";
}

// Built with += : GCC 12 reports a false -Wrestrict for "literal" + std::string&& in Release.
std::string numbered(const std::string& prefix, std::size_t n, const std::string& suffix = "") {
  std::string s = prefix;
  s += std::to_string(n);
  s += suffix;
  return s;
}

std::vector<DeviceSpec> many(std::size_t n, IdCode id, const std::string& prefix) {
  std::vector<DeviceSpec> v;
  for (std::size_t i = 0; i < n; ++i) v.push_back({numbered(prefix, i), id, {}});
  return v;
}

TEST(BusConfig, DefaultBusPlacesMc6000ThenVf1000) {
  const std::vector<DeviceSpec> ring{{"mc6000", kMc6000Supi11Remote, {}}, {"vf1000", kVf1000, {}}};
  const BusConfig c = make_bus_config(ring);
  ASSERT_EQ(c.devices.size(), 2U);
  const Device& mc = c.devices[0];
  EXPECT_EQ(mc.ring_position, 0U);
  EXPECT_EQ(mc.bus, BusKind::remote);
  EXPECT_EQ(mc.ring_words, 4U);
  EXPECT_EQ(mc.pd_in_words, 3U);
  EXPECT_EQ(mc.pd_out_words, 3U);
  EXPECT_EQ(mc.pcp_words, 1U);
  EXPECT_EQ(mc.in, (Slice{0, 3}));
  EXPECT_EQ(mc.out, (Slice{0, 3}));
  EXPECT_EQ(mc.pcp, (Slice{0, 1}));
  const Device& vf = c.devices[1];
  EXPECT_EQ(vf.ring_position, 1U);
  EXPECT_EQ(vf.pcp_words, 0U);
  EXPECT_EQ(vf.in, (Slice{3, 3}));
  EXPECT_EQ(vf.out, (Slice{3, 3}));
  EXPECT_EQ(vf.pcp, (Slice{1, 0}));
  EXPECT_EQ(c.in_words, 6U);
  EXPECT_EQ(c.out_words, 6U);
  EXPECT_EQ(c.pcp_words, 1U);
  EXPECT_EQ(c.ring_words, 7U);
  EXPECT_EQ(c.ring_bytes(), 14U);
  EXPECT_EQ(c.remote_devices, 2U);
  EXPECT_EQ(c.pcp_devices, 1U);
  EXPECT_EQ(c.find("vf1000"), &c.devices[1]);
  EXPECT_EQ(c.find("nothing"), nullptr);
}

TEST(BusConfig, InputOnlyAndOutputOnlyDevicesTakeOneImageEach) {
  const std::vector<DeviceSpec> ring{{"di", IdCode{0x0202}, {}},  // 2 words in
                                     {"do", IdCode{0x0101}, {}},  // 1 word out
                                     {"io", IdCode{0x0103}, {}}};
  const BusConfig c = make_bus_config(ring);
  EXPECT_EQ(c.devices[0].in, (Slice{0, 2}));
  EXPECT_EQ(c.devices[0].out, (Slice{0, 0}));
  EXPECT_EQ(c.devices[1].in, (Slice{2, 0}));
  EXPECT_EQ(c.devices[1].out, (Slice{0, 1}));
  EXPECT_EQ(c.devices[2].in, (Slice{2, 1}));
  EXPECT_EQ(c.devices[2].out, (Slice{1, 1}));
  EXPECT_EQ(c.in_words, 3U);
  EXPECT_EQ(c.out_words, 2U);
  EXPECT_EQ(c.ring_words, 4U);
}

TEST(BusConfig, MixedSupiDevicesGetTheirPcpSlicesInRingOrder) {
  const std::vector<DeviceSpec> ring{{"a", IdCode{0x4D9}, {}},   // SUPI 3: 4 words PCP
                                     {"b", IdCode{0x4D8}, {}},   // SUPI 9: 2 PD + 2 PCP
                                     {"c", IdCode{0x47B}, {}}};  // SUPI 12: 4 PD
  const BusConfig c = make_bus_config(ring);
  EXPECT_EQ(c.devices[0].in, (Slice{0, 0}));
  EXPECT_EQ(c.devices[0].pcp, (Slice{0, 4}));
  EXPECT_EQ(c.devices[1].in, (Slice{0, 2}));
  EXPECT_EQ(c.devices[1].pcp, (Slice{4, 2}));
  EXPECT_EQ(c.devices[2].in, (Slice{2, 4}));
  EXPECT_EQ(c.devices[2].pcp, (Slice{6, 0}));
  EXPECT_EQ(c.pcp_devices, 2U);
  EXPECT_EQ(c.ring_words, 12U);
}

TEST(BusConfig, BusKindOverrideAndErrorBitsInTheSpec) {
  const std::vector<DeviceSpec> ring{{"x", IdCode{0x833B}, BusKind::local}};
  const BusConfig c = make_bus_config(ring);
  EXPECT_EQ(c.devices[0].bus, BusKind::local);
  EXPECT_EQ(c.devices[0].id, IdCode{0x33B});
  EXPECT_EQ(c.remote_devices, 0U);
}

TEST(BusConfig, EmptyRingIsAllowed) {
  const BusConfig c = make_bus_config({});
  EXPECT_TRUE(c.devices.empty());
  EXPECT_EQ(c.ring_words, 0U);
}

TEST(BusConfig, ExactlyAtEveryLimitIsAccepted) {
  // 8 segments of (1 remote + 63 local) = 512 devices.
  std::vector<DeviceSpec> ring;
  for (std::size_t s = 0; s < 8; ++s) {
    ring.push_back({numbered("bk", s), kBusTerminal, {}});
    for (const DeviceSpec& d : many(63, kLocalNoData, numbered("l", s, "_"))) {
      ring.push_back(d);
    }
  }
  EXPECT_EQ(make_bus_config(ring).devices.size(), 512U);
  EXPECT_EQ(make_bus_config(many(254, kBusTerminal, "r")).remote_devices, 254U);
  EXPECT_EQ(make_bus_config(many(62, kRemotePcp1, "p")).pcp_words, 62U);
  EXPECT_EQ(make_bus_config(many(16, kRemoteIn16, "i")).in_words, 256U);
  EXPECT_EQ(make_bus_config(many(16, kRemoteOut16, "o")).out_words, 256U);
}

TEST(BusConfig, MoreThan512DevicesNamesTheFirstDeviceTooMany) {
  std::vector<DeviceSpec> ring;
  for (std::size_t s = 0; s < 8; ++s) {
    ring.push_back({numbered("bk", s), kBusTerminal, {}});
    for (const DeviceSpec& d : many(63, kLocalNoData, numbered("l", s, "_"))) {
      ring.push_back(d);
    }
  }
  ring.push_back({"extra", kBusTerminal, {}});
  EXPECT_EQ(config_error(ring),
            "bus configuration: device 'extra' (ring position 512): the ring holds 513 devices, "
            "the limit is 512 devices per INTERBUS system");
}

TEST(BusConfig, MoreThan254RemoteBusDevices) {
  EXPECT_EQ(config_error(many(255, kBusTerminal, "r")),
            "bus configuration: device 'r254' (ring position 254): remote bus device number 255 "
            "exceeds the limit of 254 remote bus devices");
}

TEST(BusConfig, MoreThan63DevicesInOneLocalBusSegment) {
  std::vector<DeviceSpec> ring{{"bk", kBusTerminal, {}}};
  for (const DeviceSpec& d : many(64, kLocalNoData, "l")) ring.push_back(d);
  EXPECT_EQ(config_error(ring),
            "bus configuration: device 'l63' (ring position 64): local bus segment after 'bk' "
            "would hold 64 devices, the limit is 63 per local bus segment");
}

TEST(BusConfig, ARemoteDeviceStartsANewLocalSegment) {
  std::vector<DeviceSpec> ring = many(63, kLocalNoData, "a");
  ring.push_back({"bk", kBusTerminal, {}});
  for (const DeviceSpec& d : many(63, kLocalNoData, "b")) ring.push_back(d);
  EXPECT_EQ(make_bus_config(ring).devices.size(), 127U);
  ring.push_back({"b63", kLocalNoData, {}});
  EXPECT_THAT(config_error(ring), HasSubstr("local bus segment after 'bk' would hold 64"));
  std::vector<DeviceSpec> first = many(64, kLocalNoData, "m");
  EXPECT_THAT(config_error(first), HasSubstr("local bus segment after the master would hold 64"));
}

TEST(BusConfig, MoreThan62PcpDevices) {
  EXPECT_EQ(config_error(many(63, kRemotePcp1, "p")),
            "bus configuration: device 'p62' (ring position 62): PCP device number 63 exceeds "
            "the limit of 62 PCP devices");
}

TEST(BusConfig, MoreThan256InputWords) {
  std::vector<DeviceSpec> ring = many(16, kRemoteIn16, "i");
  ring.push_back({"last", IdCode{0x0102}, {}});
  EXPECT_EQ(config_error(ring),
            "bus configuration: device 'last' (ring position 16): its 1 word of input data would "
            "end at word 257, the limit is 256 input words (4096 bits)");
}

TEST(BusConfig, MoreThan256OutputWords) {
  std::vector<DeviceSpec> ring = many(15, kRemoteOut16, "o");
  ring.push_back({"last", IdCode{0x1303}, {}});  // 24 words in/out (length code 13H)
  EXPECT_EQ(config_error(ring),
            "bus configuration: device 'last' (ring position 15): its 24 words of output data "
            "would end at word 264, the limit is 256 output words (4096 bits)");
}

TEST(BusConfig, UnknownLengthCode) {
  EXPECT_EQ(config_error({{"odd", IdCode{0x0803}, {}}}),
            "bus configuration: device 'odd' (ring position 0): ID code 803H has the unknown "
            "length code 08H in bits 8..12 (known: 00H..07H, 0EH, 0FH, 11H..13H, 15H..17H)");
}

TEST(BusConfig, UnassignedPcpWidth) {
  EXPECT_THAT(config_error({{"pcp", IdCode{0x2DA}, {}}}),
              AllOf(HasSubstr("device 'pcp' (ring position 0)"), HasSubstr("2DAH"),
                    HasSubstr("unassigned PCP width bits 10b")));
}

TEST(BusConfig, PcpWiderThanTheDevice) {
  EXPECT_EQ(config_error({{"narrow", IdCode{0x1D0}, {}}}),
            "bus configuration: device 'narrow' (ring position 0): ID code 1D0H has a PCP channel "
            "of 2 words, more than its 1 word on the bus");
}

TEST(BusConfig, DataWithoutDirection) {
  EXPECT_EQ(config_error({{"nodir", IdCode{0x0300}, {}}}),
            "bus configuration: device 'nodir' (ring position 0): ID code 300H has 3 words of "
            "process data but no direction (bits 1..0 = 00b)");
}

TEST(BusConfig, NamesMustBeGivenAndUnique) {
  EXPECT_EQ(config_error({{"", kVf1000, {}}}),
            "bus configuration: device '' (ring position 0): a device needs a name");
  EXPECT_EQ(config_error({{"vf", kVf1000, {}}, {"vf", kVf1000, {}}}),
            "bus configuration: device 'vf' (ring position 1): the name is used by an earlier "
            "device");
}

}  // namespace
}  // namespace ibs::interbus
