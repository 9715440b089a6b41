// The DFS-1's object dictionary (dictionary.hpp, issue 38 W4) against the table the controller
// uses today (parameters.hpp): entry by entry and field by field, the range check of a write, the
// defaults a controller starts with and the lookups. While both exist, this keeps them one fact.
#include "ibs/devices/dfs1/dictionary.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "ibs/devices/dfs1/controller.hpp"
#include "ibs/devices/dfs1/parameters.hpp"
#include "ibs/od/store.hpp"

namespace ibs::devices::dfs1 {
namespace {

TEST(Dfs1Dictionary, MatchesTheTable) {
  ASSERT_EQ(kEntries.size(), kParameters.size());
  EXPECT_EQ(kDictionary.profile(), od::Profile::none);
  for (std::size_t i = 0; i < kParameters.size(); ++i) {
    const ParameterInfo& p = kParameters[i];
    const od::Entry& e = kEntries[i];
    SCOPED_TRACE(p.name);
    EXPECT_EQ(e.number, p.number);
    EXPECT_EQ(e.name, p.name);
    EXPECT_EQ(e.text, "");                 // the DFS-1's parameters have names only
    EXPECT_EQ(e.type, od::Type::usign32);  // every value 4 bytes on the line
    EXPECT_EQ(e.min, p.min);
    EXPECT_EQ(e.max, p.max);
    EXPECT_EQ(e.default_value, p.default_value);
    EXPECT_EQ(e.default_text, "");
    EXPECT_EQ(e.unit, p.unit);
    EXPECT_EQ(e.scale, 1.0);
    EXPECT_EQ(e.storage, od::Storage::eeprom);  // the setup stays over a power cycle (D20)
    EXPECT_TRUE(e.writable());                  // every one takes 86
    EXPECT_EQ(e.effect, od::Effect::at_once);   // D5: from the next request on
    EXPECT_EQ(e.role, od::Role::value);
    EXPECT_EQ(e.attributes, 0U);
    EXPECT_EQ(e.elements, 1U);
    EXPECT_FALSE(e.in_data_set);  // the DFS-1 has no data-set download
    EXPECT_TRUE(e.choices.empty());
    EXPECT_FALSE(e.choices_only);
    EXPECT_EQ(e.keypad, nullptr);
    EXPECT_EQ(e.invented, p.invented);
    EXPECT_EQ(e.source, p.note);
  }
}

// A write's value: od::fit takes exactly what the controller's range check takes (NAK 83 else),
// at the limits and at random 32-bit values.
TEST(Dfs1Dictionary, FitIsTheControllersRangeCheck) {
  std::mt19937 rng(38);
  for (std::size_t i = 0; i < kParameters.size(); ++i) {
    const ParameterInfo& p = kParameters[i];
    SCOPED_TRACE(p.name);
    std::vector<std::uint32_t> values = {
        0,          1,           p.min - 1U,  p.min,       p.max,
        p.max + 1U, 0x7FFFFFFFU, 0x80000000U, 0xFFFFFFFFU, p.default_value};
    for (int k = 0; k < 2000; ++k) values.push_back(static_cast<std::uint32_t>(rng()));
    for (const std::uint32_t v : values) {
      const bool taken = v >= p.min && v <= p.max;
      EXPECT_EQ(od::fit(kEntries[i], v) == od::Fit::ok, taken) << v;
      Controller c({1});
      EXPECT_EQ(c.set_parameter(p.number, v).has_value(), !taken) << v;
    }
  }
}

// A controller starts with the table's defaults and its own UID in parameter 1: the store made
// with unit_id_default(uid) holds the same.
TEST(Dfs1Dictionary, StoreWithTheUidOverlayIsTheControllersStart) {
  for (const std::uint8_t uid : {std::uint8_t{1}, std::uint8_t{7}, std::uint8_t{255}}) {
    const std::array overlay{unit_id_default(uid)};
    const od::Store store(kDictionary, overlay);
    const Controller c({uid});
    for (std::size_t i = 0; i < kParameters.size(); ++i) {
      const auto s = static_cast<od::Slot>(i);
      EXPECT_EQ(store.ram(s), c.parameter(kParameters[i].number)) << kParameters[i].name;
      EXPECT_EQ(store.kept(s), store.ram(s));
    }
  }
}

TEST(Dfs1Dictionary, LookupsAreTodays) {
  for (unsigned n = 0; n <= 0xFF; ++n) {
    const ParameterInfo* p = find_parameter(static_cast<std::uint8_t>(n));
    const od::Entry* e = kDictionary.find(static_cast<std::uint16_t>(n));
    ASSERT_EQ(e == nullptr, p == nullptr) << n;
    if (p != nullptr) {
      EXPECT_EQ(e->name, p->name);
      EXPECT_EQ(kDictionary.slot(static_cast<std::uint16_t>(n)),
                static_cast<od::Slot>(p - kParameters.data()));  // a slot is today's row
    }
  }
  EXPECT_EQ(kDictionary.find("unit id")->number, kUnitId);  // the names as the pages give them
  EXPECT_EQ(kDictionary.find("6-maximum motor speed")->number, kMaxSpeed);
}

}  // namespace
}  // namespace ibs::devices::dfs1
