#pragma once
// Reference implementation of eq. (21) with an explicit pseudo-inverse J^† from an SVD and an
// explicit null-space projector N = I − J^† J. Same set-up, inputs and output limits as
// ResolvedMotionRateControl (ResolvedMotionRateControlBase); used by tests and the run-time
// benchmark, not in the control loop.
#include <Eigen/Core>
#include <Eigen/SVD>

#include "control/resolved_motion_rate_control.hpp"

namespace biped {

class ResolvedMotionRateControlSvd final : public ResolvedMotionRateControlBase {
 public:
  ResolvedMotionRateControlSvd(const RobotModel& model, const TaskSpace& space,
                               const ResolvedMotionRateControlParams& params);

  const Eigen::MatrixXd& pseudo_inverse() const { return pinv_; }
  const Eigen::MatrixXd& null_space_projector() const { return N_; }

 private:
  // eq. (21), third line, with explicit J^† (damped: V diag(σ/(σ² + λ²)) Uᵀ) and N; σ_min exact.
  void compute_joint_rates(const Eigen::MatrixXd& J) override;

  Eigen::JacobiSVD<Eigen::MatrixXd> svd_;
  Eigen::MatrixXd pinv_;
  Eigen::MatrixXd N_;
};

}  // namespace biped
