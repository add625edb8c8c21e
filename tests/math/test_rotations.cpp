#include "math/rotations.hpp"

#include <gtest/gtest.h>

namespace biped::math {
namespace {

using Eigen::AngleAxisd;
using Eigen::Vector3d;

TEST(Rotations, ForwardLeanIsPositiveSagittalTilt) {
  const Eigen::Matrix3d R = AngleAxisd(0.1, Vector3d::UnitY()).toRotationMatrix();
  const TiltAngles t = tilt_against_gravity(R);
  EXPECT_NEAR(t.sagittal, 0.1, 1e-12);
  EXPECT_NEAR(t.lateral, 0.0, 1e-12);
}

TEST(Rotations, LeftLeanIsPositiveLateralTilt) {
  const Eigen::Matrix3d R = AngleAxisd(-0.05, Vector3d::UnitX()).toRotationMatrix();
  const TiltAngles t = tilt_against_gravity(R);
  EXPECT_NEAR(t.lateral, 0.05, 1e-12);
  EXPECT_NEAR(t.sagittal, 0.0, 1e-12);
}

// The angles are measured in the body's own heading frame: turning does not change them.
TEST(Rotations, TiltIsIndependentOfHeading) {
  const Eigen::Matrix3d lean = (AngleAxisd(0.07, Vector3d::UnitY()) * AngleAxisd(-0.03, Vector3d::UnitX())).toRotationMatrix();
  const TiltAngles reference = tilt_against_gravity(lean);
  for (double yaw : {-3.0, -1.2, 0.4, 2.5}) {
    const Eigen::Matrix3d turned = AngleAxisd(yaw, Vector3d::UnitZ()).toRotationMatrix() * lean;
    const TiltAngles t = tilt_against_gravity(turned);
    EXPECT_NEAR(t.sagittal, reference.sagittal, 1e-12);
    EXPECT_NEAR(t.lateral, reference.lateral, 1e-12);
    EXPECT_NEAR(heading_of(turned), yaw, 1e-2);
  }
}

TEST(Rotations, TiltFromVertical) {
  EXPECT_NEAR(tilt_from_vertical(AngleAxisd(0.3, Vector3d(1, 1, 0).normalized()).toRotationMatrix()), 0.3, 1e-12);
}

TEST(Rotations, MujocoQuaternionOrderIsWxyz) {
  const double wxyz[4] = {std::cos(0.25), 0.0, 0.0, std::sin(0.25)};
  const Eigen::Quaterniond q = quat_from_mujoco(wxyz);
  EXPECT_NEAR(heading_of(q.toRotationMatrix()), 0.5, 1e-12);
}

}  // namespace
}  // namespace biped::math
