#include "math/rotations.hpp"

#include <gtest/gtest.h>

#include <random>

namespace biped::math {
namespace {

using Eigen::AngleAxisd;
using Eigen::Vector3d;

Vector3d random_unit_ball(std::mt19937& rng, double radius) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vector3d v;
  do v = Vector3d(u(rng), u(rng), u(rng));
  while (v.norm() > 1.0);
  return radius * v;
}

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

TEST(Rotations, WrapAngleStaysInMinusPiToPi) {
  EXPECT_NEAR(wrap_angle(3.0 * M_PI / 2.0), -M_PI / 2.0, 1e-15);
  EXPECT_NEAR(wrap_angle(-5.0 * M_PI / 2.0), -M_PI / 2.0, 1e-15);
  EXPECT_DOUBLE_EQ(wrap_angle(0.3), 0.3);
  for (double a = -20.0; a < 20.0; a += 0.37) {
    const double w = wrap_angle(a);
    EXPECT_LE(std::abs(w), M_PI);
    EXPECT_NEAR(std::remainder(a - w, 2.0 * M_PI), 0.0, 1e-12);
  }
}

TEST(So3, LogInvertsExp) {
  std::mt19937 rng(3);
  for (int i = 0; i < 100; ++i) {
    const Eigen::Vector3d phi = random_unit_ball(rng, 3.0);
    EXPECT_LT((so3::log(Eigen::Quaterniond(so3::exp(phi))) - phi).norm(), 1e-12);
  }
  const Eigen::Vector3d tiny(1e-14, -2e-14, 3e-14);
  EXPECT_LT((so3::log(Eigen::Quaterniond(so3::exp(tiny))) - tiny).norm(), 1e-20);
  EXPECT_EQ(so3::log(Eigen::Quaterniond::Identity()), Eigen::Vector3d::Zero());
}

TEST(So3, InverseLeftJacobianIsContinuousAtTheSeriesSwitch) {
  const Eigen::Vector3d axis = Eigen::Vector3d(1, 2, -2).normalized();
  const Eigen::Matrix3d below = so3::inverse_left_jacobian((1e-2 - 1e-12) * axis);
  const Eigen::Matrix3d above = so3::inverse_left_jacobian((1e-2 + 1e-12) * axis);
  EXPECT_LT((below - above).cwiseAbs().maxCoeff(), 1e-11);
  EXPECT_LT((so3::inverse_left_jacobian(Eigen::Vector3d::Zero()) - Eigen::Matrix3d::Identity()).norm(), 1e-15);
}

// φ̇ = J_l⁻¹(φ) ω for R = exp([φ]×), Ṙ = [ω]× R: check against the rotation-vector difference.
TEST(So3, InverseLeftJacobianMapsSpatialRates) {
  std::mt19937 rng(5);
  for (int i = 0; i < 20; ++i) {
    const Eigen::Vector3d phi = random_unit_ball(rng, 2.5);
    const Eigen::Vector3d omega = random_unit_ball(rng, 1.0);
    constexpr double h = 1e-6;
    const Eigen::Matrix3d R = so3::exp(phi);
    const Eigen::Vector3d phi_plus = so3::log(Eigen::Quaterniond(so3::exp(h * omega) * R));
    const Eigen::Vector3d phi_minus = so3::log(Eigen::Quaterniond(so3::exp(-h * omega) * R));
    const Eigen::Vector3d rate_fd = (phi_plus - phi_minus) / (2.0 * h);
    EXPECT_LT((so3::inverse_left_jacobian(phi) * omega - rate_fd).norm(), 1e-8);
  }
}

}  // namespace
}  // namespace biped::math
