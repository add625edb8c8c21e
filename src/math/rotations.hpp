#pragma once
// Rotation helpers shared by the model, the controller and the evaluation code.
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

}  // namespace biped::math
