// The plain drive behind the one served interface: the family's rules -- the 85-SIOF/SERR latch
// and its bits, the permissions by storage kind and power stage, the answer's storing time, PROG,
// SAVE and the 11.4 download -- and, operation by operation, the same values and 85-SIOF bits as
// drive::StoredParameters under the communication word's checks of today.
#include "ibs/od/stored_served.hpp"

#include <gtest/gtest.h>

#include <random>
#include <string>

#include "ibs/drive/parameter_access.hpp"
#include "sample.hpp"

namespace ibs::od {
namespace {

using namespace std::chrono_literals;
using test::kCda;
using test::kMc;
using test::kVf;

constexpr Time kNow = 1s;

Slot at(const Dictionary& d, std::uint16_t number) {
  return d.slot(number);
}

TEST(OdStoredServed, PowerOnSetsItsBitWhichRefusesEveryWriteUntilRead) {
  StoredServed d(kVf);
  EXPECT_EQ(d.error_flags(), 0x01);
  const Answer a = d.write(at(kVf, 4), 8, kNow);
  EXPECT_EQ(a.refusal, Refusal::latched);
  EXPECT_EQ(d.error_flags(), 0x01);  // a latched write enters nothing
  EXPECT_EQ(d.check(at(kVf, 4), 8, kNow), Refusal::latched);
  EXPECT_EQ(d.peek(at(kVf, 4)), 25U);
  const Reading siof = d.read(at(kVf, 85), kNow);
  EXPECT_EQ(siof.raw, 0x01U);
  EXPECT_EQ(d.error_flags(), 0x00);
  EXPECT_TRUE(d.write(at(kVf, 4), 8, kNow).ok());
  EXPECT_EQ(d.peek(at(kVf, 4)), 8U);
}

struct RefusalRow {
  const char* name;
  std::uint16_t number;  // 0xFFFF: no parameter
  Raw raw;
  bool power_stage;
  Refusal refusal;
  std::uint8_t bit;
};
// LUSTBUS manual 9.2 and the INTERBUS manual 4.1.4: 20H no parameter, 40H no change permitted, 80H invalid value.
constexpr RefusalRow kRefusals[] = {
    {"NoParameter", 0xFFFF, 0, false, Refusal::no_parameter, 0x20},
    {"RamActualValue", 91, 1, false, Refusal::read_only, 0x40},
    {"EepromWhileThePowerStageRuns", 1, 1, true, Refusal::not_now, 0x40},
    {"AboveTheMaximum", 4, 26, false, Refusal::too_high, 0x80},
    {"BelowTheMinimum", 906, 7, false, Refusal::too_low, 0x80},
    {"WiderThanTheType", 1, 0x0105, false, Refusal::too_high, 0x80},
    {"SignedBelowTheType", 911, 0xFFFF0000U, false, Refusal::too_low, 0x80},
};

TEST(OdStoredServed, EachRefusalEntersItsBitAndLatches) {
  for (const RefusalRow& r : kRefusals) {
    SCOPED_TRACE(r.name);
    StoredServed d(kVf);
    d.clear_error_flags(0xFF);
    d.set_power_stage(r.power_stage);
    const Slot s = r.number == 0xFFFF ? kNoSlot : at(kVf, r.number);
    EXPECT_EQ(d.check(s, r.raw, kNow), r.refusal);
    EXPECT_EQ(d.error_flags(), 0);  // a check enters nothing
    const Answer a = d.write(s, r.raw, kNow);
    EXPECT_EQ(a.refusal, r.refusal);
    EXPECT_EQ(error_flag(a.refusal), r.bit);
    EXPECT_EQ(d.error_flags(), r.bit);
    // Latched now: the next write, even a good one, is refused without a bit of its own.
    EXPECT_EQ(d.write(at(kVf, 3), 1, kNow).refusal, Refusal::latched);
    EXPECT_EQ(d.error_flags(), r.bit);
  }
}

TEST(OdStoredServed, ReadsEnterNothingAndAReadOf85ClearsWhatItReturned) {
  StoredServed d(kVf);
  d.clear_error_flags(0xFF);
  EXPECT_EQ(d.read(kNoSlot, kNow).refusal, Refusal::no_parameter);
  EXPECT_EQ(d.read(999, kNow).refusal, Refusal::no_parameter);
  EXPECT_EQ(d.error_flags(), 0);
  EXPECT_EQ(d.read(at(kVf, 91), kNow).raw, 1000U);
  // The comm word reads 85 at the PNR and clears at its last byte: bits set between stay.
  d.raise_error_flags(0x20);
  const Raw seen = d.peek(at(kVf, 85));
  d.raise_error_flags(0x80);
  d.clear_error_flags(static_cast<std::uint8_t>(seen));
  EXPECT_EQ(d.error_flags(), 0x80);
  // A face's own refusal: its bit, unless latched.
  EXPECT_EQ(d.refuse(Refusal::transfer_error).refusal, Refusal::latched);
  d.clear_error_flags(0xFF);
  EXPECT_EQ(d.refuse(Refusal::transfer_error).refusal, Refusal::transfer_error);
  EXPECT_EQ(d.error_flags(), 0x08);
}

// INTERBUS manual 4.1.3.3: EEPROM/RAM variables into RAM alone while the power stage runs; LUSTBUS manual 3:
// the answer once the value is stored (the VF1000's 60 ms a byte, VF-E7).
TEST(OdStoredServed, StorageKindsPowerStageAndStoringTime) {
  StoredServedConfig c;
  c.timing.eeprom_per_byte = 60ms;
  StoredServed d(kVf, c);
  d.clear_error_flags(0xFF);
  Answer a = d.write(at(kVf, 1), 2, kNow);  // 1-MODE, EEPROM, one byte
  EXPECT_TRUE(a.kept_changed);
  EXPECT_EQ(a.after, 60ms);
  a = d.write(at(kVf, 1), 2, kNow);  // the same value: nothing to store
  EXPECT_FALSE(a.kept_changed);
  EXPECT_EQ(a.after, 0ms);
  d.set_power_stage(true);
  a = d.write(at(kVf, 5), 463, kNow);  // 5-FSSIO, EEPROM/RAM, power stage on: RAM only
  EXPECT_TRUE(a.ok());
  EXPECT_FALSE(a.kept_changed);
  EXPECT_EQ(d.store().kept(at(kVf, 5)), 0U);
  d.set_power_stage(false);
  a = d.write(at(kVf, 5), 463, kNow);
  EXPECT_TRUE(a.kept_changed);
  EXPECT_EQ(a.after, 120ms);
  d.power_on();
  EXPECT_EQ(d.peek(at(kVf, 5)), 463U);
  EXPECT_EQ(d.peek(at(kVf, 1)), 2U);
  EXPECT_EQ(d.peek(at(kVf, 3)), 0U);  // RAM: the default again
  EXPECT_EQ(d.error_flags(), 0x01);
}

TEST(OdStoredServed, InitControlIsToldToTheDrive) {
  StoredServed d(kMc);
  d.clear_error_flags(0xFF);
  EXPECT_TRUE(d.write(at(kMc, 15), 1, kNow).init_control);  // 15-PLRDY (INTERBUS manual 4.2)
  EXPECT_FALSE(d.write(at(kMc, 428), 1, kNow).init_control);
}

// LUSTBUS manual 10 exception 1: PROG = 1 loads every factory default and answers when done; 85 keeps
// its bits; PROG is a command and reads its default afterwards.
TEST(OdStoredServed, ProgLoadsTheFactoryDefaults) {
  StoredServedConfig c;
  c.timing.factory_defaults = 9900ms;
  c.defaults = test::kVfStandalone;
  StoredServed d(kVf, c);
  d.clear_error_flags(0xFF);
  ASSERT_TRUE(d.write(at(kVf, 22), 0x100, kNow).ok());
  ASSERT_TRUE(d.write(at(kVf, 1), 3, kNow).ok());
  const Answer a = d.write(at(kVf, 71), 1, kNow);
  ASSERT_TRUE(a.ok());
  EXPECT_EQ(a.after, 9900ms);
  EXPECT_EQ(d.peek(at(kVf, 22)), 0xA0U);
  EXPECT_EQ(d.store().kept(at(kVf, 22)), 0xA0U);
  EXPECT_EQ(d.peek(at(kVf, 1)), 0U);  // the overlay's default
  EXPECT_EQ(d.peek(at(kVf, 71)), 0U);
  EXPECT_EQ(d.error_flags(), 0);  // 85 is the drive's flags, not a setting: not reloaded
  EXPECT_TRUE(d.write(at(kVf, 1), 2, kNow).ok());
  StoredServed m(kMc);
  m.clear_error_flags(0xFF);
  ASSERT_TRUE(m.write(at(kMc, 417), 5, kNow).ok());
  ASSERT_TRUE(m.write(at(kMc, 4), 111, kNow).ok());  // another command: taken, PROG back to 0
  EXPECT_EQ(m.peek(at(kMc, 4)), 0U);
  EXPECT_EQ(m.peek(at(kMc, 417)), 5U);
  ASSERT_TRUE(m.write(at(kMc, 4), 1, kNow).ok());
  EXPECT_EQ(m.peek(at(kMc, 417)), 0U);
  EXPECT_EQ(m.peek(at(kMc, 419)), 6U);
}

// CANLust manual 3.5.1: 150-SAVE = 1 backs the settings up in flash; until then a mains reset brings
// the old ones back, and PROG leaves the flash alone (p. 13, the CDA3000's).
TEST(OdStoredServed, SaveKeepsTheFlashValues) {
  StoredServedConfig c;
  c.timing.save = 300ms;
  StoredServed d(kCda, c);
  EXPECT_EQ(d.error_flags(), 0);  // no 85 in a CANLust dictionary: nothing latches
  const Slot cawdg = at(kCda, 574);
  ASSERT_TRUE(d.write(cawdg, 100, kNow).ok());
  EXPECT_FALSE(d.write(cawdg, 100, kNow).kept_changed);
  d.power_on();
  EXPECT_EQ(d.peek(cawdg), 0U);
  ASSERT_TRUE(d.write(cawdg, 100, kNow).ok());
  const Answer a = d.write(at(kCda, 150), 1, kNow);
  EXPECT_EQ(a.after, 300ms);
  EXPECT_EQ(d.peek(at(kCda, 150)), 0U);  // READY
  ASSERT_TRUE(d.write(at(kCda, 4), 1, kNow).ok());
  EXPECT_EQ(d.peek(cawdg), 0U);
  d.power_on();
  EXPECT_EQ(d.peek(cawdg), 100U);
  // The CANLust refusals: choices_only, a write of a text as a number.
  EXPECT_EQ(d.write(at(kCda, 260), 3, kNow).refusal, Refusal::not_a_choice);
  EXPECT_EQ(d.write(at(kCda, 90), 1, kNow).refusal, Refusal::wrong_kind);
  EXPECT_EQ(d.read(at(kCda, 90), kNow).refusal, Refusal::wrong_kind);
  EXPECT_EQ(d.error_flags(), 0);
}

TEST(OdStoredServed, Texts) {
  StoredServed d(kCda);
  char buf[100];
  TextAnswer t = d.read_text(at(kCda, 90), buf, kNow);
  ASSERT_TRUE(t.ok());
  EXPECT_EQ(std::string_view(buf, t.size), "CDA3000");
  t = d.read_text(at(kCda, 90), std::span<char>(buf, 3), kNow);
  EXPECT_EQ(std::string_view(buf, t.size), "CDA");
  EXPECT_EQ(d.read_text(at(kCda, 574), buf, kNow).refusal, Refusal::wrong_kind);
  EXPECT_EQ(d.read_text(kNoSlot, buf, kNow).refusal, Refusal::no_parameter);
  EXPECT_TRUE(d.write_text(at(kCda, 90), "PRESS 4", kNow).ok());
  EXPECT_EQ(d.store().text(at(kCda, 90)), "PRESS 4");
  EXPECT_EQ(d.write_text(at(kCda, 578), "X", kNow).refusal, Refusal::read_only);
  EXPECT_EQ(d.write_text(at(kCda, 574), "X", kNow).refusal, Refusal::wrong_kind);
  EXPECT_EQ(d.write_text(at(kCda, 90), std::string(100, 'x'), kNow).refusal, Refusal::too_high);
  EXPECT_EQ(d.write_text(at(kCda, 90), std::string_view("a\0", 2), kNow).refusal,
            Refusal::bad_value);
  EXPECT_EQ(d.store().text(at(kCda, 90)), "PRESS 4");
}

// LUSTBUS manual 11.4, the MC6000's download through 80-SLOAD.
TEST(OdStoredServed, DownloadOfAValidDataSet) {
  StoredServedConfig c;
  c.timing.download_check = 200ms;
  StoredServed d(kMc, c);
  d.clear_error_flags(0xFF);
  const Slot sload = at(kMc, 80);
  const Slot rssl1 = at(kMc, 417);
  const Slot rsio = at(kMc, 428);
  d.set_power_stage(true);
  EXPECT_EQ(d.write(sload, raw(Type::int16, -1), kNow).refusal,
            Refusal::not_now);  // "only ... in a stillstand"
  d.clear_error_flags(0xFF);
  d.set_power_stage(false);
  EXPECT_EQ(d.write(sload, raw(Type::int16, -2), kNow).refusal, Refusal::not_now);  // -2 without -1
  d.clear_error_flags(0xFF);
  ASSERT_TRUE(d.write(sload, raw(Type::int16, -1), kNow).ok());
  EXPECT_TRUE(d.downloading());
  EXPECT_EQ(number(Type::int16, d.peek(sload)), -1);
  // The data set's value untested into RAM; any other write acknowledged and dropped.
  ASSERT_TRUE(d.write(rssl1, 3, kNow).ok());
  ASSERT_TRUE(d.write(rsio, 1234, kNow).ok());
  EXPECT_EQ(d.peek(rssl1), 3U);
  EXPECT_EQ(d.store().kept(rssl1), 0U);
  EXPECT_EQ(d.peek(rsio), 0U);
  ASSERT_TRUE(d.write(sload, raw(Type::int16, -2), kNow).ok());
  EXPECT_EQ(number(Type::int16, d.read(sload, kNow + 100ms).raw), -1);  // testing
  EXPECT_EQ(d.write(rssl1, 4, kNow + 100ms).refusal, Refusal::not_now);
  d.clear_error_flags(0xFF);
  EXPECT_EQ(d.read(sload, kNow + 200ms).raw, 0U);
  EXPECT_FALSE(d.downloading());
  EXPECT_EQ(d.store().kept(rssl1), 3U);
  d.power_on();
  EXPECT_EQ(d.peek(rssl1), 3U);
}

TEST(OdStoredServed, DownloadOfAnImplausibleDataSetBringsTheOldOneBack) {
  StoredServed d(kMc);  // the check ends at once
  d.clear_error_flags(0xFF);
  const Slot sload = at(kMc, 80);
  ASSERT_TRUE(d.write(sload, raw(Type::int16, -1), kNow).ok());
  ASSERT_TRUE(d.write(at(kMc, 417), 3, kNow).ok());
  ASSERT_TRUE(d.write(at(kMc, 419), 9, kNow).ok());  // above 7: taken untested
  ASSERT_TRUE(d.write(sload, raw(Type::int16, -2), kNow).ok());
  EXPECT_EQ(d.read(sload, kNow).raw, 419U);  // the first implausible parameter
  EXPECT_EQ(d.peek(at(kMc, 417)), 0U);
  EXPECT_EQ(d.peek(at(kMc, 419)), 6U);
  EXPECT_EQ(d.write(sload, 5, kNow).refusal, Refusal::too_high);  // 0.. are the drive's answers
  d.clear_error_flags(0xFF);
  EXPECT_EQ(d.write(sload, raw(Type::int16, -3), kNow).refusal, Refusal::too_low);
}

// check() says what write() does, for any slot, value and state.
TEST(OdStoredServed, CheckAgreesWithWrite) {
  std::mt19937 gen(5);
  for (const Dictionary* dict : {&kVf, &kMc, &kCda}) {
    StoredServed d(*dict);
    for (int i = 0; i < 50000; ++i) {
      const auto s = static_cast<Slot>(gen() % (dict->size() + 1));
      const Raw values[] = {0, 1, 3, 7, 26, 0xFFFFFFFFU, 0xFFFFFFFEU, static_cast<Raw>(gen())};
      const Raw r = values[gen() % 8];
      d.set_power_stage(gen() % 4 == 0);
      const Refusal before = d.check(s, r, kNow);
      const std::uint8_t flags = d.error_flags();
      const Answer a = d.write(s, r, kNow);
      ASSERT_EQ(a.refusal, before) << i;
      const bool keeps = dict->slot_of(Role::error_flags) != kNoSlot;
      const bool enters = keeps && before != Refusal::none && before != Refusal::latched;
      ASSERT_EQ(d.error_flags(), enters ? (flags | error_flag(before)) : flags) << i;
      if (gen() % 3 == 0) d.clear_error_flags(0xFF);
      if (gen() % 500 == 0) d.power_on();
    }
  }
}

// The VF1000 of today: drive::StoredParameters behind the communication word's rules (the latch,
// drive::check_write, siof_bits_for). Random writes, reads of 85, power-ons: od::StoredServed keeps
// the same values and the same 85-SIOF.
// What a description reports as the factory default: the drive's own, its overlay's where it has
// one (VF-E20), the entry's elsewhere; a bare ServedParameters falls back on the entry's.
TEST(OdStoredServed, FactoryDefaultIsTheDrivesOwn) {
  const StoredServed interbus(kVf);
  const StoredServed standalone(kVf, {.defaults = test::kVfStandalone});
  EXPECT_EQ(interbus.factory_default(at(kVf, 1)), 4U);
  EXPECT_EQ(standalone.factory_default(at(kVf, 1)), 0U);
  EXPECT_EQ(standalone.factory_default(at(kVf, 906)), 200U);
  EXPECT_EQ(standalone.factory_default(kNoSlot), 0U);
  const ServedParameters& plain = standalone;
  EXPECT_EQ(plain.ServedParameters::factory_default(at(kVf, 1)), 4U);
  EXPECT_EQ(plain.ServedParameters::factory_default(at(kVf, 911)), 0U);
  EXPECT_EQ(plain.ServedParameters::factory_default(kNoSlot), 0U);
}

TEST(OdStoredServedKeepsTodays, DriveStoredParametersUnderTheCommWordsRules) {
  using drive::Category;
  using T = drive::DataType;
  const drive::ParameterInfo today[] = {
      {1, "MODE", "", Category::eeprom, T::usign8, 0, 4, 4, 1.0, ""},
      {3, "CNTL", "", Category::ram_control, T::binary8, 0, 0xFF, 0, 1.0, ""},
      {4, "FSSEL", "", Category::eeprom, T::usign8, 0, 25, 25, 1.0, ""},
      {5, "FSSIO", "Hz", Category::eeprom_ram, T::fixpoint16, 0, 19999, 0, 0.05, ""},
      {12, "FOUT", "Hz", Category::ram_actual, T::fixpoint16, 0, 0xFFFF, 0, 0.05, ""},
      {22, "VB2", "%", Category::eeprom, T::fixpoint16, 0, 0x01F4, 0x00A0, 0.05, ""},
      {71, "PROG", "", Category::eeprom, T::usign8, 0, 1, 0, 1.0, ""},
      {84, "SIOT", "ms", Category::eeprom, T::usign16, 0, 0xFFFF, 0, 1.0, ""},
      {85, "SIOF", "", Category::ram_actual, T::binary8, 0, 0xFF, 0, 1.0, ""},
      {91, "TYPE", "", Category::ram_actual, T::usign16, 0, 0xFFFF, 1000, 1.0, ""},
      {906, "IB-WD", "ms", Category::eeprom, T::usign16, 8, 0xFFFF, 200, 1.0, ""},
      {911, "FDRIV", "Hz", Category::ram_control, T::integer16, 0x8000, 0x7FFF, 0, 0.05, ""},
  };
  drive::StoredParameters old(today, 71);
  old.power_on();
  StoredServed now(kVf);
  ASSERT_EQ(kVf.size(), std::size(today));
  std::mt19937 gen(38);
  for (int step = 0; step < 100000; ++step) {
    const std::size_t i = gen() % std::size(today);
    const drive::ParameterInfo& p = today[i];
    const Slot s = kVf.slot(p.number);
    const bool stage = gen() % 4 == 0;
    now.set_power_stage(stage);
    const Word near[] = {
        p.min, p.max, p.default_value, static_cast<Word>(p.max + 1), static_cast<Word>(p.min - 1),
        1};
    const auto w = gen() % 2 == 0 ? near[gen() % 6] : static_cast<Word>(gen());
    switch (gen() % 8) {
      case 0: {  // a read of 85-SIOF
        const auto bits = static_cast<std::uint8_t>(old.read(old.siof_slot()));
        old.clear_siof(bits);
        ASSERT_EQ(now.read(kVf.slot(85), Time{}).raw, bits) << step;
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
        const Answer a = now.write(s, from_bus(kVf[s].type, w, 16), Time{});
        ASSERT_EQ(error_flag(a.refusal), bits) << step;
        break;
      }
    }
    ASSERT_EQ(now.error_flags(), old.siof()) << step;
    for (std::size_t k = 0; k < std::size(today); ++k) {
      const Slot t = kVf.slot(today[k].number);
      ASSERT_EQ(pattern(kVf[t].type, now.store().ram(t)), old.store().value(k))
          << step << " " << today[k].name;
      ASSERT_EQ(pattern(kVf[t].type, now.store().kept(t)), old.store().eeprom_value(k))
          << step << " " << today[k].name;
    }
  }
}

}  // namespace
}  // namespace ibs::od
