#pragma once
// Open-loop pose tracking through resolved motion rate control (eq. 21): a scripted task-space
// motion without walking. The CoM shifts over the stance foot, the other foot lifts and is put
// down again, and the CoM shifts back, each phase a quintic blend (zero velocity and acceleration
// at its ends). It exercises the task space, eq. (21) and the joint servos on their own.
#include "control/initial_configuration.hpp"
#include "control/resolved_motion_rate_control.hpp"
#include "control/sensor_check.hpp"
#include "interface/controller.hpp"
#include "model/task_space.hpp"

namespace biped {

struct WeightShiftParams {
  Side stance = Side::Left;
  double lift_height = 0.05;  // [m] of the other foot
  double start_delay = 0.5;   // [s] standing before the shift
  double shift_time = 2.0;    // [s] CoM over the stance foot (and back)
  double lift_time = 1.0;     // [s] foot up (and down)
  double hold_time = 1.0;     // [s] on one foot
  ResolvedMotionRateControlParams rmrc;
  SensorLimits sensor_limits;
};

class WeightShiftController final : public Controller {
 public:
  WeightShiftController(const RobotModel& model, const WeightShiftParams& params);
  void reset(const SensorData& first) override;
  void step(const SensorData& sensors, const WalkCommand& command, JointCommand& out) override;
  const ControllerStatus& status() const override { return status_; }
  // When the motion is complete [s after reset].
  double duration() const;

 private:
  const RobotModel& model_;
  WeightShiftParams params_;
  TaskSpace space_;
  ResolvedMotionRateControl rmrc_;
  ControllerStatus status_;
  double start_time_ = 0.0;
  Eigen::VectorXd x_start_;         // task coordinates of the initial pose
  Eigen::Vector3d com_shift_;       // CoM displacement that puts it over the stance sole's centre
  Eigen::VectorXd x_id_, xdot_id_;
  Eigen::VectorXd last_setpoint_;
};

}  // namespace biped
