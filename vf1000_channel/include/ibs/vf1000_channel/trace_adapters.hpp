// The VF1000 parameter channel in `ibs-trace 1` files with `words: comm`
// (../shared/specs/trace-format.md): the inverter (Server with the drive's parameter table) and the
// master (Client) as replay sides, and an explainer for communication words. One trace row is one
// inverter step and one master step, as the cycle tables of the INTERBUS manual 4.1.3 read.
#pragma once

#include <memory>

#include "ibs/interbus/replay.hpp"
#include "ibs/base/time.hpp"
#include "ibs/interbus/trace.hpp"
#include "ibs/vf1000_channel/client.hpp"
#include "ibs/vf1000_channel/server.hpp"

namespace ibs::vf1000_channel {

// Simulated time per trace row without a `step-time` header: two VF1000 samples of 8.2 ms. With it the manual's tables take the times of
// INTERBUS manual 7.1 (a value inquiry's 6 rows ~100 ms, a value transfer's 8 rows ~131 ms).
inline constexpr Duration kTraceStepPeriod = 16400us;

// The inverter, for `--emulate device`, serving `params` with `config` (the drive's wing gives
// both: devices/vf1000/channel.hpp). header.init: `operational` (85-SIOF clear), `power-on`
// (initialised, power-on bit set), `fault` (the channel as in `operational`; the fault belongs to
// the DRIVECOM state machine). The power stage is disabled throughout (START-UP INHIBIT / FAULT).
// Throws std::invalid_argument unless the header says `words: comm`.
std::unique_ptr<ibs::trace::DeviceSide> make_comm_device_side(const ibs::trace::Header& header,
                                                             std::span<const drive::ParameterInfo> params,
                                                             const ServerConfig& config);

// The master, for `--emulate master`: a Client that starts synchronised (row 0 of every table is
// the channel at rest) with ClientConfig's timeouts. Requests `read`, `write` (value 0..65535, or
// -32768..-1 for the two's complement) and `describe`; outcome `ok VALUE` for reads, `ok` for
// writes and descriptions, `nak`, and `timeout` for every transaction that ended without an answer
// (timeout, inverter restart, master restart, protocol error). Throws std::invalid_argument for a
// header that is not `words: comm` or whose request is `state ...`; submit() throws for a request
// the channel cannot carry.
std::unique_ptr<ibs::trace::MasterSide> make_comm_master_side(const ibs::trace::Header& header);

std::unique_ptr<ibs::trace::Explainer> make_comm_explainer();

// What the adapters cannot serve of a header: not `words: comm`, a request the channel cannot
// carry (a DRIVECOM `state`, a parameter above 3FFH, a value beyond 16 bits). Throws
// std::invalid_argument; the trace validation (devices/trace_adapters.hpp) calls it.
void check_comm_trace(const ibs::trace::Header& header);

// The trace request as a channel request (throws std::invalid_argument as above).
Request to_channel_request(const ibs::trace::Request& r);
// The client's outcome as the trace reports it.
ibs::trace::Outcome to_trace_outcome(const Outcome& o);

}  // namespace ibs::vf1000_channel
