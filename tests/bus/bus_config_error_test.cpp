// The non-throwing bus configuration (try_make_bus_config, docs/embedding.md "An embedded build"):
// every refusal comes back as its error code with the very message ConfigError carries, and a
// ring it accepts gives the configuration make_bus_config gives.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <string>
#include <vector>

#include "ibs/interbus/bus_config.hpp"
#include "ibs/base/error.hpp"

namespace ibs::interbus {
namespace {

constexpr IdCode kMc6000Supi11Remote{0x4DB};
constexpr IdCode kVf1000{0x33B};
constexpr IdCode kBusTerminal{0x0008};
constexpr IdCode kLocalNoData{0x0090};
constexpr IdCode kRemoteIn16{0x1202};
constexpr IdCode kRemoteOut16{0x1201};
constexpr IdCode kRemotePcp1{0x1DB};

std::vector<DeviceSpec> many(std::size_t n, IdCode id, const std::string& prefix) {
  std::vector<DeviceSpec> v;
  for (std::size_t i = 0; i < n; ++i) v.push_back({prefix + std::to_string(i), id, {}});
  return v;
}

// What make_bus_config throws for the ring ("" when it accepts it).
std::string thrown(const std::vector<DeviceSpec>& ring) {
  try {
    (void)make_bus_config(ring);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

struct Refused {
  const char* name;
  std::function<std::vector<DeviceSpec>()> ring;
  ErrorCode code;
};

const std::vector<Refused>& refused() {
  static const std::vector<Refused> cases{
      {"too many devices",
       [] {
         std::vector<DeviceSpec> ring;
         for (std::size_t s = 0; s < 8; ++s) {
           ring.push_back({"bk" + std::to_string(s), kBusTerminal, {}});
           for (const DeviceSpec& d : many(63, kLocalNoData, "l" + std::to_string(s) + "_"))
             ring.push_back(d);
         }
         ring.push_back({"extra", kBusTerminal, {}});
         return ring;
       },
       ErrorCode::bus_too_many_devices},
      {"unnamed",
       [] {
         return std::vector<DeviceSpec>{{"", kVf1000, {}}};
       },
       ErrorCode::bus_device_unnamed},
      {"repeated name",
       [] {
         return std::vector<DeviceSpec>{{"vf", kVf1000, {}}, {"vf", kVf1000, {}}};
       },
       ErrorCode::bus_name_repeated},
      {"unknown length code",
       [] {
         return std::vector<DeviceSpec>{{"odd", IdCode{0x0803}, {}}};
       },
       ErrorCode::bus_unknown_length_code},
      {"unassigned PCP width",
       [] {
         return std::vector<DeviceSpec>{{"pcp", IdCode{0x2DA}, {}}};
       },
       ErrorCode::bus_unassigned_pcp_width},
      {"PCP wider than the device",
       [] {
         return std::vector<DeviceSpec>{{"narrow", IdCode{0x1D0}, {}}};
       },
       ErrorCode::bus_pcp_wider_than_device},
      {"no direction",
       [] {
         return std::vector<DeviceSpec>{{"nodir", IdCode{0x0300}, {}}};
       },
       ErrorCode::bus_no_direction},
      {"too many remote devices", [] { return many(255, kBusTerminal, "r"); },
       ErrorCode::bus_too_many_remote_devices},
      {"local segment too long",
       [] {
         std::vector<DeviceSpec> ring{{"bk", kBusTerminal, {}}};
         for (const DeviceSpec& d : many(64, kLocalNoData, "l")) ring.push_back(d);
         return ring;
       },
       ErrorCode::bus_local_segment_too_long},
      {"too many PCP devices", [] { return many(63, kRemotePcp1, "p"); },
       ErrorCode::bus_too_many_pcp_devices},
      {"too many input words",
       [] {
         std::vector<DeviceSpec> ring = many(16, kRemoteIn16, "i");
         ring.push_back({"last", IdCode{0x0102}, {}});
         return ring;
       },
       ErrorCode::bus_too_many_input_words},
      {"too many output words",
       [] {
         std::vector<DeviceSpec> ring = many(15, kRemoteOut16, "o");
         ring.push_back({"last", IdCode{0x1303}, {}});
         return ring;
       },
       ErrorCode::bus_too_many_output_words},
  };
  return cases;
}

TEST(BusConfigError, EveryRefusalHasItsCodeAndTheExceptionsMessage) {
  for (const Refused& c : refused()) {
    SCOPED_TRACE(c.name);
    const std::vector<DeviceSpec> ring = c.ring();
    const Expected<BusConfig> r = try_make_bus_config(ring);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().code, c.code);
    EXPECT_TRUE(r.error().message.starts_with("bus configuration: device '"));
    EXPECT_EQ(r.error().message, thrown(ring));
  }
}

TEST(BusConfigError, TheCodesAreDistinct) {
  std::vector<ErrorCode> seen;
  for (const Refused& c : refused()) {
    EXPECT_EQ(std::count(seen.begin(), seen.end(), c.code), 0) << c.name;
    seen.push_back(c.code);
  }
}

void expect_same(const BusConfig& a, const BusConfig& b) {
  ASSERT_EQ(a.devices.size(), b.devices.size());
  for (std::size_t i = 0; i < a.devices.size(); ++i) {
    const Device& x = a.devices[i];
    const Device& y = b.devices[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.id, y.id);
    EXPECT_EQ(x.bus, y.bus);
    EXPECT_EQ(x.ring_position, y.ring_position);
    EXPECT_EQ(x.ring_words, y.ring_words);
    EXPECT_EQ(x.pd_in_words, y.pd_in_words);
    EXPECT_EQ(x.pd_out_words, y.pd_out_words);
    EXPECT_EQ(x.pcp_words, y.pcp_words);
    EXPECT_EQ(x.in, y.in);
    EXPECT_EQ(x.out, y.out);
    EXPECT_EQ(x.pcp, y.pcp);
  }
  EXPECT_EQ(a.in_words, b.in_words);
  EXPECT_EQ(a.out_words, b.out_words);
  EXPECT_EQ(a.pcp_words, b.pcp_words);
  EXPECT_EQ(a.ring_words, b.ring_words);
  EXPECT_EQ(a.remote_devices, b.remote_devices);
  EXPECT_EQ(a.pcp_devices, b.pcp_devices);
}

TEST(BusConfigError, AnAcceptedRingGivesWhatMakeBusConfigGives) {
  const std::vector<DeviceSpec> ring{{"mc6000", kMc6000Supi11Remote, {}},
                                     {"vf1000", kVf1000, {}},
                                     {"local", kLocalNoData, {}},
                                     {"in", kRemoteIn16, BusKind::local}};
  const Expected<BusConfig> r = try_make_bus_config(ring);
  ASSERT_TRUE(r.ok());
  EXPECT_FALSE(r.error());
  EXPECT_EQ(r.error().code, ErrorCode::none);
  const BusConfig thrown_form = make_bus_config(ring);
  expect_same(r.value(), thrown_form);
  EXPECT_EQ(r->devices[1].in, (Slice{3, 3}));
  EXPECT_EQ(r->devices[3].bus, BusKind::local);
}

}  // namespace
}  // namespace ibs::interbus
