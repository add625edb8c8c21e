#pragma once
// Reference implementation of eq. (21) with an explicit pseudo-inverse J^† from an SVD and an
// explicit null-space projector N = I − J^† J. Same parameters, inputs and output limits as
// ResolvedMotionRateControl; used by tests and the run-time benchmark, not in the control loop.
#include <Eigen/Core>
#include <Eigen/SVD>

#include "control/resolved_motion_rate_control.hpp"

namespace biped {

class ResolvedMotionRateControlSvd {
 public:
  ResolvedMotionRateControlSvd(const RobotModel& model, const TaskSpace& space,
                               const ResolvedMotionRateControlParams& params);

  void reset(const Eigen::VectorXd& qpos);
  const Eigen::VectorXd& step(const Eigen::VectorXd& x_id, const Eigen::VectorXd& xdot_id,
                              const Eigen::Matrix3d& R_ref);
  const Eigen::VectorXd& step(const Eigen::VectorXd& x_id, const Eigen::VectorXd& xdot_id,
                              const Eigen::Matrix3d& R_ref, const Eigen::VectorXd& delta_x,
                              const Eigen::VectorXd& delta_xdot);

  const Eigen::VectorXd& qpos_d() const { return qpos_d_; }
  const Eigen::VectorXd& x() const { return task_.x; }
  const Eigen::MatrixXd& J() const { return task_.J; }
  const Eigen::VectorXd& qdot_d() const { return qdot_d_; }
  const Eigen::MatrixXd& pseudo_inverse() const { return pinv_; }
  const Eigen::MatrixXd& null_space_projector() const { return N_; }
  double damping_squared() const { return damping_squared_; }
  double smallest_singular_value() const { return sigma_min_; }  // exact, from the SVD

 private:
  // eq. (21), third line, with explicit J^† (damped: V diag(σ/(σ² + λ²)) Uᵀ) and N.
  void compute_joint_rates(const Eigen::MatrixXd& J);

  const RobotModel& model_;
  const TaskSpace& space_;
  ResolvedMotionRateControlParams params_;
  NullSpaceObjective objective_;
  TaskSpaceData task_;
  Eigen::VectorXd gain_over_dt_;
  Eigen::VectorXd velocity_limits_;
  Eigen::VectorXd zero_task_;
  Eigen::VectorXd qpos_d_;
  Eigen::VectorXd xdot_d_;
  Eigen::VectorXd gradient_;
  Eigen::VectorXd qdot_d_;
  Eigen::MatrixXd J_locked_;
  Eigen::ArrayXi locked_;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd_;
  Eigen::MatrixXd pinv_;
  Eigen::MatrixXd N_;
  double damping_squared_ = 0.0;
  double sigma_min_ = 0.0;
};

}  // namespace biped
