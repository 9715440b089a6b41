// 85-SIOF/SERR (seed 000 9.2 table) in od, the one definition: its bits, their texts, and
// drive::'s names, which forward here.
#include <gtest/gtest.h>

#include <type_traits>

#include "ibs/drive/siof.hpp"
#include "ibs/od/siof.hpp"

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

TEST(OdSiof, DriveNamesAreTheseOnes) {
  static_assert(std::is_same_v<drive::SiofBit, SiofBit>);
  EXPECT_EQ(drive::siof_mask(drive::SiofBit::no_change), 0x40);
  EXPECT_EQ(drive::kSiofNumber, kSiofNumber);
  EXPECT_EQ(drive::describe_siof(0x80), "80H: invalid value");
  EXPECT_EQ(drive::to_string(drive::SiofBit::watchdog), "watchdog");
}

}  // namespace
}  // namespace ibs::od
