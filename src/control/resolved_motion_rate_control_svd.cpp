#include "control/resolved_motion_rate_control_svd.hpp"

namespace biped {

ResolvedMotionRateControlSvd::ResolvedMotionRateControlSvd(const RobotModel& model, const TaskSpace& space,
                                                           const ResolvedMotionRateControlParams& params)
    : model_(model),
      space_(space),
      params_(params),
      objective_(model, params.objective),
      task_(space),
      gain_over_dt_(task_gains_over_dt(params, space.dim())),
      velocity_limits_(joint_velocity_limits(params, model)),
      zero_task_(Eigen::VectorXd::Zero(space.dim())),
      qpos_d_(model.stand_qpos()),
      xdot_d_(Eigen::VectorXd::Zero(space.dim())),
      gradient_(Eigen::VectorXd::Zero(space.nv())),
      qdot_d_(Eigen::VectorXd::Zero(space.nv())),
      J_locked_(Eigen::MatrixXd::Zero(space.dim(), space.nv())),
      locked_(Eigen::ArrayXi::Zero(model.num_joints())),
      svd_(space.dim(), space.nv(), Eigen::ComputeThinU | Eigen::ComputeThinV),
      pinv_(Eigen::MatrixXd::Zero(space.nv(), space.dim())),
      N_(Eigen::MatrixXd::Zero(space.nv(), space.nv())) {}

void ResolvedMotionRateControlSvd::reset(const Eigen::VectorXd& qpos) {
  qpos_d_ = qpos;
  qdot_d_.setZero();
}

const Eigen::VectorXd& ResolvedMotionRateControlSvd::step(const Eigen::VectorXd& x_id, const Eigen::VectorXd& xdot_id,
                                                          const Eigen::Matrix3d& R_ref) {
  return step(x_id, xdot_id, R_ref, zero_task_, zero_task_);
}

const Eigen::VectorXd& ResolvedMotionRateControlSvd::step(const Eigen::VectorXd& x_id, const Eigen::VectorXd& xdot_id,
                                                          const Eigen::Matrix3d& R_ref, const Eigen::VectorXd& delta_x,
                                                          const Eigen::VectorXd& delta_xdot) {
  evaluate(space_, qpos_d_, R_ref, task_);
  desired_task_velocity(x_id, xdot_id, task_.x, delta_x, delta_xdot, gain_over_dt_, xdot_d_);
  objective_.gradient(qpos_d_, gradient_);
  compute_joint_rates(task_.J);
  // Joints at a software limit: same handling as ResolvedMotionRateControl::resolve_rates().
  locked_.setZero();
  for (int pass = 0; pass < 4 && mark_joints_pushing_limits(model_, qpos_d_, qdot_d_, locked_) > 0; ++pass) {
    J_locked_ = task_.J;
    remove_locked_joints(model_, locked_, J_locked_, gradient_);
    compute_joint_rates(J_locked_);
  }
  if (!qdot_d_.allFinite()) qdot_d_.setZero();
  limit_joint_rates(model_, velocity_limits_, qdot_d_);
  integrate_joint_rates(model_, qdot_d_, params_.dt, qpos_d_);
  return qpos_d_;
}

// eq. (21), third line: q̇_d = J^† ẋ_d − α_N N ∇H with J^† and N formed explicitly.
void ResolvedMotionRateControlSvd::compute_joint_rates(const Eigen::MatrixXd& J) {
  svd_.compute(J);
  const Eigen::VectorXd& sigma = svd_.singularValues();
  sigma_min_ = sigma[sigma.size() - 1];
  damping_squared_ = damping_squared_for(sigma_min_, params_.damping);
  const Eigen::ArrayXd denominator = sigma.array().square() + damping_squared_;
  const Eigen::VectorXd inverse_sigma = (denominator > 0.0).select(sigma.array() / denominator, 0.0);
  pinv_.noalias() = svd_.matrixV() * inverse_sigma.asDiagonal() * svd_.matrixU().transpose();
  N_.setIdentity();
  N_.noalias() -= pinv_ * J;
  qdot_d_.noalias() = pinv_ * xdot_d_;
  qdot_d_.noalias() -= params_.null_space_gain * N_ * gradient_;
}

}  // namespace biped
