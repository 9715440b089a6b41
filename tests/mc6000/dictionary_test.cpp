// The MC6000's object dictionary (devices/mc6000/dictionary, issue 38 W2) against the two tables of
// today it merges -- the PCP table kParameters (parameters.hpp, pcp::ParameterInfo) and the KEYPAD
// service structure kService (service.hpp: unit index, level, filters, areas, 11.3 texts) -- field
// by field, the defaults without the INTERBUS card (3.2.1, MC-D10) and the named numbers.
#include "ibs/devices/mc6000/dictionary.hpp"

#include <gtest/gtest.h>

#include <string>

#include "ibs/devices/mc6000/parameters.hpp"
#include "ibs/devices/mc6000/service.hpp"
#include "ibs/od/store.hpp"
#include "ibs/pcp/parameter_store.hpp"

namespace {

using namespace ibs;
using namespace ibs::devices::mc6000;

// What each of pcp::'s types is in od's one family (the plan's table 1.2).
od::Type type_of(pcp::DataType t) {
  switch (t) {
    case pcp::DataType::usign8:
      return od::Type::usign8;
    case pcp::DataType::usign16:
      return od::Type::usign16;
    case pcp::DataType::fixpoint16:
      return od::Type::fixpoint16;
    case pcp::DataType::integer16:
      return od::Type::int16;
    case pcp::DataType::int32q16:
      return od::Type::int32q16;
    case pcp::DataType::float_ieee:
      return od::Type::float_ieee;
    case pcp::DataType::mc_error:
      return od::Type::error32;
    case pcp::DataType::password:
      return od::Type::password;
  }
  ADD_FAILURE() << "a pcp::DataType without an od::Type";
  return od::Type::string;
}

od::Storage storage_of(pcp::Category c) {
  switch (c) {
    case pcp::Category::ram_actual:
      return od::Storage::ram_actual;
    case pcp::Category::ram_control:
      return od::Storage::ram_control;
    case pcp::Category::eeprom:
      return od::Storage::eeprom;
  }
  return od::Storage::flash;
}

// 107-UNIT's texts, by the unit index.
std::string_view unit_text(std::uint8_t index) {
  const od::Entry* unit = kDictionary.find(kUnit);
  const od::Choice* c = unit == nullptr ? nullptr : unit->choice(index);
  return c == nullptr ? "?" : c->name;
}

TEST(McDictionary, MatchesTableAndService) {
  const auto entries = kDictionary.entries();
  ASSERT_EQ(entries.size(), kParameters.size());
  EXPECT_EQ(kDictionary.profile(), od::Profile::lust_enhanced);
  for (std::size_t i = 0; i < kParameters.size(); ++i) {
    const pcp::ParameterInfo& p = kParameters[i];
    const od::Entry& e = entries[i];
    SCOPED_TRACE(std::to_string(p.number) + "-" + std::string(p.name));
    // The PCP table.
    EXPECT_EQ(e.number, p.number);
    EXPECT_EQ(e.name, p.name);
    EXPECT_EQ(e.type, type_of(p.type));
    EXPECT_EQ(e.storage, storage_of(p.category));
    EXPECT_EQ(e.writable(), p.writable());
    EXPECT_FALSE(e.read_only);
    EXPECT_EQ(e.min, p.min);
    EXPECT_EQ(e.max, p.max);
    EXPECT_EQ(e.default_value, p.default_value);
    // The same raw patterns PCP and LUSTBUS carry.
    EXPECT_EQ(od::pattern(e.type, e.min_raw()), pcp::ParameterStore::to_raw(p, p.min));
    EXPECT_EQ(od::pattern(e.type, e.max_raw()), pcp::ParameterStore::to_raw(p, p.max));
    EXPECT_EQ(od::pattern(e.type, e.default_raw()), pcp::ParameterStore::default_raw(p));
    EXPECT_EQ(e.attributes, p.attributes);
    EXPECT_DOUBLE_EQ(e.scale, 1.0);
    const od::Role role = p.number == kSerr    ? od::Role::error_flags
                          : p.number == kProg  ? od::Role::load_defaults
                          : p.number == kSload ? od::Role::download
                                               : od::Role::value;
    EXPECT_EQ(e.role, role);
    EXPECT_EQ(e.elements, 1);
    EXPECT_FALSE(e.choices_only) << "11.3's texts name values; a number without one is still one";
    EXPECT_FALSE(e.source.empty());
    EXPECT_FALSE(e.text.empty());
    // The service structure.
    const ServiceEntry* s = service_entry(p.number);
    ASSERT_NE(s, nullptr);
    ASSERT_NE(e.keypad, nullptr);
    EXPECT_EQ(e.keypad->unit, s->unit);
    EXPECT_EQ(e.keypad->level, s->level);
    EXPECT_EQ(e.keypad->hardware, s->hardware_filter);
    EXPECT_EQ(e.keypad->structure, s->structure_filter);
    EXPECT_EQ(e.keypad->subject, static_cast<std::uint8_t>(s->subject));
    EXPECT_EQ(e.keypad->activity, static_cast<std::uint8_t>(s->activity));
    EXPECT_EQ(e.in_data_set, card_writeable(p.number));
    // The unit: 107-UNIT's text of the KEYPAD index, written out ("" for "-").
    EXPECT_EQ(e.unit, s->unit == 0 ? std::string_view{} : unit_text(s->unit));
    // 11.3: the text of value 0, 1, ... is the choice of that code, and nothing else has one.
    ASSERT_EQ(e.choices.size(), s->texts.size());
    for (std::size_t c = 0; c < e.choices.size(); ++c) {
      EXPECT_EQ(e.choices[c].code, c);
      EXPECT_EQ(e.choices[c].name, s->texts[c]);
      EXPECT_TRUE(e.choices[c].text.empty());
    }
    // (Every value of the type: a choice is found by the value's number, 256 is no USIGN8.)
    for (std::uint32_t v = 0; v < 300 && od::fits(e.type, v); ++v) {
      const od::Choice* c = e.choice(v);
      EXPECT_EQ(c == nullptr ? std::string_view{} : c->name, substitution_text_of(p.number, v)) << v;
    }
    EXPECT_EQ(e.has(od::attr::kShowText), !e.choices.empty());
  }
}

// The store's and the PCP store's slots are the same: a core indexed by slot keeps its indices.
TEST(McDictionary, SlotsAreTheTablesPositions) {
  for (std::size_t i = 0; i < kParameters.size(); ++i) {
    EXPECT_EQ(kDictionary.slot(kParameters[i].number), static_cast<od::Slot>(i));
  }
  std::size_t found = 0;
  for (std::uint16_t n = 0; n <= od::kMaxNumber; ++n) found += kDictionary.find(n) != nullptr ? 1U : 0U;
  EXPECT_EQ(found, kParameters.size());
  EXPECT_EQ(kDictionary.slot_of(od::Role::error_flags), kDictionary.slot(kSerr));
  EXPECT_EQ(kDictionary.slot_of(od::Role::load_defaults), kDictionary.slot(kProg));
  EXPECT_EQ(kDictionary.slot_of(od::Role::download), kDictionary.slot(kSload));
  EXPECT_EQ(kDictionary.slot_of(od::Role::save), od::kNoSlot);
}

// INTERBUS manual 3.2.1's table: the eleven parameters the servo changes when it finds its INTERBUS card
// (the dictionary's defaults), and code 0 without the card (the overlay, MC-D10) -- the same as
// kOptionDefaults, which the core applies today.
TEST(McDictionary, OptionDefaultsAre3_2_1) {
  ASSERT_FALSE(od::Store::validate(kDictionary, kWithoutCardDefaults));
  ASSERT_EQ(kWithoutCardDefaults.size(), kOptionDefaults.size());
  for (std::size_t i = 0; i < kOptionDefaults.size(); ++i) {
    const OptionDefault& o = kOptionDefaults[i];
    const od::Entry* e = kDictionary.find(o.number);
    ASSERT_NE(e, nullptr) << o.number;
    EXPECT_EQ(e->default_value, o.with_card) << o.number;
    EXPECT_EQ(kWithoutCardDefaults[i].number, o.number);
    EXPECT_EQ(kWithoutCardDefaults[i].value, o.without_card) << o.number;
  }
  // 3.2.1's values by name: 402-CLSEL OPT1, 417..420-RSSLx RCON RCON OPT1 RCON, the input and
  // output functions ROPT1, 443/444-FIFx OFF.
  const std::pair<std::string_view, std::string_view> with_card[] = {
      {"CLSEL", "OPT1"}, {"RSSL1", "RCON"},  {"RSSL2", "RCON"},  {"RSSL3", "OPT1"},
      {"RSSL4", "RCON"}, {"FIS00", "ROPT1"}, {"FIS01", "ROPT1"}, {"FOS00", "ROPT1"},
      {"FOS01", "ROPT1"}, {"FIF0", "OFF"},   {"FIF1", "OFF"}};
  const od::Store card(kDictionary);
  const od::Store no_card(kDictionary, kWithoutCardDefaults);
  for (const auto& [name, text] : with_card) {
    const od::Entry* e = kDictionary.find(name);
    ASSERT_NE(e, nullptr) << name;
    const od::Slot s = kDictionary.slot(name);
    ASSERT_NE(e->choice(card.default_raw(s)), nullptr) << name;
    EXPECT_EQ(e->choice(card.default_raw(s))->name, text) << name;
    EXPECT_EQ(no_card.default_raw(s), 0U) << name << ": code 0, the one that names no option";
  }
  // Nothing else differs.
  for (od::Slot s = 0; s < kDictionary.size(); ++s) {
    bool overlaid = false;
    for (const auto& o : kWithoutCardDefaults) overlaid = overlaid || o.number == kDictionary[s].number;
    if (!overlaid) {
      EXPECT_EQ(no_card.default_raw(s), card.default_raw(s)) << kDictionary[s].name;
    }
  }
}

// The numbers the wing acts on name the entries the manuals give them, written once (409-BUTWD was
// defined three times).
TEST(McDictionary, NamedNumbersAreTheirEntries) {
  const std::pair<std::uint16_t, std::string_view> named[] = {
      {kProg, "PROG"},   {kPlrdy, "PLRDY"}, {kSpeed, "SPEED"}, {kSload, "SLOAD"},
      {kSbaud, "SBAUD"}, {kSaddr, "SADDR"}, {kSdmmy, "SDMMY"}, {kSwdgt, "SWDGT"},
      {kSerr, "SERR"},   {kType, "TYPE"},   {kUnit, "UNIT"},   {kStext, "STEXT"},
      {kCfcon, "CFCON"}, {kClsel, "CLSEL"}, {kSupi, "SUPI"},   {kIbcnf, "IBCNF"},
      {kIbstu, "IBSTU"}, {kIbsta, "IBSTA"}, {kButwd, "BUTWD"}, {kSctl1, "SCTL1"},
      {kRssl1, "RSSL1"}, {kRssl2, "RSSL2"}, {kRssl3, "RSSL3"}, {kRssl4, "RSSL4"},
      {kRsio, "RSIO"},   {kFis00, "FIS00"}, {kFis01, "FIS01"}, {kFif0, "FIF0"},
      {kFif1, "FIF1"},   {kFos00, "FOS00"}, {kFos01, "FOS01"}, {kReop1, "REOP1"},
      {kResio, "RESIO"}, {kRedev, "REDEV"}};
  ASSERT_EQ(std::size(named), kDictionary.size());
  for (const auto& [number, name] : named) {
    const od::Entry* e = kDictionary.find(number);
    ASSERT_NE(e, nullptr) << number;
    EXPECT_EQ(e->name, name);
  }
  EXPECT_EQ(kButwd, 409);
  EXPECT_EQ(kDictionary.find(kSbaud)->max, kHighestBaud);
  EXPECT_EQ(kDictionary.find(kType)->default_value, kMc6000TypeCode);
  // The selector codes the seeds name are the texts' codes.
  const od::Entry& rssl = *kDictionary.find(kRssl1);
  EXPECT_EQ(rssl.choice(kRsslRcon)->name, "RCON");
  EXPECT_EQ(rssl.choice(kRsslRsio)->name, "RSIO");
  EXPECT_EQ(rssl.choice(kRsslOpt1)->name, "OPT1");
  EXPECT_EQ(kDictionary.find(kClsel)->choice(kClselSio)->name, "SIO");
  EXPECT_EQ(kDictionary.find(kClsel)->choice(kClselOpt1)->name, "OPT1");
  EXPECT_EQ(kDictionary.find(kCfcon)->choice(kCfconScon)->name, "SCON");
  EXPECT_EQ(kDictionary.find(kFis00)->choice(kFunctionOff)->name, "OFF");
  EXPECT_EQ(kDictionary.find(kFis00)->choice(kFunctionRopt1)->name, "ROPT1");
  const od::Entry& reop = *kDictionary.find(kReop1);
  EXPECT_EQ(reop.choice(kReactionWarn)->name, "WARN");
  EXPECT_EQ(reop.choice(kReactionStop)->name, "STOP");
  EXPECT_EQ(reop.choice(kReactionOff)->name, "OFF");
  EXPECT_EQ(reop.choice(kReactionLock)->name, "LOCK");
  EXPECT_EQ(reop.choice(kReactionReset)->name, "RESET");
}

// What the PCP table has no column for, the dictionary says: when 405/406 and 81 act (at power-on,
// INTERBUS manual 3.2.2; 11.5), and which values a data set carries (11.4, the activity area).
TEST(McDictionary, KnowsWhatTheTableDidNotSay) {
  EXPECT_EQ(kDictionary.find(kSupi)->effect, od::Effect::at_restart);
  EXPECT_EQ(kDictionary.find(kIbcnf)->effect, od::Effect::at_restart);
  EXPECT_EQ(kDictionary.find(kSbaud)->effect, od::Effect::at_restart);
  EXPECT_EQ(kDictionary.find(kSbaud)->unit, "Bd");
  EXPECT_EQ(kDictionary.find(kSpeed)->unit, "rpm");
  EXPECT_EQ(kDictionary.find(kButwd)->unit, "ms");
  EXPECT_FALSE(kDictionary.find(kSbaud)->in_data_set) << "a download must not move the link";
  EXPECT_TRUE(kDictionary.find(kButwd)->in_data_set);
}

}  // namespace
