/* ibs's virtual INTERBUS board, legacy headers (docs/ddi.md, "Legacy headers"): the one header a
 * Unix program for Phoenix Contact's Ethernet controllers includes (ethunix.h): every legacy
 * header. Its target macros (LINUX, SUN, ...) are not needed. */
#ifndef IBS_PHOENIX_ETHUNIX_H
#define IBS_PHOENIX_ETHUNIX_H

#include "ddi_lib.h"

#endif /* IBS_PHOENIX_ETHUNIX_H */
