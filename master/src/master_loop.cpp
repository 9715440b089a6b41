#include "ibs/master/master_loop.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace ibs::master {

Error MasterLoop::validate(const interbus::BusConfig& config, std::size_t drivers) {
  if (drivers != config.devices.size()) {
    return {ErrorCode::master_driver_count, "master loop: " + std::to_string(drivers) +
                                                " drivers for " +
                                                std::to_string(config.devices.size()) + " devices"};
  }
  for (const interbus::Device& d : config.devices) {
    // make_bus_config keeps every slice inside its area; checked once here, not every cycle.
    if (d.in.end() > interbus::kMaxProcessWords || d.out.end() > interbus::kMaxProcessWords ||
        d.pcp.end() > interbus::kMaxPcpWords) {
      return {ErrorCode::master_device_outside_image,
              "master loop: device '" + d.name + "' lies outside the process image"};
    }
  }
  return {};
}

MasterLoop::MasterLoop(interbus::BusConfig config,
                       std::vector<std::unique_ptr<devices::DeviceDriver>> drivers)
    : config_(std::move(config)), drivers_(std::move(drivers)) {
  detail::require<std::invalid_argument>(validate(config_, drivers_.size()));
  for (const interbus::Device& d : config_.devices) places_.push_back({d.in, d.out, d.pcp});
  ios_.resize(drivers_.size());
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

void MasterLoop::bind(interbus::ProcessImage& image) noexcept {
  if (bound_ == &image) return;
  for (std::size_t i = 0; i < drivers_.size(); ++i) ios_[i] = io(image, i);
  bound_ = &image;
}

void MasterLoop::initial(interbus::ProcessImage& image) {
  bind(image);
  for (std::size_t i = 0; i < drivers_.size(); ++i) drivers_[i]->initial(ios_[i]);
}

Exchange MasterLoop::cycle(Bus& bus, interbus::ProcessImage& image, Time now) noexcept {
  const Exchange ex = bus.exchange(image, now);
  cycle(image, now, ex);
  return ex;
}

void MasterLoop::cycle(interbus::ProcessImage& image, Time now, const Exchange& exchange) noexcept {
  bind(image);
  // The vectors' storage and the exchange's flag in locals: nothing a driver does moves them (the
  // cycle allocates nothing, a driver sees neither the loop nor the exchange), and the compiler
  // need not load them again after every driver's call.
  const std::unique_ptr<devices::DeviceDriver>* const drivers = drivers_.data();
  devices::DriverIo* const ios = ios_.data();
  const LinkState* const links = exchange.links.data();
  const bool valid = exchange.data_valid;
  const std::size_t n = drivers_.size();
  const std::size_t listed = std::min(n, exchange.links.size());
  std::size_t i = 0;
  for (; i < listed; ++i) {  // Exchange::link(i), without its range check per device
    devices::DriverIo& x = ios[i];
    x.data_valid = valid && links[i].data_valid;
    x.module_error = links[i].module_error;
    drivers[i]->cycle(x, now);
  }
  for (; i < n; ++i) {  // a bus that lists no (or not every) device: valid as the whole cycle
    devices::DriverIo& x = ios[i];
    x.data_valid = valid;
    x.module_error = false;
    drivers[i]->cycle(x, now);
  }
}

void MasterLoop::restart(Time now) {
  for (auto& d : drivers_) d->restart(now);
}

}  // namespace ibs::master
