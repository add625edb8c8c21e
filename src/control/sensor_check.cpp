#include "control/sensor_check.hpp"

#include <cmath>

namespace biped {
namespace {

bool within(const Eigen::Vector3d& v, double bound) {
  return v.allFinite() && v.cwiseAbs().maxCoeff() <= bound;
}

Fault implausible(FaultSignal signal, int index = -1) { return {signal, FaultCheck::Implausible, index}; }

}  // namespace

Fault check_sensors(const RobotModel& model, const SensorLimits& limits, const SensorData& s) {
  if (!std::isfinite(s.time)) return implausible(FaultSignal::Time);
  const auto& joints = model.joints();
  for (int i = 0; i < model.num_joints(); ++i) {
    const double q = s.joint_position[i];
    if (!std::isfinite(q) || q < joints[i].lower - limits.encoder_margin ||
        q > joints[i].upper + limits.encoder_margin) {
      return implausible(FaultSignal::JointEncoder, i);
    }
  }
  if (!s.imu_orientation.coeffs().allFinite() || std::abs(s.imu_orientation.norm() - 1.0) > 1e-3) {
    return implausible(FaultSignal::ImuOrientation);
  }
  if (!within(s.imu_angular_rate, limits.max_angular_rate)) return implausible(FaultSignal::ImuAngularRate);
  if (!within(s.imu_acceleration, limits.max_acceleration)) return implausible(FaultSignal::ImuAcceleration);
  for (Side side : kSides) {
    const Wrench& w = s.foot_wrench[index_of(side)];
    if (!within(w.force, limits.max_force) || !within(w.torque, limits.max_torque)) {
      return implausible(FaultSignal::ForceTorque, index_of(side));
    }
  }
  return {};
}

}  // namespace biped
