#pragma once
// The walking state machine (Fig. 3's FSM): coordinates the planning and control modules.
//   standing ──(walk command)──► starting ──(first touchdown)──► walking
//   walking ──(stop or zero command at a touchdown)──► stopping ──(feet side by side)──► standing
//   A touchdown at which the robot must step on to keep its balance (`must_step`) plans more steps
//   instead of a stop step or standing (walking, or the safe stop's walking part); standing (also
//   at the end of a safe stop), it starts walking (a recovery step).
//   any ──(sensor fault)──► safe_stop: the walk command is ignored; a step under way is finished,
//   steps that slow down follow while the gait is too fast to stop in one step (as a normal stop
//   does), one more step puts the feet side by side, and the robot stands (the pattern and
//   eq. (21) need no sensors; what depends on the failed sensor is off). Left only by a restart.
//   any ──(upper body tilted beyond recovery)──► fallen: nothing is planned any more and the joints
//   hold their last set-points (finite, inside the software limits). Left only by a restart.
namespace biped {

enum class WalkingState { Standing, Starting, Walking, Stopping, SafeStop, Fallen };

const char* name_of(WalkingState state);

// What the FSM tells the controller to do at a touchdown (or when standing and a command arrives).
enum class StepDecision {
  None,       // keep the current plan
  StartWalk,  // plan the first steps with a longer weight shift
  Continue,   // plan three more steps with the command
  StopStep,   // one step that places the swing foot beside the stance foot
  Stand,      // no more steps: come to rest between the feet
};

class WalkingStateMachine {
 public:
  WalkingState state() const { return state_; }
  // Standing still with no step planned: after a stop, or once a safe stop has put the feet side by
  // side.
  bool standing() const {
    return state_ == WalkingState::Standing ||
           (state_ == WalkingState::SafeStop && stop_progress_ == WalkingState::Standing);
  }

  // Called every cycle: `wants_to_walk` = nonzero command without stop, or a gait too fast to stop
  // in one step (in safe_stop only the latter); `at_touchdown` = the current plan's next touchdown
  // has been reached; `must_step` = the robot is not balanced enough to stand (step adaptation).
  StepDecision update(bool wants_to_walk, bool at_touchdown, bool must_step = false);
  void enter_safe_stop();
  void enter_fallen() { state_ = WalkingState::Fallen; }

 private:
  WalkingState state_ = WalkingState::Standing;
  WalkingState stop_progress_ = WalkingState::Standing;  // in safe_stop: where the stop has got to
};

}  // namespace biped
