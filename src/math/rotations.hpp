#pragma once
// Rotation helpers shared by the model, the controller and the evaluation code: MuJoCo's layouts,
// angle wrapping, heading and tilt angles, and rotation vectors (SO(3) log and exp).
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace biped::math {

// MuJoCo stores quaternions as w, x, y, z.
inline Eigen::Quaterniond quat_from_mujoco(const double* wxyz) {
  return Eigen::Quaterniond(wxyz[0], wxyz[1], wxyz[2], wxyz[3]);
}

inline Eigen::Matrix3d mat_from_mujoco(const double* rowmajor9) {
  return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(rowmajor9);
}

// An angle wrapped into (−π, π].
inline double wrap_angle(double a) { return std::atan2(std::sin(a), std::cos(a)); }

// Heading (yaw) of a body: the angle of its x axis projected onto the ground plane.
inline double heading_of(const Eigen::Matrix3d& R) { return std::atan2(R(1, 0), R(0, 0)); }

// Angles between a body's z axis and the gravity vector, measured in the sagittal and the lateral
// plane of the body's own heading frame (the paper's phi_x and phi_y of Figs. 6 and 7).
// sagittal > 0: leaning forward; lateral > 0: leaning to the left.
struct TiltAngles {
  double sagittal = 0.0;
  double lateral = 0.0;
};

inline TiltAngles tilt_against_gravity(const Eigen::Matrix3d& R) {
  const double yaw = heading_of(R);
  const Eigen::Vector3d z_heading = Eigen::AngleAxisd(-yaw, Eigen::Vector3d::UnitZ()) * R.col(2);
  return {std::atan2(z_heading.x(), z_heading.z()), std::atan2(z_heading.y(), z_heading.z())};
}

// Total angle between a body's z axis and the vertical.
inline double tilt_from_vertical(const Eigen::Matrix3d& R) {
  return std::acos(std::clamp(R(2, 2), -1.0, 1.0));
}

// Rotation vectors (so(3) coordinates).
namespace so3 {

// φ with exp([φ]×) = R, |φ| ≤ π.
inline Eigen::Vector3d log(const Eigen::Quaterniond& q_in) {
  // q and −q are the same rotation; w ≥ 0 gives the angle in [0, π].
  const Eigen::Quaterniond q = q_in.w() < 0.0 ? Eigen::Quaterniond(-q_in.coeffs()) : q_in;
  const double s = q.vec().norm();  // sin(θ/2)
  // θ/s = 2 atan2(s, w)/s is well-conditioned down to s → 0, where it tends to 2/w.
  const double scale = s < 1e-12 ? 2.0 / q.w() : 2.0 * std::atan2(s, q.w()) / s;
  return scale * q.vec();
}

// R = exp([φ]×).
inline Eigen::Matrix3d exp(const Eigen::Vector3d& phi) {
  const double angle = phi.norm();
  if (angle < 1e-300) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, phi / angle).toRotationMatrix();
}

// J_l⁻¹(φ): for R = exp([φ]×) and Ṙ = [ω]× R, φ̇ = J_l⁻¹(φ) ω. Singular at |φ| = π.
inline Eigen::Matrix3d inverse_left_jacobian(const Eigen::Vector3d& phi) {
  // J_l⁻¹ = I − ½[φ]× + c(θ)[φ]×², c = 1/θ² − (1 + cos θ)/(2θ sin θ).
  const double theta2 = phi.squaredNorm();
  double c;
  if (theta2 < 1e-4) {
    // Taylor series of c: the closed form loses digits to cancellation for small θ.
    c = 1.0 / 12.0 + theta2 / 720.0 + theta2 * theta2 / 30240.0;
  } else {
    const double theta = std::sqrt(theta2);
    c = 1.0 / theta2 - (1.0 + std::cos(theta)) / (2.0 * theta * std::sin(theta));
  }
  Eigen::Matrix3d hat;
  hat << 0.0, -phi.z(), phi.y(), phi.z(), 0.0, -phi.x(), -phi.y(), phi.x(), 0.0;
  return Eigen::Matrix3d::Identity() - 0.5 * hat + c * hat * hat;
}

}  // namespace so3
}  // namespace biped::math
