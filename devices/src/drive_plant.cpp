#include "ibs/devices/drive_plant.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <unsupported/Eigen/MatrixFunctions>

namespace ibs::devices {

namespace {

// Below this speed (rad/s, about 1e-8 rpm) the shaft counts as standing still.
constexpr double kStandstill = 1e-9;

void require(bool ok, const char* name, double value, const char* rule) {
  if (!ok) {
    throw std::invalid_argument(std::string("drive plant: ") + name + " = " +
                                std::to_string(value) + " must be " + rule);
  }
}

double seconds(Duration d) {
  return static_cast<double>(d.count()) * 1e-9;
}

}  // namespace

double ReferenceRamp::step(double target_rpm, Duration dt) noexcept {
  if (rate_rpm_per_s <= 0.0) {
    value_rpm = target_rpm;
    return value_rpm;
  }
  const double max_change = rate_rpm_per_s * seconds(dt);
  value_rpm += std::clamp(target_rpm - value_rpm, -max_change, max_change);
  return value_rpm;
}

DrivePlant::StateSpace DrivePlant::continuous(const DrivePlantParams& p, Mode m) {
  const double j = p.motor_inertia + p.load_inertia;
  const double tau = p.torque_time_constant;
  StateSpace s{Matrix::Zero(), Matrix::Zero()};
  // J dw/dt = T - B w - d in both modes.
  s.a(0, 0) = -p.viscous_friction / j;
  s.a(0, 2) = 1.0 / j;
  s.b(0, 1) = -1.0 / j;
  s.a(2, 2) = -1.0 / tau;
  if (m == Mode::linear) {
    // di/dt = Ki (w_ref - w); tau dT/dt = Kp (w_ref - w) + i - T.
    s.a(1, 0) = -p.ki;
    s.b(1, 0) = p.ki;
    s.a(2, 0) = -p.kp / tau;
    s.a(2, 1) = 1.0 / tau;
    s.b(2, 0) = p.kp / tau;
  } else {
    // Integrator held; tau dT/dt = T_lim - T.
    s.b(2, 2) = 1.0 / tau;
  }
  return s;
}

DrivePlant::StateSpace discretise_zoh(const DrivePlant::StateSpace& c, Duration period) {
  Eigen::Matrix<double, 6, 6> m = Eigen::Matrix<double, 6, 6>::Zero();
  m.topLeftCorner<3, 3>() = c.a;
  m.topRightCorner<3, 3>() = c.b;
  const Eigen::Matrix<double, 6, 6> e = (m * seconds(period)).exp();
  return {e.topLeftCorner<3, 3>(), e.topRightCorner<3, 3>()};
}

DrivePlant::DrivePlant(const DrivePlantParams& params, Duration period)
    : p_(params), period_(period) {
  require(p_.motor_inertia > 0.0, "motor_inertia", p_.motor_inertia, "> 0 kg m^2");
  require(p_.load_inertia >= 0.0, "load_inertia", p_.load_inertia, ">= 0 kg m^2");
  require(p_.viscous_friction >= 0.0, "viscous_friction", p_.viscous_friction, ">= 0");
  require(p_.coulomb_friction >= 0.0, "coulomb_friction", p_.coulomb_friction, ">= 0");
  require(p_.kp >= 0.0, "kp", p_.kp, ">= 0");
  require(p_.ki >= 0.0, "ki", p_.ki, ">= 0");
  require(p_.torque_limit > 0.0, "torque_limit", p_.torque_limit, "> 0 Nm");
  require(p_.torque_time_constant > 0.0, "torque_time_constant", p_.torque_time_constant, "> 0 s");
  require(p_.rated_torque > 0.0, "rated_torque", p_.rated_torque, "> 0 Nm");
  require(p_.reference_window_rpm >= 0.0, "reference_window_rpm", p_.reference_window_rpm,
          ">= 0 rpm");
  require(period_.count() > 0, "period (ns)", static_cast<double>(period_.count()), "> 0");
  linear_ = discretise_zoh(continuous(p_, Mode::linear), period_);
  limited_ = discretise_zoh(continuous(p_, Mode::limited), period_);
  reset();
}

void DrivePlant::reset() noexcept {
  x_ = State::Zero();
  pending_ = Duration{0};
  out_ = PlantOutput{};
}

PlantOutput DrivePlant::step(const PlantInput& in) noexcept {
  const double w_ref = rpm_to_rad_s(in.speed_reference_rpm);
  const double w0 = x_(0);
  const double t0 = x_(2);

  // Friction and load, held over the step. At standstill, static friction balances up to its
  // full value whatever drive torque there is (stiction), so the shaft stays put.
  double friction = 0.0;
  if (std::abs(w0) > kStandstill) {
    friction = std::copysign(p_.coulomb_friction, w0);
  } else {
    friction = std::clamp(t0 - in.load_torque_nm, -p_.coulomb_friction, p_.coulomb_friction);
  }
  Input u(w_ref, in.load_torque_nm + friction, 0.0);

  Mode mode = Mode::limited;
  bool limited = false;
  if (!in.enabled) {
    x_(1) = 0.0;  // power stage off: torque decays to 0, the controller starts afresh
  } else {
    const double command = p_.kp * (w_ref - w0) + x_(1);
    if (std::abs(command) > p_.torque_limit) {
      u(2) = std::copysign(p_.torque_limit, command);
      limited = true;
    } else {
      mode = Mode::linear;
    }
  }

  const StateSpace& d = discrete(mode);
  x_ = d.a * x_ + d.b * u;

  if (mode == Mode::linear) {
    // Integrator clamp (anti-windup), and the current limit for a command that rose past
    // T_max inside the step.
    x_(1) = std::clamp(x_(1), -p_.torque_limit, p_.torque_limit);
    x_(2) = std::clamp(x_(2), -p_.torque_limit, p_.torque_limit);
  }
  // Coulomb friction only brakes: a speed it alone carried through zero stops at zero.
  const bool crossed = (w0 > kStandstill && x_(0) < 0.0) || (w0 < -kStandstill && x_(0) > 0.0);
  if (crossed && std::abs(x_(2) - in.load_torque_nm) <= p_.coulomb_friction) {
    x_(0) = 0.0;
  }

  out_.speed_rpm = rad_s_to_rpm(x_(0));
  out_.torque_nm = x_(2);
  out_.torque_percent = 100.0 * x_(2) / p_.rated_torque;
  out_.reference_reached =
      std::abs(in.speed_reference_rpm - out_.speed_rpm) <= p_.reference_window_rpm;
  out_.limit_active = limited;
  return out_;
}

PlantOutput DrivePlant::advance(Duration elapsed, const PlantInput& in) noexcept {
  pending_ += elapsed;
  while (pending_ >= period_) {
    step(in);
    pending_ -= period_;
  }
  return out_;
}

}  // namespace ibs::devices
