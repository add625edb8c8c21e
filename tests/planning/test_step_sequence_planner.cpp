#include "planning/step_sequence_planner.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace biped {
namespace {

TEST(StepSequencePlanner, SaturatesInfeasibleCommands) {
  bool saturated = false;
  const VelocityCommand s = saturate({3.0, -1.0, 2.0}, CommandLimits{}, saturated);
  EXPECT_TRUE(saturated);
  // At the full sideways speed and turn rate the forward speed keeps its share (below).
  EXPECT_DOUBLE_EQ(s.vx, CommandLimits{}.lateral_vx_share * CommandLimits{}.vx_max);
  EXPECT_DOUBLE_EQ(s.vy, -CommandLimits{}.vy_max);
  EXPECT_DOUBLE_EQ(s.omega, CommandLimits{}.omega_max);
  saturate({0.5, 0.0, 0.1}, CommandLimits{}, saturated);
  EXPECT_FALSE(saturated);
}

// The combined bound: the forward speed's limit falls linearly from vx_max without sideways speed
// or turn to its share at either one's full range; walking backwards it does not apply; the share
// of the sideways and turning ranges a forward speed leaves is its inverse.
TEST(StepSequencePlanner, SidewaysSpeedAndTurnRateTakeForwardSpeedAway) {
  CommandLimits limits;
  limits.vx_max = 0.8;
  limits.lateral_vx_share = 0.75;
  bool saturated = false;
  EXPECT_DOUBLE_EQ(saturate({1.0, limits.vy_max, 0.0}, limits, saturated).vx, 0.6);
  EXPECT_TRUE(saturated);
  EXPECT_DOUBLE_EQ(saturate({0.8, 0.0, -limits.omega_max}, limits, saturated).vx, 0.6);
  EXPECT_TRUE(saturated);
  EXPECT_DOUBLE_EQ(saturate({0.8, 0.5 * limits.vy_max, 0.2 * limits.omega_max}, limits, saturated).vx, 0.7);
  EXPECT_TRUE(saturated);
  EXPECT_DOUBLE_EQ(saturate({0.6, -limits.vy_max, limits.omega_max}, limits, saturated).vx, 0.6);
  EXPECT_FALSE(saturated);
  EXPECT_DOUBLE_EQ(saturate({limits.vx_min, limits.vy_max, limits.omega_max}, limits, saturated).vx, limits.vx_min);
  EXPECT_FALSE(saturated);
  for (double lateral : {0.0, 0.1, 0.5, 0.9, 1.0}) {
    EXPECT_NEAR(lateral_share_left(limits, forward_speed_bound(limits, 0.0, lateral * limits.omega_max)), lateral, 1e-12);
  }
  EXPECT_DOUBLE_EQ(lateral_share_left(limits, 0.3), 1.0);
  EXPECT_DOUBLE_EQ(lateral_share_left(limits, -0.3), 1.0);
  EXPECT_DOUBLE_EQ(lateral_share_left(limits, 0.9), 0.0);
  limits.lateral_vx_share = 1.0;
  EXPECT_DOUBLE_EQ(saturate({0.8, limits.vy_max, limits.omega_max}, limits, saturated).vx, 0.8);
  EXPECT_DOUBLE_EQ(lateral_share_left(limits, 0.8), 1.0);
}

TEST(StepSequencePlanner, StraightStepsAdvanceByVelocityTimesStepTime) {
  StepParameters p;
  std::array<Footstep, 3> steps;
  plan_steps(Footstep{Side::Left, {0.0, 0.09}, 0.0, 0.0}, {0.5, 0.0, 0.0}, p, 1.0, 3, steps);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(steps[k].position.x(), 0.5 * p.step_time * (k + 1), 1e-12);
    EXPECT_NEAR(std::abs(steps[k].position.y()), 0.5 * p.step_width, 1e-12);
    EXPECT_NEAR(steps[k].touchdown, 1.0 + k * p.step_time, 1e-12);
  }
  EXPECT_EQ(steps[0].side, Side::Right);
  EXPECT_EQ(steps[1].side, Side::Left);
  EXPECT_LT(steps[0].position.y(), 0.0);
}

// A constant turning command: the path has radius v/ω; each foot's prints lie on the circles
// R ∓ w/2 about the same centre (within 2 %).
TEST(StepSequencePlanner, ConstantTurnPlacesFootprintsOnACircle) {
  const VelocityCommand v{0.4, 0.0, 0.25};
  const double radius = v.vx / v.omega;
  const Eigen::Vector2d centre(0.0, radius);
  StepParameters p;
  Footstep stance{Side::Left, {0.0, 0.5 * p.step_width}, 0.0, 0.0};
  std::array<Footstep, 3> steps;
  for (int round = 0; round < 10; ++round) {
    plan_steps(stance, v, p, 0.0, 3, steps);
    for (const Footstep& f : steps) {
      const double expected = f.side == Side::Left ? radius - 0.5 * p.step_width : radius + 0.5 * p.step_width;
      EXPECT_NEAR((f.position - centre).norm(), expected, 0.02 * expected) << round;
      EXPECT_NEAR((heading_of_stance(f, p.step_width).position - centre).norm(), radius, 0.02 * radius);
    }
    stance = steps[0];
  }
}

// Sideways the foot on the side of the motion leads by 2·vy·T and the other closes to the step
// width: the feet never come closer than the width, and the robot moves vy·T per step on average.
TEST(StepSequencePlanner, SidewaysTheLeadingFootStepsOutAndTheTrailingOneClosesToTheWidth) {
  StepParameters p;
  p.step_time = 0.8;
  for (const double vy : {0.15, -0.15}) {
    const Side trailing = vy > 0.0 ? Side::Right : Side::Left;
    const double outward = trailing == Side::Left ? -1.0 : 1.0;  // the stance (leading) foot's side
    const Footstep stance{other(trailing), {0.0, outward * 0.5 * p.step_width}, 0.0, 0.0};
    std::array<Footstep, 3> steps;
    plan_steps(stance, VelocityCommand{0.0, vy, 0.0}, p, 1.0, 3, steps);
    EXPECT_EQ(steps[0].side, trailing);
    EXPECT_NEAR(std::abs(stance.position.y() - steps[0].position.y()), p.step_width, 1e-12) << "trailing closes";
    EXPECT_NEAR(std::abs(steps[1].position.y() - steps[0].position.y()), p.step_width + 2.0 * std::abs(vy) * p.step_time,
                1e-12) << "leading steps out";
    EXPECT_NEAR(steps[2].position.y() - steps[0].position.y(), 2.0 * vy * p.step_time, 1e-12) << "vy on average";
  }
}

TEST(StepSequencePlanner, ZeroCommandPlacesTheFeetSideBySide) {
  StepParameters p;
  const Footstep left{Side::Left, {1.0, 0.3}, 0.2, 0.0};
  std::array<Footstep, 3> steps;
  plan_steps(left, {}, p, 0.0, 1, steps);
  const Eigen::Vector2d gap = left.position - steps[0].position;
  EXPECT_EQ(steps[0].side, Side::Right);
  EXPECT_NEAR(gap.norm(), p.step_width, 1e-12);
  EXPECT_NEAR(std::atan2(gap.y(), gap.x()), left.yaw + M_PI / 2, 1e-12) << "right beside left, square to its heading";
  EXPECT_NEAR(steps[0].yaw, left.yaw, 1e-12);
}

// The gait's speed moves towards the command by at most the allowed change per step, both ways.
TEST(StepSequencePlanner, SpeedRampsTowardsTheCommand) {
  double v = 0.0;
  int steps = 0;
  while (v < 1.0 && steps < 100) v = ramp_towards(v, 1.0, 0.25), ++steps;
  EXPECT_EQ(steps, 4);
  EXPECT_DOUBLE_EQ(v, 1.0);
  EXPECT_DOUBLE_EQ(ramp_towards(1.0, 0.0, 0.25), 0.75);
  EXPECT_DOUBLE_EQ(ramp_towards(0.3, 0.35, 0.25), 0.35);
}

}  // namespace
}  // namespace biped
