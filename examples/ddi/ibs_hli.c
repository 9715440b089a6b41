/*****************************************************************************
**  ibs example      : an INTERBUS master written as for Phoenix Contact's  **
**                     controller boards (a Win32 HLI-style module)          **
**  Board            : ibs's virtual board (libibs-ddi), node IBETH01N1      **
******************************************************************************
**  It uses Phoenix's header names (ethwin32.h, SVC_CODE.H), node names,    **
**  message and process data macros, GetIBSDiagnostic and the service       **
**  names, and builds against libibs-ddi without edits: only Windows'       **
**  Sleep, below, is the program's own on Linux (docs/ddi.md, "Legacy       **
**  headers"). Exits 0 when the MC6000 ran ENABLED at 1000 rpm and the      **
**  VF1000 at 25 Hz and the bus stopped cleanly.                            **
*****************************************************************************/

/* Windows' Sleep, for a build outside Windows. */
#ifndef _WIN32
#define _POSIX_C_SOURCE 200809L /* nanosleep */
#include <time.h>
static void Sleep(unsigned long ms)
{
  struct timespec t;
  t.tv_sec = (time_t)(ms / 1000UL);
  t.tv_nsec = (long)(ms % 1000UL) * 1000000L;
  nanosleep(&t, NULL);
}
#endif

/*======================================================================*/
/* INCLUDE FILES AND CONSTANT DEFINITION                                */
/*======================================================================*/

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "ethwin32.h"
#include "SVC_CODE.H"

#define MAX_MSG_LENGTH 128 /* bytes of the mailbox buffer */
#define PD_LENGTH 12       /* bytes of process data: the MC6000's 3 words, the VF1000's 3 */
#define MXI_RCV_TIMEOUT 20 /* seconds to wait for a confirmation */
#define PLUG_PLAY_MODE 0x2240

/*======================================================================*/
/* GLOBAL VARIABLES                                                     */
/*======================================================================*/

/* ------ Process data objects (words 0-2 the MC6000, 3-5 the VF1000) -- */
T_IBS_WORD aMcControl;   /* MC6000 control word */
T_IBS_DWORD aMcSpeed;    /* MC6000 speed reference, rpm in Q16 */
T_IBS_WORD aVfControl;   /* VF1000 control word */
T_IBS_WORD aVfFrequency; /* VF1000 frequency reference, 0.05 Hz */
T_IBS_WORD aVfComm;      /* VF1000 communication word */
T_IBS_WORD eMcStatus;    /* MC6000 status word */
T_IBS_WORD eMcActual;    /* MC6000 actual speed, rpm (Q16 integer part) */
T_IBS_WORD eVfStatus;    /* VF1000 status word */
T_IBS_WORD eVfFrequency; /* VF1000 actual frequency, 0.05 Hz */
T_IBS_BOOL bMcEnabled;
T_IBS_BOOL bVfEnabled;

BOOL bIBSRunning;

char caOpen_MXI[20] = "IBETH01N1_M";
char caOpen_DTI[20] = "IBETH01N1_D";

IBDDIHND mxiHnd, dtiHnd;
T_DDI_MXI_ACCESS mxiAcc;
T_DDI_DTI_ACCESS dti_Write;
T_DDI_DTI_ACCESS dti_Read;

USIGN8 usMailbox[MAX_MSG_LENGTH];
USIGN8 usWriteData[PD_LENGTH];
USIGN8 usReadData[PD_LENGTH];

int iIBS_HLI_Init_g(void);
int iIBS_HLI_Exit_g(void);
int iIBS_HLI_Process_g(void);
static int iSendCommand_m(USIGN16 code, int paraCnt);
static int iWaitConfirmation_m(USIGN16 code);
static void vUpdateSendData_m(void);
static void vUpdateReceiveData_m(void);

/*======================================================================*/
/* MAILBOX                                                              */
/*======================================================================*/

/* Sends the command in usMailbox (code and paraCnt parameters already set there). */
static int iSendCommand_m(USIGN16 code, int paraCnt)
{
  IBDDIRET iRet;

  IB_SetCmdCode(usMailbox, code);
  IB_SetParaCnt(usMailbox, paraCnt);
  mxiAcc.msgType = 0;
  mxiAcc.DDIUserID = 0;
  mxiAcc.msgLength = (USIGN16)(4 + 2 * paraCnt);
  mxiAcc.msgBlk = usMailbox;
  iRet = DDI_MXI_SndMessage(mxiHnd, &mxiAcc);
  if (iRet != ERR_OK) {
    printf("Sending command %04X failed, error code 0x%04X\n", code, iRet ^ ERR_BASE);
    return -1;
  }
  return 0;
}

/* Waits for the confirmation of `code` in usMailbox; confirmations of commands sent without
 * waiting come first and are passed over. Returns 0 when it came and is positive. */
static int iWaitConfirmation_m(USIGN16 code)
{
  IBDDIRET iRet;
  time_t starttime, ltime;

  time(&starttime);
  do {
    mxiAcc.msgLength = MAX_MSG_LENGTH;
    mxiAcc.msgBlk = usMailbox;
    iRet = DDI_MXI_RcvMessage(mxiHnd, &mxiAcc);
    if (iRet == ERR_OK && (USIGN16)IB_GetMsgCode(usMailbox) == (code | 0x8000)) {
      if (IB_GetParaN(usMailbox, 1) != 0) {
        printf("Command %04X refused, result %04X\n", code, IB_GetParaN(usMailbox, 1));
        return -1;
      }
      return 0;
    }
    if (iRet != ERR_OK && iRet != ERR_NO_MSG) break;
    time(&ltime);
  } while ((ltime - starttime) < MXI_RCV_TIMEOUT);
  printf("No confirmation of command %04X, error code 0x%04X\n", code, iRet ^ ERR_BASE);
  return -1;
}

/*======================================================================*/
/* INITIALISATION, PROCESS DATA, EXIT                                   */
/*======================================================================*/

int iIBS_HLI_Init_g(void)
{
  int iRet;
  T_IBS_DIAG infoPtr;
  USIGN16 PlugPlayModus = 111;

  /* Mailbox and data channel connections */
  iRet = DDI_DevOpenNode(caOpen_MXI, DDI_RW, &mxiHnd);
  if (iRet != ERR_OK) {
    printf("Error when creating mailbox connection. Error code: 0x%x\n", iRet ^ ERR_BASE);
    return -1;
  }
  iRet = DDI_DevOpenNode(caOpen_DTI, DDI_RW, &dtiHnd);
  if (iRet != ERR_OK) {
    printf("Error when creating data channel connection. Error code: 0x%x\n", iRet ^ ERR_BASE);
    return -1;
  }
  Sleep(100);

  /* Read_Value of the plug & play mode: with it on, the board would not take process data */
  IB_SetParaN(usMailbox, 1, 1);
  IB_SetParaN(usMailbox, 2, PLUG_PLAY_MODE);
  if (iSendCommand_m(0x0351, 2) != 0 || iWaitConfirmation_m(0x0351) != 0) return -1;
  if ((USIGN16)IB_GetParaN(usMailbox, 3) == PLUG_PLAY_MODE) PlugPlayModus = (USIGN16)IB_GetParaN(usMailbox, 4);
  printf("Plug & play mode %u\n", PlugPlayModus);
  if (PlugPlayModus != 0) {
    printf("Plug & play mode is active -> aborted\n");
    return -1;
  }

  /* Activate the configuration and start the data transfer; their confirmations wait unread */
  if (iSendCommand_m(S_ACTIVATE_CFG_REQ, 0) != 0) return -1;
  Sleep(50);
  if (iSendCommand_m(S_START_DATA_TRANSFER_REQ, 0) != 0) return -1;
  Sleep(50);

  /* The bus must run before process data is read and written */
  iRet = GetIBSDiagnostic(dtiHnd, &infoPtr);
  if (iRet != ERR_OK) {
    printf("Error when reading INTERBUS status. Error code: 0x%04X\n", iRet ^ ERR_BASE);
    return -1;
  }
  printf("IBS status: 0x%04X\n", infoPtr.state);
  if (infoPtr.state != (RUN_BIT | ACTIVE_BIT | READY_BIT)) {
    printf("IBS not in RUN state. -> Abort\n");
    return -1;
  }

  /* Outputs to zero, then the cyclic accesses */
  memset(usWriteData, 0, sizeof usWriteData);
  memset(usReadData, 0, sizeof usReadData);
  dti_Write.length = PD_LENGTH;
  dti_Write.address = DTA_OFFST_IBS_MASTER;
  dti_Write.dataCons = DTI_DATA_WORD;
  dti_Write.data = usWriteData;
  dti_Read = dti_Write;
  dti_Read.data = usReadData;
  iRet = DDI_DTI_WriteData(dtiHnd, &dti_Write);
  if (iRet != ERR_OK) {
    printf("Error when resetting buffer. Error code: 0x%04X\n", iRet ^ ERR_BASE);
    return -1;
  }
  bIBSRunning = TRUE;
  return 0;
}

int iIBS_HLI_Process_g(void)
{
  IBDDIRET locRet;

  if (!bIBSRunning) return -1;
  vUpdateSendData_m();
  locRet = DDI_DTI_ReadWriteData(dtiHnd, &dti_Write, &dti_Read);
  if (locRet != ERR_OK) {
    printf("  Read/Write data failed with code 0x%04X\n", locRet ^ ERR_BASE);
    return -2;
  }
  vUpdateReceiveData_m();
  return 0;
}

int iIBS_HLI_Exit_g(void)
{
  int ok = 0;

  bIBSRunning = FALSE;
  if (iSendCommand_m(S_STOP_DATA_TRANSFER_REQ, 0) != 0 || iWaitConfirmation_m(S_STOP_DATA_TRANSFER_REQ) != 0) ok = -1;
  if (DDI_DevCloseNode(mxiHnd) != ERR_OK) ok = -1;
  if (DDI_DevCloseNode(dtiHnd) != ERR_OK) ok = -1;
  return ok;
}

static void vUpdateSendData_m(void)
{
  IB_PD_SetDataN(usWriteData, 0, aMcControl);
  IB_PD_SetLongDataN(usWriteData, 1, aMcSpeed);
  IB_PD_SetDataN(usWriteData, 3, aVfControl);
  IB_PD_SetDataN(usWriteData, 4, aVfFrequency);
  IB_PD_SetDataN(usWriteData, 5, aVfComm);
}

static void vUpdateReceiveData_m(void)
{
  eMcStatus = IB_PD_GetDataN(usReadData, 0);
  eMcActual = IBS_HIWORD(IB_PD_GetLongDataN(usReadData, 1));
  eVfStatus = IB_PD_GetDataN(usReadData, 3);
  eVfFrequency = IB_PD_GetDataN(usReadData, 4);
}

/*======================================================================*/
/* APPLICATION: both drives to ENABLED, then back to READY              */
/*======================================================================*/

int main(void)
{
  int pass, result;

  if (iIBS_HLI_Init_g() != 0) return 1;

  aMcControl = 0x0006; /* SHUTDOWN: to READY */
  aMcSpeed = 1000UL << 16;
  aVfControl = 0x0076;
  aVfFrequency = 500; /* 25 Hz */
  aVfComm = 0;
  for (pass = 0; pass < 5000 && !(bMcEnabled && bVfEnabled); ++pass) {
    if (iIBS_HLI_Process_g() != 0) return 1;
    if ((eMcStatus & 0x6F) == 0x21) aMcControl = 0x000F; /* READY -> ENABLE */
    if ((eVfStatus & 0x6F) == 0x21) aVfControl = 0x807F; /* READY -> ENABLE, clockwise */
    bMcEnabled = (eMcStatus & 0x6F) == 0x27 && (short)eMcActual > 990;
    bVfEnabled = (eVfStatus & 0x6F) == 0x27 && eVfFrequency == 500;
    Sleep(2);
  }
  printf("MC6000 status %04X actual %d rpm; VF1000 status %04X actual %u.%02u Hz\n", eMcStatus,
         (short)eMcActual, eVfStatus, eVfFrequency / 20U, (eVfFrequency % 20U) * 5U);

  /* Both drives back to READY before the bus stops */
  aMcControl = 0x0006;
  aVfControl = 0x0076;
  for (pass = 0; pass < 25; ++pass) {
    if (iIBS_HLI_Process_g() != 0) return 1;
    Sleep(2);
  }
  result = iIBS_HLI_Exit_g();
  printf("%s\n", bMcEnabled && bVfEnabled && result == 0 ? "done" : "FAILED");
  return bMcEnabled && bVfEnabled && result == 0 ? 0 : 1;
}
