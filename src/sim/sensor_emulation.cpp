#include "sim/sensor_emulation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "math/rotations.hpp"

namespace biped {
namespace {

constexpr double kGravity = 9.81;  // [m/s²] only its direction matters here

Eigen::Vector3d vec3(const double* p) { return Eigen::Vector3d(p[0], p[1], p[2]); }

// Roll, pitch, yaw about the fixed x, y, z axes: R = Rz(yaw) Ry(pitch) Rx(roll).
Eigen::Matrix3d from_roll_pitch_yaw(const Eigen::Vector3d& rpy) {
  return (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

Vector6d stack(const Wrench& w) {
  Vector6d v;
  v << w.force, w.torque;
  return v;
}

Wrench unstack(const Vector6d& v) { return {v.head<3>(), v.tail<3>()}; }

}  // namespace

SensorEmulation::SensorEmulation(const RobotModel& plant, std::vector<int> plant_joint_of,
                                 SensorEmulationParams params)
    : plant_(plant),
      plant_joint_of_(std::move(plant_joint_of)),
      params_(std::move(params)),
      encoder_offset_(plant_joint_of_.size(), 0.0),
      fault_joint_(params_.faults.size(), -1),
      clean_(static_cast<int>(plant_joint_of_.size())),
      delay_line_(params_.delay_cycles + 1, SensorData(static_cast<int>(plant_joint_of_.size()))),
      last_delivered_(static_cast<int>(plant_joint_of_.size())),
      fault_fired_(params_.faults.size(), 0) {
  const mjModel* m = plant.mj();
  for (Side side : kSides) {
    adr_force_[index_of(side)] = m->sensor_adr[plant.foot(side).force_sensor];
    adr_torque_[index_of(side)] = m->sensor_adr[plant.foot(side).torque_sensor];
  }
  adr_quat_ = plant.imu_orientation_sensor() < 0 ? -1 : m->sensor_adr[plant.imu_orientation_sensor()];
  adr_gyro_ = m->sensor_adr[plant.imu_gyro_sensor()];
  adr_accel_ = m->sensor_adr[plant.imu_accelerometer_sensor()];
  for (int bits : params_.encoder_bits) resolution_.push_back(2.0 * M_PI / std::ldexp(1.0, bits));

  auto controller_joint = [this](const std::string& name) {
    for (std::size_t i = 0; i < plant_joint_of_.size(); ++i) {
      if (plant_.joints()[plant_joint_of_[i]].name == name) return static_cast<int>(i);
    }
    return -1;
  };
  for (const auto& [name, offset] : params_.errors.encoder_offset_rad) {
    if (controller_joint(name) < 0) throw ModelError("encoder offset of an unknown joint '" + name + "'");
  }
  for (std::size_t f = 0; f < params_.faults.size(); ++f) {
    const std::string& name = params_.faults[f].sensor;
    if (std::find(kNonJointSensors.begin(), kNonJointSensors.end(), name) != kNonJointSensors.end()) continue;
    fault_joint_[f] = controller_joint(name);
    if (fault_joint_[f] < 0) throw ModelError("sensor fault of an unknown sensor '" + name + "'");
  }
  reset();
}

Eigen::Vector3d SensorEmulation::white(double sigma) {
  return Eigen::Vector3d(sigma * normal_(rng_), sigma * normal_(rng_), sigma * normal_(rng_));
}

// Every per-run error is drawn, given or not, in one fixed order: giving one value leaves the
// draws of the others as they were.
void SensorEmulation::draw_run_errors() {
  const SensorNoiseParams& n = params_.noise_levels;
  const bool drawn = params_.noise;
  auto pick3 = [&](const std::optional<Eigen::Vector3d>& given, double sigma) {
    const Eigen::Vector3d draw = white(sigma);
    return given ? *given : (drawn ? draw : Eigen::Vector3d::Zero());
  };
  const ImuSpec& imu = params_.errors.imu;
  misalignment_ = from_roll_pitch_yaw(pick3(imu.misalignment_rad, n.imu_misalignment_rad));
  gyro_bias_ = pick3(imu.gyro_bias, n.gyro_bias_rad_s);
  accel_bias_ = pick3(imu.accel_bias, n.accel_bias_m_s2);
  gyro_bias_walk_ = imu.gyro_bias_walk.value_or(drawn ? n.gyro_bias_walk : 0.0);

  for (int k = 0; k < 2; ++k) {
    const ForceTorqueSpec& ft = params_.errors.ft[k];
    auto pick6 = [&](const std::optional<Vector6d>& given, double force_sigma, double torque_sigma,
                     const Vector6d& otherwise) {
      Vector6d draw;
      draw << white(force_sigma), white(torque_sigma);
      return given ? *given : (drawn ? draw : otherwise);
    };
    const Vector6d zero = Vector6d::Zero(), one = Vector6d::Ones();
    ft_offset_[k] = pick6(ft.offset, n.ft_force_bias_n, n.ft_torque_bias_nm, zero);
    ft_scale_[k] = pick6(ft.scale, n.ft_scale_error, n.ft_scale_error, zero);
    if (!ft.scale) ft_scale_[k] += one;  // a drawn error of the gain, or none
    ft_thermal_[k] = pick6(ft.thermal_drift, n.ft_thermal_force_n, n.ft_thermal_torque_nm, zero);
    Vector6d walk;
    walk << Eigen::Vector3d::Constant(n.ft_force_drift_walk), Eigen::Vector3d::Constant(n.ft_torque_drift_walk);
    ft_drift_walk_[k] = ft.drift_walk.value_or(drawn ? walk : zero);
    ft_thermal_time_[k] = ft.thermal_time_s.value_or(n.ft_thermal_time_s);
    ft_drift_[k].setZero();
  }

  for (std::size_t i = 0; i < plant_joint_of_.size(); ++i) {
    const double draw = n.encoder_offset_rad * normal_(rng_);
    const auto& given = params_.errors.encoder_offset_rad;
    const auto it = given.find(plant_.joints()[plant_joint_of_[i]].name);
    encoder_offset_[i] = it != given.end() ? it->second : (drawn ? draw : 0.0);
  }
}

void SensorEmulation::reset() {
  rng_.seed(params_.seed);
  normal_.reset();
  draw_run_errors();
  started_ = false;
  delay_head_ = 0;
  samples_ = 0;
  std::fill(fault_fired_.begin(), fault_fired_.end(), 0);
}

double SensorEmulation::quantized(std::size_t joint, double angle) const {
  const double resolution = resolution_[plant_joint_of_[joint]];
  return std::round(angle / resolution) * resolution;
}

void SensorEmulation::read_clean(const mjData* d, double t) {
  clean_.time = t;
  for (std::size_t i = 0; i < plant_joint_of_.size(); ++i) {
    clean_.joint_position[i] = quantized(i, d->qpos[plant_.joints()[plant_joint_of_[i]].qpos_adr]);
  }
  const double* s = d->sensordata;
  if (adr_quat_ >= 0) {
    clean_.imu_orientation = math::quat_from_mujoco(s + adr_quat_).normalized();
  } else {  // no orientation sensor in the model: the IMU site's frame
    mjtNum quat[4];
    mju_mat2Quat(quat, d->site_xmat + 9 * plant_.imu_site());
    clean_.imu_orientation = math::quat_from_mujoco(quat).normalized();
  }
  clean_.imu_angular_rate = vec3(s + adr_gyro_);
  clean_.imu_acceleration = vec3(s + adr_accel_);
  // MuJoCo reports the wrench the parent (ankle side) exerts on the child (sole side); the
  // sensor convention here is the wrench the sole exerts on the ankle side, hence the sign.
  for (int k = 0; k < 2; ++k) {
    clean_.foot_wrench[k].force = -vec3(s + adr_force_[k]);
    clean_.foot_wrench[k].torque = -vec3(s + adr_torque_[k]);
  }
}

// A complementary filter on SO(3) (Mahony's without the integral term): the orientation follows
// the gyro and is turned towards the accelerometer's "up" at the rate 1/filter_time_s. The
// correction e = â × v̂ is perpendicular to up, so the heading is the gyro's integral alone and
// drifts with its bias; roll and pitch settle at bias · filter_time_s.
void SensorEmulation::update_attitude_filter(const Eigen::Vector3d& rate, const Eigen::Vector3d& specific_force,
                                             double dt) {
  const Eigen::Vector3d up_estimated = attitude_.conjugate() * Eigen::Vector3d::UnitZ();
  Eigen::Vector3d correction = Eigen::Vector3d::Zero();
  const double norm = specific_force.norm();
  if (norm > 0.0) correction = (specific_force / norm).cross(up_estimated) / params_.errors.imu.filter_time_s;
  attitude_ = (attitude_ * Eigen::Quaterniond(math::so3::exp((rate + correction) * dt))).normalized();
}

void SensorEmulation::measure_imu(double dt, SensorData& s) {
  const SensorNoiseParams& n = params_.noise_levels;
  const ImuSpec& imu = params_.errors.imu;
  if (started_ && gyro_bias_walk_ > 0.0) gyro_bias_ += white(gyro_bias_walk_ * std::sqrt(dt));
  // The IMU's axes are the upper body's turned by the misalignment.
  const Eigen::Quaterniond true_attitude(clean_.imu_orientation.toRotationMatrix() * misalignment_);
  Eigen::Vector3d rate = misalignment_.transpose() * clean_.imu_angular_rate + gyro_bias_;
  Eigen::Vector3d force = misalignment_.transpose() * clean_.imu_acceleration + accel_bias_;
  if (params_.noise) {
    rate += white(n.gyro_noise_rad_s);
    force += white(n.accel_noise_m_s2);
  }
  if (!started_ || imu.bandwidth_hz <= 0.0) {
    rate_filtered_ = rate;
    force_filtered_ = force;
  } else {
    const double blend = 1.0 - std::exp(-2.0 * M_PI * imu.bandwidth_hz * dt);
    rate_filtered_ += blend * (rate - rate_filtered_);
    force_filtered_ += blend * (force - force_filtered_);
  }
  if (!started_) {
    // The unit has been on while the robot stood before the run: roll and pitch from the
    // accelerometer at rest (gravity seen through the misalignment, plus the bias; the simulation's
    // own first steps settle the contact and are no measurement); the heading, which an IMU
    // without magnetometer cannot know, is the IMU frame's true one (the robot starts facing +x).
    const Eigen::Vector3d up = (true_attitude.conjugate() * Eigen::Vector3d::UnitZ() * kGravity + accel_bias_).normalized();
    const double roll = std::atan2(up.y(), up.z());
    const double pitch = std::asin(std::clamp(-up.x(), -1.0, 1.0));
    const double yaw = math::heading_of(true_attitude.toRotationMatrix());
    attitude_ = Eigen::Quaterniond(from_roll_pitch_yaw(Eigen::Vector3d(roll, pitch, yaw)));
  } else {
    update_attitude_filter(rate_filtered_, force_filtered_, dt);
  }
  s.imu_orientation = imu.attitude_filter ? attitude_ : true_attitude;
  s.imu_angular_rate = rate_filtered_;
  s.imu_acceleration = force_filtered_;
}

void SensorEmulation::measure_force_torque(double t, double dt, SensorData& s) {
  const SensorNoiseParams& n = params_.noise_levels;
  for (int k = 0; k < 2; ++k) {
    if (started_ && (ft_drift_walk_[k].array() > 0.0).any()) {
      for (int a = 0; a < 6; ++a) ft_drift_[k][a] += ft_drift_walk_[k][a] * std::sqrt(dt) * normal_(rng_);
    }
    const double warm = 1.0 - std::exp(-t / ft_thermal_time_[k]);
    Vector6d reading =
        ft_scale_[k].cwiseProduct(stack(clean_.foot_wrench[k])) + ft_offset_[k] + ft_drift_[k] + warm * ft_thermal_[k];
    if (params_.noise) reading << reading.head<3>() + white(n.ft_force_noise_n), reading.tail<3>() + white(n.ft_torque_noise_nm);
    s.foot_wrench[k] = unstack(reading);
  }
}

void SensorEmulation::inject_faults(SensorData& s) {
  for (std::size_t f = 0; f < params_.faults.size(); ++f) {
    const SensorFault& fault = params_.faults[f];
    const bool active = fault.duration > 0.0 ? (s.time >= fault.t && s.time < fault.t + fault.duration)
                                             : (!fault_fired_[f] && s.time >= fault.t);
    if (!active) continue;
    fault_fired_[f] = 1;
    const double v = fault.mode == SensorFault::Mode::NaN ? std::numeric_limits<double>::quiet_NaN() : fault.value;
    const bool freeze = fault.mode == SensorFault::Mode::Freeze;
    if (fault_joint_[f] >= 0) {
      double& reading = s.joint_position[fault_joint_[f]];
      if (fault.mode == SensorFault::Mode::Jump) {
        reading += fault.value;
      } else {
        reading = freeze ? last_delivered_.joint_position[fault_joint_[f]] : v;
      }
    } else if (fault.sensor == "ft_left" || fault.sensor == "ft_right") {
      const int k = fault.sensor == "ft_left" ? 0 : 1;
      s.foot_wrench[k] = freeze ? last_delivered_.foot_wrench[k]
                                : Wrench{Eigen::Vector3d::Constant(v), Eigen::Vector3d::Constant(v)};
    } else {
      const bool all = fault.sensor == "imu";
      if (all || fault.sensor == "imu_orientation") {
        if (freeze) {
          s.imu_orientation = last_delivered_.imu_orientation;
        } else {
          s.imu_orientation.coeffs().setConstant(v);
        }
      }
      if (all || fault.sensor == "imu_gyro") {
        s.imu_angular_rate = freeze ? last_delivered_.imu_angular_rate : Eigen::Vector3d::Constant(v);
      }
      if (all || fault.sensor == "imu_accel") {
        s.imu_acceleration = freeze ? last_delivered_.imu_acceleration : Eigen::Vector3d::Constant(v);
      }
    }
  }
}

void SensorEmulation::sample(const mjData* d, double t, SensorData& out) {
  read_clean(d, t);
  SensorData& slot = delay_line_[delay_head_];
  slot.time = t;
  for (std::size_t i = 0; i < plant_joint_of_.size(); ++i) {
    slot.joint_position[i] = quantized(i, d->qpos[plant_.joints()[plant_joint_of_[i]].qpos_adr] + encoder_offset_[i]);
  }
  const double dt = started_ ? t - last_t_ : 0.0;
  measure_imu(dt, slot);
  measure_force_torque(t, dt, slot);
  started_ = true;
  last_t_ = t;
  // The oldest entry of the ring is the reading from delay_cycles cycles ago (or the first one).
  delay_head_ = (delay_head_ + 1) % static_cast<int>(delay_line_.size());
  ++samples_;
  const SensorData& delayed = samples_ > params_.delay_cycles ? delay_line_[delay_head_] : delay_line_[0];
  out = delayed;
  out.time = t;
  // A signal frozen from the first reading on holds that reading.
  if (samples_ == 1) last_delivered_ = out;
  inject_faults(out);
  last_delivered_ = out;
}

}  // namespace biped
