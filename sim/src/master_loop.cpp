#include "ibs/sim/master_loop.hpp"

#include <stdexcept>
#include <string>

namespace ibs::sim {

MasterLoop::MasterLoop(interbus::BusConfig config,
                       std::vector<std::unique_ptr<devices::DeviceDriver>> drivers)
    : config_(std::move(config)), drivers_(std::move(drivers)) {
  if (drivers_.size() != config_.devices.size()) {
    throw std::invalid_argument("master loop: " + std::to_string(drivers_.size()) + " drivers for " +
                                std::to_string(config_.devices.size()) + " devices");
  }
}

devices::DriverIo MasterLoop::io(interbus::ProcessImage& image, std::size_t i) const {
  const interbus::Device& d = config_.devices[i];
  devices::DriverIo io;
  io.pd_in = interbus::in_slice(image, d);
  io.pd_out = interbus::out_slice(image, d);
  io.pcp_in = interbus::pcp_in_slice(image, d);
  io.pcp_out = interbus::pcp_out_slice(image, d);
  return io;
}

void MasterLoop::initial(interbus::ProcessImage& image) {
  for (std::size_t i = 0; i < drivers_.size(); ++i) drivers_[i]->initial(io(image, i));
}

void MasterLoop::cycle(interbus::ProcessImage& image, Time now, std::span<const LinkState> links) {
  for (std::size_t i = 0; i < drivers_.size(); ++i) {
    devices::DriverIo x = io(image, i);
    if (i < links.size()) {
      x.data_valid = links[i].data_valid;
      x.module_error = links[i].module_error;
    }
    drivers_[i]->cycle(x, now);
  }
}

void MasterLoop::restart(Time now) {
  for (auto& d : drivers_) d->restart(now);
}

}  // namespace ibs::sim
