#pragma once
// Sensor calibration and drift tracking (an extension beyond the paper, issue 15 item 4): estimates
// the errors of the IMU and the F/T sensors from what the controller knows (encoders, the plan's
// contact state, the robot's masses) and removes them from the readings the rest of the
// controller sees.
//  - Start-up, standing on both feet on level ground (the controller's assumption at reset): the
//    IMU's roll and pitch misalignment against the upper body (the IMU's orientation against the
//    upper body's from the leg encoders, each foot turned by its sole's deflection under the
//    measured wrench, −K⁻¹λ of eq. (11); it takes up the accelerometer's bias too) and the gyro bias
//    (the integrated rate against the upper body's rotation from the same kinematics); the common
//    part of the F/T force offsets (the feet's summed force against the weight above the sensors;
//    only the sum is observable on two feet).
//  - In every swing: that foot's F/T offsets (the reading against the weight and the planned
//    acceleration of the part of the foot below the sensor).
//  - The attitude filter's error caused by the gyro bias (roll/pitch off by τ·b in steady state) can
//    be predicted from the bias estimate with the filter's time constant (off by default).
//  - While walking (off by default): the remaining tilt error, slowly (the kinematic tilt from the loaded stance foot,
//    assumed flat, against the IMU's), bounded.
// Allocation-free in apply(); non-finite readings never enter an estimate.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>

#include "control/contact_model.hpp"
#include "interface/sensor_data.hpp"
#include "math/wrench.hpp"
#include "model/body_tree.hpp"
#include "model/robot_model.hpp"
#include "planning/walking_pattern_generator.hpp"

namespace biped {

struct SensorCalibrationParams {
  bool enabled = true;
  double startup_time = 1.0;                        // [s] estimation window while standing after reset
  // Each standing foot turned by its sole's deflection under the measured wrench (eq. 11's contact
  // model) in the start-up estimates; false: the feet taken as flat (JVRC-1: its roll bias estimate
  // came out 9 mrad/s off with it, docs/stabilizer.md).
  bool sole_deflection = true;
  // [s] of the IMU's attitude filter, to predict its tilt error from the gyro bias (0: no model).
  // Off by default: the start-up bias estimate is off by up to 2 mrad/s (the soles' compliance lets
  // the upper body turn more than the flat-foot kinematics say), and τ times that is as large as the
  // error it would remove (docs/stabilizer.md).
  double ahrs_time_constant = 0.0;
  // [s] time constant of the drift tracking (0: off). Off by default: on slopes and steps the stance
  // foot is not level and the correction leans the robot (docs/stabilizer.md).
  double drift_time = 0.0;
  double max_drift = 1.0 * M_PI / 180.0;            // [rad] bound of the drift correction
  double max_misalignment = 5.0 * M_PI / 180.0;     // [rad] larger start-up estimates are not used
  // [rad] smaller start-up estimates are not used: the flat-foot reference is good to about 0.2° (the
  // standing feet pitch on their compliant soles; exact sensors read 0.16°).
  double min_misalignment = 0.3 * M_PI / 180.0;
  double max_gyro_bias = 0.05;                      // [rad/s] larger start-up estimates are not used
  bool ft_swing_rezero = true;                      // re-zero each F/T sensor in its foot's swing
  double swing_clearance = 0.02;                    // [m] planned height above the stance foot to count
  double swing_force_band = 40.0;                   // [N] a swing reading further off touches something
  double max_force_offset = 50.0;                   // [N] larger offset estimates are not used
  double max_torque_offset = 5.0;                   // [N·m] larger offset estimates are not used
};

// What the controller knows besides the readings.
struct CalibrationContext {
  bool standing = false;                 // both feet flat on the ground, no walking command yet
  const PatternSample* plan = nullptr;   // contact state, stance foot, planned foot accelerations
  bool imu_healthy = true;
  std::array<bool, 2> ft_healthy{true, true};
};

class SensorCalibration {
 public:
  // `contact`: the stabilizer's contact model of eq. (11), for the soles' deflection.
  SensorCalibration(const RobotModel& model, const SensorCalibrationParams& params, const ContactModelParams& contact);

  // Forgets every estimate; `time` is the reset's (the start of the start-up window).
  void reset(double time);
  // One cycle: updates the estimates and returns the corrected readings (the input unchanged when
  // disabled). `encoders`: the frames of the readings' joint angles (EncoderKinematics). The
  // reference stays valid until the next call.
  const SensorData& apply(const SensorData& sensors, const CalibrationContext& context, const BodyFrames& encoders,
                          double dt);

  // Estimates (zero until known): IMU axes against the upper body's as a rotation vector in the
  // upper body's axes (roll, pitch; no yaw), gyro bias [rad/s] in IMU axes, the attitude filter's
  // predicted bias error and the tracked drift [rad] (rotation vectors), F/T offsets by Side.
  const Eigen::Vector3d& misalignment() const { return misalignment_; }
  const Eigen::Vector3d& gyro_bias() const { return gyro_bias_; }
  const Eigen::Vector3d& bias_tilt() const { return bias_tilt_; }
  const Eigen::Vector3d& drift() const { return drift_; }
  const std::array<Wrench, 2>& ft_offset() const { return ft_offset_; }
  bool startup_done() const { return startup_done_; }
  int swing_rezeros() const { return swing_rezeros_; }

 private:
  // The sole's tilt (x, y; z = 0) under `measured`, in the foot's axes: the rotation rows of −K⁻¹λ
  // (zero for a foot without load or a non-finite reading).
  Eigen::Vector3d sole_deflection(Side foot, const Wrench& measured) const;
  // The upper body's orientation on `foot`, turned by `sole_tilt`, in the world up to its heading.
  Eigen::Matrix3d upper_body_on_foot(Side foot, const Eigen::Vector3d& sole_tilt) const;
  // The tilt (x, y; z = 0) of `orientation` against the upper body's on `foot` lying on level
  // ground with its sole tilted by `sole_tilt`, in the upper body's axes: log(R_kinᵀ R) with R_kin's
  // heading matched to R's.
  Eigen::Vector3d tilt_against_foot(const Eigen::Quaterniond& orientation, Side foot, const Eigen::Vector3d& sole_tilt) const;
  // What foot k's F/T sensor reads without ground contact: the weight and planned acceleration of
  // the part below it, in the sensor frame, with the upper body at `upper_body`.
  Wrench swing_reading(int k, const Eigen::Quaterniond& upper_body, const Eigen::Vector3d& acceleration) const;
  void estimate_at_startup(const SensorData& s, const CalibrationContext& c, double dt);
  void track_swing_offsets(const SensorData& s, const CalibrationContext& c, const Eigen::Quaterniond& upper_body);
  void track_drift(const Eigen::Quaterniond& upper_body, const SensorData& s, const CalibrationContext& c, double dt);
  Eigen::Quaterniond corrected_orientation(const Eigen::Quaterniond& measured) const;

  const RobotModel& model_;
  SensorCalibrationParams params_;
  std::array<Eigen::Matrix3d, 2> compliance_;  // K⁻¹ of each flat foot, eq. (11)
  // The encoders' frames (base at the origin, unrotated) of the apply() under way.
  const BodyFrames* frames_ = nullptr;
  SensorData out_;

  double start_time_ = 0.0;
  bool startup_done_ = false;
  // Start-up sums.
  int startup_samples_ = 0;
  Eigen::Vector3d sum_tilt_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d rate_integral_ = Eigen::Vector3d::Zero();  // ∫ gyro dt [rad]
  double rate_time_ = 0.0;
  Eigen::Matrix3d first_body_on_foot_ = Eigen::Matrix3d::Identity();
  Eigen::Vector3d sum_up_ = Eigen::Vector3d::Zero();
  double sum_bias_gain_ = 0.0;           // Σ τ(1 − e^(−t/τ)): the filter's bias error build-up
  int force_samples_ = 0;
  Eigen::Vector3d sum_force_error_ = Eigen::Vector3d::Zero();  // world: Σ feet's force − weight above
  // Swing sums, by Side.
  std::array<int, 2> swing_samples_{};
  std::array<Wrench, 2> swing_sum_;
  int swing_rezeros_ = 0;

  Eigen::Vector3d misalignment_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d gyro_bias_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d bias_tilt_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d drift_ = Eigen::Vector3d::Zero();
  std::array<Wrench, 2> ft_offset_;
};

}  // namespace biped
