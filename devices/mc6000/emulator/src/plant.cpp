#include "ibs/devices/mc6000/plant.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <unsupported/Eigen/MatrixFunctions>

namespace ibs::devices {

namespace {

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

DrivePlant::Rows DrivePlant::rows_of(const StateSpace& d, Eigen::Index first_input) {
  Rows r{};
  for (Eigen::Index i = 0; i < 3; ++i) {
    auto& row = r[static_cast<std::size_t>(i)];
    for (Eigen::Index j = 0; j < 3; ++j) row[static_cast<std::size_t>(j)] = d.a(i, j);
    row[3] = d.b(i, first_input);
    row[4] = d.b(i, first_input + 1);
  }
  return r;
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
  rows_ = {rows_of(linear_, 0), rows_of(limited_, 1)};  // inputs (w_ref, d) and (d, T_lim)
  reset();
}

void DrivePlant::reset() noexcept {
  x_ = State::Zero();
  pending_ = Duration{0};
  reference_rpm_ = 0.0;
  limited_last_ = false;
}

PlantOutput DrivePlant::output() const noexcept {
  PlantOutput o;
  o.speed_rpm = speed_rpm();
  o.torque_nm = x_(2);
  o.torque_percent = 100.0 * x_(2) / p_.rated_torque;
  o.reference_reached = std::abs(reference_rpm_ - o.speed_rpm) <= p_.reference_window_rpm;
  o.limit_active = limited_last_;
  return o;
}

}  // namespace ibs::devices
