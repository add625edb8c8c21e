#include "control/stabilizer.hpp"

#include <algorithm>
#include <cmath>

#include "math/rotations.hpp"

namespace biped {
namespace {

Eigen::Vector3d controlled(const Wrench& w) { return {w.force.z(), w.torque.x(), w.torque.y()}; }

}  // namespace

Stabilizer::Stabilizer(const RobotModel& model, const StabilizerParams& params)
    : model_(model),
      params_(params),
      contact_params_{params.contact_stiffness, params.heel_stiffness_share, params.contact_tolerance,
                      params.toe_contact} {
  for (Side side : kSides) {
    const int k = index_of(side);
    place_contact_elements(model.foot(side), contact_params_, 0.0, elements_[k]);
    stiffness_[k] = point_contact_stiffness(elements_[k]);
    compliance_[k] = stiffness_[k].inverse();
  }
  reset();
}

void Stabilizer::update_contact_model(const Eigen::VectorXd& joint_position, const std::array<Wrench, 2>& measured) {
  for (Side side : kSides) {
    const int k = index_of(side);
    const FootInfo& foot = model_.foot(side);
    const int toe = foot.num_segments > 1 ? foot.segments[1].joint : -1;
    biped::contact_elements(foot, contact_params_, toe >= 0 ? joint_position[toe] : 0.0, measured[k], elements_[k]);
    // The support plane's edges always touch, so K is regular; the check keeps NaN out regardless.
    const Eigen::Matrix3d K = point_contact_stiffness(elements_[k]);
    const Eigen::Matrix3d compliance = K.inverse();
    if (!compliance.allFinite()) continue;
    stiffness_[k] = K;
    compliance_[k] = compliance;
  }
}

void Stabilizer::reset() {
  for (auto& m : modification_) m = FootModification{};
  for (auto& i : force_error_integral_) i.setZero();
  regression_xy_ = regression_xx_ = 0.0;
  stiffness_scale_ = 1.0;
  window_residual_ = {0.0, 0.0};
  for (auto& o : window_offset_) o.setZero();
  window_cycle_ = 0;
  filtered_force_ = {0.0, 0.0};
  alpha_ = {0.0, 0.0};
  first_ = true;
}

// eq. (10)
void Stabilizer::contact_force_modification(const StabilizerInput& in, double tilt_sagittal, double tilt_lateral,
                                            double rate_sagittal, double rate_lateral) {
  const Eigen::Vector2d& com_error = in.com_error;
  const Eigen::Vector2d& com_rate_error = in.com_rate_error;
  // Δx_IN = planned − measured; the tilt arguments are measured − planned inclination. Leaning
  // forward, or the CoM ahead of the plan, moves the desired CoP forward (T_y = −x_CoP F_z);
  // leaning left, or the CoM left of the plan, moves it left (T_x = y_CoP F_z).
  const double correction_y = params_.tilt_gain * (-tilt_sagittal) + params_.tilt_rate_gain * (-rate_sagittal) +
                              params_.com_gain * com_error.x() + params_.com_rate_gain * com_rate_error.x();
  const double correction_x = -(params_.tilt_gain * (-tilt_lateral) + params_.tilt_rate_gain * (-rate_lateral) +
                                params_.com_gain * com_error.y() + params_.com_rate_gain * com_rate_error.y());
  for (Side side : kSides) {
    const int k = index_of(side);
    Wrench& d = desired_[k];
    d = in.ideal[k];
    if (!in.planned_contact[k]) {  // sat: a swing foot carries nothing
      d.torque.setZero();
      continue;
    }
    d.torque.x() += in.load_share[k] * correction_x;
    d.torque.y() += in.load_share[k] * correction_y;
    // sat: normal force ≥ 0, centre of pressure inside the sole with a margin.
    const FootInfo& foot = model_.foot(side);
    const double fz = std::max(0.0, d.force.z());
    d.force.z() = fz;
    const double m = params_.cop_margin;
    d.torque.x() = std::clamp(d.torque.x(), fz * (foot.sole_y_min + m), fz * (foot.sole_y_max - m));
    d.torque.y() = std::clamp(d.torque.y(), -fz * (foot.sole_x_max - m), -fz * (foot.sole_x_min + m));
  }
}

void Stabilizer::hybrid_position_force_control(int k, double dt, const Wrench& measured) {
  FootModification& mod = modification_[k];
  const double a = alpha_[k];
  // eq. (20): Δẋ_λ = [S_λ∇λ (S̄_x∇x)^†]^† α_λ S_λ [K_ff λ̇_d + K_λ(λ_d − λ)] + α_x K_λx (x_d − x),
  // with S_λ∇λ(S̄_x∇x)^† = −K for the point contacts and x_d − x = −Δx_λ for the modification.
  const Eigen::Vector3d lambda_d = controlled(desired_[k]);
  const Eigen::Vector3d lambda_d_rate = (lambda_d - controlled(previous_desired_[k])) / dt;
  const Eigen::Vector3d error = lambda_d - controlled(measured);
  Eigen::Vector3d& integral = force_error_integral_[k];
  integral += dt * (a * error - (1.0 - a) * params_.position_gain * integral);
  Eigen::Vector3d force_law = params_.feedforward_gain * lambda_d_rate + params_.force_gain * error +
                              params_.force_integral_gain * integral;  // eq. (14) with K_λ,INT
  force_law[2] *= params_.pitch_gain_scale;
  mod.rate = -(compliance_[k] / stiffness_scale_) * (a * force_law) - (1.0 - a) * params_.position_gain * mod.offset;
  mod.offset += mod.rate * dt;
  mod.offset[0] = std::clamp(mod.offset[0], -params_.max_height, params_.max_height);
  mod.offset[1] = std::clamp(mod.offset[1], -params_.max_tilt, params_.max_tilt);
  mod.offset[2] = std::clamp(mod.offset[2], -params_.max_tilt, params_.max_tilt);
  // std::clamp passes NaN through: a non-finite input (which the sensor monitor keeps out) must
  // not stay in the state, so the foot returns to position control from zero.
  if (!mod.offset.allFinite() || !mod.rate.allFinite() || !integral.allFinite()) {
    mod = FootModification{};
    integral.setZero();
  }
}

// Least squares with forgetting over the double support, where the ground shares the load between
// the feet: raising one foot's commanded height by δ against the other moves the normal force
// δF = −(C/2)(δ_this − δ_other) from it to the other (two contact springs under one body). The
// nominal model's prediction of that difference is compared with the measured change of the force
// error (the part of the force change the plan did not ask for); the ratio scales C. In single
// support the foot's height does not change its load, so the estimate holds there.
void Stabilizer::adapt_contact_stiffness(double dt, const std::array<Wrench, 2>& measured) {
  // Changes over a window of cycles, so that the lag of the joint drives falls inside it.
  if (++window_cycle_ < kAdaptationWindow) return;
  window_cycle_ = 0;
  std::array<double, 2> residual, predicted;
  for (int k = 0; k < 2; ++k) {
    residual[k] = measured[k].force.z() - desired_[k].force.z();
    predicted[k] = (stiffness_[k] * (modification_[k].offset - window_offset_[k]))[0];
    window_offset_[k] = modification_[k].offset;
  }
  const double measured_shift = (residual[0] - window_residual_[0]) - (residual[1] - window_residual_[1]);
  const double predicted_shift = -(predicted[0] - predicted[1]);
  window_residual_ = residual;
  if (alpha_[0] < 1.0 || alpha_[1] < 1.0) return;
  const double forget = 1.0 - kAdaptationWindow * dt / params_.adaptation_time;
  regression_xy_ = forget * regression_xy_ + predicted_shift * measured_shift;
  regression_xx_ = forget * regression_xx_ + predicted_shift * predicted_shift;
  constexpr double kMinExcitation = 100.0;  // [N²]: about 10 N of predicted change within the memory
  if (regression_xx_ < kMinExcitation) return;
  stiffness_scale_ = std::clamp(regression_xy_ / regression_xx_, params_.adaptation_min_scale, params_.adaptation_max_scale);
}

double Stabilizer::contact_stiffness() const {
  return params_.contact_stiffness * stiffness_scale_;
}

Eigen::Vector3d Stabilizer::sole_deflection(Side side, const Wrench& measured) const {
  if (measured.force.z() <= 0.0) return Eigen::Vector3d::Zero();
  return compliance_[index_of(side)] * controlled(measured) / stiffness_scale_;
}

void Stabilizer::step(double dt, const StabilizerInput& in) {
  const math::TiltAngles tilt = math::tilt_against_gravity(in.imu_orientation.toRotationMatrix());
  // Small-angle rates of the two tilt angles from the body-frame angular rate.
  // The tilt against the planned inclination (the upper body's lean, zero in the paper).
  contact_force_modification(in, tilt.sagittal - in.upper_body_lean.x(), tilt.lateral - in.upper_body_lean.y(),
                             in.imu_rate.y() - in.upper_body_lean_rate.x(),
                             -in.imu_rate.x() - in.upper_body_lean_rate.y());
  if (first_) previous_desired_ = desired_;
  first_ = false;
  const double filter = dt / (params_.contact_filter_time + dt);
  for (int k = 0; k < 2; ++k) {
    if (!desired_[k].force.allFinite() || !desired_[k].torque.allFinite()) desired_[k] = Wrench{};
    filtered_force_[k] += filter * (in.measured[k].force.z() - filtered_force_[k]);
    if (!std::isfinite(filtered_force_[k])) filtered_force_[k] = 0.0;
    const double contact =
        std::clamp((filtered_force_[k] - params_.contact_force_low) / (params_.contact_force_high - params_.contact_force_low), 0.0, 1.0);
    alpha_[k] = in.planned_contact[k] ? contact : 0.0;
    hybrid_position_force_control(k, dt, in.measured[k]);
  }
  if (params_.stiffness_adaptation) adapt_contact_stiffness(dt, in.measured);
  previous_desired_ = desired_;
}

}  // namespace biped
