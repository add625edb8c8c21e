#pragma once
// The planning half of Fig. 3 inside the controller, advanced once per cycle: the walking state
// machine decides at touchdowns, the step sequence planner places the next three footsteps with
// the parameters of the off-line step table, and the walking pattern generator replans through
// them; every cycle then samples the pattern. It needs no sensors: it is what the robot would do on
// the ground the plan assumes.
#include <array>

#include "control/walking_state_machine.hpp"
#include "interface/commands.hpp"
#include "model/robot_model.hpp"
#include "planning/footstep.hpp"
#include "planning/step_sequence_planner.hpp"
#include "planning/step_table.hpp"
#include "planning/walking_pattern_generator.hpp"

namespace biped {

struct WalkingPlanParams {
  StepParameters step;            // step time, double support, clearance (width, com_height: measured at reset)
  StepTable table;                // off-line table: step time, double support, clearance by speed (empty: `step`)
  CommandLimits limits;           // feasible commands; beyond them the command is saturated
  double start_shift = 0.6;       // [s] extra double support before the first step from standing
  double arm_swing_gain = 0.1;    // arm CoM forward offset per metre of foot separation
};

class WalkingPlan {
 public:
  static constexpr int kMaxSteps = WalkingPatternGenerator::kMaxSteps;

  WalkingPlan(const RobotModel& model, const WalkingPlanParams& params);

  // Standing on `feet` (by Side; controller frame, t = 0) with the robot's CoM at `com`.
  void reset(const std::array<Footstep, 2>& feet, const Eigen::Vector3d& com);
  // One cycle at time t since the reset: the command is saturated to the limits, a touchdown makes
  // the landed step the new foothold and lets the FSM decide, and the pattern is sampled at t.
  const PatternSample& advance(double t, const WalkCommand& command);
  // The step in the air lands `shift` (controller frame) away from its planned foothold (step
  // adaptation): the swing foot's reference gains s·shift (s: the swing's progress) and the rate
  // ṡ·shift + s·shift_rate, and at touchdown the foothold is the shifted one. Cleared at touchdown.
  void shift_landing(const Eigen::Vector2d& shift, const Eigen::Vector2d& shift_rate);
  // Step timing (step adaptation): the steps planned at the next touchdown last at most
  // `max_step_time` [s] each (0: the table's step time). Set every cycle.
  void limit_next_step_time(double max_step_time) { max_next_step_time_ = max_step_time; }
  // Balance before a stop (step adaptation): while `unbalanced`, a touchdown that would stop or
  // stand plans more steps with a zero command instead, at most `max_steps` such touchdowns in a
  // row. Set every cycle.
  void keep_stepping(bool unbalanced, int max_steps) {
    unbalanced_ = unbalanced;
    max_balance_steps_ = max_steps;
  }
  // Recovery step from standing (step adaptation): standing (standing()), `needed` starts steps
  // with a zero command at once, `swing` first and without the start's weight shift
  // (`start_shift`); keep_stepping() then decides at their touchdowns. Set every cycle.
  void step_from_standing(bool needed, Side swing) {
    standing_step_ = needed;
    standing_step_swing_ = swing;
  }
  // The robot's CoM as the state estimate has it (controller frame) and its velocity: the next
  // replanning at a touchdown starts from it instead of the plan's own state when they differ by
  // more than `threshold` [m] (position plus velocity / ω₀). `valid` false: from the plan's state.
  void set_measured_com(const Eigen::Vector2d& position, const Eigen::Vector2d& velocity, double threshold, bool valid);
  // A sensor fault: finish the step under way, put the feet side by side, stand.
  void enter_safe_stop() { fsm_.enter_safe_stop(); }
  // The robot has fallen: advance() is not called any more.
  void enter_fallen() { fsm_.enter_fallen(); }

  WalkingState state() const { return fsm_.state(); }
  bool standing() const { return fsm_.standing(); }  // WalkingStateMachine::standing()
  const PatternSample& sample() const { return sample_; }
  bool command_saturated() const { return command_saturated_; }  // in the last advance()
  // The gait's speed and turn rate as planned at the last replanning (the command shaped).
  VelocityCommand planned_velocity() const { return {planned_vx_, planned_vy_, planned_omega_}; }
  int steps_completed() const { return steps_completed_; }
  // Steps planned in a row only to keep the balance (keep_stepping).
  int balance_steps() const { return balance_steps_; }
  int replans_from_measured() const { return replans_from_measured_; }
  int num_planned_steps() const { return num_planned_; }
  const Footstep& planned_step(int i) const { return planned_[i]; }
  const WalkingPatternGenerator& pattern_generator() const { return pattern_; }
  // The largest change of the gait's forward speed in one step (limits.vx_rate × step time).
  double max_speed_change() const;

 private:
  // Plans with the command's vx, vy and ω ramped from the current plan's (StartWalk, Continue);
  // `recovery`: a StartWalk to keep the balance (step_from_standing).
  void replan(double t, StepDecision decision, const VelocityCommand& command, bool recovery);

  WalkingPlanParams params_;
  StepParameters step_;                       // params_.step with the measured width and CoM height
  WalkingPatternGenerator pattern_;
  WalkingStateMachine fsm_;
  std::array<Footstep, 2> feet_;              // current footholds (by Side)
  std::array<Footstep, kMaxSteps> planned_;   // steps of the current plan
  int num_planned_ = 0;
  double planned_vx_ = 0.0;                   // forward speed of the current plan (ramped, limits.vx_rate)
  double planned_vy_ = 0.0;                   // its sideways speed (ramped, limits.vy_rate)
  double planned_omega_ = 0.0;                // its turn rate (ramped, limits.omega_rate)
  PatternSample sample_;
  Eigen::Vector2d landing_shift_ = Eigen::Vector2d::Zero(), landing_shift_rate_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d measured_com_ = Eigen::Vector2d::Zero(), measured_com_velocity_ = Eigen::Vector2d::Zero();
  double replan_threshold_ = 0.0;
  double max_next_step_time_ = 0.0;
  bool unbalanced_ = false;
  int max_balance_steps_ = 0;
  int balance_steps_ = 0;
  bool standing_step_ = false;
  Side standing_step_swing_ = Side::Right;
  bool measured_valid_ = false;
  int replans_from_measured_ = 0;
  bool command_saturated_ = false;
  int steps_completed_ = 0;
};

}  // namespace biped
