// `words: pd` traces of the MC6000: one row is one 1 ms servo sample of the words its 405-SUPI /
// 406-IBCNF layout gives (control/status word first); ../shared/specs/trace-format.md.
#pragma once

#include <memory>

#include "ibs/devices/mc6000/layout.hpp"
#include "ibs/interbus/replay.hpp"

namespace ibs::devices::mc6000 {

// The master: the DRIVECOM sequencer computes bits 0-3 and 7; the device bits and the reference
// come from the file.
std::unique_ptr<trace::MasterSide> make_pd_master(const Layout& l, Duration step);
std::unique_ptr<trace::Explainer> make_pd_explainer(const Layout& l);

}  // namespace ibs::devices::mc6000
