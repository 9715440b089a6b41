#include "ibs/master/master_loop.hpp"

#include <stdexcept>
#include <string>

namespace ibs::master {

MasterLoop::MasterLoop(interbus::BusConfig config,
                       std::vector<std::unique_ptr<devices::DeviceDriver>> drivers)
    : config_(std::move(config)), drivers_(std::move(drivers)) {
  if (drivers_.size() != config_.devices.size()) {
    throw std::invalid_argument("master loop: " + std::to_string(drivers_.size()) + " drivers for " +
                                std::to_string(config_.devices.size()) + " devices");
  }
  for (const interbus::Device& d : config_.devices) {
    // make_bus_config keeps every slice inside its area; checked once here, not every cycle.
    if (d.in.end() > interbus::kMaxProcessWords || d.out.end() > interbus::kMaxProcessWords ||
        d.pcp.end() > interbus::kMaxPcpWords) {
      throw std::invalid_argument("master loop: device '" + d.name + "' lies outside the process image");
    }
    places_.push_back({d.in, d.out, d.pcp});
  }
}

devices::DriverIo MasterLoop::io(interbus::ProcessImage& image, std::size_t i) const {
  const Place& p = places_[i];
  devices::DriverIo io;
  io.pd_in = {image.in.data() + p.in.offset, p.in.length};
  io.pd_out = {image.out.data() + p.out.offset, p.out.length};
  io.pcp_in = {image.pcp_in.data() + p.pcp.offset, p.pcp.length};
  io.pcp_out = {image.pcp_out.data() + p.pcp.offset, p.pcp.length};
  return io;
}

void MasterLoop::initial(interbus::ProcessImage& image) {
  for (std::size_t i = 0; i < drivers_.size(); ++i) drivers_[i]->initial(io(image, i));
}

Exchange MasterLoop::cycle(Bus& bus, interbus::ProcessImage& image, Time now) noexcept {
  const Exchange ex = bus.exchange(image, now);
  cycle(image, now, ex);
  return ex;
}

void MasterLoop::cycle(interbus::ProcessImage& image, Time now, const Exchange& exchange) noexcept {
  for (std::size_t i = 0; i < drivers_.size(); ++i) {
    devices::DriverIo x = io(image, i);
    const LinkState link = exchange.link(i);
    x.data_valid = link.data_valid;
    x.module_error = link.module_error;
    drivers_[i]->cycle(x, now);
  }
}

void MasterLoop::restart(Time now) {
  for (auto& d : drivers_) d->restart(now);
}

}  // namespace ibs::master
