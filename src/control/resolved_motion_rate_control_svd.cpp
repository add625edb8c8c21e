#include "control/resolved_motion_rate_control_svd.hpp"

namespace biped {

ResolvedMotionRateControlSvd::ResolvedMotionRateControlSvd(const RobotModel& model, const TaskSpace& space,
                                                           const ResolvedMotionRateControlParams& params)
    : ResolvedMotionRateControlBase(model, space, params),
      svd_(space.dim(), space.nv(), Eigen::ComputeThinU | Eigen::ComputeThinV),
      pinv_(Eigen::MatrixXd::Zero(space.nv(), space.dim())),
      N_(Eigen::MatrixXd::Zero(space.nv(), space.nv())) {
  reset(model.stand_qpos());
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
