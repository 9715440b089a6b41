// The one loop that serves emulated devices on a serial port, whatever their protocol (LUSTBUS
// drives, DFS-1 controllers): every byte read goes to every device that can hear it, with the time
// since the loop began; a device's bytes are written once they are due (the reaction time of
// LUSTBUS 10, the turnaround of the DFS-1), never before. Floor 4: it reads the steady clock and
// does the I/O; the devices stay sans-I/O (base::LineDevice). A byte log set on the port
// (SerialPort::set_log) sees every byte both ways.
#pragma once

#include <functional>
#include <span>

#include "ibs/base/line_device.hpp"
#include "ibs/serial/serial_port.hpp"

namespace ibs::serial {

// The longest the loop waits on the port before it asks stop() again.
inline constexpr Duration kServePoll = 20ms;

// Serves `devices` on `port` until stop() is true (asked at least every kServePoll). A device
// whose line_baud() is not the port's hears nothing (on a real line it would see garbage); a
// lone device that changes its rate takes the port with it once nothing of its is due (LUSTBUS
// 11.5: its answer goes out at the old rate first).
// One turn of that loop at `now` that never waits for the port: what has already arrived goes to
// the devices, then their bytes due at `now` go out (written as SerialPort::write does: on a real
// port it waits until the driver has sent them). For a loop with other work between two turns:
// the test bench's real-time runner (`ibs run --realtime`) turns once per bus cycle with the
// simulator's time. Returns the bytes read.
std::size_t serve_turn(SerialPort& port, std::span<base::LineDevice* const> devices, Time now);

void serve(SerialPort& port, std::span<base::LineDevice* const> devices, const std::function<bool()>& stop);

}  // namespace ibs::serial
