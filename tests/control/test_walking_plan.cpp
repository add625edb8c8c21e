// The walking plan (FSM, step sequence planner, pattern generator) advanced cycle by cycle on its
// own, LOLA's model, default parameters (no step table: one step time): standing, the start, the
// touchdowns and footholds, the first swing foot, the speed ramp, saturation, the stop and the
// safe stop.
#include "control/walking_plan.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "model/task_space.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

constexpr double kDt = 0.001;

WalkCommand walk(double vx, double vy = 0.0, double omega = 0.0) { return {vx, vy, omega, false}; }
WalkCommand stop() { return {0.0, 0.0, 0.0, true}; }

// A touchdown seen by the caller: the step the plan had listed first just before it, and the
// time it was detected.
struct Touchdown {
  Footstep planned;
  double t;
  Eigen::Vector3d landed;  // the foot's position in the sample at that cycle
  double landed_yaw;
};

// The plan reset on LOLA's feet and CoM in the stand pose, soles at z = 0 (as the controller does).
struct PlanFixture {
  RobotModel model = test::load_model("lola");
  WalkingPlanParams params;
  WalkingPlan plan{model, params};
  std::array<Footstep, 2> feet;
  double t = 0.0;
  std::vector<Touchdown> touchdowns;

  PlanFixture() {
    const TaskSpace space(model);
    TaskSpaceData data(space);
    Eigen::VectorXd q = model.stand_qpos();
    evaluate(space, q, Eigen::Matrix3d::Identity(), data);
    const double ankle_height = plan.pattern_generator().params().ankle_height;
    q[2] -= 0.5 * (data.foot_position[0].z() + data.foot_position[1].z()) - ankle_height;
    evaluate(space, q, Eigen::Matrix3d::Identity(), data);
    for (Side side : kSides) {
      const int k = index_of(side);
      feet[k] = {side, data.foot_position[k].head<2>(), 0.0, 0.0};
    }
    plan.reset(feet, data.com);
  }
  // Advances the plan until `until` with the command, noting each touchdown.
  void run(double until, const WalkCommand& command, const std::function<void()>& each_cycle = [] {}) {
    for (; t < until - 1e-9; t += kDt) {
      const int before = plan.steps_completed();
      const Footstep next = plan.num_planned_steps() > 0 ? plan.planned_step(0) : Footstep{};
      plan.advance(t, command);
      if (plan.steps_completed() > before) {
        const FootReference& foot = plan.sample().feet[index_of(next.side)];
        touchdowns.push_back({next, t, foot.position, foot.yaw});
      }
      each_cycle();
    }
  }
  double step_time() const { return params.step.step_time; }
  double step_width() const { return (feet[0].position - feet[1].position).norm(); }
};

// Side by side: the same heading, the line between the ankles square to it, a step width apart.
void expect_side_by_side(const PatternSample& s, double width) {
  EXPECT_TRUE(s.feet[0].in_contact && s.feet[1].in_contact);
  EXPECT_NEAR(std::remainder(s.feet[0].yaw - s.feet[1].yaw, 2.0 * M_PI), 0.0, 1e-9);
  const Eigen::Vector2d gap = (s.feet[0].position - s.feet[1].position).head<2>();
  EXPECT_NEAR(gap.dot(Eigen::Vector2d(std::cos(s.feet[0].yaw), std::sin(s.feet[0].yaw))), 0.0, 1e-9);
  EXPECT_NEAR(gap.norm(), width, 1e-9);
}

TEST(WalkingPlan, ZeroCommandKeepsStandingWithoutSteps) {
  PlanFixture f;
  f.run(3.0, walk(0.0), [&] {
    ASSERT_EQ(f.plan.state(), WalkingState::Standing);
    ASSERT_EQ(f.plan.num_planned_steps(), 0);
    ASSERT_TRUE(f.plan.sample().feet[0].in_contact && f.plan.sample().feet[1].in_contact);
  });
  EXPECT_EQ(f.plan.steps_completed(), 0);
  for (int k = 0; k < 2; ++k) {
    EXPECT_LT((f.plan.sample().feet[k].position.head<2>() - f.feet[k].position).norm(), 1e-12);
  }
  EXPECT_FALSE(f.plan.command_saturated());
}

// From standing the first step touches down one step time plus the start shift after the
// command; until its lift-off both feet stay down. Every touchdown comes at the time the plan
// listed and puts the foot where it listed.
TEST(WalkingPlan, ForwardCommandStartsAfterTheShiftAndLandsThePlannedSteps) {
  PlanFixture f;
  f.run(0.5, walk(0.0));
  const double start = f.t;
  f.run(0.5 + kDt, walk(0.3));
  EXPECT_EQ(f.plan.state(), WalkingState::Starting);
  ASSERT_EQ(f.plan.num_planned_steps(), 3);
  const double first_touchdown = start + f.step_time() + f.params.start_shift;
  EXPECT_NEAR(f.plan.planned_step(0).touchdown, first_touchdown, 1e-9);
  const double liftoff = first_touchdown - f.step_time() * (1.0 - f.params.step.double_support_ratio);
  f.run(liftoff - 2 * kDt, walk(0.3), [&] {
    ASSERT_TRUE(f.plan.sample().feet[0].in_contact && f.plan.sample().feet[1].in_contact) << f.t;
  });
  f.run(6.0, walk(0.3));

  ASSERT_GE(f.touchdowns.size(), 5u);
  EXPECT_EQ(f.plan.state(), WalkingState::Walking);
  EXPECT_EQ(f.plan.steps_completed(), static_cast<int>(f.touchdowns.size()));
  EXPECT_NEAR(f.touchdowns[0].t, first_touchdown, kDt);
  for (std::size_t i = 0; i < f.touchdowns.size(); ++i) {
    const Touchdown& td = f.touchdowns[i];
    EXPECT_GE(td.t, td.planned.touchdown - 1e-9) << "step " << i;
    EXPECT_LT(td.t, td.planned.touchdown + kDt) << "step " << i;
    EXPECT_LT((td.landed.head<2>() - td.planned.position).norm(), 1e-9) << "step " << i;
    EXPECT_NEAR(td.landed_yaw, td.planned.yaw, 1e-9) << "step " << i;
    if (i > 0) {
      EXPECT_NE(td.planned.side, f.touchdowns[i - 1].planned.side) << "feet alternate";
    }
  }
}

struct FirstStep {
  const char* name;
  WalkCommand command;
  Side first_swing;
};
void PrintTo(const FirstStep& c, std::ostream* os) { *os << c.name; }

class WalkingPlanFirstStep : public ::testing::TestWithParam<FirstStep> {};

// The first swing foot is on the side the robot moves or turns to (left for vy > 0, or ω > 0
// without vy); otherwise the right.
TEST_P(WalkingPlanFirstStep, SwingsTheFootOnTheSideOfTheMotion) {
  PlanFixture f;
  Side lifted = Side::Left;
  bool seen = false;
  f.run(2.0, GetParam().command, [&] {
    for (Side side : kSides) {
      if (!seen && !f.plan.sample().feet[index_of(side)].in_contact) {
        lifted = side;
        seen = true;
      }
    }
  });
  ASSERT_TRUE(seen);
  EXPECT_EQ(name_of(lifted), name_of(GetParam().first_swing));
  ASSERT_FALSE(f.touchdowns.empty());
  EXPECT_EQ(name_of(f.touchdowns[0].planned.side), name_of(GetParam().first_swing));
}

INSTANTIATE_TEST_SUITE_P(
    Commands, WalkingPlanFirstStep,
    ::testing::Values(FirstStep{"forward", walk(0.3), Side::Right}, FirstStep{"backward", walk(-0.2), Side::Right},
                      FirstStep{"left", walk(0.0, 0.1), Side::Left}, FirstStep{"right", walk(0.0, -0.1), Side::Right},
                      FirstStep{"turn_left", walk(0.2, 0.0, 0.3), Side::Left},
                      FirstStep{"turn_right", walk(0.2, 0.0, -0.3), Side::Right},
                      FirstStep{"right_turning_left", walk(0.0, -0.1, 0.3), Side::Right}),
    [](const ::testing::TestParamInfo<FirstStep>& info) { return std::string(info.param.name); });

// Walking straight at a speed v, successive footholds advance by v × step time. From standing to
// the limit and back to a stop, the gait's speed changes by at most vx_rate × step time per step,
// and does change by that much (the ramp is what limits it).
TEST(WalkingPlan, ForwardSpeedRampsByAtMostTheRatePerStep) {
  PlanFixture f;
  f.run(6.0, walk(f.params.limits.vx_max));
  const std::size_t accelerating = f.touchdowns.size();
  f.run(12.0, stop());
  EXPECT_EQ(f.plan.state(), WalkingState::Standing);

  const double max_change = f.params.limits.vx_rate * f.step_time();
  double previous_x = f.feet[0].position.x(), previous_speed = 0.0, fastest = 0.0, largest_change = 0.0;
  for (std::size_t i = 0; i < f.touchdowns.size(); ++i) {
    const double x = f.touchdowns[i].planned.position.x();
    const double speed = (x - previous_x) / f.step_time();
    EXPECT_LE(std::abs(speed - previous_speed), max_change + 1e-9) << "step " << i;
    largest_change = std::max(largest_change, std::abs(speed - previous_speed));
    fastest = std::max(fastest, speed);
    if (i + 1 == accelerating) {
      EXPECT_NEAR(speed, f.params.limits.vx_max, 1e-9) << "reached the command";
    }
    previous_x = x;
    previous_speed = speed;
  }
  EXPECT_NEAR(largest_change, max_change, 1e-9);
  EXPECT_LE(fastest, f.params.limits.vx_max + 1e-9);
  EXPECT_NEAR(previous_speed, 0.0, 1e-9) << "the last step puts the feet side by side";
}

// A joystick reversed sideways and in turning at full deflection: the sideways speed and the turn
// rate change by at most their rates × step time per step, and walking sideways the feet never
// come closer than the step width (the trailing foot closes to it, the leading one steps out).
TEST(WalkingPlan, ReversalsRampSidewaysSpeedAndTurnRateAndKeepTheFeetApart) {
  PlanFixture f;
  const CommandLimits& limits = f.params.limits;
  double narrowest = 1.0;
  std::size_t seen = 0;
  const auto check_width = [&] {
    if (f.touchdowns.size() == seen) return;
    seen = f.touchdowns.size();
    const PatternSample& s = f.plan.sample();
    const double yaw = s.feet[0].yaw;
    const Eigen::Vector2d gap = (s.feet[0].position - s.feet[1].position).head<2>();
    narrowest = std::min(narrowest, -std::sin(yaw) * gap.x() + std::cos(yaw) * gap.y());
  };
  f.run(4.0, walk(0.0, limits.vy_max), check_width);
  f.run(8.0, walk(0.0, -limits.vy_max), check_width);
  ASSERT_GT(f.touchdowns.size(), 6u);
  EXPECT_GE(narrowest, f.step_width() - 1e-9);
  f.run(12.0, walk(0.2, 0.0, limits.omega_max));
  f.run(16.0, walk(0.2, 0.0, -limits.omega_max));

  const double max_turn_change = limits.omega_rate * f.step_time() * f.step_time();
  double largest_turn_change = 0.0;
  for (std::size_t i = 2; i < f.touchdowns.size(); ++i) {
    const double turn = f.touchdowns[i].planned.yaw - f.touchdowns[i - 1].planned.yaw;
    const double previous_turn = f.touchdowns[i - 1].planned.yaw - f.touchdowns[i - 2].planned.yaw;
    largest_turn_change = std::max(largest_turn_change, std::abs(turn - previous_turn));
  }
  EXPECT_LE(largest_turn_change, max_turn_change + 1e-9);
  EXPECT_NEAR(largest_turn_change, max_turn_change, 1e-9) << "the ramp is what limits it";
}

// The joystick swung from full speed straight to full speed turning and sideways, and back: the
// plan slows before it turns or steps sideways, and speeds up only as they ease off; at every cycle
// its speed and turn rate stay inside the combined bound, and both ends are reached.
TEST(WalkingPlan, FromFullSpeedATurnSlowsFirstAndStaysInsideTheCombinedBound) {
  PlanFixture f;
  const CommandLimits& limits = f.params.limits;
  double worst = -1.0, widest_lateral_at_full_speed = 0.0;
  const auto check = [&] {
    const VelocityCommand v = f.plan.planned_velocity();
    worst = std::max(worst, v.vx - forward_speed_bound(limits, v.vy, v.omega));
    if (v.vx > limits.vx_max - 1e-9) widest_lateral_at_full_speed = std::max({widest_lateral_at_full_speed, std::abs(v.vy), std::abs(v.omega)});
  };
  f.run(6.0, walk(limits.vx_max), check);
  ASSERT_NEAR(f.plan.planned_velocity().vx, limits.vx_max, 1e-12);
  bool turned_at_full_speed = false;
  f.run(12.0, walk(limits.vx_max, -limits.vy_max, limits.omega_max), [&] {
    check();
    const VelocityCommand v = f.plan.planned_velocity();
    if (v.omega != 0.0 && v.vx > limits.vx_max - 1e-9) turned_at_full_speed = true;
  });
  EXPECT_FALSE(turned_at_full_speed);
  const VelocityCommand turning = f.plan.planned_velocity();
  EXPECT_NEAR(turning.vx, limits.lateral_vx_share * limits.vx_max, 1e-12);
  EXPECT_NEAR(turning.vy, -limits.vy_max, 1e-12);
  EXPECT_NEAR(turning.omega, limits.omega_max, 1e-12);
  f.run(18.0, walk(limits.vx_max), check);
  EXPECT_NEAR(f.plan.planned_velocity().vx, limits.vx_max, 1e-12);
  EXPECT_LE(worst, 1e-12);
  EXPECT_EQ(widest_lateral_at_full_speed, 0.0);
}

TEST(WalkingPlan, CommandBeyondTheLimitsIsSaturatedAndSaysSo) {
  const CommandLimits limits;
  for (const WalkCommand& beyond : {walk(limits.vx_max + 1.0), walk(limits.vx_min - 0.1), walk(0.2, limits.vy_max + 0.1),
                                    walk(0.2, -limits.vy_max - 0.1), walk(0.2, 0.0, -limits.omega_max - 0.1)}) {
    PlanFixture f;
    f.run(kDt, beyond);
    EXPECT_TRUE(f.plan.command_saturated()) << beyond.vx << ' ' << beyond.vy << ' ' << beyond.omega;
    f.run(2 * kDt, walk(0.2));
    EXPECT_FALSE(f.plan.command_saturated());
  }
  // Held at five times the limit, the footholds advance no faster than the limit allows.
  PlanFixture f;
  f.run(8.0, walk(5.0 * limits.vx_max));
  ASSERT_GE(f.touchdowns.size(), 4u);
  for (std::size_t i = 1; i < f.touchdowns.size(); ++i) {
    const double advance = f.touchdowns[i].planned.position.x() - f.touchdowns[i - 1].planned.position.x();
    EXPECT_LE(advance, limits.vx_max * f.step_time() + 1e-9) << "step " << i;
  }
}

TEST(WalkingPlan, StopPutsTheFeetSideBySideAndStands) {
  PlanFixture f;
  f.run(5.0, walk(0.4, 0.0, 0.2));
  ASSERT_EQ(f.plan.state(), WalkingState::Walking);
  f.run(10.0, stop());
  EXPECT_EQ(f.plan.state(), WalkingState::Standing);
  EXPECT_EQ(f.plan.num_planned_steps(), 0);
  expect_side_by_side(f.plan.sample(), f.step_width());
  const int steps = f.plan.steps_completed();
  f.run(12.0, stop());
  EXPECT_EQ(f.plan.steps_completed(), steps);
}

// Balance before a stop: while the robot is unbalanced, the touchdowns that would stop or stand
// plan more steps instead, at most `max_steps` in a row, then the stop completes as it would have;
// once balanced, the stop completes at once.
TEST(WalkingPlan, UnbalancedStopStepsOnAtMostMaxStepsThenStands) {
  const int max_steps = 3;
  // Touchdowns from the stop command on, unbalanced until `balanced_after` of them (-1: never).
  const auto touchdowns_to_stand = [&](bool keep_stepping, int balanced_after) {
    PlanFixture f;
    f.run(5.0, walk(0.3));
    EXPECT_EQ(f.plan.state(), WalkingState::Walking);
    const std::size_t before = f.touchdowns.size();
    f.plan.keep_stepping(keep_stepping, max_steps);
    f.run(15.0, stop(), [&] {
      if (balanced_after >= 0 && f.touchdowns.size() >= before + balanced_after) f.plan.keep_stepping(false, max_steps);
    });
    EXPECT_EQ(f.plan.state(), WalkingState::Standing);
    EXPECT_EQ(f.plan.num_planned_steps(), 0);
    expect_side_by_side(f.plan.sample(), f.step_width());
    EXPECT_EQ(f.plan.balance_steps(), 0) << "standing";
    return static_cast<int>(f.touchdowns.size() - before);
  };
  const int stop = touchdowns_to_stand(false, -1);
  EXPECT_GE(stop, 2) << "the step under way and the stop step";
  EXPECT_EQ(touchdowns_to_stand(true, -1), stop + max_steps);
  EXPECT_EQ(touchdowns_to_stand(true, 2), stop + 2);
}

// Recovery step from standing: step_from_standing starts steps at once with the foot it names
// (the first touchdown one step time later: no start shift), counted as a balance step; balanced
// again (keep_stepping false), the stop follows and the robot stands with its feet side by side.
TEST(WalkingPlan, StepFromStandingStartsAtOnceWithTheGivenFootAndStandsAgain) {
  for (Side swing : kSides) {
    PlanFixture f;
    f.run(0.5, walk(0.0));
    const double start = f.t;
    f.plan.step_from_standing(true, swing);
    f.run(0.5 + kDt, walk(0.0));
    f.plan.step_from_standing(false, swing);
    EXPECT_EQ(f.plan.state(), WalkingState::Starting);
    ASSERT_EQ(f.plan.num_planned_steps(), 3);
    EXPECT_EQ(f.plan.planned_step(0).side, swing);
    EXPECT_NEAR(f.plan.planned_step(0).touchdown, start + f.step_time(), 1e-9);
    EXPECT_EQ(f.plan.balance_steps(), 1);
    f.run(6.0, walk(0.0));
    EXPECT_EQ(f.plan.state(), WalkingState::Standing);
    EXPECT_EQ(f.touchdowns.size(), 2u) << "the recovery step and the stop step";
    expect_side_by_side(f.plan.sample(), f.step_width());
    EXPECT_EQ(f.plan.balance_steps(), 0);
  }
}

// Step timing: a limit set before a touchdown shortens the steps planned there, and only those;
// the steps after it keep the step time. The step under way is not touched.
TEST(WalkingPlan, LimitedStepTimeShortensTheStepsPlannedAtTheNextTouchdown) {
  PlanFixture f;
  f.run(4.0, walk(0.3));
  ASSERT_EQ(f.plan.state(), WalkingState::Walking);
  const double quick = 0.5;
  ASSERT_LT(quick, f.step_time());
  const double under_way = f.plan.planned_step(0).touchdown;
  const std::size_t before = f.touchdowns.size();
  f.plan.limit_next_step_time(quick);
  while (f.touchdowns.size() == before) f.run(f.t + kDt, walk(0.3));
  EXPECT_NEAR(f.touchdowns.back().t, under_way, kDt);
  ASSERT_EQ(f.plan.num_planned_steps(), 3);
  EXPECT_NEAR(f.plan.planned_step(0).touchdown - f.touchdowns.back().t, quick, 2 * kDt);
  EXPECT_NEAR(f.plan.planned_step(1).touchdown - f.plan.planned_step(0).touchdown, quick, 1e-9);

  f.plan.limit_next_step_time(0.0);
  const double quick_touchdown = f.plan.planned_step(0).touchdown;
  while (f.touchdowns.size() == before + 1) f.run(f.t + kDt, walk(0.3));
  EXPECT_NEAR(f.touchdowns.back().t, quick_touchdown, kDt);
  EXPECT_NEAR(f.plan.planned_step(0).touchdown - f.touchdowns.back().t, f.step_time(), 2 * kDt);
}

// A safe stop in mid-swing: the step under way lands where it was planned, one more step puts the
// feet side by side, and no step follows, whatever the command says.
TEST(WalkingPlan, SafeStopFinishesTheStepTakesOneMoreAndStands) {
  PlanFixture f;
  f.run(4.0, walk(0.4));
  ASSERT_EQ(f.plan.state(), WalkingState::Walking);
  while (f.plan.sample().feet[0].in_contact && f.plan.sample().feet[1].in_contact) f.run(f.t + kDt, walk(0.4));
  const Footstep under_way = f.plan.planned_step(0);
  const std::size_t before = f.touchdowns.size();
  f.plan.enter_safe_stop();
  f.run(12.0, walk(0.4));

  EXPECT_EQ(f.plan.state(), WalkingState::SafeStop);
  ASSERT_EQ(f.touchdowns.size(), before + 2);
  const Touchdown& finished = f.touchdowns[before];
  EXPECT_EQ(finished.planned.side, under_way.side);
  EXPECT_NEAR(finished.t, under_way.touchdown, kDt);
  EXPECT_LT((finished.landed.head<2>() - under_way.position).norm(), 1e-9);
  EXPECT_EQ(f.touchdowns[before + 1].planned.side, other(under_way.side));
  EXPECT_EQ(f.plan.num_planned_steps(), 0);
  expect_side_by_side(f.plan.sample(), f.step_width());
}

// A safe stop at the fastest gait: the walk command is ignored, the steps shorten at the ramp's rate
// (as for a normal stop) until one step can stop the gait, and the robot stands.
TEST(WalkingPlan, SafeStopFromTheFastestGaitSlowsDownFirst) {
  PlanFixture f;
  const double fastest = f.params.limits.vx_max;
  f.run(12.0, walk(fastest));
  ASSERT_EQ(f.plan.state(), WalkingState::Walking);
  ASSERT_GT(fastest, f.plan.max_speed_change()) << "the fixture's fastest gait must need slowing down";
  const std::size_t before = f.touchdowns.size();
  f.plan.enter_safe_stop();
  f.run(24.0, walk(fastest));

  EXPECT_EQ(f.plan.num_planned_steps(), 0);
  expect_side_by_side(f.plan.sample(), f.step_width());
  ASSERT_GE(f.touchdowns.size(), before + 4) << "the step under way, at least one slower step, the stop step";
  const double most_per_step = f.params.limits.vx_rate * f.step_time() * f.step_time();
  for (std::size_t i = before; i < f.touchdowns.size(); ++i) {
    const Footstep& previous = f.touchdowns[i - 1].planned;
    const Footstep& now = f.touchdowns[i].planned;
    const double advance = now.position.x() - previous.position.x();
    const double previous_advance = previous.position.x() - f.touchdowns[i - 2].planned.position.x();
    EXPECT_LE(advance, previous_advance + 1e-9) << "never faster, whatever the command: step " << i;
    EXPECT_GE(advance, previous_advance - most_per_step - 1e-9) << "no abrupt stop: step " << i;
  }
}

// Entered while standing, the safe stop never starts a step.
TEST(WalkingPlan, SafeStopFromStandingTakesNoStep) {
  PlanFixture f;
  f.plan.enter_safe_stop();
  f.run(3.0, walk(0.4));
  EXPECT_EQ(f.plan.state(), WalkingState::SafeStop);
  EXPECT_EQ(f.plan.steps_completed(), 0);
  EXPECT_EQ(f.plan.num_planned_steps(), 0);
}

}  // namespace
}  // namespace biped
