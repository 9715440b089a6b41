// The master's cycle loop (design.md floor 4): per cycle, read the input image, step every
// device driver, write the output image, with time passed in. Everything is placed at
// construction; cycle() allocates nothing, throws nothing and takes no lock.
#pragma once

#include <memory>
#include <span>
#include <vector>

#include "ibs/devices/driver.hpp"
#include "ibs/devices/mc6000/driver.hpp"
#include "ibs/devices/vf1000/driver.hpp"
#include "ibs/interbus/bus_config.hpp"
#include "ibs/interbus/process_image.hpp"

namespace ibs::sim {

// What the bus says about one device for the cycle just finished.
struct LinkState {
  bool data_valid = true;     // the cycle delivered valid data (not corrupted, not recovering)
  bool module_error = false;  // the device reports a module error or is missing
};

class MasterLoop {
 public:
  // One driver per device of the configuration, in ring order; throws std::invalid_argument when
  // the counts differ.
  MasterLoop(interbus::BusConfig config, std::vector<std::unique_ptr<devices::DeviceDriver>> drivers);

  // Writes every driver's initial output words into the image.
  void initial(interbus::ProcessImage& image);
  // One master cycle over the image; `links` has one entry per device.
  void cycle(interbus::ProcessImage& image, Time now, std::span<const LinkState> links);
  // The master restarts: every driver starts over.
  void restart(Time now);

  [[nodiscard]] const interbus::BusConfig& config() const { return config_; }
  [[nodiscard]] std::size_t size() const { return drivers_.size(); }
  devices::DeviceDriver& driver(std::size_t i) { return *drivers_[i]; }
  [[nodiscard]] const devices::DeviceDriver& driver(std::size_t i) const { return *drivers_[i]; }

 private:
  devices::DriverIo io(interbus::ProcessImage& image, std::size_t i) const;

  // Where each device's words lie in the image, from the checked configuration.
  struct Place {
    interbus::Slice in, out, pcp;
  };
  interbus::BusConfig config_;
  std::vector<std::unique_ptr<devices::DeviceDriver>> drivers_;
  std::vector<Place> places_;
};

}  // namespace ibs::sim
