// A LUSTBUS device for a loop that owns a real line (serial::serve): its Receiver, and the two
// things the loop needs of the drive behind it: time passing without a telegram (a watchdog, 5.2;
// a self-test, 8.1.1) and the rate its line runs at (81-SIOC/SBAUD, 11.5). An answer is given out
// once its reaction time (10) has passed, never before. Nothing here allocates or throws after
// construction.
#pragma once

#include <cstdint>
#include <functional>

#include "ibs/base/line_device.hpp"
#include "ibs/lustbus/receiver.hpp"
#include "ibs/lustbus/timing.hpp"

namespace ibs::lustbus {

class ServedReceiver final : public base::LineDevice {
 public:
  // `receiver` must outlive this. `advance` lets time pass for the drive (empty: nothing to do);
  // `baud` is the drive's line rate (empty: always the port's).
  explicit ServedReceiver(Receiver* receiver, std::function<void(Time)> advance = {},
                          std::function<std::uint32_t()> baud = {})
      : receiver_(receiver), advance_(std::move(advance)), baud_(std::move(baud)) {}

  [[nodiscard]] std::optional<Time> next_due() const override { return receiver_->answer_due(); }
  void advance(Time now) override {
    if (advance_) advance_(now);
  }
  void receive(std::span<const std::uint8_t> bytes, Time now) override {
    // The fragment timeout follows the drive's line rate (LB-D23); 0: the port's, taken as the
    // factory rate.
    if (baud_) {
      const std::uint32_t rate = baud_();
      receiver_->set_inter_char_timeout(inter_char_timeout(rate != 0 ? rate : kFactoryBaud));
    }
    receiver_->receive(bytes, now);
  }
  std::span<const std::uint8_t> output(Time now) override {
    const auto due = receiver_->answer_due();
    if (!due || *due > now) return {};
    return receiver_->take_answer(now);
  }
  void written(std::size_t /*n*/) override {}  // take_answer() has handed the answer over
  [[nodiscard]] std::uint32_t line_baud() const override { return baud_ ? baud_() : 0; }

  [[nodiscard]] Receiver& receiver() const { return *receiver_; }

 private:
  Receiver* receiver_;
  std::function<void(Time)> advance_;
  std::function<std::uint32_t()> baud_;
};

}  // namespace ibs::lustbus
