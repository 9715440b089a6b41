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

  void write(const canlust::CanFrame& f, Time at);
  void flush();
  [[nodiscard]] std::size_t records() const { return records_; }

 private:
  struct Handles;
  explicit PcapWriter(std::unique_ptr<Handles> h);
  std::unique_ptr<Handles> h_;
  std::size_t records_ = 0;
};

// The record bytes for one frame (8-byte header + data), as written to the file.
std::size_t socketcan_record(const canlust::CanFrame& f, std::uint8_t (&out)[16]);

}  // namespace ibs::can
