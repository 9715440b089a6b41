/* ibs's virtual INTERBUS board, legacy headers (docs/ddi.md, "Legacy headers"): the DDI's return
 * codes under the header name of Phoenix Contact's SDK. They are defined once, in ibs/ddi.h
 * (ERR_OK, ERR_BASE | code). */
#ifndef IBS_PHOENIX_DDI_ERR_H
#define IBS_PHOENIX_DDI_ERR_H

#include <ibs/ddi.h>

#endif /* IBS_PHOENIX_DDI_ERR_H */
