#include "control/com_estimator.hpp"

#include "math/rotations.hpp"
#include "model/kinematics.hpp"

namespace biped {

CoMEstimator::CoMEstimator(const RobotModel& model)
    : model_(model), qpos_(model.stand_qpos()), frames_(model.tree()) {}

Eigen::Vector3d CoMEstimator::com_from_foot(const BodyFrames& encoders, const Eigen::Quaterniond& upper_body,
                                            Side foot) const {
  // Kinematics with the base at the origin, unrotated; the measured upper-body orientation then
  // fixes the rotation of the whole chain.
  const Eigen::Matrix3d& body_in_base = encoders.rotation[model_.upper_body()];
  const Eigen::Matrix3d base = upper_body.toRotationMatrix() * body_in_base.transpose();
  const Eigen::Vector3d& com = encoders.subtree_com[model_.pelvis_body()];
  const Eigen::Vector3d& ankle = encoders.position[model_.foot(foot).body];
  const Eigen::Vector3d in_world = base * (com - ankle);
  const double heading = math::heading_of(upper_body.toRotationMatrix());
  return Eigen::AngleAxisd(-heading, Eigen::Vector3d::UnitZ()) * in_world;
}

Eigen::Quaterniond CoMEstimator::upper_body_on_flat_foot(const Eigen::VectorXd& joint_positions, Side stance,
                                                         double stance_yaw) {
  kinematics_at_origin(model_, joint_positions, qpos_, frames_);
  const Eigen::Quaterniond& foot = frames_.orientation[model_.foot(stance).body];
  const Eigen::Quaterniond& body = frames_.orientation[model_.upper_body()];
  return Eigen::Quaterniond(Eigen::AngleAxisd(stance_yaw, Eigen::Vector3d::UnitZ())) * foot.conjugate() * body;
}

void CoMEstimator::update(const SensorData& sensors, const BodyFrames& encoders, Side stance, double dt) {
  const Eigen::Vector2d estimate = com_from_foot(encoders, sensors.imu_orientation, stance).head<2>();
  const double filter = dt / (0.01 + dt);
  if (!has_estimate_) {
    rate_.setZero();
    carried_rate_.setZero();
  } else if (stance != stance_) {
    rate_.setZero();
  } else {
    rate_ += filter * ((estimate - estimate_) / dt - rate_);
    carried_rate_ += filter * ((estimate - estimate_) / dt - carried_rate_);
  }
  estimate_ = estimate;
  stance_ = stance;
  has_estimate_ = true;
}

}  // namespace biped
