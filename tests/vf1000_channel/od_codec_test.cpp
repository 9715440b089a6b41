// The communication word's codec of the object dictionary (vf1000_channel/od_codec.hpp, issue 38
// K1) against today's channel, which builds its records and NAKs from drive::ParameterInfo
// (description.hpp, server.cpp): the 18-byte description record of every VF1000 entry byte for
// byte (4.1.3.3), the type and category characters, every value word both ways, and the NAK and
// 85-SIOF bits of every refused access (4.1.4).
#include "ibs/vf1000_channel/od_codec.hpp"

#include <gtest/gtest.h>

#include <array>
#include <string>

#include "ibs/devices/vf1000/dictionary.hpp"
#include "ibs/devices/vf1000/parameters.hpp"
#include "ibs/od/stored_served.hpp"
#include "ibs/vf1000_channel/description.hpp"

namespace {

using namespace ibs;
using namespace ibs::vf1000_channel;
namespace vf = ibs::devices::vf1000;

std::string label(const od::Entry& e) {
  return std::to_string(e.number) + "-" + std::string(e.name);
}

TEST(VfCodec, DescriptionEqualsTodaysForEveryEntry) {
  const auto table = vf::parameters();
  ASSERT_EQ(table.size(), vf::kDictionary.size());
  for (std::size_t i = 0; i < table.size(); ++i) {
    const od::Entry& e = vf::kDictionary[static_cast<od::Slot>(i)];
    EXPECT_EQ(description(e), make_description(table[i])) << label(e);
    for (std::size_t b = 0; b < kDescriptionLength; ++b) {
      EXPECT_EQ(description_byte(e, b), description_byte(table[i], b)) << label(e) << " byte " << b;
    }
  }
}

// A drive without the INTERBUS software describes its own factory defaults (VF-E20): the record
// takes the default as the drive has it, the overlay's.
TEST(VfCodec, DescriptionCarriesTheDrivesOwnDefault) {
  const auto table = vf::standalone_parameters();
  const od::StoredServed standalone(vf::kDictionary, {.defaults = vf::kStandaloneDefaults});
  for (std::size_t i = 0; i < table.size(); ++i) {
    const auto s = static_cast<od::Slot>(i);
    EXPECT_EQ(description(vf::kDictionary[s], standalone.factory_default(s)),
              make_description(table[i]))
        << label(vf::kDictionary[s]);
  }
  const od::Slot mode = vf::kDictionary.slot(vf::pnr::kMode);
  EXPECT_EQ(description(vf::kDictionary[mode], standalone.factory_default(mode))[17], 0);
  EXPECT_EQ(description(vf::kDictionary[mode])[17], 4) << "the INTERBUS software's 3.1.1";
}

// The master's decoder reads every record back as the entry (name, unit, codes, limits).
TEST(VfCodec, EveryRecordDecodesToItsEntry) {
  for (const od::Entry& e : vf::kDictionary.entries()) {
    const Description d = decode_description(description(e));
    EXPECT_EQ(d.name, e.name);
    EXPECT_EQ(d.unit, e.unit);
    ASSERT_TRUE(d.category) << label(e);
    EXPECT_EQ(drive::category_code(*d.category), *category_code(e));
    ASSERT_TRUE(d.type) << label(e);
    EXPECT_EQ(drive::type_code(*d.type), *type_code(e.type));
    EXPECT_EQ(od::number(e.type, value_of(e, d.min)), e.min);
    EXPECT_EQ(od::number(e.type, value_of(e, d.max)), e.max);
    EXPECT_EQ(od::number(e.type, value_of(e, d.default_value)), e.default_value);
  }
}

// The characters of every type and category of the standard family, as drive:: codes them.
TEST(VfCodec, TypeAndCategoryCodesAreTodays) {
  const std::pair<drive::DataType, od::Type> types[] = {
      {drive::DataType::binary8, od::Type::binary8},   {drive::DataType::fixpoint16, od::Type::fixpoint16},
      {drive::DataType::usign16, od::Type::usign16},   {drive::DataType::usign8, od::Type::usign8},
      {drive::DataType::vf_error, od::Type::error16},  {drive::DataType::password, od::Type::password},
      {drive::DataType::integer16, od::Type::int16}};
  for (const auto& [today, now] : types) EXPECT_EQ(type_code(now), drive::type_code(today));
  for (const od::Type t : {od::Type::int8, od::Type::usign32, od::Type::int32, od::Type::int32q16,
                           od::Type::float_ieee, od::Type::error32, od::Type::string}) {
    EXPECT_FALSE(type_code(t)) << od::to_string(t) << " does not travel in one word";
  }
  const od::Storage storages[] = {od::Storage::ram_control, od::Storage::ram_actual,
                                  od::Storage::eeprom, od::Storage::eeprom_ram};
  for (int c = 0; c < 8; ++c) {
    od::Entry e;
    e.storage = storages[c % 4];
    e.specific = c >= 4;
    EXPECT_EQ(category_code(e), drive::category_code(static_cast<drive::Category>(c)));
  }
  od::Entry flash;
  flash.storage = od::Storage::flash;
  EXPECT_FALSE(category_code(flash));
  od::Entry kept_read_only;
  kept_read_only.storage = od::Storage::eeprom;
  kept_read_only.read_only = true;
  EXPECT_FALSE(category_code(kept_read_only));
}

// Every word of a value transfer reads as the Raw the drive checks, and every value goes out as
// the word it came in: the checks accept exactly the words today's accept.
TEST(VfCodec, EveryWordOfEveryEntryBothWays) {
  const auto table = vf::parameters();
  for (std::size_t i = 0; i < table.size(); ++i) {
    const od::Entry& e = vf::kDictionary[static_cast<od::Slot>(i)];
    for (std::uint32_t w = 0; w <= 0xFFFF; ++w) {
      const auto word = static_cast<Word>(w);
      const od::Raw r = value_of(e, word);
      ASSERT_EQ(od::fit(e, r) == od::Fit::ok, drive::in_range(table[i], word)) << label(e) << " " << w;
      if (od::fits(e.type, drive::raw_as_number(table[i].type, word))) {
        ASSERT_EQ(value_word(e, r), word) << label(e) << " " << w;
      }
    }
  }
}

// A refused access is today's NAK with today's 85-SIOF bits, for every entry, every word and both
// power-stage states: the PNR (access) and the value (4.1.3.2, 4.1.4); and 85-SIOF set refuses
// before anything (siof_pending, no bit).
TEST(VfCodec, RefusalsAreTodaysNaksForEveryEntryAndWord) {
  const auto table = vf::parameters();
  od::StoredServed served(vf::kDictionary);
  served.clear_error_flags(0xFF);
  const auto reason_today = [](drive::WriteCheck c) {
    switch (c) {
      case drive::WriteCheck::no_parameter:
        return NakReason::no_parameter;
      case drive::WriteCheck::no_change:
        return NakReason::no_change;
      default:
        return NakReason::invalid_value;
    }
  };
  for (const bool stage : {false, true}) {
    served.set_power_stage(stage);
    for (std::size_t i = 0; i < table.size(); ++i) {
      const auto s = static_cast<od::Slot>(i);
      const od::Entry& e = vf::kDictionary[s];
      const drive::WriteCheck access = drive::check_access(&table[i], stage);
      const od::Refusal a = served.check(s, std::nullopt, Time{});
      ASSERT_EQ(a == od::Refusal::none, access == drive::WriteCheck::ok) << label(e);
      if (a != od::Refusal::none) {
        EXPECT_EQ(nak_reason(a), reason_today(access)) << label(e);
        EXPECT_EQ(siof_bits(a), drive::siof_bits_for(access)) << label(e);
        continue;
      }
      for (std::uint32_t w = 0; w <= 0xFFFF; w += (w < 0x200 ? 1 : 97)) {
        const drive::WriteCheck today = drive::check_write(&table[i], static_cast<Word>(w), stage);
        const od::Refusal now = served.check(s, value_of(e, static_cast<Word>(w)), Time{});
        ASSERT_EQ(now == od::Refusal::none, today == drive::WriteCheck::ok) << label(e) << " " << w;
        if (now != od::Refusal::none) {
          ASSERT_EQ(nak_reason(now), reason_today(today)) << label(e) << " " << w;
          ASSERT_EQ(siof_bits(now), drive::siof_bits_for(today)) << label(e) << " " << w;
        }
      }
    }
  }
  // No such parameter: refused before any entry is looked at.
  EXPECT_EQ(nak_reason(served.check(od::kNoSlot, std::nullopt, Time{})), NakReason::no_parameter);
  EXPECT_EQ(siof_bits(od::Refusal::no_parameter), 0x20);
  // 85-SIOF holds a bit: every transfer refused, nothing entered (4.1.4).
  served.raise_error_flags(0x01);
  const od::Refusal latched = served.check(vf::kDictionary.slot(vf::pnr::kVb2), std::nullopt, Time{});
  EXPECT_EQ(nak_reason(latched), NakReason::siof_pending);
  EXPECT_EQ(siof_bits(latched), 0);
  EXPECT_EQ(nak_reason(od::Refusal::transfer_error), NakReason::unintended_control_bits);
  EXPECT_EQ(siof_bits(od::Refusal::transfer_error), 0x08);
}

TEST(VfCodec, CheckAcceptsTheVf1000AndRefusesWhatCannotTravel) {
  EXPECT_FALSE(check(vf::kDictionary));
  const od::Entry siof{.number = 85, .name = "SIOF", .type = od::Type::binary8, .max = 0xFF,
                       .storage = od::Storage::ram_actual, .role = od::Role::error_flags};
  const auto refused = [&siof](od::Entry e) {
    const std::array entries{siof, e};
    const od::Dictionary d(entries);
    return check(d);
  };
  const od::Entry fine{.number = 0x3FF, .name = "ABCDE", .type = od::Type::usign16, .max = 10,
                       .unit = "Hz/s", .storage = od::Storage::eeprom};
  EXPECT_FALSE(refused(fine));
  od::Entry e = fine;
  e.name = "ABCDEF";
  EXPECT_EQ(refused(e).code, ErrorCode::table_bad_name);
  EXPECT_EQ(refused(e).message,
            "vf1000_channel: dictionary entry 1 (1023-ABCDEF): name of more than 5 characters "
            "(4.1.3.3)");
  e = fine;
  e.unit = "rev/min";
  EXPECT_EQ(refused(e).code, ErrorCode::table_bad_unit);
  e = fine;
  e.storage = od::Storage::flash;
  EXPECT_EQ(refused(e).code, ErrorCode::table_bad_role);
  e = fine;
  e.type = od::Type::int32q16;
  EXPECT_EQ(refused(e).code, ErrorCode::table_limits_outside_type);
  const std::array without_siof{fine};
  EXPECT_EQ(check(od::Dictionary(without_siof)).code, ErrorCode::table_lacks_siof);
}

}  // namespace
