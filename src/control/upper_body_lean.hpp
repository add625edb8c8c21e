#pragma once
// Upper-body lean, the "hip strategy" (an extension beyond the paper's method): when the DCM error
// outgrows what the stance sole's centre of pressure and the next step take up, the upper body is
// turned about the hips towards the error. Turning it takes angular momentum from the rest of the
// robot: while the upper body accelerates, the ground's horizontal force pushes the CoM back as if
// the centre of pressure lay beyond the sole (the centroidal moment pivot). A lean θ reached
// quickly moves the DCM back by about I θ / (m z_c) (I: the upper body's inertia about the hips),
// and that correction grows like the error it counters; going upright again later gives it back
// where the next stance foot can take it.
// The lean is the upper body's planned inclination: eq. (21)'s upper-body orientation rows follow
// it (the feet's orientation rows, relative to the upper body, turn the other way so the feet stay
// level), and eq. (10)'s tilt error is taken against it.
#include <Eigen/Core>

namespace biped {

struct UpperBodyLeanParams {
  // On against off (docs/stabilizer.md, "Upper-body lean"): early sideways pushes of 10-13 N·s at
  // 0.3 m/s caught 17 of 24 times against 6; LOLA's held-out user campaign unchanged (95.2 % against
  // 95.0 %).
  bool enabled = true;
  // [rad/m] lean per metre of DCM error (measured − planned, heading frame) beyond the dead band.
  double gain = 4.0;
  // [m] DCM errors up to these (along the heading, sideways) are the state estimate's scatter in
  // undisturbed walking (the step adaptation's dead band) and do not lean the upper body.
  double dead_band_forward = 0.06;
  double dead_band_sideways = 0.04;
  double max_angle = 0.2;   // [rad] bound of the lean about each axis
  double frequency = 15.0;  // [rad/s] natural frequency of the critically damped filter the lean follows
  // [rad/s] ... when the lean goes back towards upright: going back gives the DCM correction back,
  // slowly enough for the centre of pressure to take it.
  double return_frequency = 1.5;
  double max_rate = 3.0;    // [rad/s] bound of the lean's rate about each axis
};

class UpperBodyLean {
 public:
  explicit UpperBodyLean(const UpperBodyLeanParams& params) : params_(params) {}
  void reset();
  // One cycle from the DCM error (measured − planned, heading frame: x forward, y left) [m]; a
  // non-finite error or `active` false returns the upper body upright.
  void update(double dt, const Eigen::Vector2d& dcm_error, bool active);
  // The lean as the tilt angles of math::tilt_against_gravity (sagittal: top forward positive;
  // lateral: top left positive) [rad], and their rates [rad/s].
  const Eigen::Vector2d& angle() const { return angle_; }
  const Eigen::Vector2d& rate() const { return rate_; }
  // The upper body's orientation in the heading frame that this lean is (rotation vector) [rad].
  Eigen::Vector3d rotation_vector() const { return {-angle_.y(), angle_.x(), 0.0}; }
  Eigen::Vector3d angular_rate() const { return {-rate_.y(), rate_.x(), 0.0}; }

 private:
  UpperBodyLeanParams params_;
  Eigen::Vector2d angle_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d rate_ = Eigen::Vector2d::Zero();
};

}  // namespace biped
