// A DFS-1 controller for a loop that owns a real line (serial::serve): every byte read goes to
// the controller with its time, and the plant is stepped to that time; a reply is given out once
// its turnaround (parameter 56) has passed. Events (events.hpp) posted from outside the loop --
// the control channel of `ibs dfs1 emulate --control` -- are applied at the loop's next turn, with
// the loop's time, and what they did waits in take_report(). Nothing here allocates or throws.
#pragma once

#include <array>
#include <cstddef>
#include <optional>

#include "ibs/base/line_device.hpp"
#include "ibs/devices/dfs1/controller.hpp"

namespace ibs::devices::dfs1 {

class ServedController final : public base::LineDevice {
 public:
  // Events posted and not yet applied, and reports not yet taken, each.
  static constexpr std::size_t kEventCapacity = 16;

  // `controller` must outlive this.
  explicit ServedController(Controller& controller) : controller_(&controller) {}

  [[nodiscard]] std::optional<Time> next_due() const override { return controller_->next_deadline(); }
  // Applies the events posted since the last turn, in order, at `now` (while a report has room).
  void advance(Time now) override {
    while (events_ > 0 && reports_ < kEventCapacity) {
      const EventReport r = controller_->apply(event_ring_[event_head_], now);
      event_head_ = (event_head_ + 1) % kEventCapacity;
      --events_;
      report_ring_[(report_head_ + reports_) % kEventCapacity] = r;
      ++reports_;
    }
  }
  void receive(std::span<const std::uint8_t> bytes, Time now) override {
    controller_->receive(bytes, now);
    controller_->step(now);
  }
  std::span<const std::uint8_t> output(Time now) override { return controller_->pending(now); }
  void written(std::size_t n) override { controller_->consume(n); }

  // Queues `e` for the next turn; false when kEventCapacity events already wait.
  [[nodiscard]] bool post(const Event& e) {
    if (events_ == kEventCapacity) return false;
    event_ring_[(event_head_ + events_) % kEventCapacity] = e;
    ++events_;
    return true;
  }
  // The oldest report of an applied event not yet taken.
  std::optional<EventReport> take_report() {
    if (reports_ == 0) return std::nullopt;
    const EventReport r = report_ring_[report_head_];
    report_head_ = (report_head_ + 1) % kEventCapacity;
    --reports_;
    return r;
  }
  [[nodiscard]] std::size_t events_waiting() const { return events_; }

  [[nodiscard]] Controller& controller() const { return *controller_; }

 private:
  Controller* controller_;
  std::array<Event, kEventCapacity> event_ring_{};
  std::size_t event_head_ = 0;
  std::size_t events_ = 0;
  std::array<EventReport, kEventCapacity> report_ring_{};
  std::size_t report_head_ = 0;
  std::size_t reports_ = 0;
};

}  // namespace ibs::devices::dfs1
