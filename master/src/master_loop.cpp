#include "ibs/master/master_loop.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <stdexcept>
#include <string>

namespace ibs::master {

namespace {

// The four words from `w` as one 64-bit value (the caller has checked they lie in the image).
std::uint64_t window(const Word* w) noexcept {
  std::uint64_t v;
  std::memcpy(&v, w, sizeof v);
  return v;
}

// The first `n` (0..4) words of a window.
std::uint64_t window_mask(std::size_t n) noexcept {
  std::array<Word, 4> words{};
  for (std::size_t i = 0; i < n && i < words.size(); ++i) words[i] = 0xFFFF;
  return window(words.data());
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
    // A window of four words must lie inside the image's words (validate() keeps the slices
    // there; the window may reach past a short slice's end).
    const Place& p = places_[i];
    const bool fits = p.pcp.length == 0 && p.in.length <= 4 && p.out.length <= 4 &&
                      p.in.offset + 4 <= interbus::kMaxProcessWords &&
                      p.out.offset + 4 <= interbus::kMaxProcessWords;
    b.held = Held{};
    b.held.in_mask = fits ? window_mask(p.in.length) : 0;
    b.held.out_mask = fits ? window_mask(p.out.length) : 0;
  }
  bound_ = &image;
}

void MasterLoop::disarm() noexcept {
  for (Bound& b : ios_) b.held.hold = kDisarmed;
}

bool MasterLoop::skip(Bound& b, bool data_valid, bool module_error) noexcept {
  const drivecom::Sequencer* s = b.driver->skip_while_holding();
  if (s == nullptr || s->hold_code() != b.held.hold || data_valid != b.io.data_valid ||
      module_error != b.io.module_error ||
      ((window(b.io.pd_in.data()) ^ b.held.in) & b.held.in_mask) != 0) {
    return false;
  }
  // The words its cycle would write, and the others of the window as they are.
  Word* const out = b.io.pd_out.data();
  const std::uint64_t w = (window(out) & ~b.held.out_mask) | b.held.out;
  std::memcpy(out, &w, sizeof w);
  return true;
}

void MasterLoop::record(Bound& b) noexcept {
  const drivecom::Sequencer* s = b.driver->skip_while_holding();
  if (s == nullptr || b.held.in_mask == 0) {
    b.held.hold = kDisarmed;
    return;
  }
  b.held.hold = s->hold_code();
  b.held.in = window(b.io.pd_in.data()) & b.held.in_mask;
  b.held.out = window(b.io.pd_out.data()) & b.held.out_mask;
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
