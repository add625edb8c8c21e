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
  double encoder_jump = 0.03;         // [rad] an encoder moving farther in one cycle has jumped (30 rad/s at 1 kHz)
  // [rad] an encoder reading that stays bit-identical for frozen_cycles while its set-point moves
  // by more than this is frozen (a joint that follows its set-point changes its reading).
  double encoder_frozen_motion = 0.02;
  // [s] a failed F/T sensor or IMU whose readings stay plausible and alive this long is trusted
  // again (0: every fault lasts for the run). Twice the frozen check's window at 1 kHz, so that a
  // still-frozen signal is found within it; short against a step, so that a foot that lands after a
  // transient fault has its force control back.
  double recovery_time = 0.1;
};

// Every implausible signal of the reading, added to `out` (time, encoders, IMU, F/T).
void find_implausible(const RobotModel& model, const SensorLimits& limits, const SensorData& s, FaultList& out);
// The first of them (in that order), or no fault (a false Fault).
Fault check_sensors(const RobotModel& model, const SensorLimits& limits, const SensorData& s);

}  // namespace biped
