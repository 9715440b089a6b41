// The VF1000's object dictionary (devices/vf1000/dictionary, issue 38 W1) against the table of today
// (parameters.hpp, drive::ParameterInfo), field by field, so that the switch of each consumer to the
// dictionary keeps every value, range, default and rule: the same slots, the standalone defaults of
// VF-E20, and od::StoredServed keeping drive::StoredParameters' behaviour on every real entry.
#include "ibs/devices/vf1000/dictionary.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "ibs/devices/vf1000/parameters.hpp"
#include "ibs/drive/parameter_access.hpp"
#include "ibs/drive/parameters.hpp"
#include "ibs/od/store.hpp"
#include "ibs/od/stored_served.hpp"

namespace {

using namespace ibs;
using namespace ibs::devices::vf1000;

// What each of drive::'s types is in od's one family (the plan's table 1.2).
od::Type type_of(drive::DataType t) {
  switch (t) {
    case drive::DataType::binary8:
      return od::Type::binary8;
    case drive::DataType::fixpoint16:
      return od::Type::fixpoint16;
    case drive::DataType::usign16:
      return od::Type::usign16;
    case drive::DataType::usign8:
      return od::Type::usign8;
    case drive::DataType::vf_error:
      return od::Type::error16;
    case drive::DataType::password:
      return od::Type::password;
    case drive::DataType::integer16:
      return od::Type::int16;
  }
  ADD_FAILURE() << "a drive::DataType without an od::Type";
  return od::Type::string;
}

od::Storage storage_of(drive::Category c) {
  switch (drive::storage(c)) {
    case drive::Storage::ram_control:
      return od::Storage::ram_control;
    case drive::Storage::ram_actual:
      return od::Storage::ram_actual;
    case drive::Storage::eeprom:
      return od::Storage::eeprom;
    case drive::Storage::eeprom_ram:
      return od::Storage::eeprom_ram;
  }
  return od::Storage::flash;
}

TEST(VfDictionary, MatchesTheTable) {
  const auto table = parameters();
  const auto entries = kDictionary.entries();
  ASSERT_EQ(entries.size(), table.size());
  EXPECT_EQ(kDictionary.profile(), od::Profile::lust_standard);
  for (std::size_t i = 0; i < table.size(); ++i) {
    const drive::ParameterInfo& p = table[i];
    const od::Entry& e = entries[i];
    SCOPED_TRACE(std::to_string(p.number) + "-" + std::string(p.name));
    EXPECT_EQ(e.number, p.number);
    EXPECT_EQ(e.name, p.name);
    EXPECT_EQ(e.text, p.meaning);
    EXPECT_EQ(e.unit, p.unit);
    EXPECT_EQ(e.type, type_of(p.type));
    // Limits and default: today's raw words read as numbers of the type (FDRIV's 8000H is -32768).
    EXPECT_EQ(e.min, drive::raw_as_number(p.type, p.min));
    EXPECT_EQ(e.max, drive::raw_as_number(p.type, p.max));
    EXPECT_EQ(e.default_value, drive::raw_as_number(p.type, p.default_value));
    // The same raw words back (what the comm word's description record and LUSTBUS 11.1 carry).
    EXPECT_EQ(od::pattern(e.type, e.min_raw()), p.min);
    EXPECT_EQ(od::pattern(e.type, e.max_raw()), p.max);
    EXPECT_EQ(od::pattern(e.type, e.default_raw()), p.default_value);
    // Engineering values: the same for every raw word of the type's range (scale: A-lane decision,
    // number / per_unit x scale).
    EXPECT_DOUBLE_EQ(e.scale, p.scale / drive::natural_scale(p.type));
    for (const Word w : {p.min, p.max, p.default_value, Word{1}, Word{463}}) {
      if (!od::fits(e.type, drive::raw_as_number(p.type, w))) continue;  // no value of the type
      const auto today = drive::to_engineering(p, w);
      const auto now = od::engineering(e.type, od::from_bus(e.type, w, 16), e.scale);
      ASSERT_EQ(today.has_value(), now.has_value());
      if (today) {
        EXPECT_DOUBLE_EQ(*now, *today) << w;
      }
    }
    EXPECT_EQ(e.storage, storage_of(p.category));
    EXPECT_EQ(e.specific, drive::inverter_specific(p.category));
    EXPECT_EQ(e.writable(), drive::writable(p.category));
    EXPECT_FALSE(e.read_only);
    const od::Role role = p.number == pnr::kSiof   ? od::Role::error_flags
                          : p.number == pnr::kProg ? od::Role::load_defaults
                                                   : od::Role::value;
    EXPECT_EQ(e.role, role);
    // What the standard family's table has no column for stays at od's defaults.
    EXPECT_EQ(e.effect, od::Effect::at_once);
    EXPECT_EQ(e.attributes, 0);
    EXPECT_EQ(e.elements, 1);
    EXPECT_FALSE(e.in_data_set);
    EXPECT_TRUE(e.choices.empty());
    EXPECT_EQ(e.keypad, nullptr);
    EXPECT_FALSE(e.source.empty());
  }
}

// The dictionary's slots are today's table's positions: a store, a core and a server indexed by
// slot keep their indices when they switch.
TEST(VfDictionary, SlotsAreTheTablesPositions) {
  const drive::ParameterTable table(parameters());
  for (std::uint16_t n = 0; n <= od::kMaxNumber; ++n) {
    const int today = table.slot(n);
    const od::Slot now = kDictionary.slot(n);
    if (today < 0) {
      EXPECT_EQ(now, od::kNoSlot) << n;
    } else {
      EXPECT_EQ(now, static_cast<od::Slot>(today)) << n;
    }
  }
  EXPECT_EQ(kDictionary.slot_of(od::Role::error_flags), kDictionary.slot(pnr::kSiof));
  EXPECT_EQ(kDictionary.slot_of(od::Role::load_defaults), kDictionary.slot(pnr::kProg));
  EXPECT_EQ(kDictionary.slot_of(od::Role::download), od::kNoSlot);
  EXPECT_EQ(kDictionary.find("906-IB-WD"), kDictionary.find(pnr::kIbWd));
  EXPECT_EQ(kDictionary.find("fssio"), kDictionary.find(pnr::kFssio));
}

// INTERBUS manual 3.1.1's three parameters take the standard values without the INTERBUS software, and
// nothing else changes: the overlay is exactly standalone_parameters()'s difference (VF-E20).
TEST(VfDictionary, StandaloneOverlayIsVF_E20) {
  ASSERT_FALSE(od::Store::validate(kDictionary, kStandaloneDefaults));
  const od::Store interbus(kDictionary);
  const od::Store standalone(kDictionary, kStandaloneDefaults);
  const auto with = parameters();
  const auto without = standalone_parameters();
  ASSERT_EQ(without.size(), kDictionary.size());
  std::vector<std::uint16_t> changed;
  for (std::size_t i = 0; i < without.size(); ++i) {
    const auto s = static_cast<od::Slot>(i);
    const od::Type t = kDictionary[s].type;
    EXPECT_EQ(od::pattern(t, interbus.default_raw(s)), with[i].default_value) << with[i].name;
    EXPECT_EQ(od::pattern(t, standalone.default_raw(s)), without[i].default_value)
        << without[i].name;
    // A factory-fresh drive: RAM and the kept copy at the default.
    EXPECT_EQ(standalone.ram(s), standalone.default_raw(s));
    EXPECT_EQ(standalone.kept(s), standalone.default_raw(s));
    if (with[i].default_value != without[i].default_value) changed.push_back(with[i].number);
  }
  EXPECT_EQ(changed, (std::vector<std::uint16_t>{pnr::kMode, pnr::kCsel, pnr::kFssel}));
  ASSERT_EQ(kStandaloneDefaults.size(), changed.size());
  for (std::size_t i = 0; i < changed.size(); ++i) {
    EXPECT_EQ(kStandaloneDefaults[i].number, changed[i]);
    EXPECT_EQ(kStandaloneDefaults[i].value, 0);
  }
}

// The family's rules on the real dictionary: od::StoredServed keeps what drive::StoredParameters
// does under the communication word's checks, for 100000 random accesses to every entry (values
// near the limits and at random, power stage on and off, 71-PROG = 1, power cycles, 85-SIOF read),
// with the INTERBUS and the standalone defaults.
void run_against_today(std::span<const drive::ParameterInfo> table,
                       std::span<const od::DefaultOverride> overlay, unsigned seed) {
  drive::StoredParameters old(table, pnr::kProg);
  old.power_on();
  od::StoredServed now(kDictionary, {.defaults = overlay});
  std::mt19937 gen(seed);
  for (int step = 0; step < 100000; ++step) {
    const std::size_t i = gen() % table.size();
    const drive::ParameterInfo& p = table[i];
    const auto s = static_cast<od::Slot>(i);
    const bool stage = gen() % 4 == 0;
    now.set_power_stage(stage);
    const Word near[] = {p.min,
                         p.max,
                         p.default_value,
                         static_cast<Word>(p.max + 1),
                         static_cast<Word>(p.min - 1),
                         1};
    const auto w = gen() % 2 == 0 ? near[gen() % 6] : static_cast<Word>(gen());
    switch (gen() % 8) {
      case 0: {  // a read of 85-SIOF
        const auto bits = static_cast<std::uint8_t>(old.read(old.siof_slot()));
        old.clear_siof(bits);
        ASSERT_EQ(now.read(kDictionary.slot(pnr::kSiof), Time{}).raw, bits) << step;
        break;
      }
      case 1:
        old.power_on();
        now.power_on();
        break;
      default: {  // a value transfer
        std::uint8_t bits = 0;
        if (old.siof() == 0) {
          const drive::WriteCheck c = drive::check_write(&p, w, stage);
          bits = drive::siof_bits_for(c);
          if (c == drive::WriteCheck::ok) old.write(i, w, stage, Time{});
          if (bits != 0) old.raise_siof(bits);
        }
        const od::Answer a = now.write(s, od::from_bus(kDictionary[s].type, w, 16), Time{});
        ASSERT_EQ(od::error_flag(a.refusal), bits) << step << " " << p.name << " " << w;
        break;
      }
    }
    ASSERT_EQ(now.error_flags(), old.siof()) << step;
    for (std::size_t k = 0; k < table.size(); ++k) {
      const auto t = static_cast<od::Slot>(k);
      const od::Type type = kDictionary[t].type;
      ASSERT_EQ(od::pattern(type, now.store().ram(t)), old.store().value(k))
          << step << " " << table[k].name;
      ASSERT_EQ(od::pattern(type, now.store().kept(t)), old.store().eeprom_value(k))
          << step << " " << table[k].name;
    }
  }
}

TEST(VfDictionary, StoredServedKeepsTodaysRulesOnEveryEntry) {
  run_against_today(parameters(), {}, 38);
}

TEST(VfDictionary, StoredServedKeepsTodaysRulesWithTheStandaloneDefaults) {
  run_against_today(standalone_parameters(), kStandaloneDefaults, 3811);
}

}  // namespace
