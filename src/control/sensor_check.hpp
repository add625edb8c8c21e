#pragma once
// Plausibility check of one sensor reading: every value finite and inside its physical range.
#include "interface/fault.hpp"
#include "interface/sensor_data.hpp"
#include "model/robot_model.hpp"

namespace biped {

struct SensorLimits {
  double max_force = 5000.0;          // [N] per F/T axis
  double max_torque = 500.0;          // [N·m] per F/T axis
  double max_angular_rate = 20.0;     // [rad/s]
  double max_acceleration = 160.0;    // [m/s²] (16 g)
  double encoder_margin = 0.05;       // [rad] tolerated beyond the hard joint limits
  int frozen_cycles = 50;             // identical F/T or IMU readings in a row that mean a dead signal (0: off)
};

// The first implausible signal of the reading (checked in the order time, encoders, IMU, F/T), or
// no fault (a false Fault).
Fault check_sensors(const RobotModel& model, const SensorLimits& limits, const SensorData& s);

}  // namespace biped
