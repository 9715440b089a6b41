// A pcap file of CAN frames as LINKTYPE_CAN_SOCKETCAN (227), written through libpcap: each
// record is the SocketCAN layout - the 4-byte CAN id with its flags, big-endian, the length, 3
// pad bytes, the data (public-facts "Captures") - which tshark decodes as CAN; the CANLust Lua
// dissector (tools/wireshark/canlust.lua) decodes the telegrams on top. Timestamps are the
// simulated time (or any ibs::Time) since the epoch of the file.
#pragma once

#include <memory>
#include <string>

#include "ibs/canlust/frame.hpp"
#include "ibs/can/transport.hpp"
#include "ibs/base/time.hpp"

namespace ibs::can {

inline constexpr int kLinktypeCanSocketcan = 227;

class PcapWriter {
 public:
  static Opened<PcapWriter> open(const std::string& path);
  ~PcapWriter();
  PcapWriter(const PcapWriter&) = delete;
  PcapWriter& operator=(const PcapWriter&) = delete;

  // A frame at `at`: the time since the epoch given (set_epoch), by default since 1970.
  void write(const canlust::CanFrame& f, Time at);
  // Times passed to write() count from `epoch` (nanoseconds since 1970): a run in its own time
  // gives its wall-clock start, so that Wireshark's absolute view shows when it happened.
  void set_epoch(Time epoch) { epoch_ = epoch; }
  void flush();
  [[nodiscard]] std::size_t records() const { return records_; }

 private:
  struct Handles;
  explicit PcapWriter(std::unique_ptr<Handles> h);
  std::unique_ptr<Handles> h_;
  Time epoch_{0};
  std::size_t records_ = 0;
};

// The record bytes for one frame (8-byte header + data), as written to the file.
std::size_t socketcan_record(const canlust::CanFrame& f, std::uint8_t (&out)[16]);

}  // namespace ibs::can
