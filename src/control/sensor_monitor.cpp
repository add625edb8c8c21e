#include "control/sensor_monitor.hpp"

#include <cmath>

namespace biped {

SensorMonitor::SensorMonitor(const RobotModel& model, const SensorLimits& limits)
    : model_(model),
      limits_(limits),
      last_encoder_(Eigen::VectorXd::Zero(model.num_joints())),
      setpoint_at_repeat_(Eigen::VectorXd::Zero(model.num_joints())),
      encoder_repeats_(Eigen::ArrayXi::Zero(model.num_joints())) {
  health_.encoder_failed = Eigen::ArrayXi::Zero(model.num_joints());
}

void SensorMonitor::reset(const SensorData& first) {
  frozen_.reset(first);
  health_.time = health_.imu = true;
  health_.force_torque = {true, true};
  health_.encoder_failed.setZero();
  last_encoder_ = first.joint_position;
  setpoint_at_repeat_ = first.joint_position;
  encoder_repeats_.setZero();
}

void SensorMonitor::latch(const Fault& f, FaultList& new_faults) {
  switch (f.signal) {
    case FaultSignal::None: return;
    case FaultSignal::Time:
      if (!health_.time) return;
      health_.time = false;
      break;
    case FaultSignal::JointEncoder:
      if (health_.encoder_failed[f.index]) return;
      health_.encoder_failed[f.index] = 1;
      break;
    case FaultSignal::ImuOrientation:
    case FaultSignal::ImuAngularRate:
    case FaultSignal::ImuAcceleration:
    case FaultSignal::Imu:
      if (!health_.imu) return;
      health_.imu = false;
      break;
    case FaultSignal::ForceTorque:
      if (!health_.force_torque[f.index]) return;
      health_.force_torque[f.index] = false;
      break;
  }
  new_faults.add(f);
}

void SensorMonitor::update(const SensorData& raw, const Eigen::VectorXd& setpoint, FaultList& new_faults) {
  new_faults.clear();
  found_.clear();
  find_implausible(model_, limits_, raw, found_);
  frozen_.update(raw, limits_.frozen_cycles, found_);
  for (int i = 0; i < model_.num_joints(); ++i) {
    const double q = raw.joint_position[i];
    if (health_.encoder_failed[i] || !std::isfinite(q)) continue;
    if (std::abs(q - last_encoder_[i]) > limits_.encoder_jump) {
      found_.add({FaultSignal::JointEncoder, FaultCheck::Jump, i, raw.time});
    } else if (q == last_encoder_[i]) {
      ++encoder_repeats_[i];
      if (limits_.frozen_cycles > 0 && encoder_repeats_[i] >= limits_.frozen_cycles &&
          std::abs(setpoint[i] - setpoint_at_repeat_[i]) > limits_.encoder_frozen_motion) {
        found_.add({FaultSignal::JointEncoder, FaultCheck::Frozen, i, raw.time});
      }
    } else {
      encoder_repeats_[i] = 0;
      setpoint_at_repeat_[i] = setpoint[i];
    }
    last_encoder_[i] = q;
  }
  for (int k = 0; k < found_.count; ++k) latch(found_.items[k], new_faults);
}

}  // namespace biped
