#pragma once
// The upper body's roll and pitch from the gyro and the accelerometer, aided by the leg kinematics
// (an extension beyond the paper, issue 15 item 4).
//
// Why: an IMU unit's attitude filter turns its orientation towards the accelerometer's "up", and
// while a biped walks that "up" leans with the robot's own accelerations (a leaning inverted
// pendulum accelerates towards its lean), so the unit's roll and pitch are off by 0.5–1.9° in
// walking and the stabilizer, which drives the tilt to zero, leans the real robot by as much
// (docs/stabilizer.md "What makes the noisy runs fall"). A loaded stance foot does not move, so
// the encoders give the IMU's velocity relative to the ground in the IMU's own axes:
//     v_kin = ṙ + ω × r,   r = the IMU's position relative to the stance foot (upper-body axes).
// The foot may turn on its compliant sole (the gyro's ω includes that); the point of reference is
// the sole's centre, on the ground, which moves least when it does.
// A velocity-aided complementary filter (the structure of aided inertial navigation) integrates
// the specific force f into a velocity, v̂' = f + R̂ᵀg − ω × v̂ + k_v e, e = v_kin − v̂, and turns
// R̂ by ω_c = −k_θ (R̂ᵀg × e)/|g|²: a tilt error θ makes v̂ drift by g × θ, so e's drift measures θ
// without mistaking the robot's accelerations for gravity. The error dynamics are
// θ'' + k_v θ' + k_θ θ = 0 (k_v = 2ζω_n, k_θ = ω_n²); a gyro bias error b leaves 2ζb/ω_n.
// The gyro bias left after the start-up calibration is tracked by integrating the correction,
// b̂' = −κ ω_c (its roll and pitch parts: the yaw part is not observable from gravity).
// The heading stays the IMU unit's (gravity does not observe it).
// Allocation-free in apply(); non-finite readings never enter the state.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>

#include "interface/sensor_data.hpp"
#include "model/body_tree.hpp"
#include "model/robot_model.hpp"

namespace biped {

struct AttitudeEstimatorParams {
  bool enabled = true;
  // ω_n [rad/s] of the tilt correction. LOLA's training campaign (docs/stabilizer.md) walked about
  // equally with 1, 2 and 4 rad/s (bias tracking 0.05, 0.1, 0.2/s), each far better than the unit's.
  double bandwidth = 2.0;
  double damping = 1.0;    // ζ of the tilt correction
  double bias_gain = 0.1;  // κ [1/s] of the gyro bias tracking (0: off)
  double max_bias = 0.01;  // [rad/s] bound of the tracked bias
  // A foot is a stance foot for the kinematics when it carries this share of the weight above the
  // F/T sensors and its centre of pressure lies `cop_margin` inside its sole (not rolling on an edge).
  double min_load_share = 0.3;
  double cop_margin = 0.02;  // [m]
  // [s] without a stance foot this long, the velocity restarts from the kinematics' (no stale state).
  double max_gap = 0.3;
  // [s] the restart: for this long the velocity follows the kinematics' (time constant a third of
  // it) and the tilt is not corrected. One cycle's kinematic velocity is a difference of noisy,
  // quantized encoder readings, and a foot that has just stopped rocking on its edge still moves:
  // taken as it is, it turned into degrees of tilt error after a sideways push (docs/stabilizer.md).
  double restart_time = 0.05;
};

class AttitudeEstimator {
 public:
  AttitudeEstimator(const RobotModel& model, const AttitudeEstimatorParams& params);

  // Forgets the state: the next reading with a healthy IMU starts it.
  void reset();
  // One cycle on the calibrated readings (IMU in the upper body's axes): returns them with the
  // orientation's roll and pitch replaced by the estimate (unchanged when disabled or the IMU is
  // unhealthy). `ft_healthy` says which foot's readings may choose the stance foot; `encoders`: the
  // frames of these readings' joint angles (EncoderKinematics). The reference stays valid until the
  // next call.
  const SensorData& apply(const SensorData& sensors, bool imu_healthy, const std::array<bool, 2>& ft_healthy,
                          const BodyFrames& encoders, double dt);

  // The estimate (valid once started) and the foot whose kinematics were used last cycle (−1: none).
  const Eigen::Quaterniond& orientation() const { return orientation_; }
  const Eigen::Vector3d& gyro_bias() const { return bias_; }  // tracked on top of the calibration's
  int stance_foot() const { return stance_; }

 private:
  // The foot to take the kinematics from this cycle (−1: none).
  int choose_stance(const SensorData& s, const std::array<bool, 2>& ft_healthy) const;

  const RobotModel& model_;
  AttitudeEstimatorParams params_;
  Eigen::Vector3d imu_in_upper_body_;  // the IMU site's position in the upper body's frame
  SensorData out_;

  bool started_ = false;
  Eigen::Quaterniond orientation_ = Eigen::Quaterniond::Identity();  // R̂: IMU axes in the world
  Eigen::Vector3d velocity_ = Eigen::Vector3d::Zero();                // v̂: the IMU's, IMU axes
  Eigen::Vector3d bias_ = Eigen::Vector3d::Zero();                    // b̂ [rad/s], IMU axes
  std::array<Eigen::Vector3d, 2> last_position_;  // r per foot, last cycle
  std::array<bool, 2> have_position_{false, false};
  int stance_ = -1;
  double gap_ = 0.0;  // [s] since the last cycle with a stance foot
  double restarting_ = 0.0;  // [s] left of the velocity's restart
};

}  // namespace biped
