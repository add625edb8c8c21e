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

StepDecision WalkingStateMachine::update(bool wants_to_walk, bool at_touchdown) {
  switch (state_) {
    case WalkingState::Standing:
      if (!wants_to_walk) return StepDecision::None;
      state_ = WalkingState::Starting;
      return StepDecision::StartWalk;
    case WalkingState::Starting:
    case WalkingState::Walking:
      if (!at_touchdown) return StepDecision::None;
      if (wants_to_walk) {
        state_ = WalkingState::Walking;
        return StepDecision::Continue;
      }
      state_ = WalkingState::Stopping;
      return StepDecision::StopStep;
    case WalkingState::Stopping:
      if (!at_touchdown) return StepDecision::None;
      state_ = WalkingState::Standing;
      return StepDecision::Stand;
    case WalkingState::SafeStop:
      if (!at_touchdown) return StepDecision::None;
      if (stop_progress_ == WalkingState::Starting || stop_progress_ == WalkingState::Walking) {
        if (wants_to_walk) return StepDecision::Continue;  // too fast to stop in one step: slow down
        stop_progress_ = WalkingState::Stopping;
        return StepDecision::StopStep;
      }
      if (stop_progress_ == WalkingState::Stopping) {
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
