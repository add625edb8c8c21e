#pragma once
// Step adaptation (an extension beyond the paper's method): where the foot in the air lands, from
// the measured state. The divergent component of motion (DCM, the capture point of the linear
// inverted pendulum) ξ = c + ċ/ω₀, ω₀ = √(g/z_c), runs away from the centre of pressure as
// e^{ω₀t}; the stabilizer's centre of pressure stays inside the stance sole, so a DCM error
// (measured − planned) e₀ evolves with a centre of pressure shifted by Δp from the plan as
// e(t) = (e₀ − Δp) e^{ω₀t} + Δp. The stance sole can absorb it by touchdown (time T) when
// |e₀| ≤ |Δp|(1 − e^{−ω₀T}) with Δp inside the sole's reach; beyond that the swing foot's landing
// point is shifted by what remains at touchdown, (e₀ − Δp) e^{ω₀T} + Δp with Δp at the reach
// (times a gain), inside the legs' reach and without the feet colliding, so that the next stance
// foot is where the robot is going. The planner then continues from the foothold where the foot
// landed, and, at a touchdown, from the measured CoM when the plan has lost it.
#include <Eigen/Core>

#include "math/side.hpp"

namespace biped {

struct StepAdaptationParams {
  // On against off: pushes survived and runs of LOLA's and JOHNNIE's training campaigns
  // (docs/stabilizer.md, "Step adaptation").
  bool enabled = true;
  double gain = 1.0;             // share of the DCM error left at touchdown taken up by the step
  // [-] share of the CoP's reach in the stance sole counted on for absorbing the DCM error (the rest
  // is kept for the stabilizer's balancing of the remaining motion)
  double cop_reach_share = 0.5;
  // [m] DCM errors up to these (along the heading, sideways) are the state estimate's own scatter in
  // undisturbed walking and are left to the stabilizer; only the part beyond them moves a step.
  double dead_band_forward = 0.06;
  double dead_band_sideways = 0.04;
  double max_forward = 0.15;     // [m] shift of the landing point along the heading, forward ...
  double max_backward = 0.10;    // [m] ... and backward
  double max_outward = 0.10;     // [m] sideways, away from the stance foot ...
  double max_inward = 0.06;      // [m] ... and towards it
  double min_width = 0.13;       // [m] the feet's centres stay at least this far apart sideways (collision)
  double filter_time = 0.02;     // [s] first-order filter of the shift
  double max_rate = 1.0;         // [m/s] the landing point moves at most this fast
  double freeze_time = 0.06;     // [s] the landing point is held this long before touchdown
  // At a touchdown, the pattern is replanned from the measured CoM state instead of its own when
  // their DCMs differ by more than `replan_threshold` [m] (the plan then continues from where the
  // robot is). Off: it cost pushes as much as 3 N·s and gained none (docs/stabilizer.md).
  bool replan = false;
  double replan_threshold = 0.08;
  // Step timing: a DCM error beyond the dead band larger than `quick_step_error` [m] at the end of a
  // swing makes the steps planned at its touchdown quick, at most `quick_step_time` [s] each (0: off),
  // so that the next foot reaches the DCM before it has run far. Off: with 0.6 s it changed neither
  // LOLA's push map nor its training campaign measurably (docs/stabilizer.md).
  double quick_step_time = 0.0;
  double quick_step_error = 0.05;
  // Balance before a stop: a touchdown that would end a walk (a stop, the safe stop's last step)
  // while the DCM error beyond the dead band exceeds `balance_error` [m] plans more steps instead
  // (with a zero command, the adaptation moving their landings), at most `balance_steps` in a row
  // (0: off), so that the robot does not come to stand with its DCM outside its feet.
  int balance_steps = 4;
  double balance_error = 0.02;
  // Recovery step from standing: standing (after a stop, before the first command, or at the end
  // of a safe stop), a measured DCM within `standing_step_margin` [m] of the edge of the feet's support,
  // or beyond it, starts steps at once, without the start's weight shift, and the balance before a
  // stop keeps them going until the DCM is back (`balance_steps` counts the first step too; 0
  // switches this off as well). Without, only the centre of pressure catches a push: LOLA
  // standing held 21-23 N·s in every direction, 25 with it (docs/stabilizer.md).
  bool standing_step = true;
  double standing_step_margin = 0.02;
};

// What one cycle of the adaptation reads, all in the heading frame (x forward, y left) relative to
// the stance foot.
struct StepAdaptationInput {
  Side swing = Side::Left;
  double time_to_touchdown = 0.0;                          // [s] of the swing foot
  Eigen::Vector2d planned_com = Eigen::Vector2d::Zero();   // [m] and its rate [m/s]
  Eigen::Vector2d planned_com_rate = Eigen::Vector2d::Zero();
  Eigen::Vector2d measured_com = Eigen::Vector2d::Zero();  // the state estimate
  Eigen::Vector2d measured_com_rate = Eigen::Vector2d::Zero();
  Eigen::Vector2d planned_landing = Eigen::Vector2d::Zero();  // the swing foot's planned foothold
  // How far the centre of pressure can move in the stance sole from the planned one: forward,
  // backward, sideways (each ≥ 0) [m].
  double cop_forward = 0.05, cop_backward = 0.05, cop_sideways = 0.03;
  double com_height = 0.9;                                 // [m] z_c of ω₀
  bool swing_foot_on_ground = false;  // the swing foot's measured normal force says it has landed (early)
  double gravity = 9.81;
};

class StepAdaptation {
 public:
  explicit StepAdaptation(const StepAdaptationParams& params) : params_(params) {}
  void reset();
  // One cycle of a swing: updates the shift of the landing point.
  void update(double dt, const StepAdaptationInput& in);
  // On the ground (no swing): the shift returns to zero at once (the next swing starts from its plan).
  void idle();

  // Shift of the landing point [m] and its rate [m/s] (heading frame).
  const Eigen::Vector2d& shift() const { return shift_; }
  const Eigen::Vector2d& shift_rate() const { return rate_; }
  // DCM error (measured − planned) of the last update [m] (heading frame).
  const Eigen::Vector2d& dcm_error() const { return dcm_error_; }
  // The longest step time the steps planned at the coming touchdown may have [s] (0: the table's):
  // `quick_step_time` while the DCM error beyond the dead band exceeds `quick_step_error`.
  double max_next_step_time() const;
  // The last update's DCM error is too large to stand: more steps are wanted (`balance_error`).
  bool unbalanced() const;

 private:
  // |DCM error beyond the dead band| of the last update [m]; NaN when the error is not finite.
  double error_beyond_dead_band() const;

  StepAdaptationParams params_;
  Eigen::Vector2d shift_ = Eigen::Vector2d::Zero(), rate_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d dcm_error_ = Eigen::Vector2d::Zero();
};

}  // namespace biped
