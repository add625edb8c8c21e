#include "control/contact_wrench.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

namespace biped {
namespace {

// A single ground force at a known point of the sole plane is found again as the CoP.
TEST(CenterOfPressure, RecoversThePointOfAGroundForce) {
  const double sole_z = -0.04;
  const Eigen::Vector3d point(0.07, -0.03, sole_z);
  const Eigen::Vector3d force(12.0, -5.0, 400.0);
  Wrench w;
  w.force = force;
  w.torque = point.cross(force);
  const Eigen::Vector2d cop = center_of_pressure(w, sole_z);
  EXPECT_NEAR(cop.x(), point.x(), 1e-12);
  EXPECT_NEAR(cop.y(), point.y(), 1e-12);
}

TEST(CenterOfPressure, TwoForcesGiveTheirWeightedMean) {
  const double sole_z = -0.05;
  const Eigen::Vector3d a(0.1, 0.05, sole_z), b(-0.05, -0.05, sole_z);
  const Eigen::Vector3d fa(0, 0, 300.0), fb(0, 0, 100.0);
  Wrench w;
  w.force = fa + fb;
  w.torque = a.cross(fa) + b.cross(fb);
  const Eigen::Vector2d cop = center_of_pressure(w, sole_z);
  EXPECT_NEAR(cop.x(), (0.1 * 300 - 0.05 * 100) / 400.0, 1e-12);
  EXPECT_NEAR(cop.y(), (0.05 * 300 - 0.05 * 100) / 400.0, 1e-12);
}

}  // namespace
}  // namespace biped
