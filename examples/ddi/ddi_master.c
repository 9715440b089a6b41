/* A master written the way one was for a Phoenix controller board: open the data and mailbox
 * nodes, activate the configuration, start data transfer, check the diagnostic register, then a
 * cyclic loop that reads the inputs and writes the outputs to bring the MC6000 to ENABLED at
 * 1000 rpm and the VF1000 to ENABLED at 25 Hz, a PCP read of the MC6000's 406-IBCNF over the
 * mailbox, and stop. Runs against ibs's virtual board (libibs-ddi) on the default bus: the MC6000
 * (3 words: control word, Q16 speed high, low) at bytes 0..5, the VF1000 (control word, 0.05 Hz
 * reference, communication word) at bytes 6..11. Exits 0 only when all of that happened. */
#define _POSIX_C_SOURCE 200809L /* nanosleep */
#include <stdio.h>
#include <time.h>

#include <ibs/ddi.h>

static IBDDIHND data_node, mbx_node;

static void put_word(uint8_t* b, uint16_t w) {
  b[0] = (uint8_t)(w >> 8);
  b[1] = (uint8_t)(w & 0xFF);
}

static uint16_t get_word(const uint8_t* b) { return (uint16_t)((b[0] << 8) | b[1]); }

static void sleep_ms(long ms) {
  struct timespec t = {ms / 1000, (ms % 1000) * 1000000L};
  nanosleep(&t, NULL);
}

/* Sends a request and waits (up to 5 s) for its confirmation; returns its length in words, 0 on
 * failure. */
static int request(const uint16_t* words, int count, uint16_t* answer, int capacity) {
  uint8_t buf[DDI_MAX_MESSAGE];
  T_DDI_MXI_ACCESS snd, rcv;
  int i;
  for (i = 0; i < count; ++i) put_word(buf + 2 * i, words[i]);
  snd.msgType = 0;
  snd.msgLength = (uint16_t)(2 * count);
  snd.DDIUserID = 1;
  snd.msgBlk = buf;
  if (DDI_MXI_SndMessage(mbx_node, &snd) != ERR_OK) return 0;
  for (i = 0; i < 5000; ++i) {
    IBDDIRET r;
    rcv.msgLength = sizeof buf;
    rcv.msgBlk = buf;
    r = DDI_MXI_RcvMessage(mbx_node, &rcv);
    if (r == ERR_NO_MSG) {
      sleep_ms(1);
      continue;
    }
    if (r != ERR_OK) return 0;
    if (rcv.msgType == DDI_MSG_INDICATION) {  /* e.g. an Abort of a PCP association */
      printf("indication %04X\n", get_word(buf));
      continue;
    }
    {
      int n = rcv.msgLength / 2, k;
      if (n > capacity) n = capacity;
      for (k = 0; k < n; ++k) answer[k] = get_word(buf + 2 * k);
      return n;
    }
  }
  return 0;
}

static int service(uint16_t code) {
  uint16_t req[2], ans[8];
  req[0] = code;
  req[1] = 0;
  return request(req, 2, ans, 8) >= 3 && ans[0] == (code | DDI_CONFIRMATION_BIT) && ans[2] == RES_OK;
}

static uint16_t diagnostic_status(void) {
  uint16_t req[4] = {S_READ_VALUE, 2, 1, VAR_DIAG_STATUS}, ans[8];
  /* Confirmed with [result][count] and (ID, value) per variable. */
  return request(req, 4, ans, 8) == 6 && ans[4] == VAR_DIAG_STATUS ? ans[5] : 0;
}

int main(void) {
  uint8_t out[12], in[12];
  T_DDI_DTI_ACCESS wr = {12, 0, DDI_WORD, out}, rd = {12, 0, DDI_WORD, in};
  uint16_t mc_control = 0x0006, vf_control = 0x0076, ans[16];
  int cycle, mc_enabled = 0, vf_enabled = 0, ok;
  uint16_t read_ibcnf[5] = {S_PCP_READ, 3, 0x0102, 0x5C00 + 406, 0};
  uint16_t initiate[5] = {S_PCP_INITIATE, 3, 0x0102, 0, 0};

  if (DDI_DevOpenNode(DDI_DATA_NODE, DDI_RW, &data_node) != ERR_OK ||
      DDI_DevOpenNode(DDI_MAILBOX_NODE, DDI_RW, &mbx_node) != ERR_OK) {
    fprintf(stderr, "cannot open the board's nodes\n");
    return 1;
  }
  if (!service(S_ACTIVATE_CONFIGURATION) || !service(S_START_DATA_TRANSFER)) {
    fprintf(stderr, "the board did not start\n");
    return 1;
  }
  {
    uint16_t diag = diagnostic_status();
    printf("diagnostic status %04X\n", diag);
    if ((diag & (DIAG_RUN | DIAG_ACTIVE | DIAG_READY)) != (DIAG_RUN | DIAG_ACTIVE | DIAG_READY)) return 1;
  }

  /* The cyclic part: read the inputs, decide, write the outputs; about 2 ms per pass. */
  for (cycle = 0; cycle < 5000 && !(mc_enabled && vf_enabled); ++cycle) {
    uint16_t mc_status, vf_status;
    if (DDI_DTI_ReadData(data_node, &rd) != ERR_OK) return 1;
    mc_status = get_word(in);
    vf_status = get_word(in + 6);
    if ((mc_status & 0x6F) == 0x21) mc_control = 0x000F;   /* READY -> ENABLE */
    if ((vf_status & 0x6F) == 0x21) vf_control = 0x807F;   /* READY -> ENABLE, start clockwise */
    mc_enabled = (mc_status & 0x6F) == 0x27 && (int16_t)get_word(in + 2) > 990;
    vf_enabled = (vf_status & 0x6F) == 0x27 && get_word(in + 8) == 500;
    put_word(out, mc_control);
    put_word(out + 2, 1000); /* 1000 rpm, Q16: integer part */
    put_word(out + 4, 0);
    put_word(out + 6, vf_control);
    put_word(out + 8, 500);  /* 25 Hz in 0.05 Hz */
    put_word(out + 10, 0);
    if (DDI_DTI_WriteData(data_node, &wr) != ERR_OK) return 1;
    sleep_ms(2);
  }
  printf("MC6000 status %04X actual %d rpm; VF1000 status %04X actual %.2f Hz\n", get_word(in),
         (int16_t)get_word(in + 2), get_word(in + 6), get_word(in + 8) * 0.05);

  /* 406-IBCNF through PCP: Initiate, then Read of object 5C00H + 406 on CR 2. */
  ok = request(initiate, 5, ans, 16) >= 4 && ans[0] == 0x808B && ans[3] == 0;
  ok = ok && request(read_ibcnf, 5, ans, 16) == 6 && ans[0] == 0x8081 && ans[3] == 0;
  if (ok) printf("406-IBCNF = %u (PCP, %u byte)\n", ans[5] >> 8, ans[4]);

  /* Stop: the PCP association (Abort, unconfirmed), both drives to READY, the data transfer. */
  {
    uint8_t abort_msg[6];
    T_DDI_MXI_ACCESS snd;
    put_word(abort_msg, S_PCP_ABORT);
    put_word(abort_msg + 2, 1);
    put_word(abort_msg + 4, 2);
    snd.msgType = 0;
    snd.msgLength = sizeof abort_msg;
    snd.DDIUserID = 1;
    snd.msgBlk = abort_msg;
    ok = ok && DDI_MXI_SndMessage(mbx_node, &snd) == ERR_OK;
  }
  put_word(out, 0x0006);
  put_word(out + 6, 0x0076);
  DDI_DTI_WriteData(data_node, &wr);
  sleep_ms(50);
  ok = ok && service(S_STOP_DATA_TRANSFER);
  DDI_DevCloseNode(mbx_node);
  DDI_DevCloseNode(data_node);
  printf("%s\n", mc_enabled && vf_enabled && ok ? "done" : "FAILED");
  return mc_enabled && vf_enabled && ok ? 0 : 1;
}
