// The virtual board's DDI (docs/ddi.md) fed arbitrary calls: messages of any bytes and lengths on
// the mailbox, process-data accesses at any address, length and consistency, in any order, on a
// stepped board (one bus cycle per read) of the default bus.
//
// Asserts:
// - every call returns ERR_OK or a code the header documents for that call;
// - every message received is whole: an even length of at least 4 bytes whose parameter count is
//   the rest; a confirmation answers a code that was sent (code | 8000H) with the type
//   DDI_MSG_CONFIRMATION, anything else is an indication the header names (PCP Abort, Information
//   Report) with the type DDI_MSG_INDICATION;
// - the diagnostic status register is consistent: RUN only with ACTIVE and READY, CTRL alone;
// - a process-data read succeeds only while RUN is set;
// - a read-and-write without one of its accesses, or without data behind one, is refused.
//
// Input: a sequence of operations, each one byte (the operation) and its arguments.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <set>
#include <vector>

#include "fuzz_support.hpp"
#include "ibs/ddi.h"

namespace {

using ibs::fuzz::Input;

bool one_of(IBDDIRET r, std::initializer_list<IBDDIRET> codes) {
  for (const IBDDIRET c : codes) {
    if (r == c) return true;
  }
  return false;
}

struct Session {
  IBDDIHND data = 0;
  IBDDIHND mbx = 0;
  std::set<std::uint16_t> sent;
  bool running = false;  // RUN as last read from the register
  bool fresh = false;    // the last diag() read the register (it may find the mailbox full)

  void check_message(const std::uint8_t* b, const T_DDI_MXI_ACCESS& a) {
    IBS_FUZZ_REQUIRE(a.msgLength >= 4 && a.msgLength % 2 == 0, "a received message of odd or short length");
    const auto word = [&](std::size_t k) { return static_cast<std::uint16_t>((b[2 * k] << 8U) | b[2 * k + 1]); };
    IBS_FUZZ_REQUIRE(word(1) == a.msgLength / 2 - 2, "a message whose count is not its length");
    const std::uint16_t code = word(0);
    if ((code & DDI_CONFIRMATION_BIT) != 0) {
      IBS_FUZZ_REQUIRE(a.msgType == DDI_MSG_CONFIRMATION, "a confirmation not typed as one");
      IBS_FUZZ_REQUIRE(sent.count(static_cast<std::uint16_t>(code & 0x7FFFU)) == 1, "a confirmation of nothing sent");
      if (code == (S_READ_VALUE | DDI_CONFIRMATION_BIT) && word(2) == RES_OK) {
        // [result][count] and (ID, value) per variable.
        IBS_FUZZ_REQUIRE(a.msgLength == 8U + 4U * word(3), "a Read_Value confirmation not of its count's length");
      }
    } else {
      IBS_FUZZ_REQUIRE(code == S_PCP_ABORT_IND || code == S_PCP_INFO_REPORT_IND, "an unknown indication");
      IBS_FUZZ_REQUIRE(a.msgType == DDI_MSG_INDICATION, "an indication not typed as one");
    }
  }

  void diag() {
    fresh = false;
    std::uint8_t b[10] = {0x03, 0x51, 0x00, 0x02, 0x00, 0x01, 0x22, 0x22};
    T_DDI_MXI_ACCESS s{0, 8, 0, b};
    const IBDDIRET r = DDI_MXI_SndMessage(mbx, &s);
    IBS_FUZZ_REQUIRE(one_of(r, {ERR_OK, ERR_NO_MORE_MBX, ERR_IBS_SYSFAIL}), "Read_Value refused oddly");
    if (r != ERR_OK) return;
    sent.insert(S_READ_VALUE);
    // Drain up to its confirmation.
    std::uint8_t m[DDI_MAX_MESSAGE];
    for (int k = 0; k < 64; ++k) {
      T_DDI_MXI_ACCESS a{0, sizeof m, 0, m};
      const IBDDIRET rr = DDI_MXI_RcvMessage(mbx, &a);
      IBS_FUZZ_REQUIRE(one_of(rr, {ERR_OK, ERR_NO_MSG, ERR_IBS_SYSFAIL}), "receive refused oddly");
      if (rr != ERR_OK) return;
      check_message(m, a);
      if (a.msgLength == 12 && m[0] == 0x83 && m[1] == 0x51 && m[8] == 0x22 && m[9] == 0x22) {  // VAR_DIAG_STATUS
        const auto status = static_cast<std::uint16_t>((m[10] << 8U) | m[11]);
        if ((status & DIAG_CTRL) != 0) {
          IBS_FUZZ_REQUIRE(status == DIAG_CTRL, "CTRL with other bits");
        } else {
          IBS_FUZZ_REQUIRE((status & DIAG_READY) != 0, "not READY without SysFail");
          if ((status & DIAG_RUN) != 0) IBS_FUZZ_REQUIRE((status & DIAG_ACTIVE) != 0, "RUN without ACTIVE");
        }
        running = (status & DIAG_RUN) != 0;
        fresh = true;
        return;
      }
    }
  }
};

// Requests the fuzzer would rarely build itself, with its arguments after them.
constexpr std::uint16_t kCodes[] = {S_ACTIVATE_CONFIGURATION, S_CREATE_CONFIGURATION, S_START_DATA_TRANSFER,
                                    S_STOP_DATA_TRANSFER, S_READ_VALUE, S_GET_DIAG_INFO, S_CONFIRM_DIAGNOSTICS,
                                    S_CONTROL_ACTIVE_CONFIGURATION, S_PCP_INITIATE, S_PCP_READ, S_PCP_WRITE,
                                    S_PCP_ABORT};

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  setenv("IBS_DDI_MODE", "stepped", 1);
  unsetenv("IBS_DDI_SCENARIO");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Input in(data, size);
  Session s;
  IBS_FUZZ_REQUIRE(DDI_DevOpenNode(DDI_DATA_NODE, DDI_RW, &s.data) == ERR_OK, "data node");
  IBS_FUZZ_REQUIRE(DDI_DevOpenNode(DDI_MAILBOX_NODE, DDI_RW, &s.mbx) == ERR_OK, "mailbox node");
  std::vector<std::uint8_t> buf(DDI_MAX_MESSAGE + 16);
  for (int ops = 0; ops < 200 && in.remaining_bytes() > 0; ++ops) {
    switch (in.ConsumeIntegral<std::uint8_t>() % 6) {
      case 0: {  // a message: a known code or any, a parameter count right or not, any words
        const auto pick = in.ConsumeIntegral<std::uint8_t>();
        const auto n = in.ConsumeIntegralInRange<std::uint16_t>(0, 12);
        std::vector<std::uint8_t> m = in.ConsumeBytes<std::uint8_t>(2U * n);
        std::vector<std::uint8_t> msg;
        const std::uint16_t code = pick < 2 * std::size(kCodes) ? kCodes[pick % std::size(kCodes)]
                                                                  : static_cast<std::uint16_t>(pick << 4U);
        const auto count = static_cast<std::uint16_t>(in.ConsumeBool() ? m.size() / 2 : n);
        msg = {static_cast<std::uint8_t>(code >> 8U), static_cast<std::uint8_t>(code & 0xFFU),
               static_cast<std::uint8_t>(count >> 8U), static_cast<std::uint8_t>(count & 0xFFU)};
        msg.insert(msg.end(), m.begin(), m.end());
        if (in.ConsumeBool()) msg.resize(in.ConsumeIntegralInRange<std::size_t>(0, DDI_MAX_MESSAGE + 4));
        T_DDI_MXI_ACCESS a{0, static_cast<std::uint16_t>(msg.size()), 3, msg.data()};
        const IBDDIRET r = DDI_MXI_SndMessage(s.mbx, &a);
        IBS_FUZZ_REQUIRE(one_of(r, {ERR_OK, ERR_INVLD_PARAM, ERR_MSG_TO_LONG, ERR_NO_MORE_MBX, ERR_IBS_SYSFAIL}),
                         "SndMessage returned an undocumented code");
        if (r == ERR_OK) s.sent.insert(code);
        break;
      }
      case 1: {  // receive into a buffer of some size
        const auto len = in.ConsumeIntegralInRange<std::uint16_t>(0, DDI_MAX_MESSAGE);
        T_DDI_MXI_ACCESS a{0, len, 0, buf.data()};
        const IBDDIRET r = DDI_MXI_RcvMessage(s.mbx, &a);
        IBS_FUZZ_REQUIRE(one_of(r, {ERR_OK, ERR_NO_MSG, ERR_MSG_TO_LONG, ERR_IBS_SYSFAIL}),
                         "RcvMessage returned an undocumented code");
        if (r == ERR_OK) {
          IBS_FUZZ_REQUIRE(a.msgLength <= len, "a message longer than the buffer");
          s.check_message(buf.data(), a);
        }
        break;
      }
      case 2:
      case 3:
      case 4: {  // read, write, read-and-write
        const auto op = in.ConsumeIntegral<std::uint8_t>() % 3;
        T_DDI_DTI_ACCESS a{in.ConsumeIntegralInRange<std::uint16_t>(0, 40),
                           in.ConsumeIntegralInRange<std::uint16_t>(0, DDI_IMAGE_BYTES + 8),
                           in.ConsumeIntegralInRange<std::uint16_t>(0, 4), buf.data()};
        for (std::size_t k = 0; k < a.length; ++k) buf[k] = in.ConsumeIntegral<std::uint8_t>();
        IBDDIRET r = ERR_OK;
        if (op == 0) {
          s.diag();
          const bool known = s.fresh;
          const bool was_running = s.running;
          r = DDI_DTI_ReadData(s.data, &a);
          if (r == ERR_OK && known) IBS_FUZZ_REQUIRE(was_running, "a read without RUN");
        } else if (op == 1) {
          r = DDI_DTI_WriteData(s.data, &a);
        } else {
          // Sometimes without one of the two accesses, or with no data behind one.
          const auto shape = in.ConsumeIntegral<std::uint8_t>() % 4;
          T_DDI_DTI_ACCESS no_data = a;
          no_data.data = nullptr;
          r = DDI_DTI_ReadWriteData(s.data, shape == 1 ? nullptr : &a,
                                    shape == 2 ? nullptr : shape == 3 ? &no_data : &a);
          if (shape != 0) IBS_FUZZ_REQUIRE(r != ERR_OK, "a missing access accepted");
        }
        IBS_FUZZ_REQUIRE(one_of(r, {ERR_OK, ERR_INVLD_PARAM, ERR_INVLD_DATA_CONS, ERR_AREA_EXCDED, ERR_IB_STOPPED,
                                    ERR_IBS_SYSFAIL}),
                         "a DTI call returned an undocumented code");
        break;
      }
      default: {
        T_DDI_INFO info{};
        IBS_FUZZ_REQUIRE(DDI_GetInfo(s.data, &info) == ERR_OK, "GetInfo");
        s.diag();
        break;
      }
    }
  }
  IBS_FUZZ_REQUIRE(DDI_DevCloseNode(s.data) == ERR_OK && DDI_DevCloseNode(s.mbx) == ERR_OK, "close");
  return 0;
}
