#include "control/walking_state_machine.hpp"

#include <gtest/gtest.h>

namespace biped {
namespace {

TEST(WalkingStateMachine, StartWalkStopStand) {
  WalkingStateMachine fsm;
  EXPECT_EQ(fsm.update(false, false), StepDecision::None);
  EXPECT_EQ(fsm.state(), WalkingState::Standing);
  EXPECT_EQ(fsm.update(true, false), StepDecision::StartWalk);
  EXPECT_EQ(fsm.state(), WalkingState::Starting);
  EXPECT_EQ(fsm.update(true, false), StepDecision::None);
  EXPECT_EQ(fsm.update(true, true), StepDecision::Continue);
  EXPECT_EQ(fsm.state(), WalkingState::Walking);
  EXPECT_EQ(fsm.update(false, false), StepDecision::None) << "stops only at a touchdown";
  EXPECT_EQ(fsm.update(false, true), StepDecision::StopStep);
  EXPECT_EQ(fsm.state(), WalkingState::Stopping);
  EXPECT_EQ(fsm.update(true, true), StepDecision::Stand) << "a stop completes before walking again";
  EXPECT_EQ(fsm.state(), WalkingState::Standing);
  EXPECT_STREQ(name_of(fsm.state()), "standing");
  EXPECT_TRUE(fsm.standing());
}

TEST(WalkingStateMachine, SafeStopFinishesTheStepStopsAndStaysStopped) {
  WalkingStateMachine fsm;
  fsm.update(true, false);
  fsm.update(true, true);  // walking
  fsm.enter_safe_stop();
  EXPECT_EQ(fsm.state(), WalkingState::SafeStop);
  EXPECT_STREQ(name_of(fsm.state()), "safe_stop");
  EXPECT_EQ(fsm.update(false, false), StepDecision::None);
  EXPECT_FALSE(fsm.standing());
  EXPECT_EQ(fsm.update(false, true), StepDecision::StopStep);
  EXPECT_FALSE(fsm.standing()) << "the stop step is under way";
  EXPECT_EQ(fsm.update(true, true), StepDecision::Stand);
  EXPECT_TRUE(fsm.standing()) << "the feet are side by side: it stands, in safe_stop";
  EXPECT_EQ(fsm.update(true, true), StepDecision::None);
  EXPECT_EQ(fsm.state(), WalkingState::SafeStop);
}

// Too fast to stop in one step (wants_to_walk in safe_stop): the stop waits for steps that slow down.
TEST(WalkingStateMachine, SafeStopFromAFastGaitSlowsDownBeforeTheStopStep) {
  WalkingStateMachine fsm;
  fsm.update(true, false);
  fsm.update(true, true);  // walking
  fsm.enter_safe_stop();
  EXPECT_EQ(fsm.update(true, true), StepDecision::Continue);
  EXPECT_EQ(fsm.update(true, true), StepDecision::Continue);
  EXPECT_EQ(fsm.state(), WalkingState::SafeStop);
  EXPECT_EQ(fsm.update(false, true), StepDecision::StopStep);
  EXPECT_EQ(fsm.update(true, true), StepDecision::Stand) << "once stopping, nothing restarts the walk";
  EXPECT_EQ(fsm.update(true, true), StepDecision::None);
}

// Not balanced enough to stand (must_step): a touchdown that would stop walks on, the stop step's
// touchdown steps again instead of standing, in a normal stop and in a safe stop alike.
TEST(WalkingStateMachine, MustStepKeepsSteppingInsteadOfStoppingOrStanding) {
  WalkingStateMachine fsm;
  fsm.update(true, false);
  fsm.update(true, true);  // walking
  EXPECT_EQ(fsm.update(false, true, true), StepDecision::Continue);
  EXPECT_EQ(fsm.state(), WalkingState::Walking);
  EXPECT_EQ(fsm.update(false, true), StepDecision::StopStep);
  EXPECT_EQ(fsm.update(false, true, true), StepDecision::Continue) << "the stop step's touchdown steps on";
  EXPECT_EQ(fsm.state(), WalkingState::Walking);
  EXPECT_EQ(fsm.update(false, true), StepDecision::StopStep);
  EXPECT_EQ(fsm.update(false, true), StepDecision::Stand);

  WalkingStateMachine safe;
  safe.update(true, false);
  safe.update(true, true);
  safe.enter_safe_stop();
  EXPECT_EQ(safe.update(false, true, true), StepDecision::Continue);
  EXPECT_EQ(safe.update(false, true), StepDecision::StopStep);
  EXPECT_EQ(safe.update(false, true, true), StepDecision::Continue);
  EXPECT_FALSE(safe.standing());
  EXPECT_EQ(safe.update(false, true), StepDecision::StopStep);
  EXPECT_EQ(safe.update(false, true), StepDecision::Stand);
  EXPECT_TRUE(safe.standing());
  EXPECT_EQ(safe.state(), WalkingState::SafeStop);
}

// Standing, must_step starts walking at once (a recovery step), without a command and without
// a touchdown; once stopped, the robot stands again. The same at the end of a safe stop, which
// stays a safe stop.
TEST(WalkingStateMachine, MustStepWhileStandingStartsARecoveryStep) {
  WalkingStateMachine fsm;
  EXPECT_EQ(fsm.update(false, false), StepDecision::None);
  EXPECT_EQ(fsm.update(false, false, true), StepDecision::StartWalk);
  EXPECT_EQ(fsm.state(), WalkingState::Starting);
  EXPECT_EQ(fsm.update(false, false, true), StepDecision::None) << "until the first touchdown";
  EXPECT_EQ(fsm.update(false, true), StepDecision::StopStep);
  EXPECT_EQ(fsm.update(false, true), StepDecision::Stand);
  EXPECT_EQ(fsm.state(), WalkingState::Standing);

  WalkingStateMachine safe;
  safe.enter_safe_stop();
  EXPECT_TRUE(safe.standing());
  EXPECT_EQ(safe.update(true, false), StepDecision::None) << "a command does not start a safe stop's robot";
  EXPECT_EQ(safe.update(false, false, true), StepDecision::StartWalk);
  EXPECT_EQ(safe.state(), WalkingState::SafeStop);
  EXPECT_FALSE(safe.standing());
  EXPECT_EQ(safe.update(false, true, true), StepDecision::Continue) << "still unbalanced";
  EXPECT_EQ(safe.update(false, true), StepDecision::StopStep);
  EXPECT_EQ(safe.update(false, true), StepDecision::Stand);
  EXPECT_TRUE(safe.standing());
}

TEST(WalkingStateMachine, SafeStopWhileStandingKeepsStanding) {
  WalkingStateMachine fsm;
  fsm.enter_safe_stop();
  EXPECT_EQ(fsm.update(true, true), StepDecision::None);
  EXPECT_EQ(fsm.state(), WalkingState::SafeStop);
  EXPECT_TRUE(fsm.standing());
}

}  // namespace
}  // namespace biped
