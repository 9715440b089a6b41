// The one store: each storage kind across write, power-on, save and factory defaults; the
// overlays; texts; the download's spare; no allocation after construction; and, operation by
// operation, the same values as the stores of today (drive::ParameterStore, pcp::ParameterStore).
#include "ibs/od/store.hpp"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>
#include <string>

#include "ibs/drive/parameters.hpp"
#include "ibs/pcp/parameter_store.hpp"
#include "sample.hpp"

namespace ibs::od {
namespace {

// One entry of each kind, each with the default 7 and the range 0..100.
constexpr Entry kind(std::uint16_t n, std::string_view name, Storage s,
                     std::uint16_t attributes = 0) {
  return {.number = n,
          .name = name,
          .type = Type::usign16,
          .min = 0,
          .max = 100,
          .default_value = 7,
          .storage = s,
          .attributes = attributes};
}
constexpr std::array kKinds{
    kind(1, "RAMC", Storage::ram_control), kind(2, "RAMA", Storage::ram_actual),
    kind(3, "EE", Storage::eeprom),        kind(4, "EERAM", Storage::eeprom_ram),
    kind(5, "FLASH", Storage::flash),      kind(6, "NOINI", Storage::ram_control, attr::kNoInit)};
constexpr Dictionary kKindsDict{kKinds};
enum : Slot { kRamControl, kRamActual, kEeprom, kEepromRam, kFlash, kNoInit };

TEST(OdStore, AFreshStoreHoldsTheDefaultsEverywhere) {
  const Store s(kKindsDict);
  for (Slot i = 0; i < s.size(); ++i) {
    EXPECT_EQ(s.ram(i), 7U);
    EXPECT_EQ(s.kept(i), 7U);
    EXPECT_EQ(s.default_raw(i), 7U);
    EXPECT_EQ(s.spare(i), 7U);
  }
}

struct KindRow {
  Slot slot;
  bool kept_on_write_stage_off;  // the kept copy follows a write with the power stage disabled
  bool kept_on_write_stage_on;
  bool ram_back_at_power_on;    // power-on brings back the written value (else the default)
  bool kept_by_save;            // save(kind) keeps RAM
  bool kept_reset_by_defaults;  // factory_defaults() resets the kept copy
};
// LUSTBUS manual 11.1 / INTERBUS manual 4.1.3.3 (RAM, EEPROM, EEPROM/RAM), 11.2.1 (NoInit), CANLust manual 3.5.1 and
// p. 13 (flash: kept by 150-SAVE only, PROG leaves it alone).
constexpr KindRow kRows[] = {
    {kRamControl, false, false, false, true, true}, {kRamActual, false, false, false, true, true},
    {kEeprom, true, true, true, true, true},        {kEepromRam, true, false, true, true, true},
    {kFlash, false, false, true, true, false},      {kNoInit, false, false, true, true, true},
};

TEST(OdStore, EachStorageKindAcrossWritePowerOnSaveAndDefaults) {
  for (const KindRow& row : kRows) {
    const Entry& e = kKindsDict[row.slot];
    SCOPED_TRACE(std::string(e.name));
    for (const bool stage_on : {false, true}) {
      Store s(kKindsDict);
      const bool changed = s.write(row.slot, 42, stage_on);
      EXPECT_EQ(s.ram(row.slot), 42U);
      const bool kept = stage_on ? row.kept_on_write_stage_on : row.kept_on_write_stage_off;
      EXPECT_EQ(changed, kept);
      EXPECT_EQ(s.kept(row.slot), kept ? 42U : 7U);
      s.power_on();
      EXPECT_EQ(s.ram(row.slot),
                kept || (row.ram_back_at_power_on && e.storage == Storage::ram_control) ? 42U : 7U);
    }
    Store s(kKindsDict);
    s.write(row.slot, 42, true);
    s.save(e.storage);
    EXPECT_EQ(s.kept(row.slot), row.kept_by_save ? 42U : 7U);
    s.set(row.slot, 50);
    s.factory_defaults();
    EXPECT_EQ(s.ram(row.slot), 7U);
    EXPECT_EQ(s.kept(row.slot), row.kept_reset_by_defaults ? 7U : 42U);
    s.power_on();
    EXPECT_EQ(s.ram(row.slot), e.storage == Storage::flash ? 42U : 7U);
  }
}

TEST(OdStore, SaveKeepsOnlyItsKind) {
  Store s(kKindsDict);
  for (Slot i = 0; i < s.size(); ++i) s.set(i, 9);
  s.save(Storage::flash);
  for (Slot i = 0; i < s.size(); ++i) EXPECT_EQ(s.kept(i), i == kFlash ? 9U : 7U) << i;
}

TEST(OdStore, ByNumberSetKeepAndPreset) {
  Store s(kKindsDict);
  EXPECT_EQ(s.ram_of(3), 7U);
  EXPECT_FALSE(s.ram_of(99));
  EXPECT_FALSE(s.kept_of(99));
  EXPECT_FALSE(s.set_of(99, 1));
  EXPECT_TRUE(s.set_of(3, 11));
  EXPECT_EQ(s.ram(kEeprom), 11U);
  EXPECT_EQ(s.kept(kEeprom), 7U);  // set: RAM only
  s.keep(kEeprom, 11);             // the background save ended
  EXPECT_EQ(s.kept_of(3), 11U);
  s.preset(kRamControl, 12);
  EXPECT_EQ(s.ram(kRamControl), 12U);
  EXPECT_EQ(s.kept(kRamControl), 12U);
}

// The VF1000 without the INTERBUS software (INTERBUS manual 3.1.1, VF-E20): other factory defaults.
TEST(OdStore, DefaultOverlays) {
  Store s(test::kVf, test::kVfStandalone);
  EXPECT_EQ(s.ram(test::kVf.slot(1)), 0U);
  EXPECT_EQ(s.ram(test::kVf.slot(4)), 0U);
  EXPECT_EQ(s.default_raw(test::kVf.slot(1)), 0U);
  EXPECT_EQ(s.ram(test::kVf.slot(22)), 0xA0U);
  s.write(test::kVf.slot(1), 3, false);
  s.factory_defaults();
  EXPECT_EQ(s.ram(test::kVf.slot(1)), 0U);

  const DefaultOverride unknown[] = {{2, 0}};
  EXPECT_EQ(Store::validate(test::kVf, unknown).code, ErrorCode::table_number_out_of_range);
  const DefaultOverride twice[] = {{1, 0}, {1, 1}};
  EXPECT_EQ(Store::validate(test::kVf, twice).code, ErrorCode::table_number_repeated);
  const DefaultOverride above[] = {{1, 5}};
  const Error e = Store::validate(test::kVf, above);
  EXPECT_EQ(e.code, ErrorCode::table_default_outside_limits);
  EXPECT_NE(e.message.find("1-MODE"), std::string::npos) << e.message;
  EXPECT_THROW(Store(test::kVf, above), std::invalid_argument);
  const DefaultOverride text[] = {{90, 1}};
  EXPECT_EQ(Store::validate(test::kCda, text).code, ErrorCode::table_limits_outside_type);
  const DefaultOverride not_a_choice[] = {{260, 3}};
  EXPECT_EQ(Store::validate(test::kCda, not_a_choice).code,
            ErrorCode::table_default_outside_limits);
}

// The CDA3000's 90-NAME (flash: 150-SAVE keeps it) and 578-OPTN2 (a RAM constant).
TEST(OdStore, TextsByStorageKind) {
  Store s(test::kCda);
  const Slot name = test::kCda.slot(90);
  const Slot optn2 = test::kCda.slot(578);
  EXPECT_EQ(s.text(name), "CDA3000");
  EXPECT_EQ(s.kept_text(name), "CDA3000");
  EXPECT_EQ(s.text(optn2), "LCAN");
  EXPECT_EQ(s.text(test::kCda.slot(574)), "");  // no text
  EXPECT_TRUE(s.write_text(name, "PRESS 4", false));
  EXPECT_EQ(s.text(name), "PRESS 4");
  EXPECT_EQ(s.kept_text(name), "CDA3000");  // flash: kept by a save
  s.power_on();
  EXPECT_EQ(s.text(name), "CDA3000");
  EXPECT_TRUE(s.set_text(name, "PRESS 4"));
  s.save(Storage::flash);
  s.power_on();
  EXPECT_EQ(s.text(name), "PRESS 4");
  s.factory_defaults();
  EXPECT_EQ(s.text(name), "CDA3000");
  EXPECT_EQ(s.kept_text(name), "PRESS 4");
  // Refused, nothing changed: too long, a NUL, a number entry.
  EXPECT_FALSE(s.set_text(name, std::string(100, 'x')));
  EXPECT_TRUE(s.set_text(name, std::string(99, 'x')));
  EXPECT_FALSE(s.set_text(name, std::string_view("a\0b", 3)));
  EXPECT_EQ(s.text(name), std::string(99, 'x'));
  EXPECT_FALSE(s.set_text(test::kCda.slot(574), "1"));
  EXPECT_TRUE(s.set_text(name, ""));
  EXPECT_EQ(s.text(name), "");
}

// LUSTBUS manual 11.4: the old data set in the spare, restored for the data set's entries only; or the
// data set into the kept copies.
TEST(OdStore, TheDownloadsSpare) {
  Store s(test::kMc);
  const Slot rssl1 = test::kMc.slot(417);
  const Slot rsio = test::kMc.slot(428);  // not in the data set
  s.snapshot();
  s.set(rssl1, 3);
  s.set(rsio, 1234);
  EXPECT_EQ(s.spare(rssl1), 0U);
  s.restore_data_set();
  EXPECT_EQ(s.ram(rssl1), 0U);
  EXPECT_EQ(s.ram(rsio), 1234U);
  s.set(rssl1, 5);
  s.keep_data_set();
  EXPECT_EQ(s.kept(rssl1), 5U);
  // The CDA3000's way: the new set in the spare, taken whole.
  Store c(test::kCda);
  c.snapshot();
  c.set_spare(test::kCda.slot(574), 100);
  EXPECT_EQ(c.ram(test::kCda.slot(574)), 0U);
  c.restore_data_set();
  c.keep_data_set();
  EXPECT_EQ(c.ram(test::kCda.slot(574)), 100U);
  EXPECT_EQ(c.kept(test::kCda.slot(574)), 100U);
}

// Operation by operation, od::Store keeps what drive::ParameterStore keeps (the VF1000's store of
// today): the categories map to storage kinds, the words to Raws.
TEST(OdStoreKeepsTodays, DriveParameterStore) {
  using drive::Category;
  const drive::ParameterInfo today[] = {
      {1, "MODE", "", Category::eeprom, drive::DataType::usign8, 0, 4, 4, 1.0, ""},
      {3, "CNTL", "", Category::ram_control, drive::DataType::binary8, 0, 0xFF, 0, 1.0, ""},
      {5, "FSSIO", "Hz", Category::eeprom_ram, drive::DataType::fixpoint16, 0, 19999, 0, 0.05, ""},
      {12, "FOUT", "Hz", Category::ram_actual, drive::DataType::fixpoint16, 0, 0xFFFF, 0, 0.05, ""},
      {911, "FDRIV", "Hz", Category::ram_control, drive::DataType::integer16, 0x8000, 0x7FFF, 0,
       0.05, ""},
  };
  drive::ParameterStore old(today);
  Store now(test::kVf);  // the same numbers in the sample (kVf* entries)
  const std::uint16_t numbers[] = {1, 3, 5, 12, 911};
  std::mt19937 gen(41);
  for (int step = 0; step < 20000; ++step) {
    const std::size_t i = gen() % 5;
    const Slot s = test::kVf.slot(numbers[i]);
    const auto w = static_cast<Word>(pattern(test::kVf[s].type, static_cast<Raw>(gen())));
    switch (gen() % 5) {
      case 0:
      case 1: {
        const bool stage = (gen() & 1U) != 0;
        old.write(i, w, stage);
        now.write(s, canonical(test::kVf[s].type, w), stage);
        break;
      }
      case 2:
        old.power_on();
        now.power_on();
        break;
      case 3:
        old.factory_defaults();
        now.factory_defaults();
        break;
      default:
        break;
    }
    for (std::size_t k = 0; k < 5; ++k) {
      const Slot t = test::kVf.slot(numbers[k]);
      ASSERT_EQ(pattern(test::kVf[t].type, now.ram(t)), old.value(k)) << step;
      ASSERT_EQ(pattern(test::kVf[t].type, now.kept(t)), old.eeprom_value(k)) << step;
    }
  }
}

// And what pcp::ParameterStore keeps (the MC6000's store of today).
TEST(OdStoreKeepsTodays, PcpParameterStore) {
  const pcp::ParameterInfo today[] = {
      {4, "PROG", pcp::DataType::usign8, pcp::Category::ram_control, 0, 255, 0, 0},
      {77, "SPEED", pcp::DataType::int32q16, pcp::Category::ram_actual, -2147483648LL, 2147483647LL,
       0, 0},
      {80, "SLOAD", pcp::DataType::integer16, pcp::Category::ram_control, -2, 999, 0, 0},
      {417, "RSSL1", pcp::DataType::usign8, pcp::Category::eeprom, 0, 7, 0, 0},
      {419, "RSSL3", pcp::DataType::usign8, pcp::Category::eeprom, 0, 7, 6, 0},
  };
  pcp::ParameterStore old(today);
  Store now(test::kMc);
  std::mt19937 gen(43);
  for (int step = 0; step < 20000; ++step) {
    const pcp::ParameterInfo& p = today[gen() % 5];
    const Slot s = test::kMc.slot(p.number);
    // Values of the type (what a checked write commits; pcp::ParameterStore::commit_eeprom keeps
    // any 32 bits as they come).
    const auto v = pattern(test::kMc[s].type, static_cast<Raw>(gen()));
    switch (gen() % 5) {
      case 0:  // a reading, or a write taken into RAM
        old.set(p.number, v);
        now.set(s, canonical(test::kMc[s].type, v));
        break;
      case 1:  // an EEPROM save that ended
        if (old.commit_eeprom(p.number, v)) now.keep(s, canonical(test::kMc[s].type, v));
        break;
      case 2:
        old.power_on();
        now.power_on();
        break;
      case 3:
        old.factory_defaults();
        now.factory_defaults();
        break;
      default:
        break;
    }
    for (const pcp::ParameterInfo& q : today) {
      const Slot t = test::kMc.slot(q.number);
      ASSERT_EQ(pattern(test::kMc[t].type, now.ram(t)), old.get(q.number)->raw) << step;
      if (const auto e = old.eeprom(q.number)) {
        ASSERT_EQ(pattern(test::kMc[t].type, now.kept(t)), e->raw) << step;
      }
    }
  }
}

}  // namespace
}  // namespace ibs::od
