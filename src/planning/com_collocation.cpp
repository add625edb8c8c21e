#include "planning/com_collocation.hpp"

#include <algorithm>
#include <cmath>

namespace biped {

// Uniform cubic B-spline: on interval j with u ∈ [0, 1], x = Σ_k c_{j+k} B_k(u). At a knot,
// x = (c_k + 4 c_{k+1} + c_{k+2})/6, ẋ = (c_{k+2} − c_k)/(2h), ẍ = (c_k − 2 c_{k+1} + c_{k+2})/h².
// Unknowns: c_0 … c_{N+2}, δ₁, δ₂ (N+5). Rows: x, ẋ, ẍ at t0 (3); the ZMP equation at knots
// 0 … N−1 (N); x = x_end and ẋ = 0 at the end (2).
ComCollocation::ComCollocation(int intervals)
    : intervals_(intervals),
      system_(Eigen::MatrixXd::Zero(intervals + 5, intervals + 5)),
      lu_(intervals + 5),
      b_(intervals + 5),
      solution_(intervals + 5) {}

void ComCollocation::set_horizon(double t0, double t_end) {
  t0_ = t0;
  h_ = (t_end - t0) / intervals_;
}

void ComCollocation::prepare(const Eigen::VectorXd& body_height, const Eigen::VectorXd& body_vertical_acceleration,
                             double gravity, const Eigen::VectorXd& shape1, const Eigen::VectorXd& shape2) {
  const int n = intervals_;
  const double h2 = h_ * h_;
  system_.setZero();
  system_.row(0).segment<3>(0) << 1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0;
  system_.row(1).segment<3>(0) << -0.5 / h_, 0.0, 0.5 / h_;
  system_.row(2).segment<3>(0) << 1.0 / h2, -2.0 / h2, 1.0 / h2;
  for (int k = 0; k < n; ++k) {
    auto row = system_.row(3 + k);
    const double z = body_height[k], weight = body_vertical_acceleration[k] + gravity;
    row.segment<3>(k) << z / h2 - weight / 6.0, -2.0 * z / h2 - 4.0 * weight / 6.0, z / h2 - weight / 6.0;
    row(n + 3) = gravity * shape1[k];
    row(n + 4) = gravity * shape2[k];
  }
  system_.row(n + 3).segment<3>(n) << 1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0;
  system_.row(n + 4).segment<3>(n) << -0.5 / h_, 0.0, 0.5 / h_;
  lu_.compute(system_);
}

void ComCollocation::solve(const Eigen::VectorXd& rhs, double x0, double v0, double a0, double x_end,
                           Eigen::VectorXd& coefficients, double& amplitude1, double& amplitude2) {
  const int n = intervals_;
  b_[0] = x0;
  b_[1] = v0;
  b_[2] = a0;
  b_.segment(3, n) = rhs.head(n);
  b_[n + 3] = x_end;
  b_[n + 4] = 0.0;
  solution_.noalias() = lu_.solve(b_);
  coefficients = solution_.head(n + 3);
  amplitude1 = solution_[n + 3];
  amplitude2 = solution_[n + 4];
}

void ComCollocation::evaluate(const Eigen::VectorXd& c, double t, double& x, double& v, double& a) const {
  const double s = std::clamp((t - t0_) / h_, 0.0, static_cast<double>(intervals_));
  const int j = std::min(static_cast<int>(s), intervals_ - 1);
  const double u = s - j;
  const double w = 1.0 - u;
  const double b0 = w * w * w / 6.0, b1 = (3 * u * u * u - 6 * u * u + 4) / 6.0;
  const double b2 = (-3 * u * u * u + 3 * u * u + 3 * u + 1) / 6.0, b3 = u * u * u / 6.0;
  x = b0 * c[j] + b1 * c[j + 1] + b2 * c[j + 2] + b3 * c[j + 3];
  v = (-0.5 * w * w * c[j] + (1.5 * u * u - 2 * u) * c[j + 1] + (-1.5 * u * u + u + 0.5) * c[j + 2] + 0.5 * u * u * c[j + 3]) / h_;
  a = (w * c[j] + (3 * u - 2) * c[j + 1] + (1 - 3 * u) * c[j + 2] + u * c[j + 3]) / (h_ * h_);
}

}  // namespace biped
