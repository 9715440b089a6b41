// DFS-1 frames as a person reads them, for `ibs decode` of a capture (docs/pcap.md, "Serial
// lines"; docs/dfs1.md, "Commands and responses"): a request with its command and data, a
// response read by the request to its UID before it (a status's speeds, load % and ST2 / ST1 bits
// by name, a parameter's value with the table's name and unit), a NAK with its error, and a frame
// the protocol's decoder refuses with why. The wing's: it knows the controller's parameter table
// and status bits. Report text: it allocates.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace ibs::devices::dfs1 {

class FrameExplainer {
 public:
  // One frame as it was on the line (DLE STX ... CSM, 10H doubled), from the host or from a
  // controller: "UID 1 set speed 4096 rpm", "UID 1 ACK", "UID 7 NAK 82H illegal parameter number".
  std::string explain(bool from_host, std::span<const std::uint8_t> bytes);

 private:
  std::array<std::optional<std::uint8_t>, 256> request_{};    // the last command sent to each UID
  std::array<std::optional<std::uint8_t>, 256> parameter_{};  // and its first data byte (PRM, DTA)
};

}  // namespace ibs::devices::dfs1
