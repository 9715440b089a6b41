// The virtual board's calls (docs/ddi.md, docs/performance.md): what a legacy master pays per call,
// on the default bus with data transfer running, board stepped (IBS_DDI_MODE=stepped) so that no
// board thread runs beside the measurement.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <cstdlib>

#include "ibs/ddi.h"

namespace {

struct Board {
  IBDDIHND data = 0;
  IBDDIHND mbx = 0;
  Board() {
    setenv("IBS_DDI_MODE", "stepped", 1);
    unsetenv("IBS_DDI_SCENARIO");
    DDI_DevOpenNode(DDI_DATA_NODE, DDI_RW, &data);
    DDI_DevOpenNode(DDI_MAILBOX_NODE, DDI_RW, &mbx);
    request(S_ACTIVATE_CONFIGURATION, 0);
    request(S_START_DATA_TRANSFER, 0);
  }
  ~Board() {
    DDI_DevCloseNode(data);
    DDI_DevCloseNode(mbx);
  }
  Board(const Board&) = delete;
  Board& operator=(const Board&) = delete;
  // Sends [code][n][...] with n parameters taken from the Read_Value of the diagnostic register
  // (n = 2) or none, and receives its confirmation; true when it came.
  bool request(std::uint16_t code, int n) {
    std::uint8_t m[8] = {static_cast<std::uint8_t>(code >> 8), static_cast<std::uint8_t>(code & 0xFF), 0,
                         static_cast<std::uint8_t>(n), 0x00, 0x01, 0x22, 0x22};
    T_DDI_MXI_ACCESS s{0, static_cast<std::uint16_t>(4 + 2 * n), 0, m};
    if (DDI_MXI_SndMessage(mbx, &s) != ERR_OK) return false;
    std::uint8_t r[64];
    T_DDI_MXI_ACCESS a{0, sizeof r, 0, r};
    return DDI_MXI_RcvMessage(mbx, &a) == ERR_OK;
  }
};

// 12 bytes (both drives' outputs) into the image: the call, its checks, the copy.
void BM_DdiWriteData(benchmark::State& state) {
  Board b;
  std::uint8_t out[12] = {0, 6};
  T_DDI_DTI_ACCESS a{12, 0, DDI_WORD, out};
  for (auto _ : state) benchmark::DoNotOptimize(DDI_DTI_WriteData(b.data, &a));
}
BENCHMARK(BM_DdiWriteData);

// A stepped read: one bus cycle of the default bus (both drives sampled in it, the board's
// firmware as the master) and 12 bytes read.
void BM_DdiReadDataSteppedCycle(benchmark::State& state) {
  Board b;
  std::uint8_t in[12];
  T_DDI_DTI_ACCESS a{12, 0, DDI_WORD, in};
  for (auto _ : state) benchmark::DoNotOptimize(DDI_DTI_ReadData(b.data, &a));
}
BENCHMARK(BM_DdiReadDataSteppedCycle);

// Read_Value of the diagnostic status register: a mailbox request and its confirmation.
void BM_DdiReadValueRoundTrip(benchmark::State& state) {
  Board b;
  for (auto _ : state) benchmark::DoNotOptimize(b.request(S_READ_VALUE, 2));
}
BENCHMARK(BM_DdiReadValueRoundTrip);

}  // namespace
