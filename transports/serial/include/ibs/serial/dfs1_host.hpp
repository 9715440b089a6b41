// A DFS-1 host (DFS-1 manual) on a serial port: the loop that runs one transaction of the sans-I/O
// dfs1::HostTransaction in real time -- the input flushed, the request written, every byte read
// handed to the transaction with the time, its timeouts waited for on the port (response,
// inter-byte, the overall deadline of D14) -- until it is done. Floor 4: it reads the steady clock
// and does the I/O; the protocol stays in the transaction. The commands of `ibs dfs1` ask through
// it (docs/dfs1.md, "Command line"). Library ibs_dfs1_serial.
#pragma once

#include "ibs/dfs1/host.hpp"
#include "ibs/serial/serial_port.hpp"

namespace ibs::serial {

// One transaction: flushes the input (stale bytes are no answer; nanoMODBUS flushes too), writes
// `request`, returns the result. Times count from this call. Throws std::invalid_argument
// "dfs1: request refused: WHY" for a request check_request() refuses, and what the port throws.
dfs1::HostResult transact(SerialPort& port, const dfs1::Frame& request, dfs1::HostTimeouts timeouts);

}  // namespace ibs::serial
