// The master's cycle loop (design.md floor 4): per cycle, the bus exchanges the process images
// (bus.hpp), then every device driver steps on what came back and writes its output words for
// the next exchange, with time passed in. Everything is placed at construction; the cycle
// allocates nothing, throws nothing and takes no lock. docs/embedding.md shows the loop in use.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "ibs/devices/driver.hpp"
#include "ibs/interbus/bus_config.hpp"
#include "ibs/base/error.hpp"
#include "ibs/interbus/process_image.hpp"
#include "ibs/master/bus.hpp"

namespace ibs::master {

class MasterLoop {
 public:
  // Refuses a count of drivers other than the configuration's devices
  // (ErrorCode::master_driver_count) and a device whose words lie outside the process image
  // (ErrorCode::master_device_outside_image).
  [[nodiscard]] static Error validate(const interbus::BusConfig& config, std::size_t drivers);
  // One driver per device of the configuration, in ring order, as validate() accepts them:
  // otherwise it throws std::invalid_argument with validate()'s message, or, in the embedded
  // build, aborts.
  MasterLoop(interbus::BusConfig config, std::vector<std::unique_ptr<devices::DeviceDriver>> drivers);

  // Writes every driver's initial output words into the image (before the first exchange).
  void initial(interbus::ProcessImage& image);
  // One whole master cycle: bus.exchange(image, now), then the drivers on its result. Returns
  // what the bus said.
  Exchange cycle(Bus& bus, interbus::ProcessImage& image, Time now) noexcept;
  // The drivers' half of a cycle, for a caller that has exchanged the image itself (the cycle
  // simulator is the bus and runs this half alongside its devices' next samples).
  void cycle(interbus::ProcessImage& image, Time now, const Exchange& exchange) noexcept;
  // The master restarts: every driver starts over.
  void restart(Time now);

  [[nodiscard]] const interbus::BusConfig& config() const { return config_; }
  [[nodiscard]] std::size_t size() const { return drivers_.size(); }
  devices::DeviceDriver& driver(std::size_t i) { return *drivers_[i]; }
  [[nodiscard]] const devices::DeviceDriver& driver(std::size_t i) const { return *drivers_[i]; }

 private:
  devices::DriverIo io(interbus::ProcessImage& image, std::size_t i) const;
  // Points each driver's DriverIo at its slices of `image`, when that is another image than the
  // last one: the slices stay put from cycle to cycle, only the link flags change.
  void bind(interbus::ProcessImage& image) noexcept;

  // Where each device's words lie in the image, from the checked configuration.
  struct Place {
    interbus::Slice in, out, pcp;
  };
  interbus::BusConfig config_;
  std::vector<std::unique_ptr<devices::DeviceDriver>> drivers_;
  std::vector<Place> places_;
  // The loop's record of a driver's hold (DeviceDriver::skip_while_holding): what the driver's
  // last cycle saw and wrote, each slice's words as one 64-bit value. Only a device with at most
  // four words each way and no PCP words can be skipped (`fits`); another is never armed.
  struct Held {
    std::uint64_t in = 0;   // the input words the hold saw
    std::uint64_t out = 0;  // the words it wrote
    // The sequencer's hold code when armed; kDisarmed, which no 8-bit code equals, otherwise.
    std::uint16_t hold = kDisarmed;
    bool fits = false;
  };
  static constexpr std::uint16_t kDisarmed = 0x100;
  // One per driver: the driver, its words in *bound_ and its hold, side by side, so that the
  // cycle walks one array (one pointer live across the drivers' calls, not an index into two).
  struct Bound {
    devices::DeviceDriver* driver = nullptr;
    devices::DriverIo io;
    Held held;
  };
  // The skip: true when the driver's next cycle is known to be its last one again (the hold it
  // reported, the same sequencer hold, input words and link flags), after writing its words.
  static bool skip(Bound& b, bool data_valid, bool module_error) noexcept;
  // After a driver's cycle: arms its record if it reports a hold, disarms it otherwise.
  static void record(Bound& b) noexcept;
  void disarm() noexcept;
  std::vector<Bound> ios_;
  const interbus::ProcessImage* bound_ = nullptr;
};

}  // namespace ibs::master
