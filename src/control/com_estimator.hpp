#pragma once
// State estimation from sensors only: the robot CoM relative to the stance foot (eq. (10)'s r_CoM),
// from the joint encoders and the IMU's upper-body orientation (the kinematic chain anchored at the
// stance foot), and its rate.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "interface/sensor_data.hpp"
#include "model/robot_model.hpp"

namespace biped {

class CoMEstimator {
 public:
  explicit CoMEstimator(const RobotModel& model);

  // r_CoM − r_foot in the gravity-aligned frame that has the upper body's heading, from the frames
  // of the encoder angles (EncoderKinematics) and the IMU orientation of the upper body.
  Eigen::Vector3d com_from_foot(const BodyFrames& encoders, const Eigen::Quaterniond& upper_body, Side foot) const;

  // The upper body's orientation in the world if the `stance` foot stands flat on level ground with
  // heading `stance_yaw`, from the encoders alone: what stands in for a failed IMU.
  Eigen::Quaterniond upper_body_on_flat_foot(const Eigen::VectorXd& joint_positions, Side stance, double stance_yaw);

  // Forgets the last estimate: the next update() starts the rate from zero.
  void reset() { has_estimate_ = false; }
  // One cycle: the horizontal CoM relative to `stance` and its rate, differentiated over dt and
  // filtered (T = 10 ms); a change of stance foot restarts the rate. `encoders`: the frames of the
  // readings' joint angles.
  void update(const SensorData& sensors, const BodyFrames& encoders, Side stance, double dt);
  const Eigen::Vector2d& estimate() const { return estimate_; }  // [m], heading frame (x forward, y left)
  const Eigen::Vector2d& rate() const { return rate_; }          // [m/s]
  // The same rate carried over a change of stance foot instead of restarted (both feet stand there,
  // so the CoM moves against either alike): the hip strategy's DCM error. Restarted, the rate reads
  // as a DCM error of −v/ω₀ at every change (docs/stabilizer.md); eq. (10) keeps the restarting
  // rate its gains were tuned with.
  const Eigen::Vector2d& carried_rate() const { return carried_rate_; }  // [m/s]

 private:
  const RobotModel& model_;
  // upper_body_on_flat_foot's workspace (it serves a failed IMU, outside the cycle's kinematics)
  Eigen::VectorXd qpos_;
  BodyFrames frames_;
  Eigen::Vector2d estimate_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d rate_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d carried_rate_ = Eigen::Vector2d::Zero();
  Side stance_ = Side::Left;
  bool has_estimate_ = false;
};

}  // namespace biped
