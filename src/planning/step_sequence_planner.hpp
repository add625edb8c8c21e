#pragma once
// Step sequence planner (Fig. 3): from the joystick command, the next three footsteps (position,
// heading, touchdown time) along the path of a "heading frame" that moves with the commanded
// velocity (vx, vy in the heading frame, ω turning), one step time per step. Commands outside the
// feasible range (from the off-line tables) are saturated, and the caller is told.
#include <array>

#include "planning/footstep.hpp"

namespace biped {

struct CommandLimits {
  double vx_min = -0.3, vx_max = 1.0;  // [m/s]
  // [m] a step table bounds vx_max to its fastest row with more than this ZMP margin: LOLA's 1.0 m/s
  // row has 0.5 mm, and reversals of the joystick between −0.3 and 1.0 m/s felled it in 7 of 10
  // random timelines (0 of 10 bounded to its 0.8 m/s row, 45 mm).
  double min_zmp_margin = 0.02;
  // [m/s²] the gait's forward speed changes by at most this × step time per step, starts from
  // standing and stops included: LOLA fell starting at 1.0 m/s in one step and stopping from it.
  double vx_rate = 0.5;
  double vy_max = 0.15;                // [m/s] either side
  double omega_max = 0.5;              // [rad/s] either side
  // [m/s²], [rad/s²] the gait's sideways speed and turn rate change by at most these × step time per
  // step, as vx does: a joystick reversed from one side to the other takes the robot through a few
  // steps in place of one step from the outer foot straight onto the other side.
  double vy_rate = 0.15;
  double omega_rate = 0.5;
  // Share of vx_max left to the forward speed at the full sideways speed or turn rate: the forward
  // speed's bound falls linearly from vx_max (no sideways speed, no turn) to this share of it, as a
  // car slows for a curve. Going faster, the plan first slows and then widens its sideways speed
  // and turn rate (1: no such bound). LOLA bounded to 0.8 m/s fell in 7 of 10 random timelines that
  // slam all three at their limits (6 without turning, 4 without sideways speed), none with vx at
  // most 0.6 m/s.
  double lateral_vx_share = 0.75;
};

// The planner's view of the joystick (kept free of the controller's types).
struct VelocityCommand {
  double vx = 0.0, vy = 0.0, omega = 0.0;
};

// Returns the command clamped to the limits, the forward speed also to the bound its sideways speed
// and turn rate leave; `saturated` tells whether anything was clamped.
VelocityCommand saturate(const VelocityCommand& command, const CommandLimits& limits, bool& saturated);

// The bound on the forward speed that a sideways speed and a turn rate leave (lateral_vx_share).
double forward_speed_bound(const CommandLimits& limits, double vy, double omega);

// The share of the sideways speed's and the turn rate's ranges that a forward speed leaves: the
// inverse of forward_speed_bound (1: the full ranges).
double lateral_share_left(const CommandLimits& limits, double vx);

// `current` moved towards `target` by at most `max_change`.
double ramp_towards(double current, double target, double max_change);

// The heading frame after moving for `duration` with a constant command (exact arc).
PlanarPose advance(const PlanarPose& pose, const VelocityCommand& v, double duration);

// The heading frame that has `stance` at its nominal place (half a step width to the side).
PlanarPose heading_of_stance(const Footstep& stance, double step_width);

// The next `count` (≤ 3) footsteps, alternating, the first by the foot opposite `stance` and
// touching down at `first_touchdown`. The heading frame starts at the stance foot's nominal place
// and advances one step time per step; a zero command places the swing foot beside the stance foot
// (a stop).
void plan_steps(const Footstep& stance, const VelocityCommand& v, const StepParameters& p, double first_touchdown,
                int count, std::array<Footstep, 3>& steps);

}  // namespace biped
