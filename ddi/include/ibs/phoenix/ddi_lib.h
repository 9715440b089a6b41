/* ibs's virtual INTERBUS board, legacy headers (docs/ddi.md, "Legacy headers"): the one header a
 * program for Phoenix Contact's ISA / PCI controller boards includes (ddi_lib.h): every legacy
 * header at once. */
#ifndef IBS_PHOENIX_DDI_LIB_H
#define IBS_PHOENIX_DDI_LIB_H

#include "stdtypes.h"
#include "ddi_usr.h"
#include "ddi_err.h"
#include "ddi_macr.h"
#include "ibs_util.h"
#include "svc_code.h"

#endif /* IBS_PHOENIX_DDI_LIB_H */
