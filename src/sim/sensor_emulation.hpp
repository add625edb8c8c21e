#pragma once
// Emulated robot sensors with the errors real ones have: link-side joint encoders (quantized, with
// calibration offsets), an IMU in the upper body (mounting misalignment, gyro and accelerometer
// bias, gyro bias drift, white noise, a finite bandwidth, and an attitude filter that computes the
// orientation from gyro and accelerometer as an AHRS unit does) and two 6-axis F/T sensors between
// ankle and sole (offset, scale error, random-walk drift, a temperature-like drift). Per-run errors
// are drawn from the scenario's seed unless given; a delay of whole control cycles; injected faults.
#include <mujoco/mujoco.h>

#include <array>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "interface/sensor_data.hpp"
#include "model/robot_model.hpp"

namespace biped {

using Vector6d = Eigen::Matrix<double, 6, 1>;

// Levels of the white noise and of the random per-run errors (robot file `sensor_noise`), used with
// `noise`. Each "bias", "misalignment", "offset", "scale error" and "thermal" value is the standard
// deviation of a normal draw per run and axis; the walks are the rates of random walks.
struct SensorNoiseParams {
  double imu_misalignment_rad = 0.15 * M_PI / 180.0;  // IMU mounting, roll, pitch and yaw
  double gyro_noise_rad_s = 0.005;
  double gyro_bias_rad_s = 0.002;
  double gyro_bias_walk = 5e-5;  // [rad/s/√s]
  double accel_noise_m_s2 = 0.05;
  double accel_bias_m_s2 = 0.03;
  double ft_force_noise_n = 2.0;
  double ft_force_bias_n = 3.0;
  double ft_torque_noise_nm = 0.2;
  double ft_torque_bias_nm = 0.3;
  double ft_scale_error = 0.01;         // of the gain, each axis
  double ft_force_drift_walk = 0.05;    // [N/√s]
  double ft_torque_drift_walk = 0.005;  // [N·m/√s]
  double ft_thermal_force_n = 2.0;      // offset reached after the warm-up
  double ft_thermal_torque_nm = 0.2;
  double ft_thermal_time_s = 120.0;
  double encoder_offset_rad = 0.01 * M_PI / 180.0;  // zero-position calibration error
};

// The IMU: its attitude filter and the errors given explicitly (each given value replaces the
// random draw; without `noise` an absent one is zero).
struct ImuSpec {
  bool attitude_filter = false;  // orientation from the attitude filter; false: the exact orientation
  double filter_time_s = 3.0;    // time constant of the filter's correction towards the accelerometer
  double bandwidth_hz = 0.0;     // first-order low-pass of gyro and accelerometer; 0: none
  std::optional<Eigen::Vector3d> misalignment_rad;  // roll, pitch, yaw of the IMU against the upper body
  std::optional<Eigen::Vector3d> gyro_bias;         // [rad/s] at t = 0
  std::optional<double> gyro_bias_walk;             // [rad/s/√s]
  std::optional<Eigen::Vector3d> accel_bias;        // [m/s²]
};

// One F/T sensor's errors, axes Fx Fy Fz Tx Ty Tz (N, N·m). Reading = scale ⊙ true + offset +
// random walk + thermal_drift (1 − e^(−t/thermal_time_s)) + white noise.
struct ForceTorqueSpec {
  std::optional<Vector6d> offset;
  std::optional<Vector6d> scale;
  std::optional<Vector6d> drift_walk;     // [N/√s, N·m/√s]
  std::optional<Vector6d> thermal_drift;  // offset reached after the warm-up
  std::optional<double> thermal_time_s;
};

// Everything beyond noise, delay and faults; default-constructed: ideal sensors.
struct SensorErrorSpec {
  ImuSpec imu;
  std::array<ForceTorqueSpec, 2> ft;                 // indexed by Side
  std::map<std::string, double> encoder_offset_rad;  // by joint name
};

struct SensorFault {
  enum class Mode { NaN, Value, Freeze, Jump };
  double t = 0.0;         // [s] first affected reading
  double duration = 0.0;  // [s]; 0: a single reading
  // "ft_left", "ft_right", "imu" (all of it), "imu_orientation", "imu_gyro", "imu_accel", or a
  // joint name (its encoder)
  std::string sensor;
  Mode mode = Mode::NaN;
  double value = 0.0;  // Mode::Value: every channel of the sensor reads this; Mode::Jump: added [rad]
};

// The names a fault may give besides the joints.
inline const std::vector<std::string> kNonJointSensors = {"ft_left", "ft_right", "imu", "imu_orientation",
                                                           "imu_gyro", "imu_accel"};

struct SensorEmulationParams {
  std::vector<int> encoder_bits;  // per plant joint (resolution 2π / 2^bits)
  bool noise = false;
  SensorNoiseParams noise_levels;
  SensorErrorSpec errors;
  int delay_cycles = 0;
  std::vector<SensorFault> faults;
  unsigned long long seed = 1;
};

class SensorEmulation {
 public:
  // `plant_joint_of` maps each controller joint (SensorData order) to the plant joint index.
  // Throws ModelError for an encoder offset or a fault of a joint the plant does not have.
  SensorEmulation(const RobotModel& plant, std::vector<int> plant_joint_of, SensorEmulationParams params);

  // Back to the start of a run: per-run errors drawn again from the seed, filters and delay empty.
  void reset();

  // Samples the sensors from the plant's sensordata (valid after mj_step2) and delivers, through
  // the attitude filter, the delay line and the fault injection, the reading the controller sees
  // at time t. The first call of a run initializes the attitude filter from the accelerometer.
  void sample(const mjData* d, double t, SensorData& out);

  // Error-free, delay-free reading of the same instant (for logs and tests): the upper body's IMU
  // site, the encoders quantized.
  const SensorData& latest_clean() const { return clean_; }

  // The per-run errors in effect (drawn or given), for tests and logs.
  const Eigen::Matrix3d& imu_misalignment() const { return misalignment_; }
  const Eigen::Vector3d& gyro_bias() const { return gyro_bias_; }  // now, with its drift

 private:
  void read_clean(const mjData* d, double t);
  void draw_run_errors();
  double quantized(std::size_t joint, double angle) const;  // controller joint's encoder
  void measure_imu(double dt, SensorData& s);
  void update_attitude_filter(const Eigen::Vector3d& rate, const Eigen::Vector3d& specific_force, double dt);
  void measure_force_torque(double t, double dt, SensorData& s);
  void inject_faults(SensorData& s);
  Eigen::Vector3d white(double sigma);

  const RobotModel& plant_;
  std::vector<int> plant_joint_of_;
  SensorEmulationParams params_;
  std::vector<double> resolution_;
  std::vector<double> encoder_offset_;     // per controller joint [rad]
  std::vector<int> fault_joint_;           // per fault: controller joint index, or -1
  int adr_force_[2], adr_torque_[2], adr_quat_, adr_gyro_, adr_accel_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};

  // Per-run errors in effect.
  Eigen::Matrix3d misalignment_;  // IMU frame in the upper-body (site) frame
  Eigen::Vector3d gyro_bias_, accel_bias_;
  double gyro_bias_walk_ = 0.0;
  std::array<Vector6d, 2> ft_offset_, ft_scale_, ft_drift_walk_, ft_thermal_, ft_drift_;
  std::array<double, 2> ft_thermal_time_{};

  // The IMU's state: low-passed raw signals and the attitude filter's estimate.
  bool started_ = false;
  double last_t_ = 0.0;
  Eigen::Vector3d rate_filtered_, force_filtered_;
  Eigen::Quaterniond attitude_;

  SensorData clean_;
  std::vector<SensorData> delay_line_;
  int delay_head_ = 0;
  int samples_ = 0;
  SensorData last_delivered_;
  std::vector<char> fault_fired_;
};

}  // namespace biped
