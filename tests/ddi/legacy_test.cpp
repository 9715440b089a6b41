// The legacy headers (docs/ddi.md, "Legacy headers"): a master written for Phoenix Contact's boards
// -- their node names, the IB_ message and process data macros, GetIBSDiagnostic, the S_..._REQ
// names, Read_Value of the plug & play mode -- against the virtual board, stepped.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <sys/wait.h>

#include "ddi_lib.h"

// The macros are C, with C's casts, as in Phoenix's SDK: this file uses them as a C program does.
#pragma GCC diagnostic ignored "-Wold-style-cast"
#pragma GCC diagnostic ignored "-Wuseless-cast"

namespace {

class Legacy : public ::testing::Test {
 protected:
  void SetUp() override {
    setenv("IBS_DDI_MODE", "stepped", 1);
    unsetenv("IBS_DDI_SCENARIO");
    unsetenv("IBS_DDI_RT_PRIORITY");
    unsetenv("IBS_DDI_MASTER_COMMANDS");
  }
  void TearDown() override {
    if (dti_ != 0) {
      EXPECT_EQ(DDI_DevCloseNode(dti_), ERR_OK);
    }
    if (mxi_ != 0) {
      EXPECT_EQ(DDI_DevCloseNode(mxi_), ERR_OK);
    }
  }
  void open() {
    // The node names of Phoenix's Ethernet controllers, as their sample programs write them.
    char mxi_name[20] = "IBETH01N1_M";
    char dti_name[20] = "IBETH01N1_D";
    ASSERT_EQ(DDI_DevOpenNode(mxi_name, DDI_RW, &mxi_), ERR_OK);
    ASSERT_EQ(DDI_DevOpenNode(dti_name, DDI_RW, &dti_), ERR_OK);
  }
  // Sends the command in mail_ (code, count and parameters set by the caller).
  IBDDIRET send() {
    T_DDI_MXI_ACCESS a{0, static_cast<USIGN16>(4 + 2 * IB_GetParaCnt(mail_)), 0, mail_};
    return DDI_MXI_SndMessage(mxi_, &a);
  }
  // The next message into mail_; false when none came within 100 (stepped) bus cycles.
  bool receive() {
    for (int k = 0; k < 100; ++k) {
      T_DDI_MXI_ACCESS a{0, sizeof mail_, 0, mail_};
      const IBDDIRET r = DDI_MXI_RcvMessage(mxi_, &a);
      if (r == ERR_OK) return true;
      if (r != ERR_NO_MSG) return false;
    }
    return false;
  }
  USIGN16 command(USIGN16 code) {
    IB_SetCmdCode(mail_, code);
    IB_SetParaCnt(mail_, 0);
    EXPECT_EQ(send(), ERR_OK);
    EXPECT_TRUE(receive());
    EXPECT_EQ(IB_GetMsgCode(mail_), code | 0x8000);
    return IB_GetParaN(mail_, 1);  // the result
  }
  std::uint32_t cycles() {
    T_DDI_INFO info{};
    EXPECT_EQ(DDI_GetInfo(dti_, &info), ERR_OK);
    return info.cycles;
  }

  IBDDIHND mxi_ = 0;
  IBDDIHND dti_ = 0;
  USIGN8 mail_[128] = {};
};

TEST_F(Legacy, TheNamesMeanWhatIbsDdiHMeans) {
  EXPECT_EQ(S_ACTIVATE_CFG_REQ, 0x0711);
  EXPECT_EQ(S_START_DATA_TRANSFER_REQ, 0x0701);
  EXPECT_EQ(S_STOP_DATA_TRANSFER_CNF, 0x8702);
  EXPECT_EQ(DTI_DATA_WORD, DDI_WORD);
  EXPECT_EQ(DTI_DATA_LWORD, DDI_LWORD);
  EXPECT_EQ(DTI_DATA_BYTE, DDI_BYTE);
  EXPECT_EQ(DTI_DATA_64BIT, DDI_64BIT);
  EXPECT_EQ(RUN_BIT | ACTIVE_BIT | READY_BIT, 0x00E0);
  EXPECT_EQ(sizeof(T_IBS_DIAG), 4U);
  EXPECT_EQ(sizeof(T_IBS_DIAG_EX), 6U);
  EXPECT_EQ(sizeof(T_IBS_WORD), 2U);
}

TEST_F(Legacy, MacrosPutEveryWordBigEndianWhereTheBoardReadsIt) {
  USIGN8 b[16] = {};
  IB_SetCmdCode(b, 0x0351);
  IB_SetParaCnt(b, 2);
  IB_SetParaN(b, 1, 1);
  IB_SetParaN(b, 2, 0x2240);
  const std::array<USIGN8, 8> request{0x03, 0x51, 0x00, 0x02, 0x00, 0x01, 0x22, 0x40};
  for (std::size_t k = 0; k < request.size(); ++k) EXPECT_EQ(b[k], request[k]) << k;
  EXPECT_EQ(IB_GetParaN(b, 2), 0x2240);
  EXPECT_EQ(IB_GetParaNHiByte(b, 2), 0x22);
  EXPECT_EQ(IB_GetParaNLoByte(b, 2), 0x40);
  IB_SetParaNHiByte(b, 1, 0x7F);
  EXPECT_EQ(IB_GetParaN(b, 1), 0x7F01);
  IB_SetParaNLoByte(b, 1, 0x02);
  EXPECT_EQ(IB_GetParaN(b, 1), 0x7F02);
  // Process data: word m at byte 2m; a long word high word first (the MC6000's Q16 reference).
  USIGN8 pd[8] = {};
  IB_PD_SetDataN(pd, 0, 0x000F);
  IB_PD_SetLongDataN(pd, 1, 0x03E80000UL);
  const std::array<USIGN8, 6> image{0x00, 0x0F, 0x03, 0xE8, 0x00, 0x00};
  for (std::size_t k = 0; k < image.size(); ++k) EXPECT_EQ(pd[k], image[k]) << k;
  EXPECT_EQ(IB_PD_GetDataN(pd, 1), 1000);
  EXPECT_EQ(IB_PD_GetLongDataN(pd, 1), 0x03E80000UL);
  EXPECT_EQ(IB_PD_GetDataNLoByte(pd, 0), 0x0F);
  IB_PMS_SetInvokeID(b, 5);
  IB_PMS_SetCR(b, 2);
  EXPECT_EQ(IB_GetParaN(b, 1), 0x0502);
}

TEST_F(Legacy, NodesOpenUnderTheBoardsNames) {
  IBDDIHND h = 0;
  EXPECT_EQ(DDI_DevOpenNode("IBETH02N1_D", DDI_RW, &h), ERR_INVLD_BOARD_NUM);
  EXPECT_EQ(DDI_DevOpenNode("IBETH01N0_D", DDI_RW, &h), ERR_INVLD_NODE_NUM);
  EXPECT_EQ(DDI_DevOpenNode("IBETHxN1_D", DDI_RW, &h), ERR_INVLD_PARAM);
  EXPECT_EQ(DDI_DevOpenNode("IBETH001N1_D", DDI_RW, &h), ERR_INVLD_PARAM);
  open();
  // The ISA / PCI boards' name for the same node, and the one-digit form.
  IBDDIHND other = 0;
  ASSERT_EQ(DDI_DevOpenNode("IBB1N1_D", DDI_READ, &other), ERR_OK);
  EXPECT_EQ(DDI_DevCloseNode(other), ERR_OK);
  ASSERT_EQ(DDI_DevOpenNode("IBETH1N1_M", DDI_READ, &other), ERR_OK);
  EXPECT_EQ(DDI_DevCloseNode(other), ERR_OK);
}

TEST_F(Legacy, ReadValueGivesThePlugAndPlayModeAfterItsId) {
  open();
  IB_SetCmdCode(mail_, S_READ_VALUE_REQ);
  IB_SetParaCnt(mail_, 2);
  IB_SetParaN(mail_, 1, 1);
  IB_SetParaN(mail_, 2, 0x2240);
  ASSERT_EQ(send(), ERR_OK);
  ASSERT_TRUE(receive());
  EXPECT_EQ(IB_GetMsgCode(mail_), S_READ_VALUE_CNF);
  EXPECT_EQ(IB_GetParaCnt(mail_), 4);
  EXPECT_EQ(IB_GetParaN(mail_, 1), RES_OK);
  EXPECT_EQ(IB_GetParaN(mail_, 2), 1);       // variables
  EXPECT_EQ(IB_GetParaN(mail_, 3), 0x2240);  // the ID
  EXPECT_EQ(IB_GetParaN(mail_, 4), 0);       // off: the application writes the process data
}

TEST_F(Legacy, GetIBSDiagnosticReadsTheRegistersWithoutABusCycle) {
  open();
  T_IBS_DIAG d{0xFFFF, 0xFFFF};
  ASSERT_EQ(GetIBSDiagnostic(dti_, &d), ERR_OK);
  EXPECT_EQ(d.state, READY_BIT);
  EXPECT_EQ(d.diagPara, 0);
  // A refused service: USER, the result in the parameter register.
  EXPECT_EQ(command(S_START_DATA_TRANSFER_REQ), RES_WRONG_STATE);
  ASSERT_EQ(GetIBSDiagnostic(mxi_, &d), ERR_OK);  // the mailbox node's handle serves as well
  EXPECT_EQ(d.state, READY_BIT | USER_BIT);
  EXPECT_EQ(d.diagPara, RES_WRONG_STATE);
  EXPECT_EQ(command(S_CONFIRM_DIAG_REQ), RES_OK);
  // Activate and start without reading their confirmations, as Phoenix's samples do: the
  // register shows the state at once.
  IB_SetCmdCode(mail_, S_ACTIVATE_CFG_REQ);
  IB_SetParaCnt(mail_, 0);
  ASSERT_EQ(send(), ERR_OK);
  IB_SetCmdCode(mail_, S_START_DATA_TRANSFER_REQ);
  ASSERT_EQ(send(), ERR_OK);
  const std::uint32_t before = cycles();
  T_IBS_DIAG_EX ex{0xFFFF, 0xFFFF, 0xFFFF};
  ASSERT_EQ(GetIBSDiagnosticEx(dti_, &ex), ERR_OK);
  EXPECT_EQ(ex.state, RUN_BIT | ACTIVE_BIT | READY_BIT);
  EXPECT_EQ(ex.diagPara, 0);
  EXPECT_EQ(ex.addInfo, 0);
  ASSERT_EQ(GetIBSDiagnostic(dti_, &d), ERR_OK);
  EXPECT_EQ(cycles(), before);  // a register, not a service: no bus cycle in stepped mode
  EXPECT_EQ(GetIBSDiagnostic(dti_, nullptr), ERR_INVLD_PARAM);
  EXPECT_EQ(GetIBSDiagnosticEx(dti_, nullptr), ERR_INVLD_PARAM);
  EXPECT_EQ(GetIBSDiagnostic(12345, &d), ERR_INVLD_NODE_HD);
  EXPECT_EQ(GetIBSDiagnostic(12345, nullptr), ERR_INVLD_NODE_HD);
}

TEST(LegacyMaster, BuildsAndRunsUnchangedAgainstTheVirtualBoard) {
  // examples/ddi/ibs_hli.c: opens the mailbox, checks plug & play, activates, starts, checks the
  // diagnostic register, exchanges process data until both drives are ENABLED, stops.
  setenv("IBS_DDI_MODE", "stepped", 1);
  unsetenv("IBS_DDI_SCENARIO");
  FILE* p = popen(IBS_DDI_LEGACY_MASTER " 2>&1", "r");
  ASSERT_NE(p, nullptr);
  std::string out;
  std::array<char, 256> line{};
  while (std::fgets(line.data(), static_cast<int>(line.size()), p) != nullptr) out += line.data();
  const int status = pclose(p);
  ASSERT_TRUE(WIFEXITED(status)) << out;
  EXPECT_EQ(WEXITSTATUS(status), 0) << out;
  EXPECT_NE(out.find("Plug & play mode 0\n"), std::string::npos) << out;
  EXPECT_NE(out.find("IBS status: 0x00E0\n"), std::string::npos) << out;
  EXPECT_NE(out.find("MC6000 status 0637 actual 1000 rpm; VF1000 status 0637 actual 25.00 Hz\n"), std::string::npos)
      << out;
  EXPECT_NE(out.find("done\n"), std::string::npos) << out;
}

}  // namespace
