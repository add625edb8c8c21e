#pragma once
// The robot's own decentralized joint position controllers: a PD law per joint with torque
// saturation, evaluated every physics step. Gains come from a closed-loop bandwidth and damping
// ratio and the inertia each joint sees in the reference pose (rotor inertia included), so the
// servos are as stiff as the real ones, not infinitely stiff.
#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <vector>

#include "model/robot_model.hpp"

namespace biped {

struct DriveParams {
  double bandwidth_hz = 20.0;  // closed-loop natural frequency of each position loop
  double damping_ratio = 1.0;
};

class JointDrives {
 public:
  // `plant` is the simulated robot; gains are computed at its "stand" keyframe.
  JointDrives(const RobotModel& plant, const DriveParams& params);

  // Holds new set-points (plant joint order); the velocity reference is the set-point's rate of
  // change over the last control period.
  void set_targets(const Eigen::VectorXd& position, double control_period);
  // Writes the saturated PD torques into d->ctrl for the current state of d.
  void apply(const mjModel* m, mjData* d) const;

  const Eigen::VectorXd& kp() const { return kp_; }
  const Eigen::VectorXd& kd() const { return kd_; }
  const Eigen::VectorXd& target() const { return target_; }

 private:
  const RobotModel& plant_;
  Eigen::VectorXd kp_, kd_, torque_limit_;
  Eigen::VectorXi actuator_;  // actuator id per plant joint
  Eigen::VectorXd target_, target_rate_;
  bool has_target_ = false;
};

}  // namespace biped
