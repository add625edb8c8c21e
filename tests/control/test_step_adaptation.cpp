#include "control/step_adaptation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace biped {
namespace {

constexpr double kDt = 0.001;

// A left swing in the middle of the single support: the stance (right) foot at the origin, the left
// foot planned 0.2 m to its left and 0.3 m ahead.
StepAdaptationInput mid_swing() {
  StepAdaptationInput in;
  in.swing = Side::Left;
  in.time_to_touchdown = 0.3;
  in.planned_landing = {0.3, 0.2};
  in.com_height = 0.9;
  return in;
}

// Switched on, without the dead band (its own test below), so that the capture criterion shows.
StepAdaptationParams switched_on() {
  StepAdaptationParams params;
  params.enabled = true;
  params.dead_band_forward = 0.0;
  params.dead_band_sideways = 0.0;
  return params;
}

// Runs the adaptation long enough for its filter to settle on a constant input.
Eigen::Vector2d settle(StepAdaptation& adaptation, const StepAdaptationInput& in, int cycles = 2000) {
  for (int k = 0; k < cycles; ++k) adaptation.update(kDt, in);
  return adaptation.shift();
}

// What the criterion of the header predicts along one axis: the DCM error left at touchdown with
// the centre of pressure held at its reach.
double predicted_shift(double dcm_error, double reach, double time_to_touchdown, double com_height) {
  const double omega = std::sqrt(9.81 / com_height);
  const double growth = std::exp(omega * time_to_touchdown);
  const double cop = std::copysign(reach, dcm_error);
  return (dcm_error - cop) * growth + cop;
}

TEST(StepAdaptation, NoErrorNoShift) {
  StepAdaptation adaptation{switched_on()};
  EXPECT_EQ(settle(adaptation, mid_swing()), Eigen::Vector2d::Zero());
}

// The DCM error is measured − planned of c + ċ/ω₀.
TEST(StepAdaptation, DcmErrorCombinesPositionAndRate) {
  StepAdaptation adaptation{switched_on()};
  StepAdaptationInput in = mid_swing();
  in.measured_com = {0.01, -0.02};
  in.measured_com_rate = {0.1, 0.05};
  in.planned_com_rate = {0.05, 0.0};
  adaptation.update(kDt, in);
  const double omega = std::sqrt(9.81 / 0.9);
  EXPECT_NEAR(adaptation.dcm_error().x(), 0.01 + 0.05 / omega, 1e-15);
  EXPECT_NEAR(adaptation.dcm_error().y(), -0.02 + 0.05 / omega, 1e-15);
}

// An error the stance sole's centre of pressure can take up by touchdown leaves the step as planned.
TEST(StepAdaptation, ErrorWithinTheSolesReachIsLeftToTheStabilizer) {
  const StepAdaptationParams params = switched_on();
  StepAdaptation adaptation{params};
  StepAdaptationInput in = mid_swing();
  const double omega = std::sqrt(9.81 / in.com_height);
  const double absorbable = 1.0 - std::exp(-omega * in.time_to_touchdown);
  in.measured_com.y() = 0.9 * params.cop_reach_share * in.cop_sideways * absorbable;
  EXPECT_EQ(settle(adaptation, in), Eigen::Vector2d::Zero());
}

// Beyond it, the landing point moves by the error left at touchdown, in the error's direction.
TEST(StepAdaptation, LargerErrorShiftsTheLandingPointByWhatIsLeftAtTouchdown) {
  StepAdaptationParams params = switched_on();
  params.max_outward = 1.0;
  params.max_forward = 1.0;
  StepAdaptation adaptation{params};
  StepAdaptationInput in = mid_swing();
  in.measured_com = {0.03, 0.02};
  const Eigen::Vector2d shift = settle(adaptation, in);
  EXPECT_NEAR(shift.x(), predicted_shift(0.03, params.cop_reach_share * in.cop_forward, 0.3, 0.9), 1e-9);
  EXPECT_NEAR(shift.y(), predicted_shift(0.02, params.cop_reach_share * in.cop_sideways, 0.3, 0.9), 1e-9);
  EXPECT_GT(shift.x(), 0.03);
  EXPECT_GT(shift.y(), 0.02);

  StepAdaptationParams half = params;
  half.gain = 0.5;
  StepAdaptation halved{half};
  EXPECT_NEAR(settle(halved, in).y(), 0.5 * shift.y(), 1e-9);
}

// The shift stays within the legs' reach, and the feet do not cross or collide.
TEST(StepAdaptation, ShiftStaysInsideReachAndKeepsTheFeetApart) {
  const StepAdaptationParams params = switched_on();
  for (const Side swing : {Side::Left, Side::Right}) {
    const double outward = swing == Side::Left ? 1.0 : -1.0;
    StepAdaptationInput in = mid_swing();
    in.swing = swing;
    in.planned_landing = {0.3, outward * 0.17};

    StepAdaptation out{params};
    in.measured_com = {0.5, outward * 0.5};
    const Eigen::Vector2d far = settle(out, in);
    EXPECT_NEAR(far.x(), params.max_forward, 1e-9);
    EXPECT_NEAR(far.y(), outward * params.max_outward, 1e-9);

    StepAdaptation back{params};
    in.measured_com = {-0.5, -outward * 0.5};
    const Eigen::Vector2d near = settle(back, in);
    EXPECT_NEAR(near.x(), -params.max_backward, 1e-9);
    EXPECT_NEAR(std::abs(in.planned_landing.y() + near.y()), params.min_width, 1e-9) << "stops at the minimum width";
  }
}

// An error inside the dead band moves nothing; beyond it, only the part outside counts.
TEST(StepAdaptation, DeadBandTakesTheEstimatesScatterOut) {
  StepAdaptationParams banded = switched_on();
  banded.dead_band_forward = 0.05;
  banded.dead_band_sideways = 0.03;
  StepAdaptationInput in = mid_swing();
  in.measured_com = {0.049, -0.029};
  StepAdaptation inside{banded};
  EXPECT_EQ(settle(inside, in), Eigen::Vector2d::Zero());

  in.measured_com = {0.09, 0.07};
  StepAdaptation beyond{banded};
  StepAdaptationInput reduced = in;
  reduced.measured_com = {0.04, 0.04};
  StepAdaptation unbanded{switched_on()};
  EXPECT_TRUE(settle(beyond, in).isApprox(settle(unbanded, reduced), 1e-12));
  EXPECT_GT(beyond.shift().norm(), 0.0);
}

TEST(StepAdaptation, SwitchedOffLeavesEveryStepAsPlanned) {
  StepAdaptationParams params = switched_on();
  params.enabled = false;
  StepAdaptation adaptation{params};
  StepAdaptationInput in = mid_swing();
  in.measured_com = {0.1, 0.1};
  EXPECT_EQ(settle(adaptation, in), Eigen::Vector2d::Zero());
}

// The landing point moves no faster than max_rate and is held just before touchdown; on the ground
// the next swing starts from its plan.
TEST(StepAdaptation, RateLimitedHeldBeforeTouchdownAndResetOnTheGround) {
  const StepAdaptationParams params = switched_on();
  StepAdaptation adaptation{params};
  StepAdaptationInput in = mid_swing();
  in.measured_com = {0.0, 0.08};
  for (int k = 0; k < 20; ++k) {
    const Eigen::Vector2d before = adaptation.shift();
    adaptation.update(kDt, in);
    EXPECT_LE((adaptation.shift() - before).norm(), params.max_rate * kDt + 1e-15);
  }
  const Eigen::Vector2d settled = settle(adaptation, in);
  EXPECT_GT(settled.y(), 0.0);
  in.time_to_touchdown = 0.5 * params.freeze_time;
  in.measured_com = {0.0, -0.08};
  adaptation.update(kDt, in);
  EXPECT_EQ(adaptation.shift(), settled);
  EXPECT_EQ(adaptation.shift_rate(), Eigen::Vector2d::Zero());
  adaptation.idle();
  EXPECT_EQ(adaptation.shift(), Eigen::Vector2d::Zero());
}

// A swing foot that has met the ground before its planned touchdown carries load: its landing point
// is held, whatever the DCM error does meanwhile (the impact itself swings the estimate).
TEST(StepAdaptation, HeldOnceTheSwingFootHasMetTheGround) {
  StepAdaptation adaptation{switched_on()};
  StepAdaptationInput in = mid_swing();
  in.measured_com = {0.08, 0.0};
  const Eigen::Vector2d settled = settle(adaptation, in);
  EXPECT_GT(settled.x(), 0.0);
  in.swing_foot_on_ground = true;
  in.measured_com = {0.2, 0.0};
  settle(adaptation, in, 100);
  EXPECT_EQ(adaptation.shift(), settled);
  EXPECT_EQ(adaptation.shift_rate(), Eigen::Vector2d::Zero());
  EXPECT_GT(adaptation.dcm_error().x(), 0.19) << "the error is still measured";
}

TEST(StepAdaptation, NonFiniteStateLeavesTheShiftAsItWas) {
  StepAdaptation adaptation{switched_on()};
  StepAdaptationInput in = mid_swing();
  in.measured_com = {0.0, 0.08};
  const Eigen::Vector2d settled = settle(adaptation, in);
  in.measured_com_rate.x() = std::numeric_limits<double>::quiet_NaN();
  adaptation.update(kDt, in);
  EXPECT_EQ(adaptation.shift(), settled);
  EXPECT_TRUE(adaptation.shift_rate().allFinite());
}

// One update in mid-swing with the measured CoM `error` [m] off the plan (the planned rates equal).
StepAdaptation after_one_update(const StepAdaptationParams& params, const Eigen::Vector2d& error) {
  StepAdaptation adaptation{params};
  StepAdaptationInput in = mid_swing();
  in.measured_com = error;
  adaptation.update(kDt, in);
  return adaptation;
}

// Step timing: quick steps only for an error beyond the dead band by more than quick_step_error,
// along either axis or both together; never when switched off.
TEST(StepAdaptation, QuickStepsOnlyForAnErrorBeyondTheDeadBandAndTheThreshold) {
  StepAdaptationParams params;  // the defaults: dead bands 0.06 / 0.04 m, threshold 0.05 m
  params.quick_step_time = 0.6;
  const auto next_step_time = [](const StepAdaptationParams& p, const Eigen::Vector2d& error) {
    return after_one_update(p, error).max_next_step_time();
  };
  EXPECT_EQ(next_step_time(params, {0.0, 0.0}), 0.0);
  EXPECT_EQ(next_step_time(params, {0.10, 0.0}), 0.0);   // 0.04 beyond the band
  EXPECT_EQ(next_step_time(params, {0.0, -0.085}), 0.0);  // 0.045 beyond
  EXPECT_EQ(next_step_time(params, {0.12, 0.0}), params.quick_step_time);
  EXPECT_EQ(next_step_time(params, {0.0, -0.10}), params.quick_step_time);
  EXPECT_EQ(next_step_time(params, {-0.10, 0.08}), params.quick_step_time);  // (0.04, 0.04): 0.057
  StepAdaptationParams off = params;
  off.quick_step_time = 0.0;
  EXPECT_EQ(next_step_time(off, {0.0, -0.2}), 0.0);
  StepAdaptationParams disabled = params;
  disabled.enabled = false;
  EXPECT_EQ(next_step_time(disabled, {0.0, -0.2}), 0.0);
}

// Balance before a stop: unbalanced only for an error beyond the dead band by more than
// balance_error; never when switched off (balance_steps 0, or the adaptation off) or not finite.
TEST(StepAdaptation, UnbalancedOnlyForAnErrorBeyondTheDeadBandAndTheBalanceError) {
  StepAdaptationParams params;  // the defaults: dead bands 0.06 / 0.04 m, balance_error 0.02 m
  const auto unbalanced = [](const StepAdaptationParams& p, const Eigen::Vector2d& error) {
    return after_one_update(p, error).unbalanced();
  };
  EXPECT_FALSE(unbalanced(params, {0.0, 0.0}));
  EXPECT_FALSE(unbalanced(params, {0.075, 0.0}));   // 0.015 beyond the band
  EXPECT_FALSE(unbalanced(params, {0.0, -0.055}));  // 0.015 beyond
  EXPECT_TRUE(unbalanced(params, {0.085, 0.0}));
  EXPECT_TRUE(unbalanced(params, {-0.085, 0.0}));
  EXPECT_TRUE(unbalanced(params, {0.0, 0.065}));
  EXPECT_TRUE(unbalanced(params, {0.075, -0.055}));  // (0.015, 0.015): 0.021
  EXPECT_FALSE(unbalanced(params, {NAN, 0.0}));
  StepAdaptationParams off = params;
  off.balance_steps = 0;
  EXPECT_FALSE(unbalanced(off, {0.3, 0.0}));
  StepAdaptationParams disabled = params;
  disabled.enabled = false;
  EXPECT_FALSE(unbalanced(disabled, {0.3, 0.0}));
}

}  // namespace
}  // namespace biped
