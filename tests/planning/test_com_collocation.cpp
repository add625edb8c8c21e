#include "planning/com_collocation.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace biped {
namespace {

TEST(ComCollocation, SatisfiesTheZmpEquationInitialAndTerminalConditions) {
  ComCollocation c(40);
  const double g = 9.81;
  c.set_horizon(1.0, 3.0);
  Eigen::VectorXd rhs(c.knots()), b1(c.knots()), b2(c.knots()), z(c.knots()), zdd(c.knots());
  for (int k = 0; k < c.knots(); ++k) {
    const double t = c.knot_time(k);
    z[k] = 0.8 + 0.02 * std::sin(3.0 * t);  // a prescribed vertical motion
    zdd[k] = -0.18 * std::sin(3.0 * t);
    rhs[k] = -g * 0.1 * std::sin(2.0 * t);  // ZMP p = 0.1 sin 2t
    b1[k] = std::max(0.0, 1.0 - (t - 1.0) / 0.2);
    b2[k] = std::exp(-(t - 1.5) * (t - 1.5) / 0.1);
  }
  c.prepare(z, zdd, g, b1, b2);
  Eigen::VectorXd coeff(c.intervals() + 3);
  double d1, d2;
  c.solve(rhs, 0.02, -0.1, 0.3, 0.1 * std::sin(6.0), coeff, d1, d2);
  double x, v, a;
  c.evaluate(coeff, 1.0, x, v, a);
  EXPECT_NEAR(x, 0.02, 1e-12);
  EXPECT_NEAR(v, -0.1, 1e-12);
  EXPECT_NEAR(a, 0.3, 1e-10);
  for (int k = 0; k < c.intervals(); ++k) {
    c.evaluate(coeff, c.knot_time(k), x, v, a);
    EXPECT_NEAR(z[k] * a - (zdd[k] + g) * x + g * (d1 * b1[k] + d2 * b2[k]), rhs[k], 1e-9) << k;
  }
  c.evaluate(coeff, 3.0, x, v, a);
  EXPECT_NEAR(x, 0.1 * std::sin(6.0), 1e-9);
  EXPECT_NEAR(v, 0.0, 1e-9);
}

// With the ZMP held at a point and the body at rest above it, the body stays there.
TEST(ComCollocation, EquilibriumIsKept) {
  ComCollocation c(30);
  c.set_horizon(0.0, 2.0);
  Eigen::VectorXd b1 = Eigen::VectorXd::Zero(c.knots()), b2 = b1;
  b1[0] = 1.0;
  b2.segment(5, 5).setOnes();
  c.prepare(Eigen::VectorXd::Constant(c.knots(), 0.85), Eigen::VectorXd::Zero(c.knots()), 9.81, b1, b2);
  const Eigen::VectorXd rhs = Eigen::VectorXd::Constant(c.knots(), -9.81 * 0.05);
  Eigen::VectorXd coeff(c.intervals() + 3);
  double d1, d2;
  c.solve(rhs, 0.05, 0.0, 0.0, 0.05, coeff, d1, d2);
  EXPECT_NEAR(d1, 0.0, 1e-9);
  EXPECT_NEAR(d2, 0.0, 1e-9);
  for (double t = 0.0; t <= 2.0; t += 0.1) {
    double x, v, a;
    c.evaluate(coeff, t, x, v, a);
    EXPECT_NEAR(x, 0.05, 1e-9);
    EXPECT_NEAR(v, 0.0, 1e-9);
  }
}

// Spline derivatives agree with finite differences of the spline itself.
TEST(ComCollocation, DerivativesMatchFiniteDifferences) {
  ComCollocation c(20);
  c.set_horizon(0.0, 1.0);
  Eigen::VectorXd coeff = Eigen::VectorXd::LinSpaced(c.intervals() + 3, 0.0, 1.0).array().sin();
  for (double t : {0.013, 0.31, 0.5, 0.77}) {
    const double h = 1e-5;
    double x0, v0, a0, xp, vp, ap, xm, vm, am;
    c.evaluate(coeff, t, x0, v0, a0);
    c.evaluate(coeff, t + h, xp, vp, ap);
    c.evaluate(coeff, t - h, xm, vm, am);
    EXPECT_NEAR((xp - xm) / (2 * h), v0, 1e-6);
    EXPECT_NEAR((vp - vm) / (2 * h), a0, 1e-5);
  }
}

}  // namespace
}  // namespace biped
