#include "control/state_estimation.hpp"

#include "math/rotations.hpp"

namespace biped {

CoMEstimator::CoMEstimator(const RobotModel& model) : model_(model), data_(model) {}

Eigen::Vector3d CoMEstimator::com_from_foot(const Eigen::VectorXd& joint_positions,
                                            const Eigen::Quaterniond& upper_body, Side foot) {
  const mjModel* m = model_.mj();
  mjData* d = data_.mj();
  // Kinematics with the base at the origin, unrotated; the measured upper-body orientation then
  // fixes the rotation of the whole chain.
  for (int i = 0; i < 7; ++i) d->qpos[i] = i == 3 ? 1.0 : 0.0;
  for (int i = 0; i < model_.num_joints(); ++i) d->qpos[model_.joints()[i].qpos_adr] = joint_positions[i];
  mj_kinematics(m, d);
  mj_comPos(m, d);
  const Eigen::Matrix3d body_in_base = math::mat_from_mujoco(d->xmat + 9 * model_.upper_body());
  const Eigen::Matrix3d base = upper_body.toRotationMatrix() * body_in_base.transpose();
  const Eigen::Vector3d com(d->subtree_com + 3 * model_.pelvis_body());
  const Eigen::Vector3d ankle(d->xpos + 3 * model_.foot(foot).body);
  const Eigen::Vector3d in_world = base * (com - ankle);
  const double heading = math::heading_of(upper_body.toRotationMatrix());
  return Eigen::AngleAxisd(-heading, Eigen::Vector3d::UnitZ()) * in_world;
}

}  // namespace biped
