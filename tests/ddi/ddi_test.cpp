// The virtual INTERBUS board through its C calls (ibs/ddi.h, docs/ddi.md): every call and service,
// every return code, the diagnostics under each fault kind, PCP to the MC6000 over the mailbox.
// The board runs stepped (IBS_DDI_MODE=stepped) except in the real-time test: each DTI read and
// each mailbox receive that finds nothing is one bus cycle.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <initializer_list>
#include <string>
#include <thread>
#include <vector>

#include "ibs/ddi.h"

namespace {

using Words = std::vector<std::uint16_t>;

// The default bus (sim::default_scenario): the MC6000 (SUPI 11, IBCNF 2: control word and a Q16
// reference out, status word and a Q16 actual in) at bytes 0..5, the VF1000 (control word,
// reference in 0.05 Hz, communication word) at bytes 6..11; the MC6000 is PCP CR 2.
constexpr std::uint16_t kMc = 0;
constexpr std::uint16_t kVf = 6;

// Devices of the tests' own scenarios.
const std::string kServo = "[[device]]\nname = \"servo\"\ntype = \"mc6000\"\n";
const std::string kFan = "[[device]]\nname = \"fan\"\ntype = \"vf1000\"\n";

std::string write_file(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

class Ddi : public ::testing::Test {
 protected:
  void SetUp() override {
    setenv("IBS_DDI_MODE", "stepped", 1);
    unsetenv("IBS_DDI_SCENARIO");
    unsetenv("IBS_DDI_RT_PRIORITY");
    unsetenv("IBS_DDI_MASTER_COMMANDS");
  }
  void TearDown() override {
    if (data_ != 0) {
      EXPECT_EQ(DDI_DevCloseNode(data_), ERR_OK);
    }
    if (mbx_ != 0) {
      EXPECT_EQ(DDI_DevCloseNode(mbx_), ERR_OK);
    }
  }
  // The next board's scenario: a duration that leaves its faults room, the bus cycle time (empty:
  // the formula's), the ring (kServo, kFan), then `rest` (more keys of the last device, the
  // timeline).
  static void use_scenario(const std::string& name, const std::string& cycle_time, const std::string& ring,
                           const std::string& rest) {
    std::string toml = "duration = \"10 s\"\n";
    if (!cycle_time.empty()) toml += "[bus]\ncycle_time = \"" + cycle_time + "\"\n";
    setenv("IBS_DDI_SCENARIO", write_file(name, toml + ring + rest).c_str(), 1);
  }
  // `n` bus cycles (stepped reads), each read accepted.
  void run_cycles(int n) {
    std::uint8_t b[2];
    for (int k = 0; k < n; ++k) ASSERT_EQ(read(0, 2, b), ERR_OK);
  }
  void open() {
    ASSERT_EQ(DDI_DevOpenNode(DDI_DATA_NODE, DDI_RW, &data_), ERR_OK);
    ASSERT_EQ(DDI_DevOpenNode(DDI_MAILBOX_NODE, DDI_RW, &mbx_), ERR_OK);
  }
  IBDDIRET send(const Words& w, std::uint16_t user_id = 7) {
    std::vector<std::uint8_t> b;
    for (const std::uint16_t x : w) {
      b.push_back(static_cast<std::uint8_t>(x >> 8));
      b.push_back(static_cast<std::uint8_t>(x & 0xFF));
    }
    T_DDI_MXI_ACCESS a{0, static_cast<std::uint16_t>(b.size()), user_id, b.data()};
    return DDI_MXI_SndMessage(mbx_, &a);
  }
  // The next message, waiting up to `cycles` bus cycles; empty when none came.
  Words receive(int cycles = 2000, std::uint16_t* type = nullptr, std::uint16_t* user_id = nullptr) {
    std::vector<std::uint8_t> b(DDI_MAX_MESSAGE);
    for (int k = 0; k < cycles; ++k) {
      T_DDI_MXI_ACCESS a{0, static_cast<std::uint16_t>(b.size()), 0, b.data()};
      const IBDDIRET r = DDI_MXI_RcvMessage(mbx_, &a);
      if (r == ERR_NO_MSG) {
        // In real time the board's thread brings what comes; stepped, each empty receive a cycle.
        if (realtime()) std::this_thread::sleep_for(std::chrono::microseconds(200));
        continue;
      }
      EXPECT_EQ(r, ERR_OK);
      if (r != ERR_OK) return {};
      if (type != nullptr) *type = a.msgType;
      if (user_id != nullptr) *user_id = a.DDIUserID;
      Words w;
      for (std::size_t i = 0; i + 1 < a.msgLength; i += 2) w.push_back(static_cast<std::uint16_t>((b[i] << 8) | b[i + 1]));
      return w;
    }
    return {};
  }
  static bool realtime() {
    const char* m = std::getenv("IBS_DDI_MODE");
    return m != nullptr && std::string(m) == "realtime";
  }
  Words call(const Words& request) {
    EXPECT_EQ(send(request), ERR_OK);
    return receive();
  }
  std::uint16_t diag() {
    const Words c = call({S_READ_VALUE, 2, 1, VAR_DIAG_STATUS});
    return c.size() == 6 && c[4] == VAR_DIAG_STATUS ? c[5] : 0xFFFF;
  }
  std::uint16_t diag_parameter() {
    const Words c = call({S_READ_VALUE, 2, 1, VAR_DIAG_PARAMETER});
    return c.size() == 6 && c[4] == VAR_DIAG_PARAMETER ? c[5] : 0xFFFF;
  }
  void start(std::uint16_t devices = 2) {
    ASSERT_EQ(call({S_ACTIVATE_CONFIGURATION, 0}), (Words{0x8711, 2, RES_OK, devices}));
    ASSERT_EQ(call({S_START_DATA_TRANSFER, 0}), (Words{0x8701, 1, RES_OK}));
  }
  IBDDIRET read(std::uint16_t address, std::uint16_t length, std::uint8_t* to, std::uint16_t cons = DDI_BYTE) {
    T_DDI_DTI_ACCESS a{length, address, cons, to};
    return DDI_DTI_ReadData(data_, &a);
  }
  IBDDIRET write(std::uint16_t address, const Words& w) {
    std::vector<std::uint8_t> b;
    for (const std::uint16_t x : w) {
      b.push_back(static_cast<std::uint8_t>(x >> 8));
      b.push_back(static_cast<std::uint8_t>(x & 0xFF));
    }
    T_DDI_DTI_ACCESS a{static_cast<std::uint16_t>(b.size()), address, DDI_WORD, b.data()};
    return DDI_DTI_WriteData(data_, &a);
  }
  Words read_words(std::uint16_t address, std::size_t n) {
    std::vector<std::uint8_t> b(2 * n);
    EXPECT_EQ(read(address, static_cast<std::uint16_t>(b.size()), b.data(), DDI_WORD), ERR_OK);
    Words w;
    for (std::size_t i = 0; i < n; ++i) w.push_back(static_cast<std::uint16_t>((b[2 * i] << 8) | b[2 * i + 1]));
    return w;
  }
  // Writes `out` each cycle until the status word at `in` masked with 0x6F reads `state`.
  bool drive_to(std::uint16_t in, std::uint16_t out, const Words& words, std::uint16_t state, int cycles = 6000) {
    for (int k = 0; k < cycles; ++k) {
      if (write(out, words) != ERR_OK) return false;
      if ((read_words(in, 1)[0] & 0x6F) == state) return true;
    }
    return false;
  }

  IBDDIHND data_ = 0;
  IBDDIHND mbx_ = 0;
};

TEST_F(Ddi, NodesOpenByNameAndPermission) {
  IBDDIHND h = 0;
  EXPECT_EQ(DDI_DevOpenNode("IBB2N1_D", DDI_RW, &h), ERR_INVLD_BOARD_NUM);
  EXPECT_EQ(DDI_DevOpenNode("IBB1N2_D", DDI_RW, &h), ERR_INVLD_NODE_NUM);
  EXPECT_EQ(DDI_DevOpenNode("IBB1N1_X", DDI_RW, &h), ERR_INVLD_NODE_NUM);
  EXPECT_EQ(DDI_DevOpenNode("COM1", DDI_RW, &h), ERR_INVLD_PARAM);
  EXPECT_EQ(DDI_DevOpenNode(DDI_DATA_NODE, 0, &h), ERR_INVLD_PARAM);
  EXPECT_EQ(DDI_DevOpenNode(DDI_DATA_NODE, 4, &h), ERR_INVLD_PARAM);
  EXPECT_EQ(DDI_DevOpenNode(DDI_DATA_NODE, DDI_RW, nullptr), ERR_INVLD_PARAM);
  EXPECT_EQ(DDI_DevOpenNode(nullptr, DDI_RW, &h), ERR_INVLD_PARAM);
  open();
  EXPECT_NE(data_, mbx_);
  EXPECT_EQ(DDI_DevCloseNode(12345), ERR_INVLD_NODE_HD);
  // A handle of the other node kind is not a handle for the call.
  std::uint8_t b[2];
  T_DDI_DTI_ACCESS a{2, 0, DDI_WORD, b};
  EXPECT_EQ(DDI_DTI_ReadData(mbx_, &a), ERR_INVLD_NODE_HD);
  T_DDI_MXI_ACCESS m{0, 4, 0, b};
  EXPECT_EQ(DDI_MXI_SndMessage(data_, &m), ERR_INVLD_NODE_HD);
  EXPECT_EQ(DDI_MXI_RcvMessage(data_, &m), ERR_INVLD_NODE_HD);
  // Read-only and write-only nodes.
  IBDDIHND ro = 0;
  IBDDIHND wo = 0;
  ASSERT_EQ(DDI_DevOpenNode(DDI_DATA_NODE, DDI_READ, &ro), ERR_OK);
  ASSERT_EQ(DDI_DevOpenNode(DDI_DATA_NODE, DDI_WRITE, &wo), ERR_OK);
  EXPECT_EQ(DDI_DTI_WriteData(ro, &a), ERR_INVLD_PERM);
  EXPECT_EQ(DDI_DTI_ReadData(wo, &a), ERR_INVLD_PERM);
  EXPECT_EQ(DDI_DTI_ReadWriteData(ro, &a, &a), ERR_INVLD_PERM);
  EXPECT_EQ(DDI_DTI_WriteData(wo, &a), ERR_OK);
  EXPECT_EQ(DDI_DevCloseNode(ro), ERR_OK);
  EXPECT_EQ(DDI_DevCloseNode(wo), ERR_OK);
  EXPECT_EQ(DDI_DevCloseNode(ro), ERR_INVLD_NODE_HD);
}

TEST_F(Ddi, GetInfoDescribesTheBoardAndTheNode) {
  open();
  T_DDI_INFO info{};
  ASSERT_EQ(DDI_GetInfo(data_, &info), ERR_OK);
  EXPECT_STREQ(info.driverName, "ibs virtual INTERBUS board");
  EXPECT_EQ(info.boardNumber, 1);
  EXPECT_EQ(info.nodeType, DDI_NODE_DATA);
  EXPECT_EQ(info.permission, DDI_RW);
  EXPECT_EQ(info.deviceCount, 2);
  EXPECT_EQ(info.inputBytes, 12);   // 3 + 3 words
  EXPECT_EQ(info.outputBytes, 12);
  EXPECT_EQ(info.mode, DDI_MODE_STEPPED);
  EXPECT_EQ(info.cycleTimeUs, 726U);  // docs/bus.md's worked example
  ASSERT_EQ(DDI_GetInfo(mbx_, &info), ERR_OK);
  EXPECT_EQ(info.nodeType, DDI_NODE_MAILBOX);
  EXPECT_EQ(DDI_GetInfo(mbx_, nullptr), ERR_INVLD_PARAM);
  EXPECT_EQ(DDI_GetInfo(999, &info), ERR_INVLD_NODE_HD);
}

TEST_F(Ddi, ProcessDataChecksAddressLengthAndConsistency) {
  open();
  std::uint8_t b[16] = {};
  auto access = [&](std::uint16_t address, std::uint16_t length, std::uint16_t cons) {
    T_DDI_DTI_ACCESS a{length, address, cons, b};
    return DDI_DTI_WriteData(data_, &a);
  };
  EXPECT_EQ(access(0, 2, DDI_WORD), ERR_OK);
  EXPECT_EQ(access(1, 2, DDI_WORD), ERR_INVLD_DATA_CONS);
  EXPECT_EQ(access(0, 3, DDI_WORD), ERR_INVLD_DATA_CONS);
  EXPECT_EQ(access(1, 3, DDI_BYTE), ERR_OK);
  EXPECT_EQ(access(2, 4, DDI_LWORD), ERR_INVLD_DATA_CONS);
  EXPECT_EQ(access(4, 4, DDI_LWORD), ERR_OK);
  EXPECT_EQ(access(8, 8, DDI_64BIT), ERR_OK);
  EXPECT_EQ(access(4, 8, DDI_64BIT), ERR_INVLD_DATA_CONS);
  EXPECT_EQ(access(0, 2, 4), ERR_INVLD_DATA_CONS);
  EXPECT_EQ(access(DDI_IMAGE_BYTES - 2, 2, DDI_WORD), ERR_OK);
  EXPECT_EQ(access(DDI_IMAGE_BYTES - 2, 4, DDI_WORD), ERR_AREA_EXCDED);
  EXPECT_EQ(access(0, 0, DDI_WORD), ERR_INVLD_PARAM);
  T_DDI_DTI_ACCESS null_data{2, 0, DDI_WORD, nullptr};
  EXPECT_EQ(DDI_DTI_WriteData(data_, &null_data), ERR_INVLD_PARAM);
  EXPECT_EQ(DDI_DTI_ReadData(data_, nullptr), ERR_INVLD_PARAM);
  // Reading needs the data transfer running.
  EXPECT_EQ(read(0, 2, b), ERR_IB_STOPPED);
}

TEST_F(Ddi, StartUpSequenceAndTheDiagnosticRegister) {
  open();
  EXPECT_EQ(diag(), DIAG_READY);
  EXPECT_EQ(call({S_START_DATA_TRANSFER, 0}), (Words{0x8701, 1, RES_WRONG_STATE}));  // nothing active
  EXPECT_EQ(diag(), DIAG_READY | DIAG_USER);
  EXPECT_EQ(diag_parameter(), RES_WRONG_STATE);
  EXPECT_EQ(call({S_CONFIRM_DIAGNOSTICS, 0}), (Words{0x8760, 1, RES_OK}));
  EXPECT_EQ(diag(), DIAG_READY);
  EXPECT_EQ(call({S_ACTIVATE_CONFIGURATION, 1, 1}), (Words{0x8711, 2, RES_OK, 2}));
  EXPECT_EQ(diag(), DIAG_READY | DIAG_ACTIVE);
  EXPECT_EQ(call({S_START_DATA_TRANSFER, 0}), (Words{0x8701, 1, RES_OK}));
  EXPECT_EQ(diag(), DIAG_READY | DIAG_ACTIVE | DIAG_RUN);
  // Each value after its variable's ID.
  EXPECT_EQ(call({S_READ_VALUE, 3, 2, VAR_DEVICE_COUNT, VAR_CYCLE_TIME_US}),
            (Words{0x8351, 6, RES_OK, 2, VAR_DEVICE_COUNT, 2, VAR_CYCLE_TIME_US, 726}));
  EXPECT_EQ(call({S_ACTIVATE_CONFIGURATION, 0}), (Words{0x8711, 1, RES_WRONG_STATE}));  // not while running
  EXPECT_EQ(call({S_CREATE_CONFIGURATION, 0}), (Words{0x8710, 1, RES_WRONG_STATE}));
  EXPECT_EQ(call({S_STOP_DATA_TRANSFER, 0}), (Words{0x8702, 1, RES_OK}));
  EXPECT_EQ(call({S_STOP_DATA_TRANSFER, 0}), (Words{0x8702, 1, RES_WRONG_STATE}));
  EXPECT_EQ(diag() & (DIAG_RUN | DIAG_ACTIVE), DIAG_ACTIVE);
  EXPECT_EQ(call({S_CREATE_CONFIGURATION, 0}), (Words{0x8710, 2, RES_OK, 2}));
  // Malformed and unknown services.
  EXPECT_EQ(call({S_READ_VALUE, 2, 1, 0x1234}), (Words{0x8351, 1, RES_INVALID_PARAMETER}));
  EXPECT_EQ(call({S_READ_VALUE, 2, 2, VAR_DIAG_STATUS}), (Words{0x8351, 1, RES_INVALID_PARAMETER}));
  EXPECT_EQ(call({S_START_DATA_TRANSFER, 1, 5}), (Words{0x8701, 1, RES_INVALID_PARAMETER}));
  EXPECT_EQ(call({S_ACTIVATE_CONFIGURATION, 1, 2}), (Words{0x8711, 1, RES_INVALID_PARAMETER}));
  EXPECT_EQ(call({0x0999, 0}), (Words{0x8999, 1, RES_SERVICE_NOT_SUPPORTED}));
}

TEST_F(Ddi, MailboxChecksMessages) {
  open();
  std::uint8_t b[DDI_MAX_MESSAGE + 2] = {0x03, 0x51, 0x00, 0x05};
  T_DDI_MXI_ACCESS a{0, 4, 0, b};
  EXPECT_EQ(DDI_MXI_SndMessage(mbx_, &a), ERR_INVLD_PARAM);  // count 5 but no parameters
  a.msgLength = 3;
  EXPECT_EQ(DDI_MXI_SndMessage(mbx_, &a), ERR_INVLD_PARAM);
  a.msgLength = DDI_MAX_MESSAGE + 2;
  EXPECT_EQ(DDI_MXI_SndMessage(mbx_, &a), ERR_MSG_TO_LONG);
  EXPECT_EQ(DDI_MXI_SndMessage(mbx_, nullptr), ERR_INVLD_PARAM);
  a.msgLength = 4;
  a.msgBlk = nullptr;
  EXPECT_EQ(DDI_MXI_SndMessage(mbx_, &a), ERR_INVLD_PARAM);
  // Nothing waits.
  T_DDI_MXI_ACCESS r{0, sizeof b, 0, b};
  EXPECT_EQ(DDI_MXI_RcvMessage(mbx_, &r), ERR_NO_MSG);
  // A confirmation with its user ID and type; a buffer too small keeps it.
  ASSERT_EQ(send({S_READ_VALUE, 2, 1, VAR_DIAG_STATUS}, 0x4242), ERR_OK);
  T_DDI_MXI_ACCESS small{0, 6, 0, b};
  EXPECT_EQ(DDI_MXI_RcvMessage(mbx_, &small), ERR_MSG_TO_LONG);
  std::uint16_t type = 0;
  std::uint16_t user = 0;
  EXPECT_EQ(receive(1, &type, &user), (Words{0x8351, 4, RES_OK, 1, VAR_DIAG_STATUS, DIAG_READY}));
  EXPECT_EQ(type, DDI_MSG_CONFIRMATION);
  EXPECT_EQ(user, 0x4242);
  // The board's outgoing mailbox fills up when nobody reads it.
  IBDDIRET last = ERR_OK;
  int sent = 0;
  for (; sent < 100 && last == ERR_OK; ++sent) last = send({S_READ_VALUE, 2, 1, VAR_DIAG_STATUS});
  EXPECT_EQ(last, ERR_NO_MORE_MBX);
  EXPECT_EQ(sent, 33);  // 32 accepted, the 33rd refused
  EXPECT_FALSE(receive(1).empty());
  EXPECT_EQ(send({S_READ_VALUE, 2, 1, VAR_DIAG_STATUS}), ERR_OK);
  // A node opened read-only cannot send, write-only cannot receive.
  IBDDIHND ro = 0;
  ASSERT_EQ(DDI_DevOpenNode(DDI_MAILBOX_NODE, DDI_READ, &ro), ERR_OK);
  std::uint8_t msg[4] = {0x07, 0x60, 0x00, 0x00};
  T_DDI_MXI_ACCESS m{0, 4, 0, msg};
  EXPECT_EQ(DDI_MXI_SndMessage(ro, &m), ERR_INVLD_PERM);
  EXPECT_EQ(DDI_DevCloseNode(ro), ERR_OK);
}

TEST_F(Ddi, ALegacyLoopEnablesBothDrivesAndReadsAParameterOverPcp) {
  open();
  start();
  // 406-IBCNF over PCP: Initiate, Read (index 5C00H + 406), then Abort.
  EXPECT_EQ(call({S_PCP_INITIATE, 3, 0x0102, 0, 0}), (Words{0x808B, 4, 0x0102, 0, 134, 134}));
  EXPECT_EQ(call({S_PCP_READ, 3, 0x0302, 0x5C00 + 406, 0}), (Words{0x8081, 4, 0x0302, 0, 1, 0x0200}));
  // 85-SIOF read first (it clears the power-on bit, which refuses writes: INTERBUS manual 6.1), then
  // 409-BUTWD written with the power stage off and read back (USIGN16).
  EXPECT_EQ(call({S_PCP_READ, 3, 0x0402, 0x5C00 + 85, 0}), (Words{0x8081, 4, 0x0402, 0, 1, 0x0100}));
  EXPECT_EQ(call({S_PCP_WRITE, 4, 0x0402, 0x5C00 + 409, 2, 0x0064}), (Words{0x8082, 2, 0x0402, 0}));
  EXPECT_EQ(call({S_PCP_READ, 3, 0x0502, 0x5C00 + 409, 0}), (Words{0x8081, 4, 0x0502, 0, 2, 0x0064}));
  // A parameter that does not exist: the device's negative confirmation.
  EXPECT_EQ(call({S_PCP_READ, 3, 0x0602, 0x5C00 + 999, 0}), (Words{0x8081, 3, 0x0602, 0x0607, 0}));
  // The MC6000: SHUTDOWN, then ENABLE with 1000 rpm as Q16 (high word first).
  EXPECT_TRUE(drive_to(kMc, kMc, {0x0006, 0, 0}, 0x21));
  EXPECT_TRUE(drive_to(kMc, kMc, {0x000F, 1000, 0}, 0x27));
  // The VF1000: ramp running, start clockwise, 25 Hz (500 x 0.05 Hz).
  EXPECT_TRUE(drive_to(kVf, kVf, {0x0076, 500, 0}, 0x21));
  EXPECT_TRUE(drive_to(kVf, kVf, {0x807F, 500, 0}, 0x27));
  // Running up: the actual values follow.
  for (int k = 0; k < 4000; ++k) {
    ASSERT_EQ(write(kMc, {0x000F, 1000, 0}), ERR_OK);
    ASSERT_EQ(write(kVf, {0x807F, 500, 0}), ERR_OK);
    (void)read_words(0, 6);
  }
  const Words in = read_words(0, 6);
  EXPECT_NEAR(static_cast<std::int16_t>(in[1]), 1000, 20);  // rpm, integer part of the Q16
  EXPECT_EQ(in[4], 500);                                    // 25 Hz reached on the ramp
  ASSERT_EQ(send({S_PCP_ABORT, 1, 2}), ERR_OK);  // unconfirmed
  EXPECT_TRUE(receive(50).empty());
  // Without an association the board refuses; a CR nobody has, likewise.
  EXPECT_EQ(call({S_PCP_READ, 3, 0x0702, 0x5C00 + 406, 0}), (Words{0x8081, 3, 0x0702, 0x0800, 0}));
  EXPECT_EQ(call({S_PCP_INITIATE, 3, 0x0109, 0, 0}), (Words{0x808B, 3, 0x0109, 0x0102, 0}));
  EXPECT_EQ(call({S_PCP_READ, 2, 0x0702, 0x5C00}), (Words{0x8081, 1, RES_INVALID_PARAMETER}));
}

TEST_F(Ddi, PcpNeedsTheBusAndStoppingAbortsTheAssociation) {
  open();
  EXPECT_EQ(call({S_PCP_INITIATE, 3, 0x0102, 0, 0}), (Words{0x808B, 3, 0x0102, 0x0800, 0x20}));  // not now
  start();
  EXPECT_EQ(call({S_PCP_INITIATE, 3, 0x0102, 0, 0}), (Words{0x808B, 4, 0x0102, 0, 134, 134}));
  ASSERT_EQ(send({S_PCP_READ, 3, 0x0202, 0x5C00 + 406, 0}), ERR_OK);
  EXPECT_EQ(call({S_PCP_READ, 3, 0x0302, 0x5C00 + 405, 0}), (Words{0x8081, 3, 0x0302, 0x0800, 0x20}));  // busy
  EXPECT_EQ(receive(), (Words{0x8081, 4, 0x0202, 0, 1, 0x0200}));
  std::uint16_t type = 0;
  ASSERT_EQ(send({S_STOP_DATA_TRANSFER, 0}), ERR_OK);
  EXPECT_EQ(receive(1, &type), (Words{S_PCP_ABORT_IND, 2, 2, 5}));  // the association ended
  EXPECT_EQ(type, DDI_MSG_INDICATION);
  EXPECT_EQ(receive(1), (Words{0x8702, 1, RES_OK}));
}

TEST_F(Ddi, CorruptedCyclesAreABusError) {
  use_scenario("ddi_corrupt.toml", "", kServo + kFan, R"([[timeline]]
at = "100 ms"
fault = "corrupt"
count = 3
)");
  open();
  start();
  run_cycles(100);  // 72.6 ms
  EXPECT_EQ(diag() & (DIAG_BUS | DIAG_PF), 0);
  run_cycles(100);
  EXPECT_EQ(diag() & (DIAG_BUS | DIAG_PF | DIAG_RUN), DIAG_BUS | DIAG_RUN);  // latched; data flows on
  EXPECT_EQ(call({S_GET_DIAG_INFO, 0}), (Words{0x832B, 4, RES_OK, 1, 0, DIAG_CODE_TRANSMISSION}));
  EXPECT_EQ(call({S_CONFIRM_DIAGNOSTICS, 0}), (Words{0x8760, 1, RES_OK}));
  EXPECT_EQ(diag() & DIAG_BUS, 0);
  EXPECT_EQ(call({S_GET_DIAG_INFO, 0}), (Words{0x832B, 2, RES_OK, 0}));
}

TEST_F(Ddi, ALostDeviceIsAPeripheralFault) {
  use_scenario("ddi_lost.toml", "1 ms", kServo + kFan, R"([[timeline]]
at = "50 ms"
device = "fan"
fault = "lost"
duration = "100 ms"
)");
  open();
  start();
  run_cycles(80);
  EXPECT_EQ(diag() & (DIAG_BUS | DIAG_PF), DIAG_PF);
  EXPECT_EQ(diag_parameter(), 0x0200);  // device 2.0, the second remote-bus segment
  EXPECT_EQ(read_words(kVf, 3), (Words{0, 0, 0}));  // nothing from a missing device
  EXPECT_EQ(call({S_GET_DIAG_INFO, 0}), (Words{0x832B, 4, RES_OK, 1, 0x0200, DIAG_CODE_MODULE_ERROR}));
  // Confirmed while the device is still away: it stays reported.
  EXPECT_EQ(call({S_CONFIRM_DIAGNOSTICS, 0}), (Words{0x8760, 1, RES_OK}));
  EXPECT_EQ(diag() & DIAG_PF, DIAG_PF);
  run_cycles(150);
  EXPECT_EQ(call({S_CONFIRM_DIAGNOSTICS, 0}), (Words{0x8760, 1, RES_OK}));
  EXPECT_EQ(diag() & DIAG_PF, 0);
  EXPECT_NE(read_words(kVf, 1)[0], 0);  // back, with a status word
}

TEST_F(Ddi, APowerCycledDeviceIsAPeripheralFaultWhileItInitialises) {
  use_scenario("ddi_power.toml", "2 ms", kFan, R"([[timeline]]
at = "20 ms"
device = "fan"
fault = "power-cycle"
)");
  open();
  start(1);
  run_cycles(30);
  EXPECT_EQ(diag() & DIAG_PF, DIAG_PF);
  EXPECT_EQ(diag_parameter(), 0x0100);
}

TEST_F(Ddi, ADeviceFaultIsTheDrivesNotTheBoards) {
  use_scenario("ddi_device_fault.toml", "1 ms", kServo, R"([[timeline]]
at = "20 ms"
device = "servo"
fault = "device"
)");
  open();
  start(1);
  bool fault = false;
  for (int k = 0; k < 200 && !fault; ++k) {
    ASSERT_EQ(write(kMc, {0x0006, 0, 0}), ERR_OK);
    fault = (read_words(kMc, 1)[0] & 0x4F) == 0x08;  // FAULT in the status word
  }
  EXPECT_TRUE(fault);
  EXPECT_EQ(diag() & (DIAG_PF | DIAG_BUS), 0);
}

TEST_F(Ddi, AMasterRestartInTheScenarioIsTheBoardsSysFail) {
  use_scenario("ddi_sysfail.toml", "1 ms", kServo, R"([[timeline]]
at = "10 ms"
master_restart = true
)");
  open();
  start(1);
  std::uint8_t b[2];
  IBDDIRET r = ERR_OK;
  for (int k = 0; k < 20 && r == ERR_OK; ++k) r = read(0, 2, b);
  EXPECT_EQ(r, ERR_IBS_SYSFAIL);
  EXPECT_EQ(write(0, {0}), ERR_IBS_SYSFAIL);
  EXPECT_EQ(send({S_READ_VALUE, 2, 1, VAR_DIAG_STATUS}), ERR_IBS_SYSFAIL);
  // Closing every node powers the board off; opening again starts a new one.
  ASSERT_EQ(DDI_DevCloseNode(data_), ERR_OK);
  ASSERT_EQ(DDI_DevCloseNode(mbx_), ERR_OK);
  data_ = mbx_ = 0;
  open();
  EXPECT_EQ(diag(), DIAG_READY);
}

TEST_F(Ddi, SwitchingASegmentOffBypassesIt) {
  open();
  start();
  EXPECT_TRUE(drive_to(kVf, kVf, {0x0076, 0, 0}, 0x21));
  EXPECT_EQ(call({S_CONTROL_ACTIVE_CONFIGURATION, 3, CTRL_SWITCH_OFF, 1, 0x0200}), (Words{0x8713, 1, RES_OK}));
  std::uint8_t b[2];
  ASSERT_EQ(read(0, 2, b), ERR_OK);
  EXPECT_EQ(read_words(kVf, 3), (Words{0, 0, 0}));
  EXPECT_EQ(diag() & (DIAG_BSA | DIAG_PF), DIAG_BSA);  // switched off is no fault
  EXPECT_NE(read_words(kMc, 1)[0], 0);                  // the other segment runs on
  EXPECT_EQ(call({S_CONTROL_ACTIVE_CONFIGURATION, 3, CTRL_SWITCH_OFF, 1, 0x0201}), (Words{0x8713, 1, RES_UNKNOWN_DEVICE}));
  EXPECT_EQ(call({S_CONTROL_ACTIVE_CONFIGURATION, 3, 7, 1, 0x0200}), (Words{0x8713, 1, RES_INVALID_PARAMETER}));
  EXPECT_EQ(call({S_CONTROL_ACTIVE_CONFIGURATION, 2, CTRL_SWITCH_OFF, 1}), (Words{0x8713, 1, RES_INVALID_PARAMETER}));
  EXPECT_EQ(call({S_CONTROL_ACTIVE_CONFIGURATION, 3, CTRL_SWITCH_ON, 1, 0x0200}), (Words{0x8713, 1, RES_OK}));
  EXPECT_EQ(diag() & DIAG_BSA, 0);
  ASSERT_EQ(read(0, 2, b), ERR_OK);
  EXPECT_NE(read_words(kVf, 1)[0], 0);
}

TEST_F(Ddi, AScenarioWithMasterCommandsStartsAndLeavesThemWithANote) {
  use_scenario("ddi_commands.toml", "1 ms", kServo, R"([[timeline]]
at = "0 s"
device = "servo"
state = "enabled"

[[timeline]]
at = "0 s"
device = "servo"
read = 85

[[timeline]]
at = "10 ms"
master_restart = true
)");
  // The default: the master's entries are ignored with one note; master_restart is SysFail.
  ::testing::internal::CaptureStderr();
  open();
  const std::string note = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(note.find("ddi_commands.toml:7: 2 timeline entries command a master (the first: 'state')"),
            std::string::npos)
      << note;
  EXPECT_NE(note.find("IBS_DDI_MASTER_COMMANDS=ibs-master"), std::string::npos) << note;
  start(1);
  run_cycles(5);
  EXPECT_EQ(read_words(0, 1)[0] & 0x4F, 0x40);  // START-UP INHIBIT: nobody asked the servo for more
  std::uint8_t b[2];
  IBDDIRET r = ERR_OK;
  for (int k = 0; k < 20 && r == ERR_OK; ++k) r = read(0, 2, b);
  EXPECT_EQ(r, ERR_IBS_SYSFAIL);
  ASSERT_EQ(DDI_DevCloseNode(data_), ERR_OK);
  ASSERT_EQ(DDI_DevCloseNode(mbx_), ERR_OK);
  data_ = mbx_ = 0;
  // Left to ibs's master: no note, and the restart is the master's, not the board's.
  setenv("IBS_DDI_MASTER_COMMANDS", "ibs-master", 1);
  ::testing::internal::CaptureStderr();
  open();
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
  start(1);
  run_cycles(50);
  EXPECT_EQ(diag(), DIAG_READY | DIAG_ACTIVE | DIAG_RUN);
}

TEST_F(Ddi, AnUnknownModeOrScenarioDoesNotStart) {
  IBDDIHND h = 0;
  setenv("IBS_DDI_SCENARIO", "/nonexistent/ddi.toml", 1);
  EXPECT_EQ(DDI_DevOpenNode(DDI_DATA_NODE, DDI_RW, &h), ERR_NODE_NOT_READY);
  unsetenv("IBS_DDI_SCENARIO");
  setenv("IBS_DDI_MODE", "fast", 1);
  EXPECT_EQ(DDI_DevOpenNode(DDI_DATA_NODE, DDI_RW, &h), ERR_NODE_NOT_READY);
  setenv("IBS_DDI_MODE", "stepped", 1);
  setenv("IBS_DDI_MASTER_COMMANDS", "mine", 1);
  EXPECT_EQ(DDI_DevOpenNode(DDI_DATA_NODE, DDI_RW, &h), ERR_NODE_NOT_READY);
}

TEST_F(Ddi, ReadConfigurationListsTheDevicesWithTheirIdCodes) {
  open();
  EXPECT_EQ(call({S_READ_CONFIGURATION, 0}), (Words{0x8308, 1, RES_WRONG_STATE}));  // nothing active
  ASSERT_EQ(call({S_ACTIVATE_CONFIGURATION, 0}), (Words{0x8711, 2, RES_OK, 2}));
  // The MC6000 (SUPI 11: 3 + 1 words, PCP) 0100H with 4DBH, the VF1000 0200H with 33BH.
  EXPECT_EQ(call({S_READ_CONFIGURATION, 0}), (Words{0x8308, 6, RES_OK, 2, 0x0100, 0x04DB, 0x0200, 0x033B}));
  EXPECT_EQ(call({S_READ_CONFIGURATION, 1, 1}), (Words{0x8308, 1, RES_INVALID_PARAMETER}));
}

TEST_F(Ddi, GetOvDescribesAServoParameter) {
  open();
  start();
  ASSERT_EQ(call({S_PCP_INITIATE, 3, 0x0102, 0, 0}), (Words{0x808B, 4, 0x0102, 0, 134, 134}));
  // 406-IBCNF: 26 bytes of description (docs/pcp.md): index 5D96H, object code 7, USIGN8 (1),
  // length 1, EEPROM ('2'), ...
  const Words c = call({S_PCP_GET_OV, 2, 0x0202, 0x5C00 + 406});
  ASSERT_EQ(c.size(), 18U);
  EXPECT_EQ((Words{c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]}),
            (Words{0x8088, 16, 0x0202, 0, 26, 0x5D96, 0x0701, 0x0132}));
  EXPECT_EQ(call({S_PCP_GET_OV, 3, 0x0302, 0x5C00 + 406, 0}), (Words{0x8088, 1, RES_INVALID_PARAMETER}));
  // An object the servo lacks: its negative confirmation (class 6, code 7).
  EXPECT_EQ(call({S_PCP_GET_OV, 2, 0x0402, 0x5C00 + 998}), (Words{0x8088, 3, 0x0402, 0x0607, 0}));
}

TEST_F(Ddi, SteppedAReadsCycleServesTheNextEmptyReceive) {
  open();
  start();
  T_DDI_INFO info{};
  auto cycles = [&] {
    EXPECT_EQ(DDI_GetInfo(data_, &info), ERR_OK);
    return info.cycles;
  };
  const std::uint32_t before = cycles();
  std::uint8_t b[2];
  ASSERT_EQ(read(0, 2, b), ERR_OK);  // one cycle
  std::uint8_t m[64];
  T_DDI_MXI_ACCESS a{0, sizeof m, 0, m};
  EXPECT_EQ(DDI_MXI_RcvMessage(mbx_, &a), ERR_NO_MSG);  // the read's cycle: none more
  EXPECT_EQ(cycles(), before + 1);
  a.msgLength = sizeof m;
  EXPECT_EQ(DDI_MXI_RcvMessage(mbx_, &a), ERR_NO_MSG);  // a receive alone runs one
  EXPECT_EQ(cycles(), before + 2);
}

TEST_F(Ddi, InRealTimeTheBoardCyclesByItself) {
  setenv("IBS_DDI_MODE", "realtime", 1);
  open();
  start();
  T_DDI_INFO before{};
  ASSERT_EQ(DDI_GetInfo(data_, &before), ERR_OK);
  EXPECT_EQ(before.mode, DDI_MODE_REALTIME);
  // No call of ours steps it: the cycles come from the board's thread.
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  T_DDI_INFO after{};
  ASSERT_EQ(DDI_GetInfo(data_, &after), ERR_OK);
  EXPECT_GT(after.cycles, before.cycles + 20);
  EXPECT_TRUE(drive_to(kMc, kMc, {0x0006, 0, 0}, 0x21, 1'000'000));
}

}  // namespace

namespace {

TEST_F(Ddi, ReadWriteDataWritesAndReadsInOneCall) {
  open();
  start();
  std::uint8_t out[6] = {0x00, 0x06, 0, 0, 0, 0};
  std::uint8_t in[6] = {};
  T_DDI_DTI_ACCESS w{6, kMc, DDI_WORD, out};
  T_DDI_DTI_ACCESS r{6, kMc, DDI_LWORD, in};
  EXPECT_EQ(DDI_DTI_ReadWriteData(data_, &w, &r), ERR_INVLD_DATA_CONS);  // 6 bytes are no LWORDs
  EXPECT_EQ(DDI_DTI_ReadWriteData(data_, &w, nullptr), ERR_INVLD_PARAM);
  EXPECT_EQ(DDI_DTI_ReadWriteData(data_, nullptr, &r), ERR_INVLD_PARAM);
  r.dataCons = DDI_WORD;
  bool ready = false;
  for (int k = 0; k < 4000 && !ready; ++k) {
    ASSERT_EQ(DDI_DTI_ReadWriteData(data_, &w, &r), ERR_OK);
    ready = ((in[0] << 8 | in[1]) & 0x6F) == 0x21;  // SHUTDOWN took the MC6000 to READY
  }
  EXPECT_TRUE(ready);
  IBDDIHND wo = 0;
  ASSERT_EQ(DDI_DevOpenNode(DDI_MAILBOX_NODE, DDI_WRITE, &wo), ERR_OK);
  std::uint8_t b[8];
  T_DDI_MXI_ACCESS m{0, sizeof b, 0, b};
  EXPECT_EQ(DDI_MXI_RcvMessage(wo, &m), ERR_INVLD_PERM);
  EXPECT_EQ(DDI_MXI_RcvMessage(mbx_, nullptr), ERR_INVLD_PARAM);
  EXPECT_EQ(DDI_DevCloseNode(wo), ERR_OK);
}

TEST_F(Ddi, AServoLostDuringARequestEndsItsAssociationWithAnAbortIndication) {
  use_scenario("ddi_pcp_lost.toml", "1 ms", kServo, R"([[timeline]]
at = "300 ms"
device = "servo"
fault = "lost"
duration = "2 s"
)");
  open();
  start(1);
  EXPECT_EQ(call({S_PCP_INITIATE, 3, 0x0102, 0, 0}), (Words{0x808B, 4, 0x0102, 0, 134, 134}));
  run_cycles(310);  // past 300 ms: the servo is away
  ASSERT_EQ(send({S_PCP_READ, 3, 0x0202, 0x5C00 + 406, 0}), ERR_OK);
  std::uint16_t type = 0;
  // No confirmation: the PCP link's acknowledgement timeout (100 ms) resets the channel before the
  // request's own timeout would, and the board reports an Abort indication, reason 2 (link reset).
  EXPECT_EQ(receive(700, &type), (Words{S_PCP_ABORT_IND, 2, 2, 2}));
  EXPECT_EQ(type, DDI_MSG_INDICATION);
  EXPECT_EQ(diag() & DIAG_PF, DIAG_PF);
}

TEST_F(Ddi, StoppingTheDataTransferTripsTheDrivesBusWatchdog) {
  use_scenario("ddi_watchdog.toml", "1 ms", kServo, R"(watchdog_ms = 50
)");
  open();
  start(1);
  EXPECT_TRUE(drive_to(kMc, kMc, {0x0006, 0, 0}, 0x21));
  ASSERT_EQ(call({S_STOP_DATA_TRANSFER, 0}), (Words{0x8702, 1, RES_OK}));
  std::uint8_t b[2];
  for (int k = 0; k < 100; ++k) ASSERT_EQ(read(0, 2, b), ERR_IB_STOPPED);  // 100 ms without a bus
  ASSERT_EQ(call({S_START_DATA_TRANSFER, 0}), (Words{0x8701, 1, RES_OK}));
  bool fault = false;
  for (int k = 0; k < 50 && !fault; ++k) fault = (read_words(kMc, 1)[0] & 0x4F) == 0x08;
  EXPECT_TRUE(fault);  // E-OP1: the MC6000's 409-BUTWD saw no valid cycle for 50 ms
}

}  // namespace
