// A DFS-1 controller for a loop that owns a real line (serial::serve): every byte read goes to
// the controller with its time, and the plant is stepped to that time; a reply is given out once
// its turnaround (parameter 56) has passed. Nothing here allocates or throws.
#pragma once

#include "ibs/base/line_device.hpp"
#include "ibs/devices/dfs1/controller.hpp"

namespace ibs::devices::dfs1 {

class ServedController final : public base::LineDevice {
 public:
  // `controller` must outlive this.
  explicit ServedController(Controller& controller) : controller_(&controller) {}

  [[nodiscard]] std::optional<Time> next_due() const override { return controller_->next_deadline(); }
  void advance(Time /*now*/) override {}  // receive() steps the plant after the bytes
  void receive(std::span<const std::uint8_t> bytes, Time now) override {
    controller_->receive(bytes, now);
    controller_->step(now);
  }
  std::span<const std::uint8_t> output(Time now) override { return controller_->pending(now); }
  void written(std::size_t n) override { controller_->consume(n); }

  [[nodiscard]] Controller& controller() const { return *controller_; }

 private:
  Controller* controller_;
};

}  // namespace ibs::devices::dfs1
