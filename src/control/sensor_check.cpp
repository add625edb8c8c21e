#include "control/sensor_check.hpp"

#include <algorithm>
#include <cmath>

namespace biped {
namespace {

bool within(const Eigen::Vector3d& v, double bound) {
  return v.allFinite() && v.cwiseAbs().maxCoeff() <= bound;
}

}  // namespace

const char* check_sensors(const RobotModel& model, const SensorLimits& limits, const SensorData& s) {
  if (!std::isfinite(s.time)) return "time";
  const auto& joints = model.joints();
  for (int i = 0; i < model.num_joints(); ++i) {
    const double q = s.joint_position[i];
    if (!std::isfinite(q) || q < joints[i].lower - limits.encoder_margin ||
        q > joints[i].upper + limits.encoder_margin) {
      return "joint encoder";
    }
  }
  if (!s.imu_orientation.coeffs().allFinite() || std::abs(s.imu_orientation.norm() - 1.0) > 1e-3) {
    return "imu orientation";
  }
  if (!within(s.imu_angular_rate, limits.max_angular_rate)) return "imu angular rate";
  if (!within(s.imu_acceleration, limits.max_acceleration)) return "imu acceleration";
  for (Side side : kSides) {
    const Wrench& w = s.foot_wrench[index_of(side)];
    if (!within(w.force, limits.max_force) || !within(w.torque, limits.max_torque)) {
      return side == Side::Left ? "left F/T sensor" : "right F/T sensor";
    }
  }
  return nullptr;
}

void FrozenSignalDetector::reset(const SensorData& first) {
  last_wrench_ = first.foot_wrench;
  last_rate_ = first.imu_angular_rate;
  last_acceleration_ = first.imu_acceleration;
  wrench_repeats_ = {0, 0};
  imu_repeats_ = 0;
}

const char* FrozenSignalDetector::update(const SensorData& s, int frozen_cycles) {
  for (Side side : kSides) {
    const int k = index_of(side);
    const Wrench& w = s.foot_wrench[k];
    const bool same = w.force == last_wrench_[k].force && w.torque == last_wrench_[k].torque;
    wrench_repeats_[k] = same ? wrench_repeats_[k] + 1 : 0;
    last_wrench_[k] = w;
  }
  const bool imu_same = s.imu_angular_rate == last_rate_ && s.imu_acceleration == last_acceleration_;
  imu_repeats_ = imu_same ? imu_repeats_ + 1 : 0;
  last_rate_ = s.imu_angular_rate;
  last_acceleration_ = s.imu_acceleration;
  if (frozen_cycles <= 0) return nullptr;
  if (wrench_repeats_[0] >= frozen_cycles) return "left F/T sensor frozen";
  if (wrench_repeats_[1] >= frozen_cycles) return "right F/T sensor frozen";
  if (imu_repeats_ >= frozen_cycles) return "imu frozen";
  return nullptr;
}

Eigen::VectorXd initial_joint_pose(const RobotModel& model, const SensorLimits& limits, const SensorData& first) {
  Eigen::VectorXd q = check_sensors(model, limits, first) == nullptr ? first.joint_position : model.stand_pose();
  for (int i = 0; i < model.num_joints(); ++i) {
    q[i] = std::clamp(q[i], model.joints()[i].soft_lower, model.joints()[i].soft_upper);
  }
  return q;
}

Eigen::VectorXd initial_configuration(const RobotModel& model, const SensorLimits& limits, const SensorData& first) {
  Eigen::VectorXd qpos = model.stand_qpos();
  const Eigen::VectorXd q = initial_joint_pose(model, limits, first);
  for (int i = 0; i < model.num_joints(); ++i) qpos[model.joints()[i].qpos_adr] = q[i];
  return qpos;
}

}  // namespace biped
