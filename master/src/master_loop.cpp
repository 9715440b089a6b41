#include "ibs/master/master_loop.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

namespace ibs::master {

namespace {

// A device's n (0..4) words as one 64-bit value, and back: its own words only, never a
// neighbour's, so that a skip reads and writes no word the drivers' calls would not, whatever
// memory the image is. Fewer than four words out of line: four, the common slice, is one load or
// store.
[[gnu::noinline]] std::uint64_t load_short(const Word* w, std::size_t n) noexcept {
  std::uint64_t v = 0;
  std::memcpy(&v, w, std::min(n, std::size_t{3}) * sizeof(Word));
  return v;
}

std::uint64_t load_words(const Word* w, std::size_t n) noexcept {
  if (n != 4) return load_short(w, n);
  std::uint64_t v;
  std::memcpy(&v, w, sizeof v);
  return v;
}

[[gnu::noinline]] void store_short(Word* w, std::size_t n, std::uint64_t v) noexcept {
  std::memcpy(w, &v, std::min(n, std::size_t{3}) * sizeof(Word));
}

void store_words(Word* w, std::size_t n, std::uint64_t v) noexcept {
  if (n != 4) {
    store_short(w, n, v);
    return;
  }
  std::memcpy(w, &v, sizeof v);
}

}  // namespace

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
  for (std::size_t i = 0; i < drivers_.size(); ++i) ios_[i].driver = drivers_[i].get();
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
  for (std::size_t i = 0; i < drivers_.size(); ++i) {
    Bound& b = ios_[i];
    b.io = io(image, i);
    const Place& p = places_[i];
    b.held = Held{};
    b.held.fits = p.pcp.length == 0 && p.in.length <= 4 && p.out.length <= 4;
  }
  bound_ = &image;
}

void MasterLoop::disarm() noexcept {
  for (Bound& b : ios_) b.held.hold = kDisarmed;
}

bool MasterLoop::skip(Bound& b, bool data_valid, bool module_error) noexcept {
  const drivecom::Sequencer* s = b.driver->skip_while_holding();
  if (s == nullptr || s->hold_code() != b.held.hold || data_valid != b.io.data_valid ||
      module_error != b.io.module_error || load_words(b.io.pd_in.data(), b.io.pd_in.size()) != b.held.in) {
    return false;
  }
  store_words(b.io.pd_out.data(), b.io.pd_out.size(), b.held.out);  // what its cycle would write
  return true;
}

void MasterLoop::record(Bound& b) noexcept {
  const drivecom::Sequencer* s = b.driver->skip_while_holding();
  if (s == nullptr || !b.held.fits) {
    b.held.hold = kDisarmed;
    return;
  }
  b.held.hold = s->hold_code();
  b.held.in = load_words(b.io.pd_in.data(), b.io.pd_in.size());
  b.held.out = load_words(b.io.pd_out.data(), b.io.pd_out.size());
}

void MasterLoop::initial(interbus::ProcessImage& image) {
  bind(image);
  disarm();
  for (std::size_t i = 0; i < drivers_.size(); ++i) drivers_[i]->initial(ios_[i].io);
}

Exchange MasterLoop::cycle(Bus& bus, interbus::ProcessImage& image, Time now) noexcept {
  const Exchange ex = bus.exchange(image, now);
  cycle(image, now, ex);
  return ex;
}

void MasterLoop::cycle(interbus::ProcessImage& image, Time now, const Exchange& exchange) noexcept {
  bind(image);
  // The storage and the exchange's flag in locals: nothing a driver does moves them (the cycle
  // allocates nothing, a driver sees neither the loop nor the exchange), and the compiler need
  // not load them again after every driver's call.
  Bound* b = ios_.data();
  Bound* const end = b + ios_.size();
  const LinkState* link = exchange.links.data();
  const bool valid = exchange.data_valid;
  Bound* const listed_end = b + std::min(ios_.size(), exchange.links.size());
  // A driver that reported a hold and sees the same again is not called: its words are written
  // from the record (skip, record; DeviceDriver::skip_while_holding says when that is the call's
  // whole effect; MasterLoopSkip.* compares the loop with every driver called).
  for (; b != listed_end; ++b, ++link) {  // Exchange::link(i), without its range check per device
    const bool v = valid && link->data_valid;
    const bool m = link->module_error;
    if (skip(*b, v, m)) continue;
    b->io.data_valid = v;
    b->io.module_error = m;
    b->driver->cycle(b->io, now);
    record(*b);
  }
  for (; b != end; ++b) {  // a bus that lists no (or not every) device: valid as the whole cycle
    if (skip(*b, valid, false)) continue;
    b->io.data_valid = valid;
    b->io.module_error = false;
    b->driver->cycle(b->io, now);
    record(*b);
  }
}

void MasterLoop::restart(Time now) {
  disarm();
  for (auto& d : drivers_) d->restart(now);
}

}  // namespace ibs::master
