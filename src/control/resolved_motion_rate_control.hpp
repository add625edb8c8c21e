#pragma once
// Resolved motion rate control with null-space optimization, the paper's eq. (21):
//   ẋ_d = ẋ_id + Δẋ + (K_x/Δt)(x_id − x + Δx)
//   q̇_d = J^† ẋ_d − α_N N ∇H,   N = I − J^† J
//   q_d = ∫ q̇_d dt
// computed in Klein & Huang's form without forming J^† or N: with A = J Jᵀ (+ λ² I),
//   q̇_d = Jᵀ A⁻¹ (ẋ_d + α_N J ∇H) − α_N ∇H,
// one Cholesky factorization per cycle.
// Δẋ and Δx (default zero) are the stabilizer's S̄ᵀΔẋ_λ and S̄ᵀΔx_λ, with Δx = ∫Δẋ dt kept by the caller.
#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "control/null_space_objective.hpp"
#include "model/task_space.hpp"

namespace biped {

// Damped least squares near singular configurations (stretched knee): A = J Jᵀ + λ² I with
//   λ² = λ_max² (1 − (σ_min/σ_t)²) for σ_min < σ_t, else 0,
// so the result is the exact pseudo-inverse solution whenever σ_min(J) ≥ σ_t.
struct RmrcDampingParams {
  double singular_value_threshold = 0.003;  // σ_t [1]; LOLA's stand pose has σ_min ≈ 0.009
  double max_damping = 0.02;                // λ_max [1]: joint rates ≤ ‖ẋ_d‖ / (2 λ_max) at σ_min = 0
  int inverse_iterations = 3;               // for the σ_min estimate (warm-started every cycle)
};

struct ResolvedMotionRateControlParams {
  double dt = 0.001;                      // Δt [s]
  double task_gain = 0.2;                 // K_x [1]: fraction of the task error removed per cycle
  Eigen::VectorXd task_gains;             // per-row K_x (size dim(x)); empty: task_gain for all rows
  double null_space_gain = 1.0;           // α_N [1/s]
  double joint_velocity_limit = 8.0;      // [rad/s], every joint
  Eigen::VectorXd joint_velocity_limits;  // per joint, RobotModel::joints() order; empty: the scalar
  NullSpaceObjectiveParams objective;
  RmrcDampingParams damping;
};

// Construction-time helpers shared with the SVD reference; both throw std::invalid_argument on
// sizes that do not match or values that are not positive.
Eigen::VectorXd task_gains_over_dt(const ResolvedMotionRateControlParams& params, int dim);  // K_x/Δt
Eigen::VectorXd joint_velocity_limits(const ResolvedMotionRateControlParams& params, const RobotModel& model);

// eq. (21), first line: ẋ_d = ẋ_id + Δẋ + (K_x/Δt)(x_id − x + Δx). `gain_over_dt` holds K_x/Δt per row.
void desired_task_velocity(const Eigen::VectorXd& x_id, const Eigen::VectorXd& xdot_id,
                           const Eigen::VectorXd& x, const Eigen::VectorXd& delta_x,
                           const Eigen::VectorXd& delta_xdot, const Eigen::VectorXd& gain_over_dt,
                           Eigen::VectorXd& xdot_d);

// λ² of the damping law above for a smallest singular value σ_min of J.
double damping_squared_for(double sigma_min, const RmrcDampingParams& params);

// Joint-limit handling shared by both implementations: marks joints (RobotModel::joints() order)
// that sit at a software limit while q̇ pushes them further out; returns how many were newly
// marked. Marked joints get a zero Jacobian column and ∇H entry in a second solve, so the other
// joints take over their share of the task instead of drifting away from it.
int mark_joints_pushing_limits(const RobotModel& model, const Eigen::VectorXd& qpos, const Eigen::VectorXd& qdot,
                               Eigen::ArrayXi& locked);
// Zeroes the columns of J and the entries of ∇H of the marked joints.
void remove_locked_joints(const RobotModel& model, const Eigen::ArrayXi& locked, Eigen::MatrixXd& J,
                          Eigen::VectorXd& gradient);

// Output limits shared by both implementations. Scales the whole q̇ (floating base included, so
// the task-space direction is kept) until no joint exceeds its limit; returns the factor (≤ 1).
double limit_joint_rates(const RobotModel& model, const Eigen::VectorXd& velocity_limits,
                         Eigen::VectorXd& qdot);
// eq. (21), last line: q_d ← q_d ⊕ q̇_d Δt (integrate_configuration), then joint angles clamped to the
// software limits.
void integrate_joint_rates(const RobotModel& model, const Eigen::VectorXd& qdot, double dt,
                           Eigen::VectorXd& qpos);

// What both implementations of eq. (21) share: the parameters, the null-space objective, the task
// workspace, the integrated q_d, and the cycle around the solve (x and J at q_d, ẋ_d, ∇H, the
// solve with joints at their limits locked, the output limits, the integration). Only the solve of
// the third line differs: Klein & Huang's (ResolvedMotionRateControl) or explicit SVD
// (ResolvedMotionRateControlSvd). The RMRC integrates its own q_d (floating base included) and
// evaluates x and J there: it is a kinematic loop, not fed by measurements.
class ResolvedMotionRateControlBase {
 public:
  virtual ~ResolvedMotionRateControlBase() = default;

  // Sets q_d (full qpos, size nq), evaluates x and J there (R_ref = identity) and forgets the
  // solver's warm start.
  void reset(const Eigen::VectorXd& qpos);

  // One cycle: x, J at q_d, eq. (21), integration. Returns the new q_d. Allocation-free; never
  // throws; when the rates come out non-finite (NaN/inf input, or an exact singularity with
  // max_damping = 0) q_d is held and fault() is set for that cycle.
  const Eigen::VectorXd& step(const Eigen::VectorXd& x_id, const Eigen::VectorXd& xdot_id,
                              const Eigen::Matrix3d& R_ref);
  const Eigen::VectorXd& step(const Eigen::VectorXd& x_id, const Eigen::VectorXd& xdot_id,
                              const Eigen::Matrix3d& R_ref, const Eigen::VectorXd& delta_x,
                              const Eigen::VectorXd& delta_xdot);

  const Eigen::VectorXd& qpos_d() const { return qpos_d_; }
  // Joint set-points in RobotModel::joints() order (what is sent to the robot).
  const Eigen::VectorXd& joint_positions() const { return joint_positions_; }

  // Of the last cycle (x and J at q_d before the integration step):
  const Eigen::VectorXd& x() const { return task_.x; }
  const TaskSpaceData& task() const { return task_; }
  const Eigen::MatrixXd& J() const { return task_.J; }
  const Eigen::VectorXd& xdot_d() const { return xdot_d_; }
  const Eigen::VectorXd& qdot_d() const { return qdot_d_; }        // after the velocity limit
  const Eigen::VectorXd& objective_gradient() const { return gradient_; }
  double damping_squared() const { return damping_squared_; }      // λ² used (0: exact J^†)
  double smallest_singular_value() const { return sigma_min_; }    // σ_min(J): estimate or exact
  double velocity_scale() const { return velocity_scale_; }        // 1: no joint at its limit
  int locked_joints() const { return locked_.sum(); }              // held at a software limit
  bool fault() const { return fault_; }

  const ResolvedMotionRateControlParams& params() const { return params_; }
  const NullSpaceObjective& objective() const { return objective_; }

 protected:
  // Throws std::invalid_argument on parameters of the wrong size or non-positive Δt / limits.
  // `model` and `space` must outlive the object. The derived constructor calls reset().
  ResolvedMotionRateControlBase(const RobotModel& model, const TaskSpace& space,
                                const ResolvedMotionRateControlParams& params);

  // eq. (21), third line, for the Jacobian J (columns of locked joints zeroed): q̇_d into qdot_d_
  // from xdot_d_ and gradient_, with damping_squared_ and sigma_min_ set. Non-finite rates mean
  // the solve failed.
  virtual void compute_joint_rates(const Eigen::MatrixXd& J) = 0;
  virtual void reset_solver() {}

  const RobotModel& model_;
  const TaskSpace& space_;
  ResolvedMotionRateControlParams params_;
  Eigen::VectorXd xdot_d_;
  Eigen::VectorXd gradient_;
  Eigen::VectorXd qdot_d_;
  double damping_squared_ = 0.0;
  double sigma_min_ = 0.0;

 private:
  // x, J at q_d, ẋ_d, ∇H, then eq. (21) with joints at their limits locked; fills qdot_d_.
  void resolve_rates(const Eigen::VectorXd& x_id, const Eigen::VectorXd& xdot_id, const Eigen::Matrix3d& R_ref,
                     const Eigen::VectorXd& delta_x, const Eigen::VectorXd& delta_xdot);

  NullSpaceObjective objective_;
  TaskSpaceData task_;
  Eigen::VectorXd gain_over_dt_;      // K_x/Δt per row
  Eigen::VectorXd velocity_limits_;   // per joint
  Eigen::VectorXd zero_task_;         // default Δx, Δẋ
  Eigen::VectorXd qpos_d_;
  Eigen::VectorXd joint_positions_;
  Eigen::MatrixXd J_locked_;          // J with the columns of locked joints zeroed
  Eigen::ArrayXi locked_;             // per joint: 1 = held at a software limit this cycle
  double velocity_scale_ = 1.0;
  bool fault_ = false;
};

// eq. (21) in Klein & Huang's form: one Cholesky factorization of A = J Jᵀ (+ λ² I) per cycle,
// never forming J^† or N. The one used in the control loop.
class ResolvedMotionRateControl final : public ResolvedMotionRateControlBase {
 public:
  ResolvedMotionRateControl(const RobotModel& model, const TaskSpace& space,
                            const ResolvedMotionRateControlParams& params);

 private:
  // eq. (21), third line: q̇_d = Jᵀ A⁻¹ (ẋ_d + α_N J ∇H) − α_N ∇H, A = J Jᵀ + λ² I.
  void compute_joint_rates(const Eigen::MatrixXd& J) override;
  void reset_solver() override;
  // Upper estimate of σ_min(J)² from the Cholesky factor of J Jᵀ: the smallest pivot and a few
  // warm-started inverse-iteration steps (both bound λ_min(J Jᵀ) from above; their minimum is used).
  double estimate_smallest_eigenvalue();

  Eigen::MatrixXd A_;                 // J Jᵀ (+ λ² I), lower triangle
  Eigen::LLT<Eigen::MatrixXd, Eigen::Lower> llt_;
  Eigen::VectorXd rhs_;
  Eigen::VectorXd inverse_iterate_;   // warm start of the σ_min estimate
};

}  // namespace biped
