/* ibs's virtual INTERBUS board, legacy headers (docs/ddi.md, "Legacy headers"): the one header a
 * Windows program for Phoenix Contact's Ethernet controllers includes (ethwin32.h): every legacy
 * header, and the Windows base types such programs use (BOOL, BYTE, WORD, DWORD, USHORT, UINT,
 * ULONG). Windows' functions are not here: a program that calls Sleep brings its own. */
#ifndef IBS_PHOENIX_ETHWIN32_H
#define IBS_PHOENIX_ETHWIN32_H

#include "ddi_lib.h"

typedef int BOOL;
typedef unsigned char BYTE;
typedef unsigned short WORD;
typedef uint32_t DWORD;
typedef unsigned short USHORT;
typedef unsigned int UINT;
typedef uint32_t ULONG;

#endif /* IBS_PHOENIX_ETHWIN32_H */
