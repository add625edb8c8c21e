#include "planning/step_sequence_planner.hpp"

#include <algorithm>
#include <cmath>

namespace biped {

VelocityCommand saturate(const VelocityCommand& c, const CommandLimits& limits, bool& saturated) {
  VelocityCommand out;
  out.vx = std::clamp(c.vx, limits.vx_min, limits.vx_max);
  out.vy = std::clamp(c.vy, -limits.vy_max, limits.vy_max);
  out.omega = std::clamp(c.omega, -limits.omega_max, limits.omega_max);
  out.vx = std::min(out.vx, forward_speed_bound(limits, out.vy, out.omega));
  saturated = out.vx != c.vx || out.vy != c.vy || out.omega != c.omega;
  return out;
}

double forward_speed_bound(const CommandLimits& limits, double vy, double omega) {
  const double sideways = limits.vy_max > 0.0 ? std::abs(vy) / limits.vy_max : 0.0;
  const double turning = limits.omega_max > 0.0 ? std::abs(omega) / limits.omega_max : 0.0;
  const double lateral = std::min(1.0, std::max(sideways, turning));
  return limits.vx_max * (1.0 - (1.0 - limits.lateral_vx_share) * lateral);
}

double lateral_share_left(const CommandLimits& limits, double vx) {
  const double given_up = (1.0 - limits.lateral_vx_share) * limits.vx_max;
  if (vx <= limits.vx_max - given_up) return 1.0;
  return std::clamp((limits.vx_max - vx) / given_up, 0.0, 1.0);
}

double ramp_towards(double current, double target, double max_change) {
  return current + std::clamp(target - current, -max_change, max_change);
}

PlanarPose advance(const PlanarPose& pose, const VelocityCommand& v, double duration) {
  const double dyaw = v.omega * duration;
  // Displacement in the starting heading frame of a constant body velocity turning at ω.
  double dx, dy;
  if (std::abs(dyaw) < 1e-9) {
    dx = v.vx * duration;
    dy = v.vy * duration;
  } else {
    const double s = std::sin(dyaw), c = std::cos(dyaw);
    dx = (v.vx * s + v.vy * (c - 1.0)) / v.omega;
    dy = (v.vx * (1.0 - c) + v.vy * s) / v.omega;
  }
  const double cy = std::cos(pose.yaw), sy = std::sin(pose.yaw);
  PlanarPose out;
  out.position = pose.position + Eigen::Vector2d(cy * dx - sy * dy, sy * dx + cy * dy);
  out.yaw = pose.yaw + dyaw;
  return out;
}

PlanarPose heading_of_stance(const Footstep& stance, double step_width) {
  const double lateral = (stance.side == Side::Left ? -0.5 : 0.5) * step_width;
  PlanarPose h;
  h.yaw = stance.yaw;
  h.position = stance.position + lateral * Eigen::Vector2d(-std::sin(stance.yaw), std::cos(stance.yaw));
  return h;
}

void plan_steps(const Footstep& stance, const VelocityCommand& v, const StepParameters& p, double first_touchdown,
                int count, std::array<Footstep, 3>& steps) {
  PlanarPose h = heading_of_stance(stance, p.step_width);
  Side side = stance.side == Side::Left ? Side::Right : Side::Left;
  // Sideways, the foot on the side of the motion leads: its step moves the heading frame by 2·vy·T
  // and the other foot's by none, so the trailing foot closes to the step width instead of coming
  // vy·T closer than it, and vy is kept on average.
  const Side leading = v.vy >= 0.0 ? Side::Left : Side::Right;
  for (int k = 0; k < std::min(count, 3); ++k) {
    VelocityCommand step_velocity = v;
    step_velocity.vy = side == leading ? 2.0 * v.vy : 0.0;
    h = advance(h, step_velocity, p.step_time);
    const double lateral = (side == Side::Left ? 0.5 : -0.5) * p.step_width;
    Footstep& f = steps[k];
    f.side = side;
    f.yaw = h.yaw;
    f.position = h.position + lateral * Eigen::Vector2d(-std::sin(h.yaw), std::cos(h.yaw));
    f.touchdown = first_touchdown + k * p.step_time;
    side = side == Side::Left ? Side::Right : Side::Left;
  }
}

}  // namespace biped
