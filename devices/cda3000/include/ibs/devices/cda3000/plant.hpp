// The CDA3000's speed plant (decision D28): the output frequency follows its target as a first-
// order lag, f(t) = target + (f0 - target) e^(-(t - t0) / tau), computed in closed form from the
// last change, so the result does not depend on how often it is asked. The time constant depends
// on what the power stage does: following the reference, an emergency / quick stop, or coasting
// with the power stage off ("the motor runs out freely", 5.1). No allocation, no exceptions.
#pragma once

#include <cmath>

#include "ibs/base/time.hpp"

namespace ibs::devices::cda3000 {

struct PlantConfig {
  double fmax_hz = 400.0;             // the reference is limited to +-fmax (status bit 11)
  Duration time_constant = 200ms;     // following the reference, and the STOP reaction
  Duration quick_stop_time_constant = 50ms;  // EMERGENCY STOP ACTIVE, the quick-stop reaction
  Duration coast_time_constant = 2s;  // power stage off: the motor runs out
  double stop_threshold_hz = 0.1;     // at or below: stopped (transition 12, the STOP reactions)
  double reached_window_hz = 0.5;     // status bit 10: |actual - reference| within this
  double rated_slip_hz = 3.0;         // D35: the motor's slip at its rated torque (100 % load)
};

class SpeedPlant {
 public:
  // The target from `now` on (the frequency so far is kept continuous).
  void set(double target_hz, Duration tau, Time now) {
    f0_ = hz(now);
    t0_ = now;
    target_ = target_hz;
    tau_ = tau;
  }
  void reset(Time now) {
    f0_ = 0.0;
    target_ = 0.0;
    t0_ = now;
  }
  [[nodiscard]] double hz(Time now) const {
    if (now <= t0_ || tau_ <= Duration::zero()) return now <= t0_ ? f0_ : target_;
    const double x = static_cast<double>((now - t0_).count()) / static_cast<double>(tau_.count());
    return target_ + (f0_ - target_) * std::exp(-x);
  }
  [[nodiscard]] double target() const { return target_; }
  // When |f| comes down to `threshold` while the target is 0; Time::max() when it never does.
  [[nodiscard]] Time stopped_at(double threshold) const {
    if (target_ != 0.0) return Time::max();
    const double a = std::fabs(f0_);
    if (a <= threshold) return t0_;
    const double ns = static_cast<double>(tau_.count()) * std::log(a / threshold);
    return t0_ + Duration(static_cast<Duration::rep>(std::ceil(ns)));
  }

 private:
  double f0_ = 0.0;
  Time t0_{};
  double target_ = 0.0;
  Duration tau_ = 2s;
};

}  // namespace ibs::devices::cda3000
