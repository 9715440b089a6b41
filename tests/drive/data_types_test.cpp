// The VF1000 data types (LUSTBUS manual 2.3.1; INTERBUS manual 4.1.3.3): type and category codes, raw <->
// engineering conversions, the error-variable coding.
#include "ibs/drive/data_types.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace {

using namespace ibs::drive;

TEST(DataTypeCodes, AsciiCharactersOfTheDescriptionRecord) {
  EXPECT_EQ(type_code(DataType::binary8), '1');
  EXPECT_EQ(type_code(DataType::fixpoint16), '2');
  EXPECT_EQ(type_code(DataType::usign16), '3');
  EXPECT_EQ(type_code(DataType::usign8), '4');
  EXPECT_EQ(type_code(DataType::vf_error), '5');
  EXPECT_EQ(type_code(DataType::password), '6');
  EXPECT_EQ(type_code(DataType::integer16), '7');
  for (char c = '1'; c <= '7'; ++c) EXPECT_EQ(type_code(*data_type_from_code(c)), c);
  EXPECT_FALSE(data_type_from_code('0').has_value());
  EXPECT_FALSE(data_type_from_code('8').has_value());
  EXPECT_EQ(to_string(DataType::fixpoint16), "PT_FIXPOINT16");
}

TEST(DataTypeRanges, SingleByteTypesHaveAZeroHighByte) {
  EXPECT_EQ(type_max_raw(DataType::binary8), 0x00FF);
  EXPECT_EQ(type_max_raw(DataType::usign8), 0x00FF);
  EXPECT_EQ(type_max_raw(DataType::usign16), 0xFFFF);
  EXPECT_EQ(type_max_raw(DataType::password), 0xFFFF);
  EXPECT_EQ(type_min_raw(DataType::integer16), 0x8000);
  EXPECT_EQ(type_max_raw(DataType::integer16), 0x7FFF);
  EXPECT_TRUE(raw_in_range(DataType::integer16, 0xFFFF, 0x8000, 0x7FFF));  // -1
  EXPECT_FALSE(raw_in_range(DataType::usign16, 0xFFFF, 0, 0x7FFF));
  EXPECT_FALSE(raw_in_range(DataType::integer16, 0x8000, 0xFFF6, 0x000A));  // -32768 < -10
  EXPECT_TRUE(raw_in_range(DataType::integer16, 0xFFF6, 0xFFF6, 0x000A));
}

TEST(Fixpoint16, ConvertsInFiveHundredthsBothWays) {
  // LUSTBUS manual 6.2.2: 50.00 Hz = 03E8H; 7.1.1: 23.15 Hz = 463; INTERBUS manual 4.1.3.2.1: 1F4H = 25 Hz.
  EXPECT_EQ(from_engineering(DataType::fixpoint16, 50.00), 0x03E8);
  EXPECT_EQ(from_engineering(DataType::fixpoint16, 23.15), 463);
  EXPECT_DOUBLE_EQ(*to_engineering(DataType::fixpoint16, 0x01F4), 25.0);
  EXPECT_DOUBLE_EQ(*to_engineering(DataType::fixpoint16, 0x00A0), 8.0);  // 4.1.3.3.1: 20*8
  for (unsigned raw = 0; raw <= 0xFFFF; raw += 7) {
    const auto w = static_cast<ibs::Word>(raw);
    ASSERT_EQ(from_engineering(DataType::fixpoint16, *to_engineering(DataType::fixpoint16, w)), w);
  }
}

TEST(Fixpoint16, LargestValueIs3276p75NotThe3276p80OfTheTable) {
  EXPECT_EQ(from_engineering(DataType::fixpoint16, 3276.75), 0xFFFF);
  EXPECT_FALSE(from_engineering(DataType::fixpoint16, 3276.80).has_value());
  EXPECT_FALSE(from_engineering(DataType::fixpoint16, -0.05).has_value());
  EXPECT_EQ(from_engineering(DataType::fixpoint16, -0.02), 0);  // rounds to 0.00
  EXPECT_FALSE(from_engineering(DataType::fixpoint16, std::nan("")).has_value());
  EXPECT_FALSE(
      from_engineering(DataType::fixpoint16, std::numeric_limits<double>::infinity()).has_value());
}

TEST(IntegerTypes, ConvertWithinTheirRanges) {
  EXPECT_EQ(from_engineering(DataType::usign8, 255.0), 0x00FF);
  EXPECT_FALSE(from_engineering(DataType::usign8, 256.0).has_value());
  EXPECT_EQ(from_engineering(DataType::binary8, 128.0), 0x0080);  // LUSTBUS manual 7.1.1: CNTL = 128
  EXPECT_EQ(from_engineering(DataType::usign16, 65535.0), 0xFFFF);
  EXPECT_FALSE(from_engineering(DataType::usign16, 65536.0).has_value());
  EXPECT_EQ(from_engineering(DataType::password, 1234.0), 1234);
  EXPECT_EQ(from_engineering(DataType::integer16, -1.0), 0xFFFF);
  EXPECT_EQ(from_engineering(DataType::integer16, -32768.0), 0x8000);
  EXPECT_FALSE(from_engineering(DataType::integer16, 32768.0).has_value());
  EXPECT_DOUBLE_EQ(*to_engineering(DataType::integer16, 0xFFEC), -20.0);
  EXPECT_DOUBLE_EQ(*to_engineering(DataType::integer16, 0xFFEC, 0.05), -1.0);
  EXPECT_EQ(from_engineering(DataType::integer16, -1.0, 0.05), 0xFFEC);
}

TEST(VfError, CodingOfSection4133) {
  // "no error" in both fields: 0FH each.
  EXPECT_EQ(decode_vf_error(kVfErrorNone), (VfError{}));
  EXPECT_EQ(encode_vf_error(VfError{}), kVfErrorNone);
  // Error code 3 entered 12 minutes (2 x 6 min) after power-on.
  const VfError e{3, 2};
  EXPECT_EQ(encode_vf_error(e), 0x0302);
  EXPECT_EQ(decode_vf_error(0x0302), e);
  EXPECT_EQ(e.time_minutes(), 12U);
  // Highest valid code 0EH and time 0EH (84 min).
  EXPECT_EQ(encode_vf_error(VfError{14, 14}), 0x0E0E);
  EXPECT_EQ(decode_vf_error(0x0E0E).time_minutes(), 84U);
  EXPECT_FALSE(encode_vf_error(VfError{15, std::nullopt}).has_value());
  EXPECT_FALSE(encode_vf_error(VfError{1, 15}).has_value());
  EXPECT_FALSE(to_engineering(DataType::vf_error, 0x0302).has_value());
  EXPECT_FALSE(from_engineering(DataType::vf_error, 3.0).has_value());
}

TEST(VfError, ErrorTimeIsInTenthsOfAnHourNotHours) {
  // Erratum VF-E10: LUSTBUS manual 2.3.1 says "time of error (0-15h)" but its own table gives the unit
  // 1/10 h; INTERBUS manual 4.1.3.3: "in 6-minute increments (max. 15 * 6 minutes)". 0FH is the basic
  // state, so 14 steps = 84 minutes is the longest time, never 14 hours.
  EXPECT_EQ(decode_vf_error(0x0501).time_minutes(), 6U);
  EXPECT_EQ(decode_vf_error(0x050A).time_minutes(), 60U);  // ten steps: one hour
  EXPECT_EQ(decode_vf_error(0x050E).time_minutes(), 84U);
  EXPECT_EQ(decode_vf_error(0x050F).time_minutes(), std::nullopt);  // 0FH: no time entered
  EXPECT_EQ(encode_vf_error(VfError{5, 10}), 0x050A);
}

TEST(VfError, ErasedEepromFFFFReadsAsNoError) {
  // LUSTBUS manual 2.3.1: erasing the EEPROM leaves FFH, "error number 15 means no error".
  EXPECT_EQ(decode_vf_error(0xFFFF), (VfError{}));
  EXPECT_EQ(decode_vf_error(0xF3F2), (VfError{3, 2}));  // high nibbles are ignored
}

TEST(Categories, CodesStorageAndWritability) {
  for (char c = '0'; c <= '7'; ++c) EXPECT_EQ(category_code(*category_from_code(c)), c);
  EXPECT_FALSE(category_from_code('8').has_value());
  EXPECT_EQ(storage(Category::eeprom_specific), Storage::eeprom);
  EXPECT_EQ(storage(Category::ram_actual_specific), Storage::ram_actual);
  EXPECT_TRUE(inverter_specific(Category::ram_control_specific));
  EXPECT_FALSE(inverter_specific(Category::eeprom_ram));
  EXPECT_FALSE(writable(Category::ram_actual));
  EXPECT_FALSE(writable(Category::ram_actual_specific));
  EXPECT_TRUE(writable(Category::eeprom));
  EXPECT_TRUE(needs_power_stage_disabled(Category::eeprom));
  EXPECT_TRUE(needs_power_stage_disabled(Category::eeprom_specific));
  EXPECT_FALSE(needs_power_stage_disabled(Category::eeprom_ram));
  EXPECT_FALSE(needs_power_stage_disabled(Category::ram_control));
}

}  // namespace
