// What the board tests share (tests/board): scenario files both sides read, a master on the
// virtual board cycled by the test (Rig), and the paces of a board whose bus cycles run at
// another rate than the master's loop (through the wrapped DDI calls, ddi_shim.hpp).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "ddi_shim.hpp"
#include "ibs/board/run.hpp"
#include "ibs/master/ddi_board.hpp"
#include "ibs/sim/scenario.hpp"

namespace ibs::test {

using drivecom::State;
using master::BoardEvent;
using master::DdiBoard;
namespace shim = ddi_shim;

inline const std::string kServo = "[[device]]\nname = \"servo\"\ntype = \"mc6000\"\n";
inline const std::string kFan = "[[device]]\nname = \"fan\"\ntype = \"vf1000\"\n";

inline std::string write_file(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

// A scenario file both sides read: 20 s, a 1 ms bus cycle (unless `cycle_time` is empty: the
// formula's), the ring, then `rest`.
inline std::string scenario_file(const std::string& name, const std::string& ring, const std::string& rest,
                          const std::string& cycle_time = "1 ms") {
  std::string toml = "duration = \"20 s\"\n";
  if (!cycle_time.empty()) toml += "[bus]\ncycle_time = \"" + cycle_time + "\"\n";
  return write_file(name, toml + ring + rest);
}

class Board : public ::testing::Test {
 protected:
  void SetUp() override {
    setenv("IBS_DDI_MODE", "stepped", 1);
    unsetenv("IBS_DDI_SCENARIO");
    unsetenv("IBS_DDI_RT_PRIORITY");
    unsetenv("IBS_DDI_MASTER_COMMANDS");
    shim::reset();
  }
  void TearDown() override { shim::reset(); }

  // The virtual board runs `path` (its ring and faults).
  static void board_runs(const std::string& path) { setenv("IBS_DDI_SCENARIO", path.c_str(), 1); }
  // A board no earlier test left open: opening a node starts a new one, READY and nothing else.
  static bool fresh_board() {
    IBDDIHND h = 0;
    if (DDI_DevOpenNode("IBB1N1_M", DDI_RW, &h) != ERR_OK) return false;
    T_IBS_DIAG d{};
    const bool fresh = GetIBSDiagnostic(h, &d) == ERR_OK && d.state == DIAG_READY;
    DDI_DevCloseNode(h);
    return fresh;
  }
};

// A master on the board, cycled by the test.
struct Rig {
  board::MasterRing ring;
  std::unique_ptr<DdiBoard> board;
  std::unique_ptr<master::MasterLoop> loop;
  interbus::ProcessImage image;
  master::Exchange last;
  Time t{0};
  Duration period{0};
  std::vector<BoardEvent> events;

  // The master side of `path` on the virtual board running the same file.
  explicit Rig(const std::string& path) : ring(board::make_master_ring(sim::load_scenario(path))) {
    setenv("IBS_DDI_SCENARIO", path.c_str(), 1);
    auto b = DdiBoard::open(ring.config);
    if (!b) {
      ADD_FAILURE() << b.error().message;
      return;
    }
    board = std::move(b.value());
    loop = std::make_unique<master::MasterLoop>(ring.config, std::move(ring.drivers));
    board->attach(*loop);
    loop->initial(image);
    period = board->cycle_time();
  }
  [[nodiscard]] bool up() const { return board != nullptr; }
  void cycle() {
    t += period;
    last = loop->cycle(board->bus(), image, t);
    for (const BoardEvent& e : board->bus().events()) events.push_back(e);
    board->bus().clear_events();
  }
  void cycles(int n) {
    for (int k = 0; k < n; ++k) cycle();
  }
  devices::DeviceDriver& driver(std::size_t i) { return loop->driver(i); }
  std::optional<State> seen(std::size_t i) { return driver(i).sequencer().report().state_seen; }
  // Cycles until `done` (at most `n` cycles); whether it came.
  template <typename F>
  bool until(F done, int n) {
    for (int k = 0; k < n; ++k) {
      if (done()) return true;
      cycle();
    }
    return done();
  }
  bool enable_all(int n = 5000) {
    for (std::size_t i = 0; i < loop->size(); ++i) driver(i).sequencer().request(drivecom::Target::enabled, t);
    return until(
        [&] {
          for (std::size_t i = 0; i < loop->size(); ++i) {
            if (seen(i) != State::enabled) return false;
          }
          return true;
        },
        n);
  }
  // A parameter transaction of driver i to its end.
  devices::ParamStatus transact(std::size_t i, devices::ParamOp op, std::uint16_t number, std::int64_t value = 0) {
    const devices::ParamId id = driver(i).parameters().submit(op, number, value);
    until([&] { return driver(i).parameters().status(id).done(); }, 20000);
    last_id = id;
    return driver(i).parameters().status(id);
  }
  std::string describe_last(std::size_t i) { return driver(i).parameters().describe(last_id); }
  bool saw(BoardEvent::Kind k) const {
    return std::any_of(events.begin(), events.end(), [k](const BoardEvent& e) { return e.kind == k; });
  }
  devices::ParamId last_id = 0;
};

// The master's loop three times as fast as the board: two of three exchanges find the same bus
// cycle -- the outputs written, the same inputs read again, no new message (messages come with the
// board's cycles; a stepped board would run a cycle for an empty receive).
inline void master_three_times_as_fast() {
  struct Pace {
    int k = 0;
    bool cycled = true;  // until the loop's first exchange (the bring-up's messages come at once)
    std::vector<std::uint8_t> in = std::vector<std::uint8_t>(512);
  };
  auto pace = std::make_shared<Pace>();
  shim::hooks().read_write = [pace](IBDDIHND h, T_DDI_DTI_ACCESS* w, T_DDI_DTI_ACCESS* r) -> IBDDIRET {
    pace->cycled = pace->k++ % 3 == 0;
    if (!pace->cycled) {
      const IBDDIRET rc = DDI_DTI_WriteData(h, w);
      std::memcpy(r->data, pace->in.data(), r->length);
      return rc;
    }
    const IBDDIRET rc = __real_DDI_DTI_ReadWriteData(h, w, r);
    std::memcpy(pace->in.data(), r->data, r->length);
    return rc;
  };
  shim::hooks().receive = [pace](IBDDIHND h, T_DDI_MXI_ACCESS* a) -> IBDDIRET {
    return pace->cycled ? __real_DDI_MXI_RcvMessage(h, a) : IBDDIRET{ERR_NO_MSG};
  };
}

// The master's loop three times as slow: each exchange finds the board three bus cycles on.
inline void master_three_times_as_slow() {
  shim::hooks().read_write = [](IBDDIHND h, T_DDI_DTI_ACCESS* w, T_DDI_DTI_ACCESS* r) -> IBDDIRET {
    for (int k = 0; k < 2; ++k) {
      if (const IBDDIRET rc = DDI_DTI_ReadData(h, r); rc != ERR_OK) return rc;  // a cycle each
    }
    return __real_DDI_DTI_ReadWriteData(h, w, r);
  };
}

// The next PCP Read confirmation (8081H) the board gives, through `edit`; true drops it. Over
// the receive hook already set (a pace), if any.
inline void edit_next_read_confirmation(std::function<bool(T_DDI_MXI_ACCESS*)> edit) {
  auto receive = shim::hooks().receive;
  if (!receive) receive = [](IBDDIHND h, T_DDI_MXI_ACCESS* a) { return __real_DDI_MXI_RcvMessage(h, a); };
  shim::hooks().receive = [edit = std::move(edit), receive, done = false](IBDDIHND h, T_DDI_MXI_ACCESS* a) mutable {
    const IBDDIRET r = receive(h, a);
    if (r == ERR_OK && !done && a->msgLength >= 6 && a->msgBlk[0] == 0x80 && a->msgBlk[1] == 0x81) {
      done = true;
      if (edit(a)) return IBDDIRET{ERR_NO_MSG};
    }
    return r;
  };
}

}  // namespace ibs::test
