#include "control/attitude_estimator.hpp"

#include <algorithm>
#include <cmath>

#include "math/rotations.hpp"

namespace biped {

AttitudeEstimator::AttitudeEstimator(const RobotModel& model, const AttitudeEstimatorParams& params)
    : model_(model),
      params_(params),
      imu_in_upper_body_(model.imu_position()),
      out_(model.num_joints()) {
  reset();
}

void AttitudeEstimator::reset() {
  started_ = false;
  orientation_.setIdentity();
  velocity_.setZero();
  bias_.setZero();
  have_position_ = {false, false};
  stance_ = -1;
  gap_ = 0.0;
  restarting_ = 0.0;
}

int AttitudeEstimator::choose_stance(const SensorData& s, const std::array<bool, 2>& ft_healthy) const {
  int best = -1;
  double best_load = params_.min_load_share * model_.weight_above_sensors();
  for (int k = 0; k < 2; ++k) {
    if (!ft_healthy[k]) continue;
    const Wrench& w = s.foot_wrench[k];
    const double load = w.force.z();
    if (!(load > best_load)) continue;
    // The centre of pressure on the sole plane, in the sensor frame: the foot rocks about an edge
    // when it gets there.
    const SoleSegment& sole = model_.foot(kSides[k]).segments[0];
    const double cop_x = (sole.z * w.force.x() - w.torque.y()) / load;
    const double cop_y = (w.torque.x() + sole.z * w.force.y()) / load;
    const double m = params_.cop_margin;
    if (!(cop_x > sole.x_min + m && cop_x < sole.x_max - m && cop_y > sole.y_min + m && cop_y < sole.y_max - m)) continue;
    best = k;
    best_load = load;
  }
  return best;
}

const SensorData& AttitudeEstimator::apply(const SensorData& s, bool imu_healthy, const std::array<bool, 2>& ft_healthy,
                                           const BodyFrames& frames, double dt) {
  if (!params_.enabled) return s;
  if (!imu_healthy || !s.imu_orientation.coeffs().allFinite() || !s.imu_angular_rate.allFinite() ||
      !s.imu_acceleration.allFinite() || !s.joint_position.allFinite()) {
    // The substitute the fault handling gives is used as it is; the estimate restarts from the
    // IMU when it is healthy again.
    reset();
    return s;
  }
  out_ = s;
  if (!started_) {
    orientation_ = s.imu_orientation.normalized();
    started_ = true;
  }

  // The IMU's position relative to each foot's sole centre, in the upper body's axes (the
  // kinematics with the base at the origin, unrotated: only relative positions and the upper body's
  // axes are used).
  const Eigen::Matrix3d& upper_body = frames.rotation[model_.upper_body()];
  const Eigen::Vector3d imu = frames.position[model_.upper_body()] + upper_body * imu_in_upper_body_;
  std::array<Eigen::Vector3d, 2> position;
  for (int k = 0; k < 2; ++k) {
    const FootInfo& foot = model_.foot(kSides[k]);
    const SoleSegment& sole = foot.segments[0];
    const Eigen::Vector3d centre(0.5 * (sole.x_min + sole.x_max), 0.5 * (sole.y_min + sole.y_max), sole.z);
    const Eigen::Matrix3d& R = frames.rotation[foot.body];
    const Eigen::Vector3d point = frames.position[foot.body] + R * (foot.sensor_position + centre);
    position[k] = upper_body.transpose() * (imu - point);
  }

  const Eigen::Vector3d rate = s.imu_angular_rate - bias_;
  const Eigen::Vector3d gravity = orientation_.conjugate() * Eigen::Vector3d(0.0, 0.0, -model_.gravity());
  const int stance = choose_stance(s, ft_healthy);
  Eigen::Vector3d correction = Eigen::Vector3d::Zero();  // ω_c
  Eigen::Vector3d velocity_rate = s.imu_acceleration + gravity - rate.cross(velocity_);
  if (stance >= 0 && have_position_[stance] && dt > 0.0) {
    const Eigen::Vector3d kinematic = (position[stance] - last_position_[stance]) / dt + rate.cross(position[stance]);
    if (gap_ > params_.max_gap) restarting_ = params_.restart_time;
    const Eigen::Vector3d error = kinematic - velocity_;
    if (restarting_ > 0.0) {
      // (A restart time of a few cycles or less takes the kinematics' velocity as it is.)
      velocity_rate += std::min(3.0 / params_.restart_time, 1.0 / dt) * error;
      restarting_ -= dt;
    } else {
      const double wn = params_.bandwidth;
      velocity_rate += 2.0 * params_.damping * wn * error;
      correction = -(wn * wn / gravity.squaredNorm()) * gravity.cross(error);
    }
    gap_ = 0.0;
  } else {
    gap_ += dt;
  }
  const Eigen::Vector3d next_velocity = velocity_ + dt * velocity_rate;
  const Eigen::Quaterniond next_orientation =
      (orientation_ * Eigen::Quaterniond(math::so3::exp((rate + correction) * dt))).normalized();
  Eigen::Vector3d next_bias = bias_ - (dt * params_.bias_gain) * correction;
  if (next_bias.norm() > params_.max_bias) next_bias *= params_.max_bias / next_bias.norm();
  if (next_velocity.allFinite() && next_orientation.coeffs().allFinite() && next_bias.allFinite()) {
    velocity_ = next_velocity;
    orientation_ = next_orientation;
    bias_ = next_bias;
  }
  stance_ = stance;
  for (int k = 0; k < 2; ++k) {
    last_position_[k] = position[k];
    have_position_[k] = position[k].allFinite();
  }

  // Roll and pitch of the estimate, heading of the IMU unit.
  const Eigen::Matrix3d estimate = orientation_.toRotationMatrix();
  const double turn = math::wrap_angle(math::heading_of(s.imu_orientation.toRotationMatrix()) - math::heading_of(estimate));
  out_.imu_orientation = Eigen::Quaterniond(Eigen::AngleAxisd(turn, Eigen::Vector3d::UnitZ()) * estimate).normalized();
  return out_;
}

}  // namespace biped
