#include "control/upper_body_lean.hpp"

#include <algorithm>
#include <cmath>

namespace biped {

void UpperBodyLean::reset() {
  angle_.setZero();
  rate_.setZero();
}

void UpperBodyLean::update(double dt, const Eigen::Vector2d& dcm_error, bool active) {
  Eigen::Vector2d target = Eigen::Vector2d::Zero();
  if (active && params_.enabled && dcm_error.allFinite()) {
    const double dead_band[2] = {params_.dead_band_forward, params_.dead_band_sideways};
    for (int a = 0; a < 2; ++a) {
      const double beyond = std::max(0.0, std::abs(dcm_error[a]) - dead_band[a]);
      target[a] = std::copysign(std::min(params_.max_angle, params_.gain * beyond), dcm_error[a]);
    }
  }
  // Critically damped second order towards the target, its rate and angle bounded.
  for (int a = 0; a < 2; ++a) {
    const bool returning = std::abs(target[a]) < std::abs(angle_[a]) && target[a] * angle_[a] >= 0.0;
    const double w = returning ? params_.return_frequency : params_.frequency;
    const double acceleration = w * w * (target[a] - angle_[a]) - 2.0 * w * rate_[a];
    rate_[a] = std::clamp(rate_[a] + dt * acceleration, -params_.max_rate, params_.max_rate);
    angle_[a] = std::clamp(angle_[a] + dt * rate_[a], -params_.max_angle, params_.max_angle);
  }
}

}  // namespace biped
