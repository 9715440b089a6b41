/* ibs's virtual INTERBUS board, legacy headers (docs/ddi.md, "Legacy headers"): the helpers of
 * Phoenix Contact's DDI_MACR.H for building mailbox messages and reading them, and for the words
 * of a process data buffer. Macros, as in Phoenix's SDK: they work on a buffer of any pointer
 * type, are usable as expressions, and leave nothing to link.
 *
 * Layout (public facts, docs/ddi.md): a message is big-endian words [code][parameter count]
 * [parameter 1] ...; parameter m (counted from 1) lies at byte 2m + 2. Process data word m
 * (counted from 0) lies at byte 2m, high byte first. Every argument is evaluated once per byte it
 * touches: pass no expression with side effects. */
#ifndef IBS_PHOENIX_DDI_MACR_H
#define IBS_PHOENIX_DDI_MACR_H

#include "stdtypes.h"

/* Bytes of words, words of long words. */
#define IBS_HIBYTE(w) ((USIGN8)(((USIGN16)(w)) >> 8))
#define IBS_LOBYTE(w) ((USIGN8)(((USIGN16)(w)) & 0xFFU))
#define IBS_HIWORD(l) ((USIGN16)(((USIGN32)(l)) >> 16))
#define IBS_LOWORD(l) ((USIGN16)(((USIGN32)(l)) & 0xFFFFU))
#define IBS_MAKELONG(low, high) ((USIGN32)((((USIGN32)(USIGN16)(high)) << 16) | (USIGN32)(USIGN16)(low)))

/* ibs's building blocks: byte k of a buffer; the big-endian word at byte k. */
#define IBS_MACR_BYTE(buf, k) (((USIGN8*)(buf))[k])
#define IBS_MACR_CBYTE(buf, k) (((const USIGN8*)(buf))[k])
#define IBS_MACR_PUT(buf, k, w) (IBS_MACR_BYTE(buf, k) = IBS_HIBYTE(w), IBS_MACR_BYTE(buf, (k) + 1) = IBS_LOBYTE(w))
#define IBS_MACR_GET(buf, k) ((USIGN16)((IBS_MACR_CBYTE(buf, k) << 8) | IBS_MACR_CBYTE(buf, (k) + 1)))

/* Building a request. */
#define IB_SetCmdCode(n, m) IBS_MACR_PUT(n, 0, m)
#define IB_SetParaCnt(n, m) IBS_MACR_PUT(n, 2, m)
#define IB_SetParaN(n, m, o) IBS_MACR_PUT(n, 2 * (m) + 2, o)
#define IB_SetParaNHiByte(n, m, o) (IBS_MACR_BYTE(n, 2 * (m) + 2) = (USIGN8)(o))
#define IB_SetParaNLoByte(n, m, o) (IBS_MACR_BYTE(n, 2 * (m) + 3) = (USIGN8)(o))

/* Reading a confirmation or indication. */
#define IB_GetMsgCode(n) IBS_MACR_GET(n, 0)
#define IB_GetParaCnt(n) IBS_MACR_GET(n, 2)
#define IB_GetParaN(n, m) IBS_MACR_GET(n, 2 * (m) + 2)
#define IB_GetParaNHiByte(n, m) IBS_MACR_CBYTE(n, 2 * (m) + 2)
#define IB_GetParaNLoByte(n, m) IBS_MACR_CBYTE(n, 2 * (m) + 3)

/* PCP messages: the first parameter is [invoke ID][communication reference]; a confirmation's
 * second is the result, 0 when positive, else [error class][error code], then the additional
 * code (docs/ddi.md, "PCP over the mailbox"). */
#define IB_PMS_SetInvokeID(n, o) (IBS_MACR_BYTE(n, 4) = (USIGN8)(o))
#define IB_PMS_SetCR(n, o) (IBS_MACR_BYTE(n, 5) = (USIGN8)(o))
#define IB_PMS_GetInvokeID(n) IBS_MACR_CBYTE(n, 4)
#define IB_PMS_GetCR(n) IBS_MACR_CBYTE(n, 5)
#define IB_PMS_GetCnfResult(n) IBS_MACR_CBYTE(n, 6)
#define IB_PMS_GetNCnfErrClass(n) IBS_MACR_CBYTE(n, 6)
#define IB_PMS_GetNCnfErrCode(n) IBS_MACR_CBYTE(n, 7)
#define IB_PMS_GetNCnfAddCode(n) IBS_MACR_GET(n, 8)

/* Process data: word m of a DTI buffer. */
#define IB_PD_SetDataN(n, m, o) IBS_MACR_PUT(n, 2 * (m), o)
#define IB_PD_GetDataN(n, m) IBS_MACR_GET(n, 2 * (m))
#define IB_PD_SetDataNHiByte(n, m, o) (IBS_MACR_BYTE(n, 2 * (m)) = (USIGN8)(o))
#define IB_PD_SetDataNLoByte(n, m, o) (IBS_MACR_BYTE(n, 2 * (m) + 1) = (USIGN8)(o))
#define IB_PD_GetDataNHiByte(n, m) IBS_MACR_CBYTE(n, 2 * (m))
#define IB_PD_GetDataNLoByte(n, m) IBS_MACR_CBYTE(n, 2 * (m) + 1)
/* A long word in words m and m + 1, the high word first (the MC6000's Q16 values). */
#define IB_PD_SetLongDataN(n, m, o) (IB_PD_SetDataN(n, m, IBS_HIWORD(o)), IB_PD_SetDataN(n, (m) + 1, IBS_LOWORD(o)))
#define IB_PD_GetLongDataN(n, m) IBS_MAKELONG(IB_PD_GetDataN(n, (m) + 1), IB_PD_GetDataN(n, m))

#endif /* IBS_PHOENIX_DDI_MACR_H */
