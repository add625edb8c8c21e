#pragma once
// Emulated robot sensors: link-side joint encoders (quantized), an IMU in the upper body
// (orientation, angular rate, specific force) and two 6-axis F/T sensors between ankle and sole.
// Optional white noise and per-run bias drawn from the scenario's seed, a delay of whole control
// cycles, and injected faults.
#include <mujoco/mujoco.h>

#include <random>
#include <string>
#include <vector>

#include "interface/sensor_data.hpp"
#include "model/robot_model.hpp"

namespace biped {

struct SensorNoiseParams {
  double imu_orientation_noise_rad = 0.002;  // white noise, each axis
  double imu_orientation_bias_rad = 0.003;   // constant per run, each axis
  double gyro_noise_rad_s = 0.005;
  double gyro_bias_rad_s = 0.002;
  double accel_noise_m_s2 = 0.05;
  double accel_bias_m_s2 = 0.05;
  double ft_force_noise_n = 2.0;
  double ft_force_bias_n = 3.0;
  double ft_torque_noise_nm = 0.2;
  double ft_torque_bias_nm = 0.3;
};

struct SensorFault {
  enum class Mode { NaN, Value, Freeze };
  double t = 0.0;         // [s] first affected reading
  double duration = 0.0;  // [s]; 0: a single reading
  std::string sensor;     // "ft_left", "ft_right", "imu", or a joint name (its encoder)
  Mode mode = Mode::NaN;
  double value = 0.0;     // Mode::Value: every channel of the sensor reads this
};

struct SensorEmulationParams {
  std::vector<int> encoder_bits;  // per plant joint (resolution 2π / 2^bits)
  bool noise = false;
  SensorNoiseParams noise_levels;
  int delay_cycles = 0;
  std::vector<SensorFault> faults;
  unsigned long long seed = 1;
};

class SensorEmulation {
 public:
  // `plant_joint_of` maps each controller joint (SensorData order) to the plant joint index.
  SensorEmulation(const RobotModel& plant, std::vector<int> plant_joint_of, SensorEmulationParams params);

  // Samples the sensors from the plant's sensordata (valid after mj_step2) and delivers, through
  // the delay line and the fault injection, the reading the controller sees at time t.
  void sample(const mjData* d, double t, SensorData& out);

  // Fault-free, delay-free reading of the same instant (for logs and tests).
  const SensorData& latest_clean() const { return clean_; }

 private:
  void read_clean(const mjData* d, double t);
  void add_noise(SensorData& s);
  void inject_faults(SensorData& s);

  const RobotModel& plant_;
  std::vector<int> plant_joint_of_;
  SensorEmulationParams params_;
  std::vector<double> resolution_;
  int adr_force_[2], adr_torque_[2], adr_quat_, adr_gyro_, adr_accel_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
  Eigen::Vector3d orientation_bias_, gyro_bias_, accel_bias_;
  Eigen::Vector3d force_bias_[2], torque_bias_[2];
  SensorData clean_;
  std::vector<SensorData> delay_line_;
  int delay_head_ = 0;
  int samples_ = 0;
  SensorData last_delivered_;
  std::vector<char> fault_fired_;
};

}  // namespace biped
