// The DDI calls the adapter makes, wrapped at link time (ld --wrap, tests/board/CMakeLists.txt):
// each wrapped call goes to the virtual board unchanged unless a test sets a hook, through which a
// test makes the board do what ibs's virtual board never does by itself -- report plug & play on,
// lose a confirmation, answer with another invoke ID, run its bus cycles at another rate than the
// master's loop -- and around which the allocation test stops counting (the board's own work is
// the board's). The adapter and the application see the plain DDI.
#pragma once

#include <functional>

#include "ibs/ddi.h"
#include "ibs/phoenix/ibs_util.h"

extern "C" {
IBDDIRET __real_DDI_DTI_ReadWriteData(IBDDIHND handle, T_DDI_DTI_ACCESS* write, T_DDI_DTI_ACCESS* read);
IBDDIRET __real_DDI_MXI_RcvMessage(IBDDIHND handle, T_DDI_MXI_ACCESS* access);
IBDDIRET __real_DDI_MXI_SndMessage(IBDDIHND handle, T_DDI_MXI_ACCESS* access);
IBDDIRET __real_GetIBSDiagnostic(IBDDIHND handle, T_IBS_DIAG* info);
}

namespace ibs::test::ddi_shim {

struct Hooks {
  // Instead of the call (call the __real_ function for the board's own answer).
  std::function<IBDDIRET(IBDDIHND, T_DDI_DTI_ACCESS*, T_DDI_DTI_ACCESS*)> read_write;
  std::function<IBDDIRET(IBDDIHND, T_DDI_MXI_ACCESS*)> receive;
  // Around every wrapped call that reaches the board.
  void (*enter)() = nullptr;
  void (*leave)() = nullptr;
};
Hooks& hooks();
inline void reset() { hooks() = Hooks{}; }

}  // namespace ibs::test::ddi_shim
