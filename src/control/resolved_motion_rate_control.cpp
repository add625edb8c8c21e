#include "control/resolved_motion_rate_control.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "model/kinematics.hpp"

namespace biped {

Eigen::VectorXd task_gains_over_dt(const ResolvedMotionRateControlParams& params, int dim) {
  if (!(params.dt > 0.0)) throw std::invalid_argument("resolved motion rate control: dt must be positive");
  Eigen::VectorXd gains = params.task_gains.size() == 0 ? Eigen::VectorXd::Constant(dim, params.task_gain)
                                                        : params.task_gains;
  if (gains.size() != dim) {
    throw std::invalid_argument("resolved motion rate control: task_gains has " + std::to_string(gains.size()) +
                                " entries, x has " + std::to_string(dim));
  }
  if ((gains.array() < 0.0).any() || !gains.allFinite()) {
    throw std::invalid_argument("resolved motion rate control: task gains must be finite and >= 0");
  }
  return gains / params.dt;
}

Eigen::VectorXd joint_velocity_limits(const ResolvedMotionRateControlParams& params, const RobotModel& model) {
  Eigen::VectorXd limits = params.joint_velocity_limits.size() == 0
                               ? Eigen::VectorXd::Constant(model.num_joints(), params.joint_velocity_limit)
                               : params.joint_velocity_limits;
  if (limits.size() != model.num_joints()) {
    throw std::invalid_argument("resolved motion rate control: joint_velocity_limits has " +
                                std::to_string(limits.size()) + " entries, the model has " +
                                std::to_string(model.num_joints()) + " joints");
  }
  if (!(limits.array() > 0.0).all()) {
    throw std::invalid_argument("resolved motion rate control: joint velocity limits must be positive");
  }
  return limits;
}

// eq. (21), first line.
void desired_task_velocity(const Eigen::VectorXd& x_id, const Eigen::VectorXd& xdot_id,
                           const Eigen::VectorXd& x, const Eigen::VectorXd& delta_x,
                           const Eigen::VectorXd& delta_xdot, const Eigen::VectorXd& gain_over_dt,
                           Eigen::VectorXd& xdot_d) {
  // x_id − x is the task error x_id ⊖ x (task_error()): plain differences of the coordinates.
  xdot_d = xdot_id + delta_xdot + gain_over_dt.cwiseProduct(x_id - x + delta_x);
}

double damping_squared_for(double sigma_min, const RmrcDampingParams& params) {
  const double threshold = params.singular_value_threshold;
  if (sigma_min >= threshold) return 0.0;
  const double ratio = sigma_min > 0.0 ? sigma_min / threshold : 0.0;  // NaN: full damping
  return params.max_damping * params.max_damping * (1.0 - ratio * ratio);
}

int mark_joints_pushing_limits(const RobotModel& model, const Eigen::VectorXd& qpos, const Eigen::VectorXd& qdot,
                               Eigen::ArrayXi& locked) {
  constexpr double kAtLimit = 1e-9;  // [rad]; integrate_joint_rates() clamps exactly onto the limit
  int newly_locked = 0;
  for (int i = 0; i < model.num_joints(); ++i) {
    const JointInfo& j = model.joints()[i];
    const double q = qpos[j.qpos_adr];
    const double rate = qdot[j.dof_adr];
    const bool pushing_out = (q <= j.soft_lower + kAtLimit && rate < 0.0) || (q >= j.soft_upper - kAtLimit && rate > 0.0);
    if (pushing_out && !locked[i]) {
      locked[i] = 1;
      ++newly_locked;
    }
  }
  return newly_locked;
}

void remove_locked_joints(const RobotModel& model, const Eigen::ArrayXi& locked, Eigen::MatrixXd& J,
                          Eigen::VectorXd& gradient) {
  for (int i = 0; i < model.num_joints(); ++i) {
    if (!locked[i]) continue;
    J.col(model.joints()[i].dof_adr).setZero();
    gradient[model.joints()[i].dof_adr] = 0.0;
  }
}

double limit_joint_rates(const RobotModel& model, const Eigen::VectorXd& velocity_limits, Eigen::VectorXd& qdot) {
  double scale = 1.0;
  for (int i = 0; i < model.num_joints(); ++i) {
    const double rate = std::abs(qdot[model.joints()[i].dof_adr]);
    if (rate * scale > velocity_limits[i]) scale = velocity_limits[i] / rate;
  }
  if (scale < 1.0) qdot *= scale;
  return scale;
}

// eq. (21), last line.
void integrate_joint_rates(const RobotModel& model, const Eigen::VectorXd& qdot, double dt, Eigen::VectorXd& qpos) {
  integrate_configuration(model, qdot, dt, qpos);
  for (const JointInfo& joint : model.joints()) {
    qpos[joint.qpos_adr] = std::clamp(qpos[joint.qpos_adr], joint.soft_lower, joint.soft_upper);
  }
}

ResolvedMotionRateControlBase::ResolvedMotionRateControlBase(const RobotModel& model, const TaskSpace& space,
                                                             const ResolvedMotionRateControlParams& params)
    : model_(model),
      space_(space),
      params_(params),
      xdot_d_(Eigen::VectorXd::Zero(space.dim())),
      gradient_(Eigen::VectorXd::Zero(space.nv())),
      qdot_d_(Eigen::VectorXd::Zero(space.nv())),
      objective_(model, params.objective),
      task_(space),
      gain_over_dt_(task_gains_over_dt(params, space.dim())),
      velocity_limits_(joint_velocity_limits(params, model)),
      zero_task_(Eigen::VectorXd::Zero(space.dim())),
      qpos_d_(model.stand_qpos()),
      joint_positions_(Eigen::VectorXd::Zero(model.num_joints())),
      J_locked_(Eigen::MatrixXd::Zero(space.dim(), space.nv())),
      locked_(Eigen::ArrayXi::Zero(model.num_joints())) {
  if (!(params.damping.singular_value_threshold > 0.0) || !(params.damping.max_damping >= 0.0) ||
      params.damping.inverse_iterations < 1) {
    throw std::invalid_argument("resolved motion rate control: damping needs threshold > 0, max >= 0, iterations >= 1");
  }
}

void ResolvedMotionRateControlBase::reset(const Eigen::VectorXd& qpos) {
  qpos_d_ = qpos;
  for (int i = 0; i < model_.num_joints(); ++i) joint_positions_[i] = qpos_d_[model_.joints()[i].qpos_adr];
  reset_solver();
  qdot_d_.setZero();
  locked_.setZero();
  damping_squared_ = 0.0;
  velocity_scale_ = 1.0;
  fault_ = false;
  evaluate(space_, qpos_d_, Eigen::Matrix3d::Identity(), task_);  // task() is valid before the first step
}

const Eigen::VectorXd& ResolvedMotionRateControlBase::step(const Eigen::VectorXd& x_id, const Eigen::VectorXd& xdot_id,
                                                           const Eigen::Matrix3d& R_ref) {
  return step(x_id, xdot_id, R_ref, zero_task_, zero_task_);
}

const Eigen::VectorXd& ResolvedMotionRateControlBase::step(const Eigen::VectorXd& x_id, const Eigen::VectorXd& xdot_id,
                                                           const Eigen::Matrix3d& R_ref, const Eigen::VectorXd& delta_x,
                                                           const Eigen::VectorXd& delta_xdot) {
  resolve_rates(x_id, xdot_id, R_ref, delta_x, delta_xdot);

  // Non-finite rates (NaN/inf in x_id, R_ref, ...) must not reach the set-points: hold q_d.
  fault_ = !qdot_d_.allFinite();
  if (fault_) qdot_d_.setZero();
  velocity_scale_ = limit_joint_rates(model_, velocity_limits_, qdot_d_);
  integrate_joint_rates(model_, qdot_d_, params_.dt, qpos_d_);
  for (int i = 0; i < model_.num_joints(); ++i) joint_positions_[i] = qpos_d_[model_.joints()[i].qpos_adr];
  return qpos_d_;
}

void ResolvedMotionRateControlBase::resolve_rates(const Eigen::VectorXd& x_id, const Eigen::VectorXd& xdot_id,
                                                  const Eigen::Matrix3d& R_ref, const Eigen::VectorXd& delta_x,
                                                  const Eigen::VectorXd& delta_xdot) {
  evaluate(space_, qpos_d_, R_ref, task_);
  desired_task_velocity(x_id, xdot_id, task_.x, delta_x, delta_xdot, gain_over_dt_, xdot_d_);
  objective_.gradient(qpos_d_, gradient_);
  compute_joint_rates(task_.J);

  // A joint clamped at its limit would not follow q̇_d; solving again without it keeps the task
  // error from growing in the other rows. Each pass locks at least one more joint.
  locked_.setZero();
  constexpr int kMaxPasses = 4;
  for (int pass = 0; pass < kMaxPasses && mark_joints_pushing_limits(model_, qpos_d_, qdot_d_, locked_) > 0; ++pass) {
    J_locked_ = task_.J;
    remove_locked_joints(model_, locked_, J_locked_, gradient_);
    compute_joint_rates(J_locked_);
  }
}

ResolvedMotionRateControl::ResolvedMotionRateControl(const RobotModel& model, const TaskSpace& space,
                                                     const ResolvedMotionRateControlParams& params)
    : ResolvedMotionRateControlBase(model, space, params),
      A_(Eigen::MatrixXd::Zero(space.dim(), space.dim())),
      llt_(space.dim()),
      rhs_(Eigen::VectorXd::Zero(space.dim())),
      inverse_iterate_(Eigen::VectorXd::Zero(space.dim())) {
  reset(model.stand_qpos());
}

void ResolvedMotionRateControl::reset_solver() {
  inverse_iterate_.setConstant(1.0 / std::sqrt(static_cast<double>(space_.dim())));
}

// eq. (21), third line, Klein & Huang form: q̇_d = Jᵀ A⁻¹ (ẋ_d + α_N J ∇H) − α_N ∇H, A = J Jᵀ + λ² I.
void ResolvedMotionRateControl::compute_joint_rates(const Eigen::MatrixXd& J) {
  const double alpha = params_.null_space_gain;

  A_.setZero();
  A_.selfadjointView<Eigen::Lower>().rankUpdate(J);
  llt_.compute(A_);
  const double lambda_min = llt_.info() == Eigen::Success ? estimate_smallest_eigenvalue() : 0.0;
  sigma_min_ = std::sqrt(std::max(lambda_min, 0.0));
  damping_squared_ = damping_squared_for(sigma_min_, params_.damping);
  if (damping_squared_ > 0.0) {
    A_.diagonal().array() += damping_squared_;
    llt_.compute(A_);
  }
  if (llt_.info() != Eigen::Success) {  // only with λ_max = 0 at an exact singularity
    qdot_d_.setConstant(std::numeric_limits<double>::quiet_NaN());
    return;
  }

  rhs_ = xdot_d_;
  rhs_.noalias() += alpha * J * gradient_;
  llt_.solveInPlace(rhs_);
  qdot_d_.noalias() = J.transpose() * rhs_;
  qdot_d_ -= alpha * gradient_;
}

double ResolvedMotionRateControl::estimate_smallest_eigenvalue() {
  const double smallest_pivot = llt_.matrixLLT().diagonal().array().square().minCoeff();
  // Inverse iteration: ‖A⁻¹v‖ → 1/λ_min for a unit v; warm-started from the last cycle's vector,
  // which is close because the configuration changes little per cycle.
  double estimate = smallest_pivot;
  for (int k = 0; k < params_.damping.inverse_iterations; ++k) {
    llt_.solveInPlace(inverse_iterate_);
    const double norm = inverse_iterate_.norm();
    if (!(norm > 0.0) || !std::isfinite(norm)) {
      inverse_iterate_.setConstant(1.0 / std::sqrt(static_cast<double>(inverse_iterate_.size())));
      return 0.0;
    }
    inverse_iterate_ /= norm;
    estimate = std::min(estimate, 1.0 / norm);
  }
  return estimate;
}

}  // namespace biped
