#include "ibs/master/memory_bus.hpp"

#include <algorithm>

namespace ibs::master {

using interbus::Area;

MemoryBus::MemoryBus(interbus::BusConfig config) : config_(std::move(config)), links_(config_.devices.size()) {}

Exchange MemoryBus::exchange(interbus::ProcessImage& image, Time now) noexcept {
  ++exchanges_;
  last_ = now;
  if (valid_) {
    std::copy_n(image.out.begin(), config_.out_words, wire_.out.begin());
    std::copy_n(image.pcp_out.begin(), config_.pcp_words, wire_.pcp_out.begin());
    std::copy_n(wire_.in.begin(), config_.in_words, image.in.begin());
    std::copy_n(wire_.pcp_in.begin(), config_.pcp_words, image.pcp_in.begin());
  }
  return {valid_, links_};
}

// A position past the ring gets an empty slice.
namespace {
interbus::Slice place(const interbus::BusConfig& c, std::size_t i, interbus::Slice interbus::Device::*area) {
  return i < c.devices.size() ? c.devices[i].*area : interbus::Slice{};
}
}  // namespace

std::span<Word> MemoryBus::device_sends(std::size_t i) noexcept {
  return wire_.slice(Area::in, place(config_, i, &interbus::Device::in));
}
std::span<const Word> MemoryBus::device_receives(std::size_t i) const noexcept {
  return wire_.slice(Area::out, place(config_, i, &interbus::Device::out));
}
std::span<Word> MemoryBus::device_sends_pcp(std::size_t i) noexcept {
  return wire_.slice(Area::pcp_in, place(config_, i, &interbus::Device::pcp));
}
std::span<const Word> MemoryBus::device_receives_pcp(std::size_t i) const noexcept {
  return wire_.slice(Area::pcp_out, place(config_, i, &interbus::Device::pcp));
}

void MemoryBus::set_link(std::size_t i, LinkState s) noexcept {
  if (i < links_.size()) links_[i] = s;
}

}  // namespace ibs::master
