// The master's cycle on a controller board allocates nothing (docs/embedding.md, "What is safe in
// the cycle"): 10^6 cycles of MasterLoop::cycle over the DDI bus adapter, with both drives'
// parameter channels busy all along -- the servo's PCP through the board's mailbox, the
// inverter's communication word -- and the board's diagnostics at work (random bus errors and a
// device now and then lost from the ring), counted with the replaced operator new of
// tests/support/counting_new.hpp. What the board's own library does inside its calls is the
// board's (on a real board, its firmware): the count stops inside each wrapped DDI call
// (ddi_shim.hpp); everything on the application's side of the calls counts.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "../support/counting_new.hpp"
#include "ddi_shim.hpp"
#include "ibs/board/run.hpp"
#include "ibs/master/ddi_board.hpp"
#include "ibs/sim/scenario.hpp"

namespace ibs {
namespace {

namespace shim = test::ddi_shim;

bool g_was_counting = false;
void pause_count() { g_was_counting = test::g_counting.exchange(false); }
void resume_count() { test::g_counting = g_was_counting; }

TEST(BoardCyclePath, TheCounterSeesTheApplicationsAllocationsNotTheBoards) {
  setenv("IBS_DDI_MODE", "stepped", 1);
  unsetenv("IBS_DDI_SCENARIO");
  shim::reset();
  shim::hooks().enter = &pause_count;
  shim::hooks().leave = &resume_count;
  IBDDIHND h = 0;
  ASSERT_EQ(DDI_DevOpenNode("IBB1N1_M", DDI_RW, &h), ERR_OK);
  {
    test::AllocationCounter c;
    // The board allocates a confirmation inside the wrapped call: not counted.
    std::uint8_t m[8] = {0x03, 0x51, 0x00, 0x02, 0x00, 0x01, 0x22, 0x22};
    T_DDI_MXI_ACCESS a{0, sizeof m, 0, m};
    ASSERT_EQ(DDI_MXI_SndMessage(h, &a), ERR_OK);
    EXPECT_EQ(c.count(), 0);
    // One of ours is.
    auto* p = new int(1);
    test::escape(p);
    delete p;
    EXPECT_EQ(c.count(), 1);
  }
  DDI_DevCloseNode(h);
  shim::reset();
}

TEST(BoardCyclePath, AMillionCyclesWithParameterTrafficAllocateNothing) {
  setenv("IBS_DDI_MODE", "stepped", 1);
  unsetenv("IBS_DDI_MASTER_COMMANDS");
  // The default bus (a 1 ms cycle), with random bus errors and lost devices for the diagnostics.
  const std::string path = ::testing::TempDir() + "board_alloc.toml";
  std::ofstream(path) << R"(duration = "10 s"
[bus]
cycle_time = "1 ms"

[[device]]
name = "servo"
type = "mc6000"

[[device]]
name = "fan"
type = "vf1000"

[random_faults]
seed = 7
corrupt_per_s = 0.5
lost_per_s = 0.02
)";
  setenv("IBS_DDI_SCENARIO", path.c_str(), 1);
  board::MasterRing ring = board::make_master_ring(sim::load_scenario(path));
  auto opened = master::DdiBoard::open(ring.config);
  ASSERT_TRUE(opened) << opened.error().message;
  master::DdiBoard& board = *opened.value();
  master::MasterLoop loop(ring.config, std::move(ring.drivers));
  board.attach(loop);
  interbus::ProcessImage image;
  loop.initial(image);
  shim::hooks().enter = &pause_count;
  shim::hooks().leave = &resume_count;

  Time t{0};
  for (std::size_t i = 0; i < 2; ++i) loop.driver(i).sequencer().request(drivecom::Target::enabled, t);
  // One transaction always in flight per drive: a read of 85 (which clears the power-on bit that
  // refuses writes, INTERBUS manual 6.1) and a write by turns.
  struct Traffic {
    devices::ParamId id = 0;
    std::uint16_t number = 0;
    std::int64_t value = 0;
    std::uint64_t done = 0;
    std::uint64_t values = 0;  // answered with a value or written
    bool write = true;
  };
  Traffic traffic[2] = {{0, 409, 100}, {0, 22, 1000}};
  const auto turn = [&] {
    for (std::size_t i = 0; i < 2; ++i) {
      Traffic& tr = traffic[i];
      devices::ParameterAccess& p = loop.driver(i).parameters();
      if (tr.id != 0) {
        const devices::ParamStatus s = p.status(tr.id);
        if (!s.done()) continue;
        ++tr.done;
        if (s.kind == devices::ParamKind::value || s.kind == devices::ParamKind::written) ++tr.values;
      }
      tr.write = !tr.write;
      tr.id = tr.write ? p.submit(devices::ParamOp::write, tr.number, tr.value) : p.submit(devices::ParamOp::read, 85, 0);
    }
  };
  // Warm up: both drives up, both channels' first transactions done, every buffer at its size.
  for (int k = 0; k < 5000; ++k) {
    t += 1ms;
    loop.cycle(board.bus(), image, t);
    board.bus().clear_events();
    turn();
  }
  const std::uint64_t before = traffic[0].done + traffic[1].done;
  {
    test::AllocationCounter c;
    for (int k = 0; k < 1'000'000; ++k) {
      t += 1ms;
      loop.cycle(board.bus(), image, t);
      board.bus().clear_events();
      turn();
    }
    EXPECT_EQ(c.count(), 0);
  }
  shim::reset();
  // The traffic was there: thousands of transactions through both channels, most of them answered.
  EXPECT_GT(traffic[0].done, 10000U);
  EXPECT_GT(traffic[1].done, 1000U);
  EXPECT_GT(traffic[0].values, traffic[0].done / 2);
  EXPECT_GT(traffic[1].values, traffic[1].done / 2);
  EXPECT_GT(traffic[0].done + traffic[1].done, before);
  EXPECT_GT(board.bus().valid_exchanges(), 900'000U);
  EXPECT_FALSE(board.close());
}

}  // namespace
}  // namespace ibs
