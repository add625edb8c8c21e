#include "control/walking_state_machine.hpp"

namespace biped {

const char* name_of(WalkingState state) {
  switch (state) {
    case WalkingState::Standing: return "standing";
    case WalkingState::Starting: return "starting";
    case WalkingState::Walking: return "walking";
    case WalkingState::Stopping: return "stopping";
    case WalkingState::SafeStop: return "safe_stop";
    case WalkingState::Fallen: return "fallen";
  }
  return "unknown";
}

StepDecision WalkingStateMachine::update(bool wants_to_walk, bool at_touchdown, bool must_step) {
  switch (state_) {
    case WalkingState::Standing:
      if (!wants_to_walk && !must_step) return StepDecision::None;
      state_ = WalkingState::Starting;
      return StepDecision::StartWalk;
    case WalkingState::Starting:
    case WalkingState::Walking:
      if (!at_touchdown) return StepDecision::None;
      if (wants_to_walk || must_step) {
        state_ = WalkingState::Walking;
        return StepDecision::Continue;
      }
      state_ = WalkingState::Stopping;
      return StepDecision::StopStep;
    case WalkingState::Stopping:
      if (!at_touchdown) return StepDecision::None;
      if (must_step) {
        state_ = WalkingState::Walking;
        return StepDecision::Continue;
      }
      state_ = WalkingState::Standing;
      return StepDecision::Stand;
    case WalkingState::SafeStop:
      // Standing at the end of the safe stop: a recovery step, then the stop again.
      if (stop_progress_ == WalkingState::Standing && must_step) {
        stop_progress_ = WalkingState::Starting;
        return StepDecision::StartWalk;
      }
      if (!at_touchdown) return StepDecision::None;
      if (stop_progress_ == WalkingState::Starting || stop_progress_ == WalkingState::Walking) {
        // Too fast to stop in one step: slow down; or not balanced enough to stand.
        if (wants_to_walk || must_step) return StepDecision::Continue;
        stop_progress_ = WalkingState::Stopping;
        return StepDecision::StopStep;
      }
      if (stop_progress_ == WalkingState::Stopping) {
        if (must_step) {
          stop_progress_ = WalkingState::Walking;
          return StepDecision::Continue;
        }
        stop_progress_ = WalkingState::Standing;
        return StepDecision::Stand;
      }
      return StepDecision::None;
    case WalkingState::Fallen:
      return StepDecision::None;
  }
  return StepDecision::None;
}

void WalkingStateMachine::enter_safe_stop() {
  if (state_ == WalkingState::SafeStop || state_ == WalkingState::Fallen) return;
  stop_progress_ = state_;
  state_ = WalkingState::SafeStop;
}

}  // namespace biped
