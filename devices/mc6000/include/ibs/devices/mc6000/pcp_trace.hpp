// `ibs replay` adapters for MC6000 PCP channel traces: the PCP client and server of pcp/ with the
// MC6000's parameter table and layouts (`words: pcp`,
// ../shared/specs/trace-format.md). One trace step = one master cycle = one device step = 1 ms of
// simulated time; the server runs with LatencyModel::immediate() (a request is executed in the
// step it completes) so that recorded traces stay short (docs/pcp.md, "Replay").
//
// The words are always computed by the real Client and Server, never copied from the file.
// Factories are configuration-time: they throw std::invalid_argument for a header they cannot
// serve (not `device: mc6000` / `words: pcp`, a SUPI without PCP words).
#pragma once

#include <memory>

#include "ibs/interbus/replay.hpp"
#include "ibs/interbus/trace.hpp"

namespace ibs::devices::mc6000 {

// The PCP channel width for a trace header (405-SUPI, INTERBUS manual 3.2.2).
int trace_channel_words(const ibs::trace::Header& header);
// What the PCP adapters cannot serve of a header: not `words: pcp`, a SUPI without PCP words, a
// request the channel cannot carry (`state`: DRIVECOM states travel in `words: pd`). Throws
// std::invalid_argument; the trace validation (devices/trace_adapters.hpp) calls it.
void check_pcp_trace(const ibs::trace::Header& header);

// The servo's PCP server; honours `init` (operational: running, SERR clear; power-on: restarted,
// SERR power-on bit, the link announces the restart; fault: running with a device fault).
std::unique_ptr<ibs::trace::DeviceSide> make_pcp_device_side(const ibs::trace::Header& header);
// The master's PCP client. submit() takes `read PNR`, `write PNR VALUE` (VALUE raw, sized by the
// MC6000 parameter's type), `describe PNR` (Get-OV long); it first resynchronises the channel
// and runs Initiate. outcome(): `ok`, `ok VALUE` (a read: the raw value, zero-extended), `nak`
// (negative confirmation, Abort, refused Initiate), `timeout`.
std::unique_ptr<ibs::trace::MasterSide> make_pcp_master_side(const ibs::trace::Header& header);
std::unique_ptr<ibs::trace::Explainer> make_pcp_explainer(const ibs::trace::Header& header);

}  // namespace ibs::devices::mc6000
