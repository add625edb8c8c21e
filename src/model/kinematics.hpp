#pragma once
// Kinematic computations on the controller's model that control/ and planning/ need, as free
// functions of the read-only RobotModel and a RobotData workspace (allocation-free), so that only
// model/ and sim/ touch MuJoCo.
#include <Eigen/Core>

#include "model/body_tree.hpp"
#include "model/robot_model.hpp"

namespace biped {

// Every body, site and joint frame at the configuration data.qpos() (mj_kinematics).
void forward_kinematics(const RobotModel& model, RobotData& data);
// The same and every subtree's CoM (mj_kinematics, mj_comPos): RobotData::subtree_com().
void forward_kinematics_with_com(const RobotModel& model, RobotData& data);

// Every body's frame with the floating base at the origin, unrotated, and the joints at
// `joint_positions` (RobotModel::joints() order): relative positions and orientations, as the
// estimators use them. `qpos` (size nq) and `frames` are the caller's workspace; no allocation.
void kinematics_at_origin(const RobotModel& model, const Eigen::VectorXd& joint_positions, Eigen::VectorXd& qpos,
                          BodyFrames& frames);

// The encoders' kinematics of one control cycle: kinematics_at_origin and every subtree's CoM,
// computed once and read by each estimator (the calibration, the attitude estimation, the CoM
// estimate). Allocation-free after construction.
class EncoderKinematics {
 public:
  explicit EncoderKinematics(const RobotModel& model);
  void update(const Eigen::VectorXd& joint_positions);
  // The frames of the last update(), with subtree_com filled in.
  const BodyFrames& frames() const { return frames_; }

 private:
  const RobotModel& model_;
  Eigen::VectorXd qpos_;
  BodyFrames frames_;
};

// qpos ← qpos ⊕ qdot·dt on the configuration manifold (the free joint's quaternion is rotated,
// not added to); qdot has one entry per generalized velocity (nv).
void integrate_configuration(const RobotModel& model, const Eigen::VectorXd& qdot, double dt, Eigen::VectorXd& qpos);

// How a swinging leg's mass moves with its foot, for the walking pattern generator's simplified
// model, in the stand pose: a leg pivots about its hip, so a segment's CoM follows the ankle's
// horizontal motion by the share r = (z_hip − z)/(z_hip − z_ankle) of its depth below the hip.
struct LegMassSplit {
  double moving_mass = 0.0;     // [kg] Σ m r over both legs: the mass that moves with the feet
  double moving_height = 0.0;   // [m] Σ m r (z − z_ankle) / Σ m r: its height above the ankles
  double ankle_height = 0.0;    // [m] ankle above the sole plane (mean of both feet)
};
// Throws ModelError when a leg has no root joint (ModelMap).
LegMassSplit leg_mass_split(const RobotModel& model);

}  // namespace biped
