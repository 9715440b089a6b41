/* ibs's virtual INTERBUS board, legacy headers (docs/ddi.md, "Legacy headers"): the diagnostic
 * register's reading under the names of Phoenix Contact's IBS_UTIL.H -- GetIBSDiagnostic,
 * T_IBS_DIAG and the register's bits. The bit positions are those of ibs/ddi.h's DIAG_* (the same
 * register); the virtual board sets USER, PF, BUS, CTRL, RUN, ACTIVE, READY and BSA, never the
 * others, which are named so that code testing them compiles. */
#ifndef IBS_PHOENIX_IBS_UTIL_H
#define IBS_PHOENIX_IBS_UTIL_H

#include "stdtypes.h"
#include <ibs/ddi.h>

#ifdef __cplusplus
extern "C" {
#endif

#define USER_BIT DIAG_USER       /* a service was refused */
#define PF_BIT DIAG_PF           /* peripheral fault */
#define BUS_BIT DIAG_BUS         /* bus error */
#define CTRL_BIT DIAG_CTRL       /* controller error (SysFail) */
#define DETECT_BIT 0x0010        /* never set: the virtual board locates no error */
#define RUN_BIT DIAG_RUN         /* data transfer runs */
#define ACTIVE_BIT DIAG_ACTIVE   /* a configuration is active */
#define READY_BIT DIAG_READY     /* the board is ready */
#define BSA_BIT DIAG_BSA         /* a bus segment is switched off */
#define BASP_BIT 0x0200          /* never set */
#define RESULT_BIT 0x0400        /* never set */
#define SYNCHRON_RESULT_BIT 0x0800   /* never set */
#define DATA_CYCLE_RESULT_BIT 0x1000 /* never set */
#define WARN_BIT 0x2000          /* never set */
#define QUALITY_BIT 0x4000       /* never set */
#define SS_INFO_BIT 0x8000       /* never set */

#if defined(_MSC_VER) || defined(__GNUC__)
#pragma pack(push, 2)
#endif

typedef struct {
  USIGN16 state;    /* the diagnostic status register */
  USIGN16 diagPara; /* the diagnostic parameter register */
} T_IBS_DIAG;

typedef struct {
  USIGN16 state;    /* the diagnostic status register */
  USIGN16 diagPara; /* the diagnostic parameter register */
  USIGN16 addInfo;  /* additional error information: always 0 on the virtual board */
} T_IBS_DIAG_EX;

#if defined(_MSC_VER) || defined(__GNUC__)
#pragma pack(pop)
#endif

/* The registers of the board of `nodeHd` (an open data or mailbox node), read at once: no
 * message, no bus cycle (also in stepped mode). ERR_OK, ERR_INVLD_NODE_HD, ERR_INVLD_PARAM (null).
 * After a SysFail they still answer, with CTRL alone in the status register. */
IBDDIRET GetIBSDiagnostic(IBDDIHND nodeHd, T_IBS_DIAG* infoPtr);
IBDDIRET GetIBSDiagnosticEx(IBDDIHND nodeHd, T_IBS_DIAG_EX* infoPtr);

#ifdef __cplusplus
}
#endif

#endif /* IBS_PHOENIX_IBS_UTIL_H */
