#include "ddi_shim.hpp"

namespace ibs::test::ddi_shim {

Hooks& hooks() {
  static Hooks h;
  return h;
}

namespace {
struct Around {
  Around() {
    if (hooks().enter != nullptr) hooks().enter();
  }
  ~Around() {
    if (hooks().leave != nullptr) hooks().leave();
  }
  Around(const Around&) = delete;
  Around& operator=(const Around&) = delete;
};
}  // namespace

}  // namespace ibs::test::ddi_shim

using ibs::test::ddi_shim::Around;
using ibs::test::ddi_shim::hooks;

extern "C" {

IBDDIRET __wrap_DDI_DTI_ReadWriteData(IBDDIHND handle, T_DDI_DTI_ACCESS* write, T_DDI_DTI_ACCESS* read) {
  const Around a;
  if (hooks().read_write) return hooks().read_write(handle, write, read);
  return __real_DDI_DTI_ReadWriteData(handle, write, read);
}

IBDDIRET __wrap_DDI_MXI_RcvMessage(IBDDIHND handle, T_DDI_MXI_ACCESS* access) {
  const Around a;
  if (hooks().receive) return hooks().receive(handle, access);
  return __real_DDI_MXI_RcvMessage(handle, access);
}

IBDDIRET __wrap_DDI_MXI_SndMessage(IBDDIHND handle, T_DDI_MXI_ACCESS* access) {
  const Around a;
  return __real_DDI_MXI_SndMessage(handle, access);
}

IBDDIRET __wrap_GetIBSDiagnostic(IBDDIHND handle, T_IBS_DIAG* info) {
  const Around a;
  return __real_GetIBSDiagnostic(handle, info);
}

}  // extern "C"
