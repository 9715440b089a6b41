// MC6000 drive plant: the servo's PI speed loop with torque limit, its current loop as a first-
// order lag, and a rigidly coupled mechanical load, as a continuous-time state-space model
// discretised exactly (zero-order hold, matrix exponential) for the sample period.
//
// It supplies what the MC6000 emulator reports: actual speed and torque, and the status-word
// bits 10 "reference reached" and 11 "limit value" (INTERBUS manual 5.1.3 and 5.3.2). The speed loop
// is a modelling choice: the manual gives no controller structure or motor data.
//
// States x = [w, i, T]: w motor speed (rad/s), i the PI integrator (Nm), T motor torque (Nm).
// Inputs u = [w_ref (rad/s), d (Nm), T_lim (Nm)]: d = load torque + friction torque, held over
// a step; T_lim the clipped command in the limited mode.
//
//   linear mode  (|c| <= T_max, c = Kp (w_ref - w) + i):
//     J dw/dt = T - B w - d,   di/dt = Ki (w_ref - w),   tau dT/dt = c - T
//   limited mode (|c| > T_max, also used with T_lim = 0 for a disabled power stage):
//     J dw/dt = T - B w - d,   di/dt = 0 (anti-windup), tau dT/dt = T_lim - T
//
// The mode is chosen at the start of each step from the state and held for the step. Nothing in
// step() allocates, throws or reads a clock; the matrices are computed in the constructor.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "ibs/devices/mc6000/descriptor.hpp"
#include "ibs/base/time.hpp"

namespace ibs::devices {

// Defaults: a servo motor with about 4 Nm rated torque, 2.5 x peak, driving a load of three
// times its inertia. 0 -> 2500.25 rpm (INTERBUS manual 5.3.4) takes about 0.22 s in the torque limit.
struct DrivePlantParams {
  double motor_inertia = 0.002;          // J_m, kg m^2
  double load_inertia = 0.006;           // J_L, kg m^2, rigidly coupled: J = J_m + J_L
  double viscous_friction = 2.0e-4;      // B, Nm per rad/s
  double coulomb_friction = 0.1;         // Nm, opposes motion; holds the shaft at standstill
  double kp = 2.0;                       // speed controller gain, Nm per rad/s (kp/J = 250 rad/s)
  double ki = 50.0;                      // integral gain, Nm per rad (integral time kp/ki = 40 ms)
  double torque_limit = 10.0;            // T_max, Nm, symmetric
  double torque_time_constant = 0.5e-3;  // tau, s: the closed current loop as a first-order lag
  double rated_torque = 4.0;             // Nm that read as 100 % in PlantOutput::torque_percent
  double reference_window_rpm = 10.0;    // "reference reached" when |ref - actual| <= this
};

struct PlantInput {
  double speed_reference_rpm = 0.0;
  double load_torque_nm = 0.0;  // positive: opposes positive speed (a braking load)
  bool enabled = true;          // false: power stage off, torque 0, integrator cleared; coasts
};

struct PlantOutput {
  double speed_rpm = 0.0;
  double torque_nm = 0.0;          // motor torque (the current loop's output)
  double torque_percent = 0.0;     // torque_nm in % of DrivePlantParams::rated_torque
  bool reference_reached = false;  // status bit 10: |ref - speed| <= reference_window_rpm
  bool limit_active = false;       // status bit 11: the torque command was clipped in this step
};

// A speed reference ramp (the MC6000's reference channel has a ramp generator, INTERBUS manual 3.2.1).
struct ReferenceRamp {
  double rate_rpm_per_s = 0.0;  // <= 0: no ramp, the output jumps to the target
  double value_rpm = 0.0;

  // Moves value_rpm towards target by at most rate * dt and returns it.
  double step(double target_rpm, Duration dt) noexcept;
};

constexpr double rpm_to_rad_s(double rpm) {
  return rpm * 0.10471975511965977;
}  // 2 pi / 60
constexpr double rad_s_to_rpm(double w) {
  return w * 9.549296585513720;
}  // 60 / 2 pi

class DrivePlant {
 public:
  using State = Eigen::Vector3d;  // [w rad/s, integrator Nm, torque Nm]
  using Input = Eigen::Vector3d;  // [w_ref rad/s, d Nm, T_lim Nm]
  using Matrix = Eigen::Matrix3d;

  enum class Mode { linear, limited };

  struct StateSpace {
    Matrix a;
    Matrix b;
  };

  // Throws std::invalid_argument naming a parameter out of range (configuration time).
  explicit DrivePlant(const DrivePlantParams& params = {}, Duration period = mc6000::kSamplePeriod);

  // One sample period with the input held; returns the output after it.
  PlantOutput step(const PlantInput& in) noexcept {
    update(in);
    return output();
  }
  // The same without forming the output: the per-sample path of the device models.
  void update(const PlantInput& in) noexcept;
  // `count` periods with the input held (the same as as many update() calls).
  void update_held(const PlantInput& in, std::uint32_t count) noexcept;
  // As many whole periods as `elapsed` (plus what earlier calls left over) covers; the remainder
  // waits for the next call.
  void advance(Duration elapsed, const PlantInput& in) noexcept {
    if (pending_.count() == 0 && elapsed == period_) {
      update(in);  // the usual case: one call per sample period
      return;
    }
    pending_ += elapsed;
    while (pending_ >= period_) {
      update(in);
      pending_ -= period_;
    }
  }

  // advance(elapsed, in) `count` times with the same input: one loop for the samples of a bus
  // cycle in which the device's inputs do not change.
  void advance_held(Duration elapsed, const PlantInput& in, std::uint32_t count) noexcept {
    if (pending_.count() == 0 && elapsed == period_) {
      update_held(in, count);
      return;
    }
    for (std::uint32_t k = 0; k < count; ++k) advance(elapsed, in);
  }

  // The output after the last step (formed from the state when asked for).
  [[nodiscard]] PlantOutput output() const noexcept;
  [[nodiscard]] double speed_rpm() const noexcept { return rad_s_to_rpm(x_(0)); }
  [[nodiscard]] double torque_nm() const noexcept { return x_(2); }
  const State& state() const noexcept { return x_; }
  void set_state(const State& x) noexcept { x_ = x; }
  void reset() noexcept;

  Duration period() const noexcept { return period_; }
  const DrivePlantParams& params() const noexcept { return p_; }
  double inertia() const noexcept { return p_.motor_inertia + p_.load_inertia; }

  // The continuous model of a mode and its discretisation for period().
  static StateSpace continuous(const DrivePlantParams& p, Mode m);
  const StateSpace& discrete(Mode m) const noexcept {
    return m == Mode::linear ? linear_ : limited_;
  }

 private:
  // [Ad | two columns of Bd] of a mode, row by row: x'(r) = sum over c of rows[r][c] * [x; u1; u2](c)
  // with (u1, u2) = (w_ref, d) in the linear mode and (d, T_lim) in the limited one. The input a
  // mode does not use has a zero column in B, so its column of Bd (the zero-order hold of a zero
  // column) is exactly zero and is left out. The step reads these plain arrays; the Eigen
  // matrices stay for discretising and inspecting.
  using Rows = std::array<std::array<double, 5>, 3>;
  static Rows rows_of(const StateSpace& d, Eigen::Index first_input);

  DrivePlantParams p_;
  Duration period_;
  Duration pending_{0};
  StateSpace linear_;
  StateSpace limited_;
  std::array<Rows, 2> rows_{};  // [linear, limited]
  State x_ = State::Zero();
  double reference_rpm_ = 0.0;  // the last step's input, for PlantOutput::reference_reached
  bool limited_last_ = false;   // the last step ran in the torque limit
};

// Below this speed (rad/s, about 1e-8 rpm) the shaft counts as standing still.
inline constexpr double kPlantStandstill = 1e-9;

// Inline: every simulated servo sample runs it, inside the device model's sample loop.
inline void DrivePlant::update(const PlantInput& in) noexcept { update_held(in, 1); }

inline void DrivePlant::update_held(const PlantInput& in, std::uint32_t count) noexcept {
  if (count == 0) return;
  // The state and the input in locals for the loop: the steps of a cycle's stretch run on them.
  const double w_ref = rpm_to_rad_s(in.speed_reference_rpm);
  const double load = in.load_torque_nm;
  const double tmax = p_.torque_limit;
  const double tc = p_.coulomb_friction;
  const double kp = p_.kp;
  double w0 = x_(0);
  double i0 = x_(1);
  double t0 = x_(2);
  bool linear = false;
  for (std::uint32_t k = 0; k < count; ++k) {
    // Friction and load, held over the step. At standstill, static friction balances up to its
    // full value whatever drive torque there is (stiction), so the shaft stays put.
    const double friction =
        std::abs(w0) > kPlantStandstill ? std::copysign(tc, w0) : std::clamp(t0 - load, -tc, tc);
    const double d = load + friction;

    // The mode for this step: limited (clipped command T_lim, or T_lim = 0 with the power stage
    // off) or linear.
    linear = false;
    double t_lim = 0.0;
    if (!in.enabled) {
      i0 = 0.0;  // power stage off: torque decays to 0, the controller starts afresh
    } else {
      const double command = kp * (w_ref - w0) + i0;
      if (std::abs(command) > tmax) {
        t_lim = std::copysign(tmax, command);
      } else {
        linear = true;
      }
    }

    // x' = Ad x + Bd u with u = [w_ref, d, T_lim], the input the mode does not use left out.
    const Rows& r = rows_[linear ? 0 : 1];
    const double u1 = linear ? w_ref : d;
    const double u2 = linear ? d : t_lim;
    const auto row = [&](const std::array<double, 5>& c) {
      return c[0] * w0 + c[1] * i0 + c[2] * t0 + c[3] * u1 + c[4] * u2;
    };
    double w1 = row(r[0]);
    double i1 = row(r[1]);
    double t1 = row(r[2]);
    if (linear) {
      // Integrator clamp (anti-windup), and the current limit for a command that rose past
      // T_max inside the step.
      i1 = std::clamp(i1, -tmax, tmax);
      t1 = std::clamp(t1, -tmax, tmax);
    }
    // Coulomb friction only brakes: a speed it alone carried through zero stops at zero.
    const bool crossed = (w0 > kPlantStandstill && w1 < 0.0) || (w0 < -kPlantStandstill && w1 > 0.0);
    if (crossed && std::abs(t1 - load) <= tc) w1 = 0.0;
    w0 = w1;
    i0 = i1;
    t0 = t1;
  }
  x_ = State(w0, i0, t0);
  reference_rpm_ = in.speed_reference_rpm;
  limited_last_ = in.enabled && !linear;
}

// Zero-order-hold discretisation: exp([[A, B], [0, 0]] * T) = [[Ad, Bd], [0, I]].
DrivePlant::StateSpace discretise_zoh(const DrivePlant::StateSpace& c, Duration period);

}  // namespace ibs::devices
