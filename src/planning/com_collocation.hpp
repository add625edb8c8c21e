#pragma once
// The horizontal CoM trajectory of the simplified model of the paper's reference [8], found by
// spline collocation: the upper-body mass point's coordinate x_b(t) is a uniform cubic B-spline over
// the planning horizon and the ZMP equation z_b ẍ_b − g x_b = −g p̃(t) − (leg terms) is required at
// the spline knots. Boundary conditions: the current position, velocity and acceleration (so the
// plan continues the previous one), and the body at rest at a given position at the end.
//
// A given initial state and a given ZMP reference over-determine an unstable system (the
// divergent mode e^{ωt} would grow), so the ZMP reference is modified at the start of the plan by
// two shape functions with free amplitudes: p̃ = p + δ₁ b₁(t) + δ₂ b₂(t) (b₁ takes up the ZMP at the
// replanning instant, b₂ steers the divergent mode). One banded system with two bordering columns,
// the same matrix for x and y.
#include <Eigen/Core>
#include <Eigen/LU>

namespace biped {

class ComCollocation {
 public:
  // `intervals`: number of spline intervals over the horizon (fixed, so the workspace is fixed).
  explicit ComCollocation(int intervals = 48);

  int intervals() const { return intervals_; }
  int knots() const { return intervals_ + 1; }
  // Knot times of the horizon set by prepare() (where right-hand sides and shapes are sampled).
  double knot_time(int k) const { return t0_ + k * h_; }
  void set_horizon(double t0, double t_end);

  // Builds and factorizes the system for the body's prescribed height z_b and vertical acceleration
  // z̈_b and the ZMP shape functions, all sampled at the knots (entries 0..N−1 used). No allocation.
  void prepare(const Eigen::VectorXd& body_height, const Eigen::VectorXd& body_vertical_acceleration, double gravity,
               const Eigen::VectorXd& shape1, const Eigen::VectorXd& shape2);

  // Solves one axis: `rhs[k]` = −g p(t_k) − leg terms, k = 0..N−1; x0, v0, a0: state at t0;
  // x_end: the body's final rest position. Stores the spline control points (size N+3) and the two ZMP shape amplitudes.
  void solve(const Eigen::VectorXd& rhs, double x0, double v0, double a0, double x_end,
             Eigen::VectorXd& coefficients, double& amplitude1, double& amplitude2);

  // Position, velocity and acceleration of a spline at time t (clamped to the horizon).
  void evaluate(const Eigen::VectorXd& coefficients, double t, double& x, double& v, double& a) const;

  double t0() const { return t0_; }
  double t_end() const { return t0_ + intervals_ * h_; }

 private:
  int intervals_;
  double t0_ = 0.0, h_ = 1.0;
  Eigen::MatrixXd system_;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
  Eigen::VectorXd b_, solution_;
};

}  // namespace biped
