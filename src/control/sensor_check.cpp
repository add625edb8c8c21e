#include "control/sensor_check.hpp"

#include <cmath>

namespace biped {
namespace {

bool within(const Eigen::Vector3d& v, double bound) {
  return v.allFinite() && v.cwiseAbs().maxCoeff() <= bound;
}

Fault implausible(FaultSignal signal, double time, int index = -1) {
  return {signal, FaultCheck::Implausible, index, std::isfinite(time) ? time : 0.0};
}

}  // namespace

void find_implausible(const RobotModel& model, const SensorLimits& limits, const SensorData& s, FaultList& out) {
  if (!std::isfinite(s.time)) out.add(implausible(FaultSignal::Time, s.time));
  const auto& joints = model.joints();
  for (int i = 0; i < model.num_joints(); ++i) {
    const double q = s.joint_position[i];
    if (!std::isfinite(q) || q < joints[i].lower - limits.encoder_margin ||
        q > joints[i].upper + limits.encoder_margin) {
      out.add(implausible(FaultSignal::JointEncoder, s.time, i));
    }
  }
  if (!s.imu_orientation.coeffs().allFinite() || std::abs(s.imu_orientation.norm() - 1.0) > 1e-3) {
    out.add(implausible(FaultSignal::ImuOrientation, s.time));
  }
  if (!within(s.imu_angular_rate, limits.max_angular_rate)) out.add(implausible(FaultSignal::ImuAngularRate, s.time));
  if (!within(s.imu_acceleration, limits.max_acceleration)) out.add(implausible(FaultSignal::ImuAcceleration, s.time));
  for (Side side : kSides) {
    const Wrench& w = s.foot_wrench[index_of(side)];
    if (!within(w.force, limits.max_force) || !within(w.torque, limits.max_torque)) {
      out.add(implausible(FaultSignal::ForceTorque, s.time, index_of(side)));
    }
  }
}

Fault check_sensors(const RobotModel& model, const SensorLimits& limits, const SensorData& s) {
  FaultList faults;
  find_implausible(model, limits, s, faults);
  return faults.count > 0 ? faults.items[0] : Fault{};
}

}  // namespace biped
