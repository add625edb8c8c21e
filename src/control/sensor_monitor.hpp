#pragma once
// Watches every sensor signal, every cycle, for the whole run: plausibility (control/sensor_check),
// frozen F/T and IMU channels (control/frozen_signal_detector), and encoders that jump or freeze.
// A failed signal stays failed (latched) and is reported once, as a typed Fault; the health record
// tells the controller which signals it may still use, so that each fault disables only what
// depends on it, and a second or third fault at any time is handled like the first.
// A failed F/T sensor or IMU whose readings have been plausible and alive (not frozen) for
// SensorLimits::recovery_time is trusted again (a transient fault: a dropped bus frame, a converter
// reset); encoders and the time stamp never are (a jumped encoder may have lost its zero).
#include <Eigen/Core>

#include "control/frozen_signal_detector.hpp"
#include "control/sensor_check.hpp"
#include "interface/fault.hpp"
#include "interface/sensor_data.hpp"
#include "model/robot_model.hpp"

namespace biped {

struct SensorHealth {
  bool time = true;
  bool imu = true;                      // every IMU channel (a failed one makes the unit untrusted)
  std::array<bool, 2> force_torque{true, true};
  Eigen::ArrayXi encoder_failed;        // per joint (RobotModel::joints() order): 1 = failed
  bool all_good() const { return time && imu && force_torque[0] && force_torque[1] && encoder_failed.sum() == 0; }
};

class SensorMonitor {
 public:
  SensorMonitor(const RobotModel& model, const SensorLimits& limits);
  void reset(const SensorData& first);
  // One cycle: checks the raw reading; `setpoint` is the joint command in force while it was taken
  // (the encoders' frozen check compares against its motion). Adds the newly failed signals to
  // `new_faults` (cleared first). Allocation-free.
  void update(const SensorData& raw, const Eigen::VectorXd& setpoint, FaultList& new_faults);
  const SensorHealth& health() const { return health_; }
  // The signals trusted again in the last update (check None, the time of the re-admission).
  const FaultList& recovered() const { return recovered_; }

 private:
  void latch(const Fault& f, FaultList& new_faults);
  // Re-admits failed F/T sensors and the IMU whose readings have been healthy for recovery_time.
  void readmit_recovered(double time);
  bool found(FaultSignal signal, int index) const;

  const RobotModel& model_;
  SensorLimits limits_;
  FrozenSignalDetector frozen_;
  SensorHealth health_;
  FaultList found_;                     // this cycle's findings before latching
  FaultList recovered_;                 // re-admitted in the last update
  std::array<double, 2> ft_healthy_since_{};  // [s] time of the first healthy reading of a failed F/T
  double imu_healthy_since_ = 0.0;            // ... of the failed IMU
  Eigen::VectorXd last_encoder_;        // the last reading of each joint
  Eigen::VectorXd setpoint_at_repeat_;  // the set-point when each joint's reading last changed
  Eigen::ArrayXi encoder_repeats_;      // identical readings in a row, per joint
};

}  // namespace biped
