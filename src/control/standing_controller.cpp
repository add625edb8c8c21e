#include "control/standing_controller.hpp"

#include <algorithm>

#include "control/initial_configuration.hpp"

namespace biped {
namespace {

// Quintic blend 0 -> 1 with zero velocity and acceleration at both ends.
double smooth_blend(double s) {
  s = std::clamp(s, 0.0, 1.0);
  return s * s * s * (10.0 + s * (-15.0 + 6.0 * s));
}

}  // namespace

StandingController::StandingController(const RobotModel& model, const StandingControllerParams& params)
    : model_(model),
      params_(params),
      start_pose_(model.stand_pose()),
      last_setpoint_(model.stand_pose()) {
  const double half_load = 0.5 * model.weight_above_sensors();
  for (Wrench& w : status_.desired_wrench) w.force.z() = half_load;
}

void StandingController::reset(const SensorData& first) {
  start_time_ = first.time;
  status_.fault = false;
  status_.first_fault = Fault{};
  status_.state = "standing";
  start_pose_ = initial_joint_pose(model_, params_.sensor_limits, first);
  last_setpoint_ = start_pose_;
}

void StandingController::step(const SensorData& sensors, const WalkCommand& /*command*/, JointCommand& out) {
  if (!status_.fault) {
    if (const Fault fault = check_sensors(model_, params_.sensor_limits, sensors)) {
      status_.fault = true;
      status_.first_fault = fault;
      status_.state = "safe_stop";
    }
  }
  if (!status_.fault) {
    const double blend =
        params_.ramp_time > 0.0 ? smooth_blend((sensors.time - start_time_) / params_.ramp_time) : 1.0;
    for (int i = 0; i < model_.num_joints(); ++i) {
      const JointInfo& j = model_.joints()[i];
      const double q = start_pose_[i] + blend * (model_.stand_pose()[i] - start_pose_[i]);
      last_setpoint_[i] = std::clamp(q, j.soft_lower, j.soft_upper);
    }
  }
  out.position = last_setpoint_;
}

}  // namespace biped
