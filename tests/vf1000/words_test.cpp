// The VF1000's own bits of the control word (INTERBUS manual 5.2.1) and its reference and actual words.
#include <gtest/gtest.h>

#include "ibs/devices/vf1000/descriptor.hpp"

namespace ibs::devices::vf1000 {
namespace {

TEST(ControlWord, Vf1000BitsOf521) {
  const auto b = decode_control_bits(0x8070);
  EXPECT_TRUE(b.ramp_enable);
  EXPECT_TRUE(b.ramp_run);
  EXPECT_TRUE(b.ramp_follow);
  EXPECT_TRUE(b.str);
  EXPECT_FALSE(b.stl);
  EXPECT_FALSE(b.s1ind);
  EXPECT_FALSE(b.s2ind);
  EXPECT_TRUE(decode_control_bits(0x4000).stl);
  EXPECT_TRUE(decode_control_bits(0x2000).s1ind);
  EXPECT_TRUE(decode_control_bits(0x1000).s2ind);
  for (unsigned w = 0; w <= 0xFFFF; w += 0x10) {
    const auto masked = static_cast<Word>(w & 0xF070U);
    EXPECT_EQ(encode_control_bits(decode_control_bits(masked)), masked);
  }
}

}  // namespace
}  // namespace ibs::devices::vf1000
