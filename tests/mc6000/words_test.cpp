// The MC6000's own bits of the control word (INTERBUS manual 5.3.1).
#include <gtest/gtest.h>

#include "ibs/devices/mc6000/descriptor.hpp"

namespace ibs::devices::mc6000 {
namespace {

TEST(ControlWord, Mc6000BitsOf531) {
  EXPECT_TRUE(decode_control_bits(0x4000).os00);
  EXPECT_FALSE(decode_control_bits(0x4000).os01);
  EXPECT_TRUE(decode_control_bits(0x8000).os01);
}

}  // namespace
}  // namespace ibs::devices::mc6000
