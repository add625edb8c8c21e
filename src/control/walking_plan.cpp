#include "control/walking_plan.hpp"

#include <algorithm>
#include <cmath>

namespace biped {
namespace {

PatternGeneratorParams pattern_params(const RobotModel& model, const WalkingPlanParams& params) {
  PatternGeneratorParams p = simplified_model_of(model);
  p.arm_swing_gain = params.arm_swing_gain;
  return p;
}

}  // namespace

WalkingPlan::WalkingPlan(const RobotModel& model, const WalkingPlanParams& params)
    : params_(params), step_(params.step), pattern_(pattern_params(model, params)) {}

void WalkingPlan::reset(const std::array<Footstep, 2>& feet, const Eigen::Vector3d& com) {
  fsm_ = WalkingStateMachine{};
  feet_ = feet;
  num_planned_ = 0;
  planned_vx_ = 0.0;
  planned_vy_ = 0.0;
  planned_omega_ = 0.0;
  command_saturated_ = false;
  steps_completed_ = 0;
  landing_shift_.setZero();
  landing_shift_rate_.setZero();
  measured_valid_ = false;
  max_next_step_time_ = 0.0;
  unbalanced_ = false;
  balance_steps_ = 0;
  standing_step_ = false;
  replans_from_measured_ = 0;
  step_ = params_.step;
  step_.com_height = com.z();
  step_.step_width = (feet_[0].position - feet_[1].position).norm();

  // Body mass point of the simplified model so that its CoM is the robot's.
  const PatternGeneratorParams& p = pattern_.params();
  const double m_total = p.body_mass + 2.0 * p.leg_mass;
  AxisState bx, by;
  bx.position = (m_total * com.x() - p.leg_mass * (feet_[0].position.x() + feet_[1].position.x())) / p.body_mass;
  by.position = (m_total * com.y() - p.leg_mass * (feet_[0].position.y() + feet_[1].position.y())) / p.body_mass;
  pattern_.replan(0.0, feet_, planned_, 0, step_, bx, by, com.head<2>());
  pattern_.sample(0.0, sample_);
}

double WalkingPlan::max_speed_change() const {
  return params_.limits.vx_rate * params_.table.lookup(planned_vx_, step_).step_time;
}

const PatternSample& WalkingPlan::advance(double t, const WalkCommand& command) {
  const VelocityCommand v = saturate({command.vx, command.vy, command.omega}, params_.limits, command_saturated_);
  const bool commanded = !command.stop && fsm_.state() != WalkingState::SafeStop &&
                         (std::abs(v.vx) + std::abs(v.vy) + std::abs(v.omega) > 1e-3);
  // Too fast to stop in one step: keep walking and slow down first.
  const bool wants_to_walk = commanded || std::abs(planned_vx_) > max_speed_change() + 1e-9;
  const bool at_touchdown = num_planned_ > 0 && t >= pattern_.next_touchdown() - 1e-9;
  if (at_touchdown) {
    Footstep landed = planned_[0];
    landed.position += landing_shift_;
    feet_[index_of(landed.side)] = landed;
    ++steps_completed_;
    landing_shift_.setZero();
    landing_shift_rate_.setZero();
  }
  const bool must_step = fsm_.standing() ? standing_step_ : unbalanced_ && balance_steps_ < max_balance_steps_;
  const StepDecision decision = fsm_.update(wants_to_walk, at_touchdown, must_step);
  const bool balance_step = (decision == StepDecision::Continue || decision == StepDecision::StartWalk) && !wants_to_walk;
  // Counted until the robot walks on by command or stands: the stop step after the last of them
  // does not start a new count.
  if (balance_step) {
    ++balance_steps_;
  } else if (decision == StepDecision::Continue || decision == StepDecision::Stand) {
    balance_steps_ = 0;
  }
  replan(t, decision, commanded ? v : VelocityCommand{}, balance_step);
  pattern_.sample(t, sample_);
  for (FootReference& foot : sample_.feet) {
    if (foot.in_contact) continue;
    foot.position.head<2>() += foot.swing_progress * landing_shift_;
    foot.velocity.head<2>() += foot.swing_progress_rate * landing_shift_ + foot.swing_progress * landing_shift_rate_;
  }
  return sample_;
}

void WalkingPlan::set_measured_com(const Eigen::Vector2d& position, const Eigen::Vector2d& velocity, double threshold,
                                   bool valid) {
  measured_com_ = position;
  measured_com_velocity_ = velocity;
  replan_threshold_ = threshold;
  measured_valid_ = valid;
}

void WalkingPlan::shift_landing(const Eigen::Vector2d& shift, const Eigen::Vector2d& shift_rate) {
  landing_shift_ = shift;
  landing_shift_rate_ = shift_rate;
}

void WalkingPlan::replan(double t, StepDecision decision, const VelocityCommand& command, bool recovery) {
  if (decision == StepDecision::None) return;
  const bool walking = decision == StepDecision::StartWalk || decision == StepDecision::Continue;
  const double step_time = params_.table.lookup(planned_vx_, step_).step_time;
  // Sideways speed and turn rate first, as far as the present forward speed leaves room for them;
  // then the forward speed, as far as they leave room for it: the plan stays inside the limits'
  // combined bound (a car slows before the curve).
  const CommandLimits& limits = params_.limits;
  const double lateral = lateral_share_left(limits, planned_vx_);
  planned_vy_ = walking ? std::clamp(ramp_towards(planned_vy_, command.vy, limits.vy_rate * step_time),
                                     -lateral * limits.vy_max, lateral * limits.vy_max)
                        : 0.0;
  planned_omega_ = walking ? std::clamp(ramp_towards(planned_omega_, command.omega, limits.omega_rate * step_time),
                                        -lateral * limits.omega_max, lateral * limits.omega_max)
                           : 0.0;
  planned_vx_ = walking ? ramp_towards(planned_vx_, std::min(command.vx, forward_speed_bound(limits, planned_vy_, planned_omega_)),
                                       max_speed_change())
                        : 0.0;
  const VelocityCommand v{planned_vx_, planned_vy_, planned_omega_};
  PatternSample now;
  pattern_.sample(t, now);
  if (measured_valid_) {
    // The body mass point that puts the simplified model's CoM at the measured one, the legs where
    // the plan has them (at a touchdown they stand still).
    const PatternGeneratorParams& p = pattern_.params();
    const double omega = std::sqrt(p.gravity / std::max(0.3, now.com.z()));
    const Eigen::Vector2d deviation = (measured_com_ - now.com.head<2>()) +
                                      (measured_com_velocity_ - now.com_velocity.head<2>()) / omega;
    if (deviation.norm() > replan_threshold_) {
      const double m_total = p.body_mass + 2.0 * p.leg_mass;
      Eigen::Vector2d legs = Eigen::Vector2d::Zero(), legs_velocity = Eigen::Vector2d::Zero();
      for (const FootReference& foot : now.feet) {
        legs += foot.position.head<2>();
        legs_velocity += foot.velocity.head<2>();
      }
      const Eigen::Vector2d body = (m_total * measured_com_ - p.leg_mass * legs) / p.body_mass;
      const Eigen::Vector2d body_velocity = (m_total * measured_com_velocity_ - p.leg_mass * legs_velocity) / p.body_mass;
      now.body_x = {body.x(), body_velocity.x(), 0.0};
      now.body_y = {body.y(), body_velocity.y(), 0.0};
      ++replans_from_measured_;
    }
  }
  StepParameters step = params_.table.lookup(decision == StepDecision::StopStep ? 0.0 : v.vx, step_);
  const bool at_touchdown = decision == StepDecision::Continue || decision == StepDecision::StopStep;
  if (at_touchdown && max_next_step_time_ > 0.0) step.step_time = std::min(step.step_time, max_next_step_time_);
  switch (decision) {
    case StepDecision::StartWalk: {
      // Step first with the foot on the side the robot moves or turns to; a recovery step at once
      // with the foot it was given.
      const Side first_swing = recovery ? standing_step_swing_
                               : (v.vy > 1e-3 || (std::abs(v.vy) <= 1e-3 && v.omega > 1e-3)) ? Side::Left
                                                                                           : Side::Right;
      const double shift = recovery ? 0.0 : params_.start_shift;
      plan_steps(feet_[index_of(other(first_swing))], v, step, t + step.step_time + shift, 3, planned_);
      num_planned_ = 3;
      break;
    }
    case StepDecision::Continue:
      plan_steps(feet_[index_of(planned_[0].side)], v, step, t + step.step_time, 3, planned_);
      num_planned_ = 3;
      break;
    case StepDecision::StopStep:
      plan_steps(feet_[index_of(planned_[0].side)], VelocityCommand{}, step, t + step.step_time, 1, planned_);
      num_planned_ = 1;
      break;
    case StepDecision::Stand:
      num_planned_ = 0;
      break;
    case StepDecision::None:
      return;
  }
  pattern_.replan(t, feet_, planned_, num_planned_, step, now.body_x, now.body_y, now.zmp);
}

}  // namespace biped
