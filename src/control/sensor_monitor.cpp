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
  recovered_.clear();
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
  readmit_recovered(raw.time);
}

bool SensorMonitor::found(FaultSignal signal, int index) const {
  for (int k = 0; k < found_.count; ++k) {
    const Fault& f = found_.items[k];
    const bool imu = f.signal == FaultSignal::Imu || f.signal == FaultSignal::ImuOrientation ||
                     f.signal == FaultSignal::ImuAngularRate || f.signal == FaultSignal::ImuAcceleration;
    if (signal == FaultSignal::Imu ? imu : f.signal == signal && f.index == index) return true;
  }
  return false;
}

void SensorMonitor::readmit_recovered(double time) {
  recovered_.clear();
  if (limits_.recovery_time <= 0.0) return;
  // A reading with a finding restarts the clock; found_ holds every finding of this cycle, also
  // those of signals already failed (a frozen signal is found every cycle once frozen_cycles pass).
  for (int k = 0; k < 2; ++k) {
    if (health_.force_torque[k]) continue;
    if (found(FaultSignal::ForceTorque, k)) {
      ft_healthy_since_[k] = time;
    } else if (time - ft_healthy_since_[k] >= limits_.recovery_time) {
      health_.force_torque[k] = true;
      recovered_.add({FaultSignal::ForceTorque, FaultCheck::None, k, time});
    }
  }
  if (!health_.imu) {
    if (found(FaultSignal::Imu, -1)) {
      imu_healthy_since_ = time;
    } else if (time - imu_healthy_since_ >= limits_.recovery_time) {
      health_.imu = true;
      recovered_.add({FaultSignal::Imu, FaultCheck::None, -1, time});
    }
  }
}

}  // namespace biped
