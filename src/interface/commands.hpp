#pragma once
// What goes into a controller besides the sensors (the joystick) and what comes out of it (joint
// position set-points).
#include <Eigen/Core>

namespace biped {

// Joint position set-points, in RobotModel::joints() order.
struct JointCommand {
  Eigen::VectorXd position;
  explicit JointCommand(int num_joints = 0) : position(Eigen::VectorXd::Zero(num_joints)) {}
};

// The "joystick": desired walking velocity in the robot's heading frame.
struct WalkCommand {
  double vx = 0.0;     // forward [m/s]
  double vy = 0.0;     // to the left [m/s]
  double omega = 0.0;  // turning rate [rad/s]
  bool stop = false;   // come to a standstill with both feet side by side
};

}  // namespace biped
