// The hip strategy's lean: none inside the dead band, towards the DCM error beyond it and bounded,
// back to upright more slowly than it leans, upright again when switched off or fed NaN, and its
// rotation vector is the upper body's orientation with exactly the lean's tilt angles.
#include "control/upper_body_lean.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "math/rotations.hpp"

namespace biped {
namespace {

constexpr double kDt = 0.001;

UpperBodyLeanParams switched_on() {
  UpperBodyLeanParams p;
  p.enabled = true;
  return p;
}

// Cycles until the angle about `axis` passes `level` (or the limit); returns the time [s].
double time_to_reach(UpperBodyLean& lean, const Eigen::Vector2d& error, int axis, double level, bool rising) {
  for (int k = 1; k <= 20000; ++k) {
    lean.update(kDt, error, true);
    const double a = std::abs(lean.angle()[axis]);
    if (rising ? a >= level : a <= level) return k * kDt;
  }
  return std::numeric_limits<double>::infinity();
}

TEST(UpperBodyLean, UprightInsideTheDeadBand) {
  const UpperBodyLeanParams p = switched_on();
  UpperBodyLean lean(p);
  for (int k = 0; k < 2000; ++k) lean.update(kDt, {0.99 * p.dead_band_forward, -0.99 * p.dead_band_sideways}, true);
  EXPECT_EQ(lean.angle(), Eigen::Vector2d::Zero());
  EXPECT_EQ(lean.rate(), Eigen::Vector2d::Zero());
}

// Forward error: the top goes forward (sagittal > 0); error to the right: the top goes right
// (lateral < 0); each by the gain times the error beyond the dead band, within the bound.
TEST(UpperBodyLean, LeansTowardsTheErrorBeyondTheDeadBand) {
  const UpperBodyLeanParams p = switched_on();
  UpperBodyLean lean(p);
  const Eigen::Vector2d error(p.dead_band_forward + 0.02, -(p.dead_band_sideways + 0.01));
  for (int k = 0; k < 5000; ++k) lean.update(kDt, error, true);
  EXPECT_NEAR(lean.angle().x(), p.gain * 0.02, 1e-6);
  EXPECT_NEAR(lean.angle().y(), -p.gain * 0.01, 1e-6);
  for (int k = 0; k < 5000; ++k) lean.update(kDt, {1.0, 1.0}, true);
  EXPECT_NEAR(lean.angle().x(), p.max_angle, 1e-12);
  EXPECT_NEAR(lean.angle().y(), p.max_angle, 1e-12);
}

TEST(UpperBodyLean, RateStaysWithinItsBound) {
  UpperBodyLeanParams p = switched_on();
  p.max_rate = 0.5;
  UpperBodyLean lean(p);
  double previous = 0.0;
  for (int k = 0; k < 2000; ++k) {
    lean.update(kDt, {-1.0, 0.0}, true);
    EXPECT_LE(std::abs(lean.rate().x()), p.max_rate + 1e-12);
    EXPECT_LE(std::abs(lean.angle().x() - previous), p.max_rate * kDt + 1e-12);
    previous = lean.angle().x();
  }
}

// Going back gives the DCM correction back: it takes longer than leaning did.
TEST(UpperBodyLean, ReturnsMoreSlowlyThanItLeans) {
  const UpperBodyLeanParams p = switched_on();
  UpperBodyLean lean(p);
  const double half = 0.5 * p.max_angle;
  const double out = time_to_reach(lean, {0.0, 1.0}, 1, 0.9 * p.max_angle, true);
  for (int k = 0; k < 3000; ++k) lean.update(kDt, {0.0, 1.0}, true);
  const double back = time_to_reach(lean, {0.0, 0.0}, 1, half, false);
  EXPECT_LT(out, back);
  EXPECT_GT(back, 1.0 / p.return_frequency * 0.5);
}

// Upright again once the error is back in the dead band (variant 0), when inactive (1: no state
// estimate), and when the error is NaN (2); never leaning when switched off.
TEST(UpperBodyLean, UprightWhenTheErrorVanishesInactiveOrFedNan) {
  for (int variant = 0; variant < 3; ++variant) {
    UpperBodyLeanParams p = switched_on();
    UpperBodyLean lean(p);
    for (int k = 0; k < 1000; ++k) lean.update(kDt, {0.3, 0.3}, true);
    ASSERT_GT(lean.angle().norm(), 0.1);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const Eigen::Vector2d error =
        variant == 2 ? Eigen::Vector2d(nan, nan) : variant == 1 ? Eigen::Vector2d(0.3, 0.3) : Eigen::Vector2d::Zero();
    for (int k = 0; k < 20000; ++k) lean.update(kDt, error, variant != 1);
    EXPECT_LT(lean.angle().norm(), 1e-6) << variant;
    EXPECT_TRUE(lean.angle().allFinite() && lean.rate().allFinite());
  }
  UpperBodyLeanParams off;
  off.enabled = false;
  UpperBodyLean lean(off);
  for (int k = 0; k < 1000; ++k) lean.update(kDt, {0.3, 0.3}, true);
  EXPECT_EQ(lean.angle(), Eigen::Vector2d::Zero()) << "switched off";
}

// The orientation exp(rotation_vector) has the lean's sagittal and lateral tilt angles.
TEST(UpperBodyLean, RotationVectorHasTheLeansTiltAngles) {
  const UpperBodyLeanParams p = switched_on();
  UpperBodyLean lean(p);
  for (int k = 0; k < 5000; ++k) lean.update(kDt, {0.09, -0.07}, true);
  const math::TiltAngles tilt = math::tilt_against_gravity(math::so3::exp(lean.rotation_vector()));
  // Composed about two axes, the angles agree to second order.
  EXPECT_NEAR(tilt.sagittal, lean.angle().x(), 2e-3);
  EXPECT_NEAR(tilt.lateral, lean.angle().y(), 2e-3);
  EXPECT_GT(std::abs(lean.angle().x()), 0.05);
  EXPECT_GT(std::abs(lean.angle().y()), 0.05);
}

}  // namespace
}  // namespace biped
