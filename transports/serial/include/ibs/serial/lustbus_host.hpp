// A LUSTBUS host (LUSTBUS manual) on a serial port: the loop that runs one request of the sans-I/O
// lustbus::Host in real time -- the request's telegrams written, every character read handed to
// the host with the time, its timeouts (response, inter-character, the exchange limit of LB-D24)
// waited for on the port -- until the host is idle again (its closing EOT written, 3). Floor 4:
// it reads the steady clock and does the I/O; the protocol stays in the Host. The commands of
// `ibs lustbus` ask through it (docs/lustbus.md, "Command line"). Library ibs_lustbus_serial.
#pragma once

#include <chrono>

#include "ibs/base/time.hpp"
#include "ibs/lustbus/host.hpp"
#include "ibs/serial/serial_port.hpp"

namespace ibs::serial {

// The longest the loop waits on the port before it looks at the host's deadlines again.
inline constexpr Duration kHostPoll = 20ms;

// Runs `request` on `host` over `port` and returns its outcome (a default Outcome when the host
// kept none). Input not yet read is discarded first: stale bytes are no answer to this request.
// The host's times count from this call. Throws std::invalid_argument "request refused: WHY" when
// the host does not take the request, and what the port throws.
lustbus::Outcome transact(SerialPort& port, lustbus::Host& host, const lustbus::Request& request);

}  // namespace ibs::serial
