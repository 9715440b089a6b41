/* ibs's virtual INTERBUS board, legacy headers (docs/ddi.md, "Legacy headers"): the basic types
 * under the names Phoenix Contact's DDI headers and their users write, so that a master written
 * for one of Phoenix's controller boards compiles against libibs-ddi without edits.
 *
 * Written for ibs from the names public code uses; the sizes are the DDI structures' (USIGN16 a
 * 16-bit word, ...). T_IBS_BOOL .. T_IBS_DWORD are macros with the very tokens of the HLI export's
 * ibs_cfg.h, so that a project's own ibs_cfg.h, included before or after, redefines them
 * identically. C89-compatible apart from <stdint.h> (C99). */
#ifndef IBS_PHOENIX_STDTYPES_H
#define IBS_PHOENIX_STDTYPES_H

#include <stdint.h>

typedef uint8_t USIGN8;
typedef uint16_t USIGN16;
typedef uint32_t USIGN32;
typedef int8_t INT8;
typedef int16_t INT16;
typedef int32_t INT32;
typedef char CHAR;

#ifndef VOID
#define VOID void
#endif
/* Pointer and calling-convention qualifiers of the 16-bit and Windows builds: empty here. */
#ifndef IBPTR
#define IBPTR
#endif
#ifndef IBDDIFUNC
#define IBDDIFUNC
#endif
#ifndef FAR
#define FAR
#endif
#ifndef TRUE
#define TRUE 1
#endif
#ifndef FALSE
#define FALSE 0
#endif

/* Process data object types of the HLI export (ibs_cfg.h). */
#define T_IBS_BOOL unsigned short
#define T_IBS_BITSTRING unsigned short
#define T_IBS_BYTE unsigned char
#define T_IBS_WORD unsigned short
#define T_IBS_DWORD unsigned long

#endif /* IBS_PHOENIX_STDTYPES_H */
