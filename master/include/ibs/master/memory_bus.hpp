// A bus in memory (bus.hpp): the far side of the seam as plain word arrays. Whatever stands for
// the devices -- a test, the emulators of examples/embed, a board driver's DMA buffers copied in
// and out -- writes each device's input words and link state and reads the words the master
// sent. exchange() copies image.out -> the devices' side and the devices' side -> image.in, both
// PCP areas alike; a cycle marked invalid carries nothing either way, as a failed bus cycle.
// Nothing here allocates after construction.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "ibs/interbus/bus_config.hpp"
#include "ibs/master/bus.hpp"

namespace ibs::master {

class MemoryBus final : public Bus {
 public:
  explicit MemoryBus(interbus::BusConfig config);

  Exchange exchange(interbus::ProcessImage& image, Time now) noexcept override;

  // The device side of ring position i (a BusConfig index).
  std::span<Word> device_sends(std::size_t i) noexcept;                 // pd words to the master, status word first
  [[nodiscard]] std::span<const Word> device_receives(std::size_t i) const noexcept;  // the master's pd words, control word first
  std::span<Word> device_sends_pcp(std::size_t i) noexcept;
  [[nodiscard]] std::span<const Word> device_receives_pcp(std::size_t i) const noexcept;

  // The next exchanges' validity, and one device's link state (module error, its data).
  void set_valid(bool valid) noexcept { valid_ = valid; }
  void set_link(std::size_t i, LinkState s) noexcept;

  [[nodiscard]] const interbus::BusConfig& config() const { return config_; }
  [[nodiscard]] std::uint64_t exchanges() const { return exchanges_; }
  [[nodiscard]] Time last_exchange() const { return last_; }

 private:
  interbus::BusConfig config_;
  interbus::ProcessImage wire_;  // in: what the devices send; out: what the master sent
  std::vector<LinkState> links_;
  bool valid_ = true;
  std::uint64_t exchanges_ = 0;
  Time last_{0};
};

}  // namespace ibs::master
