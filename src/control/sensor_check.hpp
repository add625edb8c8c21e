#pragma once
// Plausibility check of one sensor reading: every value finite and inside its physical range.
#include "control/interface.hpp"

namespace biped {

struct SensorLimits {
  double max_force = 5000.0;          // [N] per F/T axis
  double max_torque = 500.0;          // [N·m] per F/T axis
  double max_angular_rate = 20.0;     // [rad/s]
  double max_acceleration = 160.0;    // [m/s²] (16 g)
  double encoder_margin = 0.05;       // [rad] tolerated beyond the hard joint limits
  int frozen_cycles = 50;             // identical F/T or IMU readings in a row that mean a dead signal (0: off)
};

// Returns nullptr when the reading is plausible, else a static string naming the faulty signal.
const char* check_sensors(const RobotModel& model, const SensorLimits& limits, const SensorData& s);

// Detects a signal that stopped changing. A working F/T sensor or IMU always shows some noise, so
// `frozen_cycles` bit-identical readings in a row mean a dead channel (cable, converter, driver).
// Encoders are not watched: quantized, they rightly repeat while a joint stands still.
class FrozenSignalDetector {
 public:
  void reset(const SensorData& first);
  // Returns nullptr, or a static string naming the frozen signal.
  const char* update(const SensorData& s, int frozen_cycles);

 private:
  std::array<Wrench, 2> last_wrench_;
  Eigen::Vector3d last_rate_ = Eigen::Vector3d::Zero(), last_acceleration_ = Eigen::Vector3d::Zero();
  std::array<int, 2> wrench_repeats_ = {0, 0};
  int imu_repeats_ = 0;
};

// The joint angles a controller starts from: the encoder readings when the reading is plausible,
// else the stand pose; clamped to the software limits.
Eigen::VectorXd initial_joint_pose(const RobotModel& model, const SensorLimits& limits, const SensorData& first);
// The same written into a full configuration (the stand keyframe's floating base).
Eigen::VectorXd initial_configuration(const RobotModel& model, const SensorLimits& limits, const SensorData& first);

}  // namespace biped
