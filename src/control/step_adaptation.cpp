#include "control/step_adaptation.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace biped {

void StepAdaptation::reset() {
  shift_.setZero();
  rate_.setZero();
  dcm_error_.setZero();
}

void StepAdaptation::idle() {
  shift_.setZero();
  rate_.setZero();
}

double StepAdaptation::error_beyond_dead_band() const {
  if (!dcm_error_.allFinite()) return NAN;
  const Eigen::Vector2d beyond(std::max(0.0, std::abs(dcm_error_.x()) - params_.dead_band_forward),
                               std::max(0.0, std::abs(dcm_error_.y()) - params_.dead_band_sideways));
  return beyond.norm();
}

double StepAdaptation::max_next_step_time() const {
  if (!params_.enabled || params_.quick_step_time <= 0.0) return 0.0;
  return error_beyond_dead_band() > params_.quick_step_error ? params_.quick_step_time : 0.0;
}

bool StepAdaptation::unbalanced() const {
  return params_.enabled && params_.balance_steps > 0 && error_beyond_dead_band() > params_.balance_error;
}

void StepAdaptation::update(double dt, const StepAdaptationInput& in) {
  const double omega = std::sqrt(in.gravity / in.com_height);
  dcm_error_ = (in.measured_com - in.planned_com) + (in.measured_com_rate - in.planned_com_rate) / omega;
  if (!params_.enabled || !dcm_error_.allFinite() || in.time_to_touchdown < params_.freeze_time ||
      in.swing_foot_on_ground) {
    rate_.setZero();
    return;
  }
  // Per axis, what the centre of pressure cannot absorb by touchdown, as it will be then.
  const double growth = std::exp(omega * in.time_to_touchdown);
  const double absorbable = 1.0 - 1.0 / growth;
  const double s = params_.cop_reach_share;
  const std::array<double, 2> reach_plus = {s * in.cop_forward, s * in.cop_sideways};
  const std::array<double, 2> reach_minus = {s * in.cop_backward, s * in.cop_sideways};
  const std::array<double, 2> dead_band = {params_.dead_band_forward, params_.dead_band_sideways};
  Eigen::Vector2d target = Eigen::Vector2d::Zero();
  for (int a = 0; a < 2; ++a) {
    const double e = std::copysign(std::max(0.0, std::abs(dcm_error_[a]) - dead_band[a]), dcm_error_[a]);
    const double cop_shift = std::clamp(e / absorbable, -reach_minus[a], reach_plus[a]);
    const double left = (e - cop_shift) * growth + cop_shift;
    if (std::abs(e) > std::abs(cop_shift) * absorbable + 1e-12) target[a] = params_.gain * left;
  }
  // Reach: along the heading, and sideways away from / towards the stance foot; the feet keep
  // their distance sideways.
  target.x() = std::clamp(target.x(), -params_.max_backward, params_.max_forward);
  const double outward = in.swing == Side::Left ? 1.0 : -1.0;
  const double separation = outward * in.planned_landing.y();  // planned sideways distance from the stance foot
  const double inward_room = std::clamp(separation - params_.min_width, 0.0, params_.max_inward);
  target.y() = outward * std::clamp(outward * target.y(), -inward_room, params_.max_outward);

  const Eigen::Vector2d before = shift_;
  shift_ += dt / (params_.filter_time + dt) * (target - shift_);
  const Eigen::Vector2d step = shift_ - before;
  const double limit = params_.max_rate * dt;
  if (step.norm() > limit) shift_ = before + step * (limit / step.norm());
  rate_ = (shift_ - before) / dt;
}

}  // namespace biped
