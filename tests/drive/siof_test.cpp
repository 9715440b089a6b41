// 85-SIOF bits (LUSTBUS manual 9.2) and their description.
#include "ibs/drive/siof.hpp"

#include <gtest/gtest.h>

namespace {

using namespace ibs::drive;

TEST(Siof, BitValuesOfTheLustbusTable) {
  EXPECT_EQ(siof_mask(SiofBit::power_on), 0x01);
  EXPECT_EQ(siof_mask(SiofBit::watchdog), 0x02);
  EXPECT_EQ(siof_mask(SiofBit::eeprom_busy), 0x04);
  EXPECT_EQ(siof_mask(SiofBit::checksum), 0x08);
  EXPECT_EQ(siof_mask(SiofBit::no_parameter), 0x20);
  EXPECT_EQ(siof_mask(SiofBit::no_change), 0x40);
  EXPECT_EQ(siof_mask(SiofBit::invalid_value), 0x80);
  EXPECT_TRUE(siof_has(0x81, SiofBit::power_on));
  EXPECT_TRUE(siof_has(0x81, SiofBit::invalid_value));
  EXPECT_FALSE(siof_has(0x81, SiofBit::no_change));
}

TEST(Siof, DescribesEverySetBitAndNamesUndefinedOnes) {
  EXPECT_EQ(describe_siof(0x00), "00H: no error bit");
  EXPECT_EQ(describe_siof(0x80), "80H: invalid value");
  EXPECT_EQ(describe_siof(0x21), "21H: power on, no parameter");
  EXPECT_EQ(describe_siof(0x10), "10H: undefined bit 4");
  EXPECT_EQ(describe_siof(0x48),
            "48H: checksum error (unintended control bits), no change permitted");
}

}  // namespace
