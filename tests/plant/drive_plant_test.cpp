// MC6000 drive plant: speed loop behaviour, status flags (INTERBUS manual 5.3.2 bits 10 and 11), and the
// exact discretisation against a fine-step Euler integration of the equations in drive_plant.hpp.
#include "ibs/devices/mc6000/plant.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace ibs::devices {
namespace {

using ::testing::HasSubstr;

constexpr double kRef534 = 2500.25;  // INTERBUS manual 5.3.4: 09C44000H in Q16

// The equations of drive_plant.hpp written out again, so the Euler reference does not reuse the
// plant's own matrices. x = [w, i, T], u = [w_ref, d, T_lim].
std::array<double, 3> derivative(const DrivePlantParams& p, DrivePlant::Mode m,
                                 const std::array<double, 3>& x, const std::array<double, 3>& u) {
  const double j = p.motor_inertia + p.load_inertia;
  const double dw = (x[2] - p.viscous_friction * x[0] - u[1]) / j;
  if (m == DrivePlant::Mode::linear) {
    const double e = u[0] - x[0];
    return {dw, p.ki * e, (p.kp * e + x[1] - x[2]) / p.torque_time_constant};
  }
  return {dw, 0.0, (u[2] - x[2]) / p.torque_time_constant};
}

// Forward Euler over one period with the input held, 1e-7 s steps.
std::array<double, 3> euler(const DrivePlantParams& p, DrivePlant::Mode m, std::array<double, 3> x,
                            const std::array<double, 3>& u, double period_s) {
  constexpr double kH = 1e-7;
  const int n = static_cast<int>(std::lround(period_s / kH));
  for (int k = 0; k < n; ++k) {
    const std::array<double, 3> dx = derivative(p, m, x, u);
    for (std::size_t i = 0; i < 3; ++i) x[i] += kH * dx[i];
  }
  return x;
}

TEST(DrivePlant, DiscreteMatricesMatchFineStepEulerInBothModes) {
  const DrivePlantParams p;
  const DrivePlant plant(p);
  const std::array<std::array<double, 3>, 3> states{
      {{0.0, 0.0, 0.0}, {250.0, 0.3, 2.0}, {-100.0, -1.5, -8.0}}};
  const std::array<std::array<double, 3>, 3> inputs{
      {{261.8, 0.1, 10.0}, {255.0, 3.1, -10.0}, {-90.0, -0.1, 0.0}}};
  for (const auto mode : {DrivePlant::Mode::linear, DrivePlant::Mode::limited}) {
    const auto& d = plant.discrete(mode);
    for (const auto& x0 : states) {
      for (const auto& u : inputs) {
        const Eigen::Vector3d x(x0[0], x0[1], x0[2]);
        const Eigen::Vector3d uu(u[0], u[1], u[2]);
        const Eigen::Vector3d exact = d.a * x + d.b * uu;
        const std::array<double, 3> ref = euler(p, mode, x0, u, 1e-3);
        for (Eigen::Index i = 0; i < 3; ++i) {
          const auto k = static_cast<std::size_t>(i);
          EXPECT_NEAR(exact(i), ref[k], 1e-3 * (1.0 + std::abs(ref[k])))
              << "mode " << static_cast<int>(mode) << " state " << i;
        }
      }
    }
  }
}

TEST(DrivePlant, EachModeLeavesOutTheInputItDoesNotUseExactly) {
  // The step leaves out T_lim in the linear mode and w_ref in the limited one: their columns of
  // B are zero, so the zero-order hold gives columns of Bd that are exactly zero, not merely
  // small, and leaving them out changes nothing.
  for (const Duration period : {Duration{1ms}, Duration{500us}, Duration{8200us}}) {
    const DrivePlant plant(DrivePlantParams{}, period);
    const auto& lin = plant.discrete(DrivePlant::Mode::linear);
    const auto& lim = plant.discrete(DrivePlant::Mode::limited);
    for (Eigen::Index i = 0; i < 3; ++i) {
      EXPECT_EQ(lin.b(i, 2), 0.0) << i;
      EXPECT_EQ(lim.b(i, 0), 0.0) << i;
    }
    // ...while the inputs each mode does use act on the speed.
    EXPECT_NE(lin.b(0, 0), 0.0);
    EXPECT_NE(lim.b(0, 2), 0.0);
  }
}

TEST(DrivePlant, TwoHalfPeriodsEqualOneFullPeriod) {
  // Exact ZOH: with the input held, exp(A T) = exp(A T/2)^2, so a 0.5 ms plant stepped twice
  // lands where the 1 ms plant does in one step (friction sign and mode unchanged here).
  DrivePlant full(DrivePlantParams{}, 1ms);
  DrivePlant half(DrivePlantParams{}, 500us);
  const DrivePlant::State x0(100.0, 0.2, 1.0);
  full.set_state(x0);
  half.set_state(x0);
  const PlantInput in{1000.0, 0.5, true};
  full.step(in);
  half.step(in);
  half.step(in);
  EXPECT_LT((full.state() - half.state()).norm(), 1e-9);
}

TEST(DrivePlant, TrajectoryMatchesFineStepEulerOfTheSwitchedModel) {
  // The whole 0 -> 2500.25 rpm run, mode and friction chosen per period as documented.
  const DrivePlantParams p;
  DrivePlant plant(p);
  std::array<double, 3> x{0.0, 0.0, 0.0};
  const double w_ref = rpm_to_rad_s(kRef534);
  double worst = 0.0;
  for (int k = 0; k < 400; ++k) {
    const double friction = x[0] > 1e-9 ? p.coulomb_friction
                                        : std::clamp(x[2], -p.coulomb_friction, p.coulomb_friction);
    const double command = p.kp * (w_ref - x[0]) + x[1];
    const bool clip = std::abs(command) > p.torque_limit;
    const auto mode = clip ? DrivePlant::Mode::limited : DrivePlant::Mode::linear;
    x = euler(p, mode, x, {w_ref, friction, std::copysign(p.torque_limit, command)}, 1e-3);
    x[1] = std::clamp(x[1], -p.torque_limit, p.torque_limit);
    const PlantOutput o = plant.step({kRef534, 0.0, true});
    EXPECT_EQ(o.limit_active, clip) << k;
    worst = std::max(worst, std::abs(o.speed_rpm - rad_s_to_rpm(x[0])));
  }
  EXPECT_LT(worst, 0.05);  // rpm
}

TEST(DrivePlant, Example534ReachesTheReferenceInAFewHundredMilliseconds) {
  DrivePlant plant;
  int reached_at = -1;
  int last_limit = -1;
  double peak = 0.0;
  for (int k = 1; k <= 1000; ++k) {
    const PlantOutput o = plant.step({kRef534, 0.0, true});
    if (o.reference_reached && reached_at < 0) reached_at = k;
    if (o.limit_active) last_limit = k;
    if (k <= 150) {
      EXPECT_TRUE(o.limit_active) << k;  // accelerating in the torque limit
    }
    if (reached_at > 0) {
      EXPECT_TRUE(o.reference_reached) << k;  // and no dropping out again
    }
    peak = std::max(peak, o.speed_rpm);
  }
  EXPECT_GE(reached_at, 150);
  EXPECT_LE(reached_at, 300);
  EXPECT_LT(last_limit, reached_at);
  EXPECT_LT(peak, kRef534 * 1.005);  // overshoot below 0.5 %
  EXPECT_NEAR(plant.output().speed_rpm, kRef534, 1e-3);
  EXPECT_FALSE(plant.output().limit_active);
}

TEST(DrivePlant, AccelerationInTheLimitIsTorqueOverInertia) {
  const DrivePlantParams p;
  DrivePlant plant(p);
  for (int k = 0; k < 50; ++k) plant.step({kRef534, 0.0, true});
  const double w50 = plant.state()(0);
  for (int k = 0; k < 100; ++k) plant.step({kRef534, 0.0, true});
  const double w150 = plant.state()(0);
  const double w_mid = 0.5 * (w50 + w150);
  const double expected = (p.torque_limit - p.coulomb_friction - p.viscous_friction * w_mid) /
                          (p.motor_inertia + p.load_inertia);
  EXPECT_NEAR((w150 - w50) / 0.1, expected, expected * 1e-3);
  EXPECT_NEAR(plant.output().torque_nm, p.torque_limit, 1e-9);
  EXPECT_NEAR(plant.output().torque_percent, 250.0, 1e-6);  // 10 Nm of 4 Nm rated
}

TEST(DrivePlant, TorqueNeverExceedsTheLimitThroughAReversal) {
  const DrivePlantParams p;
  DrivePlant plant(p);
  double peak = 0.0;
  int limited = 0;
  for (int k = 0; k < 2000; ++k) {
    const double ref = k < 600 ? kRef534 : -kRef534;
    const PlantOutput o = plant.step({ref, 0.0, true});
    peak = std::max(peak, std::abs(o.torque_nm));
    limited += o.limit_active ? 1 : 0;
  }
  EXPECT_LE(peak, p.torque_limit + 1e-9);
  EXPECT_GT(limited, 500);  // both the start and the reversal run in the limit
  EXPECT_NEAR(plant.output().speed_rpm, -kRef534, 1e-2);
  EXPECT_TRUE(plant.output().reference_reached);
}

TEST(DrivePlant, NoSteadyStateErrorUnderALoadTorque) {
  const DrivePlantParams p;
  DrivePlant plant(p);
  for (int k = 0; k < 600; ++k) plant.step({1000.0, 0.0, true});
  double lowest = 1e9;
  for (int k = 0; k < 1500; ++k) {
    lowest = std::min(lowest, plant.step({1000.0, 3.0, true}).speed_rpm);
  }
  EXPECT_LT(lowest, 995.0);                             // the load step is felt ...
  EXPECT_NEAR(plant.output().speed_rpm, 1000.0, 1e-3);  // ... and integrated away
  const double w = rpm_to_rad_s(1000.0);
  EXPECT_NEAR(plant.output().torque_nm, 3.0 + p.coulomb_friction + p.viscous_friction * w, 1e-4);
  EXPECT_TRUE(plant.output().reference_reached);
  EXPECT_FALSE(plant.output().limit_active);
}

TEST(DrivePlant, LoadBeyondTheTorqueLimitPullsTheSpeedDown) {
  DrivePlant plant;
  for (int k = 0; k < 600; ++k) plant.step({1000.0, 0.0, true});
  PlantOutput o;
  for (int k = 0; k < 200; ++k) o = plant.step({1000.0, 12.0, true});
  EXPECT_TRUE(o.limit_active);
  EXPECT_FALSE(o.reference_reached);
  EXPECT_LT(o.speed_rpm, 800.0);
  EXPECT_NEAR(o.torque_nm, 10.0, 1e-6);
}

TEST(DrivePlant, DisabledDriveCoastsToStandstillAndStaysThere) {
  DrivePlant plant;
  for (int k = 0; k < 500; ++k) plant.step({100.0, 0.0, true});
  ASSERT_NEAR(plant.output().speed_rpm, 100.0, 0.5);
  double previous = plant.output().speed_rpm;
  int stopped_at = -1;
  for (int k = 1; k <= 2000; ++k) {
    const PlantOutput o = plant.step({100.0, 0.0, false});
    EXPECT_LE(o.speed_rpm, previous) << k;
    EXPECT_GE(o.speed_rpm, 0.0) << k;
    EXPECT_FALSE(o.limit_active);
    previous = o.speed_rpm;
    if (stopped_at < 0 && o.speed_rpm == 0.0) stopped_at = k;
    if (k == 20) {
      EXPECT_LT(std::abs(o.torque_nm), 1e-6);  // the torque decays with tau
    }
  }
  EXPECT_GT(stopped_at, 100);
  EXPECT_LT(stopped_at, 1500);
  EXPECT_EQ(plant.state()(0), 0.0);
  EXPECT_EQ(plant.state()(1), 0.0);
}

TEST(DrivePlant, StictionHoldsASmallLoadAndYieldsToALargeOne) {
  DrivePlant plant;
  for (int k = 0; k < 200; ++k) plant.step({0.0, 0.05, false});
  EXPECT_EQ(plant.output().speed_rpm, 0.0);
  for (int k = 0; k < 200; ++k) plant.step({0.0, 0.5, false});
  EXPECT_LT(plant.output().speed_rpm, -10.0);  // the load turns the shaft backwards
}

TEST(DrivePlant, ReferenceWindowIsAParameter) {
  auto reached_after = [](double window) {
    DrivePlantParams p;
    p.reference_window_rpm = window;
    DrivePlant plant(p);
    for (int k = 1; k <= 2000; ++k) {
      if (plant.step({kRef534, 0.0, true}).reference_reached) return k;
    }
    return -1;
  };
  const int wide = reached_after(100.0);
  const int standard = reached_after(10.0);
  const int narrow = reached_after(0.1);
  EXPECT_GT(wide, 0);
  EXPECT_LT(wide, standard);
  EXPECT_LT(standard, narrow);
}

TEST(DrivePlant, ReferenceReachedIsNotSetBeforeEnabling) {
  // INTERBUS manual 5.3.4: READY (0231H) with the reference already set: bit 10 stays 0.
  DrivePlant plant;
  const PlantOutput o = plant.step({kRef534, 0.0, false});
  EXPECT_FALSE(o.reference_reached);
  EXPECT_EQ(o.speed_rpm, 0.0);
}

TEST(DrivePlant, AdvanceTakesWholePeriodsAndCarriesTheRest) {
  // Driven at the default bus cycle (726 us): 10 cycles = 7.26 ms = 7 plant steps.
  DrivePlant by_cycle;
  DrivePlant by_step;
  const PlantInput in{kRef534, 0.0, true};
  for (int c = 0; c < 10; ++c) by_cycle.advance(726us, in);
  for (int k = 0; k < 7; ++k) by_step.step(in);
  EXPECT_EQ(by_cycle.state(), by_step.state());
  for (int c = 0; c < 3; ++c) by_cycle.advance(726us, in);  // 9.438 ms
  for (int k = 0; k < 2; ++k) by_step.step(in);
  EXPECT_EQ(by_cycle.state(), by_step.state());
}

TEST(DrivePlant, ResetReturnsToRest) {
  DrivePlant plant;
  for (int k = 0; k < 100; ++k) plant.step({kRef534, 0.0, true});
  plant.reset();
  EXPECT_EQ(plant.state(), DrivePlant::State::Zero());
  EXPECT_EQ(plant.output().speed_rpm, 0.0);
  EXPECT_FALSE(plant.output().limit_active);
}

TEST(DrivePlant, InvalidParametersAreRefusedByName) {
  auto error = [](const DrivePlantParams& p, Duration period = 1ms) -> std::string {
    try {
      DrivePlant plant(p, period);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "(accepted)";
  };
  DrivePlantParams p;
  p.motor_inertia = 0.0;
  EXPECT_THAT(error(p), HasSubstr("motor_inertia = 0.000000 must be > 0"));
  p = {};
  p.torque_limit = -1.0;
  EXPECT_THAT(error(p), HasSubstr("torque_limit"));
  p = {};
  p.torque_time_constant = 0.0;
  EXPECT_THAT(error(p), HasSubstr("torque_time_constant"));
  EXPECT_THAT(error({}, 0ms), HasSubstr("period"));
  EXPECT_EQ(error({}), "(accepted)");
}

TEST(DrivePlant, UnitConversions) {
  EXPECT_NEAR(rpm_to_rad_s(60.0), 2.0 * std::numbers::pi, 1e-12);
  EXPECT_NEAR(rad_s_to_rpm(rpm_to_rad_s(kRef534)), kRef534, 1e-9);
}

}  // namespace
}  // namespace ibs::devices
