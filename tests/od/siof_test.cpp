// 85-SIOF/SERR (LUSTBUS manual 9.2 table) in od, the one definition: its bits, their texts, each
// refusal's bit, and drive::'s names, which forward here.
#include "ibs/drive/siof.hpp"

#include <gtest/gtest.h>

#include <type_traits>

#include "ibs/od/served.hpp"

namespace ibs::od {
namespace {

TEST(OdSiof, BitValuesOfTheLustbusTable) {
  EXPECT_EQ(siof_mask(SiofBit::power_on), 0x01);
  EXPECT_EQ(siof_mask(SiofBit::watchdog), 0x02);
  EXPECT_EQ(siof_mask(SiofBit::eeprom_busy), 0x04);
  EXPECT_EQ(siof_mask(SiofBit::checksum), 0x08);
  EXPECT_EQ(siof_mask(SiofBit::no_parameter), 0x20);
  EXPECT_EQ(siof_mask(SiofBit::no_change), 0x40);
  EXPECT_EQ(siof_mask(SiofBit::invalid_value), 0x80);
  EXPECT_EQ(describe_siof(0x21), "21H: power on, no parameter");
  EXPECT_EQ(describe_siof(0x10), "10H: undefined bit 4");
  EXPECT_EQ(kSiofNumber, 85);
}

// LUSTBUS manual 9.2: 20H "no parameter", 40H "change not permitted", 80H "invalid value", 04H "EEPROM
// busy", 08H "error in the data transfer"; a latched write and a taken one enter nothing.
TEST(OdSiof, EachRefusalsBit) {
  EXPECT_EQ(error_flag(Refusal::none), 0);
  EXPECT_EQ(error_flag(Refusal::latched), 0);
  EXPECT_EQ(error_flag(Refusal::no_parameter), 0x20);
  EXPECT_EQ(error_flag(Refusal::read_only), 0x40);
  EXPECT_EQ(error_flag(Refusal::not_now), 0x40);
  EXPECT_EQ(error_flag(Refusal::wrong_kind), 0x40);
  EXPECT_EQ(error_flag(Refusal::busy), 0x04);
  EXPECT_EQ(error_flag(Refusal::transfer_error), 0x08);
  for (const Refusal r :
       {Refusal::bad_value, Refusal::too_high, Refusal::too_low, Refusal::not_a_choice}) {
    EXPECT_EQ(error_flag(r), 0x80) << to_string(r);
  }
  EXPECT_EQ(refusal_of(Fit::too_low), Refusal::too_low);
  EXPECT_EQ(refusal_of(Fit::wrong_type), Refusal::bad_value);
}

TEST(OdSiof, DriveNamesAreTheseOnes) {
  static_assert(std::is_same_v<drive::SiofBit, SiofBit>);
  EXPECT_EQ(drive::siof_mask(drive::SiofBit::no_change), 0x40);
  EXPECT_EQ(drive::kSiofNumber, kSiofNumber);
  EXPECT_EQ(drive::describe_siof(0x80), "80H: invalid value");
  EXPECT_EQ(drive::to_string(drive::SiofBit::watchdog), "watchdog");
}

}  // namespace
}  // namespace ibs::od
