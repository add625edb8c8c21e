// Resolved motion rate control, eq. (21), Klein & Huang form.
#include "control/resolved_motion_rate_control.hpp"

#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <cmath>
#include <cstdlib>
#include <new>
#include <ostream>
#include <random>

#include "control/resolved_motion_rate_control_svd.hpp"

#include "apps/allocation_counter.hpp"
#include "math/rotations.hpp"

namespace biped {
namespace {

constexpr double kMargin = 5.0 * M_PI / 180.0;

struct Robot {
  const char* name;
  const char* path;
};
void PrintTo(const Robot& robot, std::ostream* os) { *os << robot.name; }  // readable test names
const Robot kRobots[] = {{"lola", BIPED_SOURCE_DIR "/models/lola/lola.xml"},
                         {"johnnie", BIPED_SOURCE_DIR "/models/johnnie/johnnie.xml"}};

Eigen::VectorXd random_vector(std::mt19937& rng, int n, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) v[i] = u(rng);
  return v;
}

// Joint angles in the middle 60 % of each software range, random base orientation.
Eigen::VectorXd random_configuration(const RobotModel& model, std::mt19937& rng) {
  Eigen::VectorXd q = model.stand_qpos();
  for (const JointInfo& j : model.joints()) {
    const double margin = 0.2 * (j.soft_upper - j.soft_lower);
    q[j.qpos_adr] = std::uniform_real_distribution<double>(j.soft_lower + margin, j.soft_upper - margin)(rng);
  }
  const Eigen::Quaterniond base = Eigen::Quaterniond::UnitRandom();
  q.segment<4>(3) << base.w(), base.x(), base.y(), base.z();
  return q;
}

double smallest_singular_value(const Eigen::MatrixXd& J) {
  return Eigen::JacobiSVD<Eigen::MatrixXd>(J).singularValues().minCoeff();
}

class RmrcTest : public ::testing::TestWithParam<Robot> {
 protected:
  RmrcTest() : model(RobotModel::load(GetParam().path, kMargin)), space(model), task(space) {}

  // Velocity limits out of the way, so rates can be compared before any scaling.
  static ResolvedMotionRateControlParams unlimited() {
    ResolvedMotionRateControlParams p;
    p.joint_velocity_limit = 1e9;
    return p;
  }

  // A random configuration with σ_min(J) above twice the damping threshold and an R_ref near its
  // upper-body orientation; returns false when the draw was too close to a singularity.
  bool draw_well_conditioned(std::mt19937& rng, Eigen::VectorXd& q, Eigen::Matrix3d& R_ref) {
    q = random_configuration(model, rng);
    evaluate(space, q, Eigen::Matrix3d::Identity(), task);
    R_ref = task.upper_body_rotation * math::so3::exp(random_vector(rng, 3, 0.2));
    evaluate(space, q, R_ref, task);
    return smallest_singular_value(task.J) > 2.0 * RmrcDampingParams{}.singular_value_threshold;
  }

  RobotModel model;
  TaskSpace space;
  TaskSpaceData task;
};

// Klein & Huang and the explicit SVD pseudo-inverse agree to |Δq̇| < 1e-9 where λ = 0.
TEST_P(RmrcTest, KleinHuangMatchesSvdReference) {
  ResolvedMotionRateControl rmrc(model, space, unlimited());
  ResolvedMotionRateControlSvd reference(model, space, unlimited());
  std::mt19937 rng(11);
  int compared = 0;
  for (int draw = 0; draw < 200 && compared < 10; ++draw) {
    Eigen::VectorXd q;
    Eigen::Matrix3d R_ref;
    if (!draw_well_conditioned(rng, q, R_ref)) continue;
    // Realistic magnitudes: millimetre errors, task rates up to 0.3 m/s or rad/s.
    const Eigen::VectorXd x_id = task.x + random_vector(rng, space.dim(), 1e-3);
    const Eigen::VectorXd xdot_id = random_vector(rng, space.dim(), 0.3);
    const Eigen::VectorXd delta_x = random_vector(rng, space.dim(), 1e-4);
    const Eigen::VectorXd delta_xdot = random_vector(rng, space.dim(), 0.01);
    rmrc.reset(q);
    reference.reset(q);
    rmrc.step(x_id, xdot_id, R_ref, delta_x, delta_xdot);
    reference.step(x_id, xdot_id, R_ref, delta_x, delta_xdot);
    EXPECT_EQ(rmrc.damping_squared(), 0.0);
    EXPECT_EQ(reference.damping_squared(), 0.0);
    EXPECT_GT(rmrc.objective_gradient().norm(), 0.0);  // the null-space term takes part
    EXPECT_LT((rmrc.qdot_d() - reference.qdot_d()).cwiseAbs().maxCoeff(), 1e-9) << "draw " << draw;
    ++compared;
  }
  EXPECT_EQ(compared, 10);
}

// The null-space term does not change the task velocity: J q̇(α_N) = J q̇(0) to 1e-10.
TEST_P(RmrcTest, NullSpaceTermLeavesTaskVelocityUnchanged) {
  ResolvedMotionRateControlParams with = unlimited();
  with.null_space_gain = 2.0;
  with.objective.comfort_pose = Eigen::VectorXd::Zero(model.num_joints());  // far away: large ∇H
  ResolvedMotionRateControlParams without = with;
  without.null_space_gain = 0.0;
  ResolvedMotionRateControl a(model, space, with), b(model, space, without);
  std::mt19937 rng(12);
  int compared = 0;
  for (int draw = 0; draw < 200 && compared < 10; ++draw) {
    Eigen::VectorXd q;
    Eigen::Matrix3d R_ref;
    if (!draw_well_conditioned(rng, q, R_ref)) continue;
    const Eigen::VectorXd x_id = task.x + random_vector(rng, space.dim(), 1e-3);
    const Eigen::VectorXd xdot_id = random_vector(rng, space.dim(), 0.3);
    a.reset(q);
    b.reset(q);
    a.step(x_id, xdot_id, R_ref);
    b.step(x_id, xdot_id, R_ref);
    const Eigen::VectorXd difference = a.qdot_d() - b.qdot_d();
    EXPECT_GT(difference.norm(), 1e-3);  // the null-space motion is there ...
    EXPECT_LT((a.J() * difference).cwiseAbs().maxCoeff(), 1e-10);  // ... and invisible in x
    EXPECT_LT((a.J() * a.qdot_d() - a.xdot_d()).cwiseAbs().maxCoeff(), 1e-10);  // exact J^† (λ = 0)
    ++compared;
  }
  EXPECT_EQ(compared, 10);
}

// Random smooth task trajectories, 2 s of 1 ms cycles from the stand pose: x_id(t) = x(q_ref(t)) with
// q_ref = stand pose + sinusoidal offsets (0.1 rad, 0.3–1 Hz) of every leg joint and of the base
// (2 cm, 0.05 rad), ẋ_id = J(q_ref) q̇_ref. The feet and the CoM move by centimetres, and the
// targets are reachable by construction (the arms' targets stay consistent with the rest).
// Per cycle the error obeys e⁺ = (1 − K_x) e + r with a second-order remainder
// |r| ≲ ½Δt²(|ẍ_id| + |q̇ᵀ∇²x q̇|), so the steady error is ≲ |r|/K_x.
// Bound used: 10 Δt² max|ẍ_id| / K_x (the factor covers the curvature term).
TEST_P(RmrcTest, TracksSmoothTaskTrajectories) {
  const ResolvedMotionRateControlParams params;
  ResolvedMotionRateControl rmrc(model, space, params);
  std::mt19937 rng(13);
  std::vector<int> moving;  // velocity indices
  for (int v = 0; v < 6; ++v) moving.push_back(v);
  for (const JointInfo& j : model.joints()) {
    const bool leg = j.name.find("hip") != std::string::npos || j.name.find("knee") != std::string::npos ||
                     j.name.find("ankle") != std::string::npos;
    if (leg) moving.push_back(j.dof_adr);
  }
  const int n = static_cast<int>(moving.size());
  Eigen::VectorXd amplitude = random_vector(rng, n, 0.1);
  amplitude.head<3>() *= 0.2;               // base position [m]
  amplitude.segment<3>(3) *= 0.5;           // base orientation [rad]
  const Eigen::VectorXd omega = 2.0 * M_PI * (0.65 * Eigen::VectorXd::Ones(n) + random_vector(rng, n, 0.35));
  const Eigen::VectorXd phase = random_vector(rng, n, M_PI);

  // q_ref(t) = stand ⊕ offset(t); offset and its rate in velocity coordinates, zero at t = 0.
  Eigen::VectorXd offset(space.nv()), rate(space.nv()), q_ref(space.nq());
  auto reference = [&](double t, Eigen::VectorXd& x_id, Eigen::VectorXd& xdot_id) {
    offset.setZero();
    rate.setZero();
    for (int i = 0; i < n; ++i) {
      offset[moving[i]] = amplitude[i] * (std::sin(omega[i] * t + phase[i]) - std::sin(phase[i]));
      rate[moving[i]] = amplitude[i] * omega[i] * std::cos(omega[i] * t + phase[i]);
    }
    // Base orientation R_stand exp([θ]): its body-frame angular velocity is J_r(θ) θ̇ with the
    // right Jacobian J_r(θ) = J_l(θ)ᵀ.
    const Eigen::Vector3d theta = offset.segment<3>(3);
    rate.segment<3>(3) = math::so3::inverse_left_jacobian(theta).inverse().transpose() * rate.segment<3>(3).eval();
    q_ref = model.stand_qpos();
    mj_integratePos(model.mj(), q_ref.data(), offset.data(), 1.0);
    evaluate(space, q_ref, Eigen::Matrix3d::Identity(), task);
    x_id = task.x;
    xdot_id.noalias() = task.J * rate;
  };

  Eigen::VectorXd x_id(space.dim()), xdot_id(space.dim()), previous_xdot(space.dim());
  double max_acceleration = 0.0;
  double max_error_late = 0.0;
  const int cycles = 2000;
  for (int k = 0; k < cycles; ++k) {
    reference(k * params.dt, x_id, xdot_id);
    if (k > 0) max_acceleration = std::max(max_acceleration, ((xdot_id - previous_xdot) / params.dt).cwiseAbs().maxCoeff());
    previous_xdot = xdot_id;
    rmrc.step(x_id, xdot_id, Eigen::Matrix3d::Identity());
    ASSERT_FALSE(rmrc.fault());
    EXPECT_EQ(rmrc.velocity_scale(), 1.0);
    EXPECT_EQ(rmrc.locked_joints(), 0);
    if (k >= cycles / 2) max_error_late = std::max(max_error_late, (x_id - rmrc.x()).cwiseAbs().maxCoeff());
  }
  const double bound = 10.0 * params.dt * params.dt * max_acceleration / params.task_gain;
  EXPECT_LT(max_error_late, bound) << "bound " << bound;
}

// Pulling the right foot 0.3 m down stretches the knee into its software limit: every joint stays
// inside its software limits, rates stay finite and within the velocity limits, and damping engages.
TEST_P(RmrcTest, PullingAFootAwayKeepsJointsInsideLimits) {
  const ResolvedMotionRateControlParams params;
  ResolvedMotionRateControl rmrc(model, space, params);
  evaluate(space, model.stand_qpos(), Eigen::Matrix3d::Identity(), task);
  Eigen::VectorXd x_id = task.x;
  x_id[space.layout().foot_position[index_of(Side::Right)] + 2] -= 0.3;
  const Eigen::VectorXd xdot_id = Eigen::VectorXd::Zero(space.dim());
  const int knee = model.joint_index("right_knee");
  double max_damping = 0.0;
  for (int k = 0; k < 1000; ++k) {
    rmrc.step(x_id, xdot_id, Eigen::Matrix3d::Identity());
    ASSERT_TRUE(rmrc.qpos_d().allFinite());
    ASSERT_TRUE(rmrc.qdot_d().allFinite());
    for (int i = 0; i < model.num_joints(); ++i) {
      const JointInfo& j = model.joints()[i];
      ASSERT_GE(rmrc.joint_positions()[i], j.soft_lower) << j.name;
      ASSERT_LE(rmrc.joint_positions()[i], j.soft_upper) << j.name;
      ASSERT_LE(std::abs(rmrc.qdot_d()[j.dof_adr]), params.joint_velocity_limit * (1 + 1e-12)) << j.name;
    }
    max_damping = std::max(max_damping, rmrc.damping_squared());
  }
  EXPECT_NEAR(rmrc.joint_positions()[knee], model.joints()[knee].soft_lower, 0.02);
  EXPECT_GT(max_damping, 0.0);
}

// At a stretched knee (exactly singular for JOHNNIE) the damped rates are finite and obey the
// damped-least-squares bound ‖Jᵀ(JJᵀ + λ²I)⁻¹ b‖ ≤ ‖b‖/(2λ).
TEST_P(RmrcTest, StretchedKneeGivesFiniteBoundedRates) {
  ResolvedMotionRateControlParams params = unlimited();
  params.null_space_gain = 0.0;
  ResolvedMotionRateControl rmrc(model, space, params);
  Eigen::VectorXd q = model.stand_qpos();
  for (const JointInfo& j : model.joints()) {
    if (j.name.find("knee") != std::string::npos || j.name.find("pitch") != std::string::npos) q[j.qpos_adr] = 0.0;
  }
  evaluate(space, q, Eigen::Matrix3d::Identity(), task);
  Eigen::VectorXd x_id = task.x;
  x_id[space.layout().foot_position[index_of(Side::Left)] + 2] -= 0.05;  // beyond reach
  const Eigen::VectorXd xdot_id = Eigen::VectorXd::Zero(space.dim());
  rmrc.reset(q);
  rmrc.step(x_id, xdot_id, Eigen::Matrix3d::Identity());
  ASSERT_TRUE(rmrc.qdot_d().allFinite());
  ASSERT_GT(rmrc.damping_squared(), 0.0);
  EXPECT_LT(rmrc.smallest_singular_value(), params.damping.singular_value_threshold);
  const double lambda = std::sqrt(rmrc.damping_squared());
  EXPECT_LE(rmrc.qdot_d().norm(), rmrc.xdot_d().norm() / (2.0 * lambda) * (1 + 1e-9));
}

TEST_P(RmrcTest, NonFiniteInputHoldsTheSetPoint) {
  ResolvedMotionRateControl rmrc(model, space, ResolvedMotionRateControlParams{});
  evaluate(space, model.stand_qpos(), Eigen::Matrix3d::Identity(), task);
  Eigen::VectorXd x_id = task.x;
  x_id[0] = std::numeric_limits<double>::quiet_NaN();
  const Eigen::VectorXd before = rmrc.qpos_d();
  rmrc.step(x_id, Eigen::VectorXd::Zero(space.dim()), Eigen::Matrix3d::Identity());
  EXPECT_TRUE(rmrc.fault());
  EXPECT_TRUE(rmrc.qpos_d().allFinite());
  EXPECT_LT((rmrc.qpos_d() - before).cwiseAbs().maxCoeff(), 1e-15);
}

TEST_P(RmrcTest, StepDoesNotAllocate) {
  ResolvedMotionRateControl rmrc(model, space, ResolvedMotionRateControlParams{});
  evaluate(space, model.stand_qpos(), Eigen::Matrix3d::Identity(), task);
  Eigen::VectorXd x_id = task.x;
  const Eigen::VectorXd xdot_id = Eigen::VectorXd::Constant(space.dim(), 0.01);
  const Eigen::VectorXd delta = Eigen::VectorXd::Constant(space.dim(), 1e-4);
  const Eigen::Matrix3d R_ref = Eigen::Matrix3d::Identity();
  rmrc.step(x_id, xdot_id, R_ref);  // warm-up outside the window

  long before = heap_allocations();
  for (int k = 0; k < 10; ++k) rmrc.step(x_id, xdot_id, R_ref);
  rmrc.step(x_id, xdot_id, R_ref, delta, delta);
  EXPECT_EQ(heap_allocations() - before, 0) << "well-conditioned";

  // The damped branch (second factorization) too: a foot pulled out of reach.
  x_id[space.layout().foot_position[index_of(Side::Right)] + 2] -= 0.3;
  for (int k = 0; k < 300; ++k) rmrc.step(x_id, xdot_id, R_ref);
  ASSERT_GT(rmrc.damping_squared(), 0.0);
  before = heap_allocations();
  for (int k = 0; k < 10; ++k) rmrc.step(x_id, xdot_id, R_ref);
  EXPECT_EQ(heap_allocations() - before, 0) << "damped";
}

TEST_P(RmrcTest, RejectsParametersOfTheWrongSize) {
  ResolvedMotionRateControlParams params;
  params.task_gains = Eigen::VectorXd::Ones(3);
  EXPECT_THROW(ResolvedMotionRateControl(model, space, params), std::invalid_argument);
  params = ResolvedMotionRateControlParams{};
  params.joint_velocity_limits = Eigen::VectorXd::Ones(model.num_joints() + 1);
  EXPECT_THROW(ResolvedMotionRateControl(model, space, params), std::invalid_argument);
  params = ResolvedMotionRateControlParams{};
  params.dt = 0.0;
  EXPECT_THROW(ResolvedMotionRateControl(model, space, params), std::invalid_argument);
}

INSTANTIATE_TEST_SUITE_P(Robots, RmrcTest, ::testing::ValuesIn(kRobots),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace biped
