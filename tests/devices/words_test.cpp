// Control and status words in words: the DRIVECOM part (INTERBUS manual 5.1.2, 5.1.3) and each drive's
// own bits as its descriptor names them (VF1000 5.2.1/5.2.2, MC6000 5.3.1/5.3.2).
#include <gtest/gtest.h>

#include <string>

#include "ibs/devices/mc6000/descriptor.hpp"
#include "ibs/devices/vf1000/descriptor.hpp"
#include "ibs/drivecom/status_word.hpp"

namespace ibs::devices {
namespace {

TEST(ControlWord, ExplanationNamesCommandEdgeAndDeviceBits) {
  EXPECT_EQ(mc6000::explain_control_word(0x000F, 0x0006), "000F POWER-ON/ENABLE");
  EXPECT_EQ(mc6000::explain_control_word(0x0080, 0x0000), "0080 BLOCK POWER, RESET FAULT edge");
  EXPECT_EQ(vf1000::explain_control_word(0x807F, 0x807F), "807F POWER-ON/ENABLE, STR");
  EXPECT_NE(vf1000::explain_control_word(0x0106, 0).find("reserved bits 8-10"), std::string::npos);
}

TEST(StatusWord, DeviceBitsOf522And532) {
  drivecom::StatusExtras e{};
  e.remote = false;
  e.alarm = true;
  e.limit_value = true;
  e.bit14 = true;
  e.bit15 = true;
  EXPECT_EQ(drivecom::extras_bits(e), 0xC880);
  EXPECT_EQ(vf1000::explain_status_word(0xC231), "C231 READY, remote, S2OUT, S1OUT");
  EXPECT_EQ(mc6000::explain_status_word(0xC231), "C231 READY, remote, IS00, IS01");
  EXPECT_EQ(mc6000::explain_status_word(0x0240),
            "0240 START-UP INHIBIT, block-power request, e-stop request, remote");
  EXPECT_EQ(mc6000::explain_status_word(0x0001), "0001 no DRIVECOM state, block-power request, e-stop request");
}

}  // namespace
}  // namespace ibs::devices
