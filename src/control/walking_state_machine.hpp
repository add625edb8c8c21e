#pragma once
// The walking state machine (Fig. 3's FSM): coordinates the planning and control modules.
//   standing ──(walk command)──► starting ──(first touchdown)──► walking
//   walking ──(stop or zero command at a touchdown)──► stopping ──(feet side by side)──► standing
//   any ──(fall or sensor fault)──► safe_stop (holds a safe pose; left only by a restart)
namespace biped {

enum class WalkingState { Standing, Starting, Walking, Stopping, SafeStop };

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

  // Called every cycle: `wants_to_walk` = nonzero command without stop; `at_touchdown` = the
  // current plan's next touchdown has been reached.
  StepDecision update(bool wants_to_walk, bool at_touchdown);
  void enter_safe_stop() { state_ = WalkingState::SafeStop; }

 private:
  WalkingState state_ = WalkingState::Standing;
};

}  // namespace biped
