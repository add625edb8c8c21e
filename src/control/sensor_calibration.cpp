#include "control/sensor_calibration.hpp"

#include <cmath>

#include "math/rotations.hpp"

namespace biped {
namespace {

bool finite(const Wrench& w) { return w.force.allFinite() && w.torque.allFinite(); }

// The part of v perpendicular to the unit vector `up`.
Eigen::Vector3d perpendicular(const Eigen::Vector3d& v, const Eigen::Vector3d& up) { return v - up * up.dot(v); }

Eigen::Quaterniond rotation(const Eigen::Vector3d& phi) {
  const double angle = phi.norm();
  if (angle < 1e-300) return Eigen::Quaterniond::Identity();
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, phi / angle));
}

Eigen::Vector3d bounded(const Eigen::Vector3d& v, double bound) {
  const double n = v.norm();
  return n > bound ? Eigen::Vector3d(v * (bound / n)) : v;
}

}  // namespace

SensorCalibration::SensorCalibration(const RobotModel& model, const SensorCalibrationParams& params,
                                     const ContactModelParams& contact)
    : model_(model), params_(params), out_(model.num_joints()) {
  for (Side side : kSides) {
    const Eigen::Matrix3d compliance = point_contact_stiffness(model.foot(side), contact).inverse();
    compliance_[index_of(side)] = compliance.allFinite() ? compliance : Eigen::Matrix3d::Zero();
  }
}

void SensorCalibration::reset(double time) {
  start_time_ = time;
  startup_done_ = false;
  startup_samples_ = 0;
  sum_tilt_.setZero();
  rate_integral_.setZero();
  rate_time_ = 0.0;
  first_body_on_foot_.setIdentity();
  sum_up_.setZero();
  sum_bias_gain_ = 0.0;
  force_samples_ = 0;
  sum_force_error_.setZero();
  swing_samples_ = {0, 0};
  swing_sum_ = {};
  swing_rezeros_ = 0;
  misalignment_.setZero();
  gyro_bias_.setZero();
  bias_tilt_.setZero();
  drift_.setZero();
  ft_offset_ = {};
}

Eigen::Vector3d SensorCalibration::sole_deflection(Side foot, const Wrench& measured) const {
  if (!params_.sole_deflection || !(measured.force.z() > 0.0)) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d delta =
      -compliance_[index_of(foot)] * Eigen::Vector3d(measured.force.z(), measured.torque.x(), measured.torque.y());
  return delta.allFinite() ? Eigen::Vector3d(delta.y(), delta.z(), 0.0) : Eigen::Vector3d::Zero();
}

Eigen::Matrix3d SensorCalibration::upper_body_on_foot(Side foot, const Eigen::Vector3d& sole_tilt) const {
  const Eigen::Matrix3d& sole = frames_->rotation[model_.foot(foot).body];
  return math::so3::exp(sole_tilt) * sole.transpose() * frames_->rotation[model_.upper_body()];
}

Eigen::Vector3d SensorCalibration::tilt_against_foot(const Eigen::Quaterniond& orientation, Side foot,
                                                     const Eigen::Vector3d& sole_tilt) const {
  const Eigen::Matrix3d body_on_foot = upper_body_on_foot(foot, sole_tilt);
  const Eigen::Matrix3d R = orientation.toRotationMatrix();
  const double yaw = math::heading_of(R) - math::heading_of(body_on_foot);
  const Eigen::Matrix3d kinematic = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * body_on_foot;
  Eigen::Vector3d tilt = math::so3::log(Eigen::Quaterniond(kinematic.transpose() * R));
  tilt.z() = 0.0;
  return tilt;
}

Wrench SensorCalibration::swing_reading(int k, const Eigen::Quaterniond& upper_body,
                                        const Eigen::Vector3d& acceleration) const {
  const FootInfo& foot = model_.foot(kSides[k]);
  const Eigen::Matrix3d& sole = frames_->rotation[foot.body];
  // The sensor's axes are the foot body's (as the pattern generator's λ_id assumes).
  const Eigen::Matrix3d sensor_in_world =
      upper_body.toRotationMatrix() * frames_->rotation[model_.upper_body()].transpose() * sole;
  const Eigen::Vector3d sensor_point = frames_->position[foot.body] + sole * foot.sensor_position;
  const Eigen::Vector3d lever = sole.transpose() * (frames_->subtree_com[foot.body] - sensor_point);
  Wrench w;
  w.force = foot.mass_below_sensor * sensor_in_world.transpose() *
            (-acceleration - model_.gravity() * Eigen::Vector3d::UnitZ());
  w.torque = lever.cross(w.force);
  return w;
}

Eigen::Quaterniond SensorCalibration::corrected_orientation(const Eigen::Quaterniond& measured) const {
  // R_IMU = R_UB · exp(c) · exp(δ_b) (misalignment c, the filter's bias error δ_b), then the drift d.
  return (measured * rotation(-bias_tilt_) * rotation(-misalignment_) * rotation(-drift_)).normalized();
}

void SensorCalibration::estimate_at_startup(const SensorData& s, const CalibrationContext& c, double dt) {
  const double t = s.time - start_time_;
  if (c.imu_healthy && s.imu_orientation.coeffs().allFinite() && s.imu_angular_rate.allFinite()) {
    // Before the F/T offsets are known: their error on the tilt is small (0.3 N·m: 0.004°).
    const std::array<Eigen::Vector3d, 2> sole_tilt = {
        c.ft_healthy[0] ? sole_deflection(Side::Left, s.foot_wrench[0]) : Eigen::Vector3d::Zero(),
        c.ft_healthy[1] ? sole_deflection(Side::Right, s.foot_wrench[1]) : Eigen::Vector3d::Zero()};
    const Eigen::Vector3d tilt = 0.5 * (tilt_against_foot(s.imu_orientation, Side::Left, sole_tilt[0]) +
                                        tilt_against_foot(s.imu_orientation, Side::Right, sole_tilt[1]));
    // The upper body's orientation on the left foot: its rotation since the first sample is the
    // motion the gyro saw besides its bias (the robot sways while it stands, and its soles give).
    const Eigen::Matrix3d body_on_foot = upper_body_on_foot(Side::Left, sole_tilt[0]);
    if (tilt.allFinite() && body_on_foot.allFinite()) {
      if (startup_samples_ == 0) first_body_on_foot_ = body_on_foot;
      ++startup_samples_;
      sum_tilt_ += tilt;
      if (startup_samples_ > 1) {
        rate_integral_ += dt * s.imu_angular_rate;
        rate_time_ += dt;
      }
      sum_up_ += s.imu_orientation.conjugate() * Eigen::Vector3d::UnitZ();
      const double tau = params_.ahrs_time_constant;
      sum_bias_gain_ += tau > 0.0 ? tau * (1.0 - std::exp(-t / tau)) : 0.0;
      if (rate_time_ > 0.0) {
        const Eigen::Vector3d moved = math::so3::log(Eigen::Quaterniond(first_body_on_foot_.transpose() * body_on_foot));
        const Eigen::Vector3d bias = (rate_integral_ - moved) / rate_time_;
        gyro_bias_ = bias.allFinite() && bias.norm() <= params_.max_gyro_bias ? bias : Eigen::Vector3d::Zero();
      }
    }
  }
  if (startup_samples_ > 0) {
    const double n = startup_samples_;
    const Eigen::Vector3d up = sum_up_.normalized();
    // The filter's tilt error from the bias while standing is part of the mean tilt, not of the mounting.
    Eigen::Vector3d mounting = sum_tilt_ / n - (sum_bias_gain_ / n) * perpendicular(gyro_bias_, up);
    mounting.z() = 0.0;
    const double size = mounting.norm();
    misalignment_ = size >= params_.min_misalignment && size <= params_.max_misalignment ? mounting : Eigen::Vector3d::Zero();
    bias_tilt_ = params_.ahrs_time_constant > 0.0
                     ? Eigen::Vector3d(params_.ahrs_time_constant * (1.0 - std::exp(-t / params_.ahrs_time_constant)) *
                                       perpendicular(gyro_bias_, up))
                     : Eigen::Vector3d::Zero();
  }
  // The F/T sensors: the summed force against the weight above them (each foot's share: half).
  if (c.ft_healthy[0] && c.ft_healthy[1] && finite(s.foot_wrench[0]) && finite(s.foot_wrench[1])) {
    const Eigen::Quaterniond upper_body = corrected_orientation(s.imu_orientation);
    const Eigen::Matrix3d base = upper_body.toRotationMatrix() * frames_->rotation[model_.upper_body()].transpose();
    Eigen::Vector3d total = -model_.weight_above_sensors() * Eigen::Vector3d::UnitZ();
    for (int k = 0; k < 2; ++k) total += base * frames_->rotation[model_.foot(kSides[k]).body] * s.foot_wrench[k].force;
    if (total.allFinite()) {
      ++force_samples_;
      sum_force_error_ += total;
      const Eigen::Vector3d error = sum_force_error_ / force_samples_;
      for (int k = 0; k < 2; ++k) {
        const Eigen::Vector3d offset =
            0.5 * (base * frames_->rotation[model_.foot(kSides[k]).body]).transpose() * error;
        if (offset.norm() <= params_.max_force_offset) ft_offset_[k].force = offset;
      }
    }
  }
}

void SensorCalibration::track_swing_offsets(const SensorData& s, const CalibrationContext& c,
                                            const Eigen::Quaterniond& upper_body) {
  const PatternSample& plan = *c.plan;
  for (int k = 0; k < 2; ++k) {
    const FootReference& foot = plan.feet[k];
    if (foot.in_contact) {
      // The swing has ended: its mean difference to the expected reading is the sensor's offset.
      if (swing_samples_[k] >= 20) {
        Wrench offset;
        offset.force = swing_sum_[k].force / swing_samples_[k];
        offset.torque = swing_sum_[k].torque / swing_samples_[k];
        if (offset.force.norm() <= params_.max_force_offset && offset.torque.norm() <= params_.max_torque_offset) {
          ft_offset_[k] = offset;
          ++swing_rezeros_;
        }
      }
      swing_samples_[k] = 0;
      swing_sum_[k] = {};
      continue;
    }
    const double clearance = foot.position.z() - plan.feet[1 - k].position.z();
    if (!c.ft_healthy[k] || !finite(s.foot_wrench[k]) || clearance < params_.swing_clearance) continue;
    const Wrench expected = swing_reading(k, upper_body, foot.acceleration);
    const Eigen::Vector3d force_error = s.foot_wrench[k].force - expected.force;
    if (!force_error.allFinite() || force_error.norm() > params_.swing_force_band) continue;
    ++swing_samples_[k];
    swing_sum_[k].force += force_error;
    swing_sum_[k].torque += s.foot_wrench[k].torque - expected.torque;
  }
}

void SensorCalibration::track_drift(const Eigen::Quaterniond& upper_body, const SensorData& s,
                                    const CalibrationContext& c, double dt) {
  if (params_.drift_time <= 0.0 || !c.imu_healthy) return;
  const PatternSample& plan = *c.plan;
  Eigen::Vector3d tilt;
  if (c.standing) {
    tilt = 0.5 * (tilt_against_foot(upper_body, Side::Left, sole_deflection(Side::Left, s.foot_wrench[0])) +
                  tilt_against_foot(upper_body, Side::Right, sole_deflection(Side::Right, s.foot_wrench[1])));
  } else {
    // Single support on a loaded stance foot: its sole lies flat on the ground.
    const int k = index_of(plan.stance);
    if (plan.double_support || !plan.feet[k].in_contact || !c.ft_healthy[k]) return;
    if (!(s.foot_wrench[k].force.z() > 0.8 * model_.weight_above_sensors())) return;
    tilt = tilt_against_foot(upper_body, plan.stance, sole_deflection(plan.stance, s.foot_wrench[k]));
  }
  if (!tilt.allFinite()) return;
  drift_ = bounded(drift_ + (dt / params_.drift_time) * (tilt - drift_), params_.max_drift);
}

const SensorData& SensorCalibration::apply(const SensorData& s, const CalibrationContext& c, const BodyFrames& encoders,
                                           double dt) {
  if (!params_.enabled) return s;
  out_ = s;
  frames_ = &encoders;
  if (!startup_done_) {
    if (c.standing && s.time - start_time_ < params_.startup_time) {
      estimate_at_startup(s, c, dt);
    } else {
      startup_done_ = true;
    }
  } else if (params_.ahrs_time_constant > 0.0 && c.imu_healthy && s.imu_orientation.coeffs().allFinite()) {
    // The attitude filter's response to the bias: δ̇ = b⊥ − δ/τ (steady state τ·b⊥).
    const Eigen::Vector3d up = s.imu_orientation.conjugate() * Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d next =
        bias_tilt_ + dt * (perpendicular(gyro_bias_, up) - bias_tilt_ / params_.ahrs_time_constant);
    if (next.allFinite()) bias_tilt_ = next;
  }
  if (c.imu_healthy) {
    const Eigen::Matrix3d mounting = math::so3::exp(misalignment_);
    // Corrected before the drift tracking so that it sees the start-up calibration's result.
    out_.imu_orientation = (s.imu_orientation * rotation(-bias_tilt_) * rotation(-misalignment_)).normalized();
    if (startup_done_) track_drift(out_.imu_orientation, s, c, dt);
    out_.imu_orientation = (out_.imu_orientation * rotation(-drift_)).normalized();
    out_.imu_angular_rate = mounting * (s.imu_angular_rate - gyro_bias_);
    out_.imu_acceleration = mounting * s.imu_acceleration;
  }
  if (params_.ft_swing_rezero && startup_done_ && c.plan) track_swing_offsets(s, c, out_.imu_orientation);
  for (int k = 0; k < 2; ++k) {
    if (!c.ft_healthy[k]) continue;
    out_.foot_wrench[k].force = s.foot_wrench[k].force - ft_offset_[k].force;
    out_.foot_wrench[k].torque = s.foot_wrench[k].torque - ft_offset_[k].torque;
  }
  return out_;
}

}  // namespace biped
