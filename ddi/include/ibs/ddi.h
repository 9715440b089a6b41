/* ibs's virtual INTERBUS board: the calls of Phoenix Contact's Device Driver Interface (DDI) over
 * the cycle simulator and its emulated VF1000 and MC6000 drives (docs/ddi.md).
 *
 * Written for ibs from the public facts of ../shared/notes/public-facts.md ("Phoenix Contact's PC
 * driver interface"): the calls' names and shapes, the structures (packed to 2 bytes), the
 * consistency modes and the return codes named there. What those facts leave open -- the value
 * of ERR_BASE, the codes marked "ibs" below, DDI_GetInfo's structure, the message types -- is
 * ibs's choice, listed in docs/ddi.md. Link with -libs-ddi (pkg-config ibs-ddi, or the CMake
 * target ibs::ddi). Every call may be made from any thread; the board serialises them. */
#ifndef IBS_DDI_H
#define IBS_DDI_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef int32_t IBDDIHND; /* a node handle, > 0 */
typedef int32_t IBDDIRET; /* ERR_OK or one of the codes below */

/* Node names: board 1, node 1, data (DTI) or mailbox (MXI). */
#define DDI_DATA_NODE "IBB1N1_D"
#define DDI_MAILBOX_NODE "IBB1N1_M"

/* DDI_DevOpenNode permissions. */
#define DDI_READ 1
#define DDI_WRITE 2
#define DDI_RW 3

/* Data consistency of a DTI access: the unit the board keeps whole; the address and length are
 * multiples of it. */
#define DDI_WORD 0   /* 2 bytes */
#define DDI_LWORD 1  /* 4 bytes */
#define DDI_BYTE 2   /* 1 byte */
#define DDI_64BIT 3  /* 8 bytes */

/* Return codes (ERR_BASE | code). */
#define ERR_BASE 0x0000
#define ERR_OK 0
#define ERR_INVLD_BOARD_NUM (ERR_BASE | 0x0080) /* ibs: the node name's board is not 1 */
#define ERR_INVLD_NODE_NUM (ERR_BASE | 0x0081)  /* ibs: the node name's node is not 1, or not _D / _M */
#define ERR_INVLD_NODE_HD (ERR_BASE | 0x0085)   /* not an open handle, or not one of this node kind */
#define ERR_INVLD_PERM (ERR_BASE | 0x0086)      /* ibs: the node was not opened for this access */
#define ERR_NODE_NOT_READY (ERR_BASE | 0x0087)  /* the board could not start (its scenario) */
#define ERR_INVLD_PARAM (ERR_BASE | 0x008D)     /* a null pointer, a bad permission or length */
#define ERR_AREA_EXCDED (ERR_BASE | 0x0096)     /* the access leaves the process image */
#define ERR_INVLD_DATA_CONS (ERR_BASE | 0x0097) /* unknown consistency, or address/length not a multiple of it */
#define ERR_MSG_TO_LONG (ERR_BASE | 0x009A)     /* over DDI_MAX_MESSAGE, or the receive buffer is too small */
#define ERR_NO_MSG (ERR_BASE | 0x009B)          /* no message waits */
#define ERR_NO_MORE_MBX (ERR_BASE | 0x009C)     /* the board's outgoing mailbox is full: receive first */
#define ERR_SVR_TIMEOUT (ERR_BASE | 0x009E)     /* never returned: the virtual board takes a message at once */
#define ERR_AVR_TIMEOUT (ERR_BASE | 0x009F)     /* never returned: likewise */
#define ERR_IBS_SYSFAIL (ERR_BASE | 0x00A2)     /* the board's controller failed (SysFail): close all nodes */
#define ERR_DATA_TIMEOUT (ERR_BASE | 0x00E8)    /* never returned: process data is copied at once */
#define ERR_IB_STOPPED (ERR_BASE | 0x00ED)      /* read: the bus runs no data transfer */

/* The size of the process image (each direction) and the longest mailbox message, in bytes. */
#define DDI_IMAGE_BYTES 512
#define DDI_MAX_MESSAGE 1024

#if defined(_MSC_VER) || defined(__GNUC__)
#pragma pack(push, 2)
#endif

/* A DTI access. The devices' process data lie in ring order, each device's words after those of
 * the devices before it; the PCP channel is the mailbox's, not the image's. The default bus: bytes
 * 0-5 the MC6000 (control word, reference Q16 high, low / status word, actual Q16 high, low),
 * bytes 6-11 the VF1000 (control word, frequency reference, communication word / status word,
 * actual frequency, communication word); docs/ddi.md, "Where each drive's bytes lie".
 * In real-time mode the image changes at every bus cycle, on the board's thread: read what belongs
 * together in one access, which a bus cycle never splits. */
typedef struct {
  uint16_t length;   /* bytes */
  uint16_t address;  /* byte address in the image: byte 2k is the high byte of word k */
  uint16_t dataCons; /* DDI_WORD, DDI_LWORD, DDI_BYTE, DDI_64BIT */
  uint8_t* data;
} T_DDI_DTI_ACCESS;

typedef struct {
  uint16_t msgType;   /* send: the caller's; receive: DDI_MSG_CONFIRMATION or DDI_MSG_INDICATION */
  uint16_t msgLength; /* send: the message's bytes; receive: in the buffer's size, out the message's */
  uint16_t DDIUserID; /* send: the caller's; receive: that of the request confirmed (0: indication) */
  uint8_t* msgBlk;    /* [code][parameter count in words][parameter words], big-endian */
} T_DDI_MXI_ACCESS;

#define DDI_MSG_CONFIRMATION 0x0001
#define DDI_MSG_INDICATION 0x0002

typedef struct {
  char driverName[32];   /* "ibs virtual INTERBUS board", 0-terminated */
  uint16_t driverVersion; /* 0x0100 */
  uint16_t boardNumber;   /* 1 */
  uint16_t nodeType;      /* DDI_NODE_DATA or DDI_NODE_MAILBOX */
  uint16_t permission;    /* as opened */
  uint16_t deviceCount;   /* devices of the configuration */
  uint16_t inputBytes;    /* configured process data the devices send */
  uint16_t outputBytes;   /* configured process data the devices receive */
  uint16_t mode;          /* DDI_MODE_REALTIME or DDI_MODE_STEPPED */
  uint32_t cycleTimeUs;   /* the bus cycle time, microseconds */
  uint32_t cycles;        /* bus cycles run since the board started (with or without data) */
} T_DDI_INFO;

#if defined(_MSC_VER) || defined(__GNUC__)
#pragma pack(pop)
#endif

#define DDI_NODE_DATA 1
#define DDI_NODE_MAILBOX 2
#define DDI_MODE_REALTIME 0
#define DDI_MODE_STEPPED 1

IBDDIRET DDI_DevOpenNode(const char* name, int16_t perm, IBDDIHND* handle);
IBDDIRET DDI_DevCloseNode(IBDDIHND handle);
IBDDIRET DDI_DTI_ReadData(IBDDIHND handle, T_DDI_DTI_ACCESS* access);
IBDDIRET DDI_DTI_WriteData(IBDDIHND handle, T_DDI_DTI_ACCESS* access);
IBDDIRET DDI_DTI_ReadWriteData(IBDDIHND handle, T_DDI_DTI_ACCESS* write, T_DDI_DTI_ACCESS* read);
IBDDIRET DDI_MXI_SndMessage(IBDDIHND handle, T_DDI_MXI_ACCESS* access);
IBDDIRET DDI_MXI_RcvMessage(IBDDIHND handle, T_DDI_MXI_ACCESS* access);
IBDDIRET DDI_GetInfo(IBDDIHND handle, T_DDI_INFO* info);

/* Firmware services (mailbox), confirmed with code | 8000H and a result word first. */
#define S_START_DATA_TRANSFER 0x0701
#define S_STOP_DATA_TRANSFER 0x0702
#define S_CREATE_CONFIGURATION 0x0710
#define S_ACTIVATE_CONFIGURATION 0x0711
#define S_CONTROL_ACTIVE_CONFIGURATION 0x0713 /* ibs's code */
#define S_READ_VALUE 0x0351
#define S_GET_DIAG_INFO 0x032B
#define S_CONFIRM_DIAGNOSTICS 0x0760
#define S_READ_CONFIGURATION 0x0308 /* ibs's code: the active configuration, device by device */
/* PCP services towards the devices (communication reference 2 = the first PCP device). */
#define S_PCP_READ 0x0081
#define S_PCP_WRITE 0x0082
#define S_PCP_GET_OV 0x0088 /* Get-OV long, one object per request */
#define S_PCP_INITIATE 0x008B
#define S_PCP_ABORT 0x088D            /* unconfirmed */
#define S_PCP_ABORT_IND 0x408D        /* ibs: the board ended an association */
#define S_PCP_INFO_REPORT_IND 0x4085  /* ibs: a device's Information Report */
#define DDI_CONFIRMATION_BIT 0x8000

/* Results of firmware services (ibs's codes; 0 = positive). */
#define RES_OK 0x0000
#define RES_SERVICE_NOT_SUPPORTED 0x0901
#define RES_WRONG_STATE 0x0902
#define RES_INVALID_PARAMETER 0x0903
#define RES_UNKNOWN_DEVICE 0x0904

/* Read_Value variables; the confirmation carries (ID, value) per variable. */
#define VAR_DIAG_STATUS 0x2222
#define VAR_DIAG_PARAMETER 0x2223
#define VAR_DEVICE_COUNT 0x2230
#define VAR_CYCLE_TIME_US 0x2231
#define VAR_PLUG_AND_PLAY_MODE 0x2240 /* 0: off (the virtual board's configuration is the scenario's) */

/* The diagnostic status register. */
#define DIAG_USER 0x0001   /* a service was refused; the parameter register holds its result */
#define DIAG_PF 0x0002     /* peripheral fault: a device reports a module error or is missing */
#define DIAG_BUS 0x0004    /* bus error: cycles without valid data */
#define DIAG_CTRL 0x0008   /* controller error (SysFail) */
#define DIAG_RUN 0x0020    /* data transfer running */
#define DIAG_ACTIVE 0x0040 /* a configuration is active */
#define DIAG_READY 0x0080  /* the board is ready */
#define DIAG_BSA 0x0100    /* a bus segment is switched off */

/* Get_Diag_Info entry codes. */
#define DIAG_CODE_MODULE_ERROR 0x0001 /* peripheral fault of the device */
#define DIAG_CODE_TRANSMISSION 0x0002 /* bus error, device number 0 */

/* Control_Active_Configuration sub-commands. */
#define CTRL_SWITCH_OFF 0x0001
#define CTRL_SWITCH_ON 0x0002

/* The switch between real time and stepping, read when the board starts (the first open): the
 * environment variable IBS_DDI_MODE = "realtime" (the default) or "stepped"; IBS_DDI_SCENARIO
 * names a scenario file (TOML or JSON, docs/scenarios.md) with the bus and its faults, else the
 * default bus; IBS_DDI_MASTER_COMMANDS = "ignore" (the default: the file's commands for a master
 * are ignored with a note on stderr) or "ibs-master" (`ibs master --board` runs them, its
 * master_restart entries too). docs/ddi.md, "The board". */

#ifdef __cplusplus
}
#endif

#endif /* IBS_DDI_H */
