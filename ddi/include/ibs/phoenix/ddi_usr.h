/* ibs's virtual INTERBUS board, legacy headers (docs/ddi.md, "Legacy headers"): the DDI calls
 * under the header name of Phoenix Contact's SDK. The calls, their structures and permissions are
 * ibs/ddi.h's; this adds the consistency names Phoenix's programs write (DTI_DATA_WORD, ...). */
#ifndef IBS_PHOENIX_DDI_USR_H
#define IBS_PHOENIX_DDI_USR_H

#include "stdtypes.h"
#include <ibs/ddi.h>

/* Data consistency of a DTI access (T_DDI_DTI_ACCESS.dataCons). Bit access (DTI_DATA_BIT) is not
 * offered: a program that uses it does not compile rather than access the wrong bytes. */
#define DTI_DATA_WORD DDI_WORD
#define DTI_DATA_LWORD DDI_LWORD
#define DTI_DATA_BYTE DDI_BYTE
#define DTI_DATA_64BIT DDI_64BIT
#define DTI_DATA_8BIT DTI_DATA_BYTE
#define DTI_DATA_16BIT DTI_DATA_WORD
#define DTI_DATA_32BIT DTI_DATA_LWORD

/* The start of the master's process data in the DTI area: byte 0 (docs/ddi.md, "Where each
 * drive's bytes lie"). */
#define DTA_OFFST_IBS_MASTER 0x0000

#endif /* IBS_PHOENIX_DDI_USR_H */
