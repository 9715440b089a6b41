// One master cycle through the DDI bus adapter (master/ddi, docs/board.md) against ibs's virtual
// board stepped -- every exchange one bus cycle of the board -- beside the same cycle over the
// in-memory bus (docs/performance.md, "The master on a board"). The default bus: an MC6000 with
// its PCP channel (idle: no request) and a VF1000, both ENABLED and holding.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <memory>

#include "ibs/board/run.hpp"
#include "ibs/ddi.h"
#include "ibs/master/ddi_board.hpp"
#include "ibs/master/memory_bus.hpp"

namespace {

using namespace ibs;

constexpr Duration kCycle = 726us;  // the default bus's (the formula's)

struct Master {
  board::MasterRing ring = board::make_master_ring(sim::default_scenario());
  std::unique_ptr<master::MasterLoop> loop;
  interbus::ProcessImage image;
  Time t{0};
  Master() {
    loop = std::make_unique<master::MasterLoop>(ring.config, std::move(ring.drivers));
    loop->initial(image);
    for (std::size_t i = 0; i < loop->size(); ++i) loop->driver(i).sequencer().request(drivecom::Target::enabled, t);
  }
  [[nodiscard]] bool enabled() {
    for (std::size_t i = 0; i < loop->size(); ++i) {
      if (loop->driver(i).sequencer().report().state_seen != drivecom::State::enabled) return false;
    }
    return true;
  }
};

// The cycle over plain word arrays: the drives' status words ENABLED, the inverter's
// communication word in its wait mode.
void BM_MasterCycleMemoryBus(benchmark::State& state) {
  Master m;
  master::MemoryBus bus(m.loop->config());
  bus.device_sends(0)[0] = 0x0637;
  bus.device_sends(1)[0] = 0x0637;
  bus.device_sends(1)[2] = 0x8000;
  for (int k = 0; k < 100; ++k) m.loop->cycle(bus, m.image, m.t += kCycle);
  if (!m.enabled()) state.SkipWithError("the drives did not hold ENABLED");
  for (auto _ : state) {
    m.loop->cycle(bus, m.image, m.t += kCycle);
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_MasterCycleMemoryBus);

// The board: opened, brought up, the drives of its simulator enabled by the master first.
struct OnBoard {
  Master m;
  std::unique_ptr<master::DdiBoard> board;
  OnBoard() {
    setenv("IBS_DDI_MODE", "stepped", 1);
    unsetenv("IBS_DDI_SCENARIO");
    auto b = master::DdiBoard::open(m.loop->config());
    if (!b) return;
    board = std::move(b.value());
    board->attach(*m.loop);
    for (int k = 0; k < 5000 && !m.enabled(); ++k) cycle();
    for (int k = 0; k < 100; ++k) cycle();
  }
  void cycle() {
    m.loop->cycle(board->bus(), m.image, m.t += kCycle);
    board->bus().clear_events();
  }
};

// The same master cycle through the adapter: ReadWriteData (which runs the board's bus cycle:
// both drives' samples and its firmware), GetIBSDiagnostic, an empty mailbox, then the drivers.
void BM_MasterCycleDdiBoardStepped(benchmark::State& state) {
  OnBoard b;
  if (!b.board || !b.m.enabled()) {
    state.SkipWithError("the board did not come up with both drives ENABLED");
    return;
  }
  for (auto _ : state) {
    b.cycle();
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_MasterCycleDdiBoardStepped);

// The adapter's exchange alone, the drivers not called: what the board and the DDI cost a cycle.
void BM_DdiBusExchangeStepped(benchmark::State& state) {
  OnBoard b;
  if (!b.board) {
    state.SkipWithError("the board did not come up");
    return;
  }
  for (auto _ : state) {
    benchmark::DoNotOptimize(b.board->bus().exchange(b.m.image, b.m.t += kCycle));
    b.board->bus().clear_events();
  }
}
BENCHMARK(BM_DdiBusExchangeStepped);

// The board's bus cycle alone, as a legacy master's stepped read runs it (bench/ddi/ddi_bench.cpp,
// here with the drives ENABLED and running): the part of the exchange that is the simulated
// board's, not the adapter's.
void BM_DdiSteppedReadAlone(benchmark::State& state) {
  OnBoard b;
  if (!b.board) {
    state.SkipWithError("the board did not come up");
    return;
  }
  IBDDIHND h = 0;
  DDI_DevOpenNode(DDI_DATA_NODE, DDI_READ, &h);
  std::uint8_t in[12];
  T_DDI_DTI_ACCESS a{12, 0, DDI_WORD, in};
  for (auto _ : state) benchmark::DoNotOptimize(DDI_DTI_ReadData(h, &a));
  DDI_DevCloseNode(h);
}
BENCHMARK(BM_DdiSteppedReadAlone);

}  // namespace
