#include "sim/sensor_emulation.hpp"

#include <cmath>
#include <limits>

#include "math/rotations.hpp"

namespace biped {
namespace {

int sensor_adr(const RobotModel& plant, const char* name) {
  const mjModel* m = plant.mj();
  return m->sensor_adr[mj_name2id(m, mjOBJ_SENSOR, name)];
}

Eigen::Vector3d vec3(const double* p) { return Eigen::Vector3d(p[0], p[1], p[2]); }

}  // namespace

SensorEmulation::SensorEmulation(const RobotModel& plant, std::vector<int> plant_joint_of,
                                 SensorEmulationParams params)
    : plant_(plant),
      plant_joint_of_(std::move(plant_joint_of)),
      params_(std::move(params)),
      rng_(params_.seed),
      clean_(static_cast<int>(plant_joint_of_.size())),
      delay_line_(params_.delay_cycles + 1, SensorData(static_cast<int>(plant_joint_of_.size()))),
      last_delivered_(static_cast<int>(plant_joint_of_.size())),
      fault_fired_(params_.faults.size(), 0) {
  for (Side side : kSides) {
    const std::string prefix = name_of(side);
    adr_force_[index_of(side)] = sensor_adr(plant, (prefix + "_ft_force").c_str());
    adr_torque_[index_of(side)] = sensor_adr(plant, (prefix + "_ft_torque").c_str());
  }
  adr_quat_ = sensor_adr(plant, "imu_quat");
  adr_gyro_ = sensor_adr(plant, "imu_gyro");
  adr_accel_ = sensor_adr(plant, "imu_accel");
  for (int bits : params_.encoder_bits) resolution_.push_back(2.0 * M_PI / std::ldexp(1.0, bits));

  // Per-run biases come first from the seeded generator so they do not depend on run length.
  const SensorNoiseParams& n = params_.noise_levels;
  auto draw3 = [this](double sigma) {
    return Eigen::Vector3d(sigma * normal_(rng_), sigma * normal_(rng_), sigma * normal_(rng_));
  };
  orientation_bias_ = draw3(n.imu_orientation_bias_rad);
  gyro_bias_ = draw3(n.gyro_bias_rad_s);
  accel_bias_ = draw3(n.accel_bias_m_s2);
  for (int k = 0; k < 2; ++k) {
    force_bias_[k] = draw3(n.ft_force_bias_n);
    torque_bias_[k] = draw3(n.ft_torque_bias_nm);
  }
}

void SensorEmulation::read_clean(const mjData* d, double t) {
  clean_.time = t;
  const auto& joints = plant_.joints();
  for (std::size_t i = 0; i < plant_joint_of_.size(); ++i) {
    const int p = plant_joint_of_[i];
    const double q = d->qpos[joints[p].qpos_adr];
    clean_.joint_position[i] = std::round(q / resolution_[p]) * resolution_[p];
  }
  const double* s = d->sensordata;
  clean_.imu_orientation = math::quat_from_mujoco(s + adr_quat_).normalized();
  clean_.imu_angular_rate = vec3(s + adr_gyro_);
  clean_.imu_acceleration = vec3(s + adr_accel_);
  // MuJoCo reports the wrench the parent (ankle side) exerts on the child (sole side); the
  // sensor convention here is the wrench the sole exerts on the ankle side, hence the sign.
  for (int k = 0; k < 2; ++k) {
    clean_.foot_wrench[k].force = -vec3(s + adr_force_[k]);
    clean_.foot_wrench[k].torque = -vec3(s + adr_torque_[k]);
  }
}

void SensorEmulation::add_noise(SensorData& s) {
  const SensorNoiseParams& n = params_.noise_levels;
  auto white = [this](double sigma) {
    return Eigen::Vector3d(sigma * normal_(rng_), sigma * normal_(rng_), sigma * normal_(rng_));
  };
  const Eigen::Vector3d rotation_error = orientation_bias_ + white(n.imu_orientation_noise_rad);
  const double angle = rotation_error.norm();
  if (angle > 0.0) {
    s.imu_orientation =
        (s.imu_orientation * Eigen::AngleAxisd(angle, rotation_error / angle)).normalized();
  }
  s.imu_angular_rate += gyro_bias_ + white(n.gyro_noise_rad_s);
  s.imu_acceleration += accel_bias_ + white(n.accel_noise_m_s2);
  for (int k = 0; k < 2; ++k) {
    s.foot_wrench[k].force += force_bias_[k] + white(n.ft_force_noise_n);
    s.foot_wrench[k].torque += torque_bias_[k] + white(n.ft_torque_noise_nm);
  }
}

void SensorEmulation::inject_faults(SensorData& s) {
  for (std::size_t f = 0; f < params_.faults.size(); ++f) {
    const SensorFault& fault = params_.faults[f];
    const bool active = fault.duration > 0.0 ? (s.time >= fault.t && s.time < fault.t + fault.duration)
                                             : (!fault_fired_[f] && s.time >= fault.t);
    if (!active) continue;
    fault_fired_[f] = 1;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double v = fault.mode == SensorFault::Mode::NaN ? nan : fault.value;
    const bool freeze = fault.mode == SensorFault::Mode::Freeze;
    if (fault.sensor == "ft_left" || fault.sensor == "ft_right") {
      const int k = fault.sensor == "ft_left" ? 0 : 1;
      s.foot_wrench[k] = freeze ? last_delivered_.foot_wrench[k]
                                : Wrench{Eigen::Vector3d::Constant(v), Eigen::Vector3d::Constant(v)};
    } else if (fault.sensor == "imu") {
      if (freeze) {
        s.imu_orientation = last_delivered_.imu_orientation;
        s.imu_angular_rate = last_delivered_.imu_angular_rate;
        s.imu_acceleration = last_delivered_.imu_acceleration;
      } else {
        s.imu_orientation.coeffs().setConstant(v);
        s.imu_angular_rate.setConstant(v);
        s.imu_acceleration.setConstant(v);
      }
    } else {
      for (std::size_t i = 0; i < plant_joint_of_.size(); ++i) {
        if (plant_.joints()[plant_joint_of_[i]].name == fault.sensor) {
          s.joint_position[i] = freeze ? last_delivered_.joint_position[i] : v;
        }
      }
    }
  }
}

void SensorEmulation::sample(const mjData* d, double t, SensorData& out) {
  read_clean(d, t);
  SensorData& slot = delay_line_[delay_head_];
  slot = clean_;
  if (params_.noise) add_noise(slot);
  // The oldest entry of the ring is the reading from delay_cycles cycles ago (or the first one).
  delay_head_ = (delay_head_ + 1) % static_cast<int>(delay_line_.size());
  ++samples_;
  const SensorData& delayed = samples_ > params_.delay_cycles ? delay_line_[delay_head_] : delay_line_[0];
  out = delayed;
  out.time = t;
  inject_faults(out);
  last_delivered_ = out;
}

}  // namespace biped
