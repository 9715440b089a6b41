// The bus seam (design.md floor 4): the one place where the master's cycle loop meets whatever
// carries its process images -- the cycle simulator, an in-memory bus in tests (memory_bus.hpp),
// a controller board's driver. One exchange per master cycle, time passed in; the result says
// whether the cycle's data is valid and which devices report a module error.
//
// Cycle-path rules (docs/embedding.md): exchange() allocates nothing, throws nothing, takes no
// lock that the cycle could wait on, and reads no clock (`now` is the cycle's time).
#pragma once

#include <span>

#include "ibs/interbus/process_image.hpp"
#include "ibs/base/time.hpp"

namespace ibs::master {

// What the bus says about one device for the cycle just exchanged.
struct LinkState {
  bool data_valid = true;     // the device's words of this cycle are valid (not corrupted, not recovering)
  bool module_error = false;  // the device reports a module error (initialising, faulty) or is missing
};

// What one exchange delivered.
struct Exchange {
  // False: the whole cycle failed (e.g. a CRC error on the ring); image.in holds nothing new.
  bool data_valid = true;
  // One entry per device in ring order, owned by the bus and valid until its next exchange;
  // empty: every device delivered valid data without a module error.
  std::span<const LinkState> links;

  // The state of device `i`, with the whole cycle's validity folded in.
  [[nodiscard]] LinkState link(std::size_t i) const noexcept {
    LinkState s = i < links.size() ? links[i] : LinkState{};
    s.data_valid = s.data_valid && data_valid;
    return s;
  }
};

class Bus {
 public:
  virtual ~Bus() = default;
  // One bus cycle at `now`: carries image.out and image.pcp_out (what the master's last cycle
  // wrote) to the devices and fills image.in and image.pcp_in with what they sent. An invalid
  // cycle may leave image.in as it was.
  virtual Exchange exchange(interbus::ProcessImage& image, Time now) noexcept = 0;
};

}  // namespace ibs::master
