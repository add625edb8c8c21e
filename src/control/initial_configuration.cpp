#include "control/initial_configuration.hpp"

#include <algorithm>

namespace biped {

Eigen::VectorXd initial_joint_pose(const RobotModel& model, const SensorLimits& limits, const SensorData& first) {
  Eigen::VectorXd q = check_sensors(model, limits, first) ? model.stand_pose() : first.joint_position;
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
