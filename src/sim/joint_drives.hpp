#pragma once
// The robot's own decentralized joint position controllers, as on LOLA: a cascade of a
// proportional position loop and a proportional-integral velocity loop (the current loop is taken
// as ideal), with torque saturation by the drive's speed–torque envelope (available_torque),
// evaluated every physics step:
//   v_ref = K_p (q_d − q) + q̇_d,   τ = sat(K_v (v_ref − q̇) + K_i ∫(v_ref − q̇) dt)
// Gains come from the loop bandwidths and the inertia J each joint's drive moves in the reference
// pose with the floating base free (rotor inertia included): K_p = ω_p, K_v = J ω_v, K_i = K_v ω_i. The integrator carries static loads
// (a stance ankle holding the robot) without a standing position error, like a real drive; the
// finite bandwidth keeps the servo from being infinitely stiff.
// Each joint's Coulomb friction and viscous damping (gear and bearing losses) are the MJCF's
// `frictionloss` and `damping`, which MuJoCo applies.
#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <vector>

#include "model/robot_model.hpp"

namespace biped {

struct DriveParams {
  double bandwidth_hz = 20.0;         // position loop: ω_p = 2π·bandwidth (robots.md: 15–25 Hz)
  double velocity_loop_ratio = 4.0;   // ω_v / ω_p
  double integral_ratio = 0.25;       // ω_i / ω_v
  // Speed–torque envelope (motor voltage limit) of every drive, as a joint's no-load speed ω_0 and its
  // stall torque at full voltage as a multiple of the current-limited peak torque τ_max.
  double no_load_speed = 10.5;         // [rad/s] ω_0 at the joint
  double voltage_stall_ratio = 3.0;    // τ_stall / τ_max
};

// Torque a drive can deliver in the direction of `torque` at joint speed `velocity`: τ_max braking
// (torque against the motion, the back-EMF helps), and while motoring the lesser of τ_max (current
// limit) and the voltage limit's line τ_stall·(1 − |q̇|/ω_0), which reaches τ_max at the corner speed
// ω_0·(1 − τ_max/τ_stall) and falls to zero at ω_0.
double available_torque(double torque, double velocity, double peak_torque, const DriveParams& params);

class JointDrives {
 public:
  // `plant` is the simulated robot; gains are computed at its "stand" keyframe.
  JointDrives(const RobotModel& plant, const DriveParams& params);

  // Holds new set-points (plant joint order); the velocity reference q̇_d is the set-point's rate
  // of change over the last control period.
  void set_targets(const Eigen::VectorXd& position, double control_period);
  // Writes the saturated torques into d->ctrl for the current state of d and advances the velocity
  // loops' integrators by dt.
  void apply(const mjModel* m, mjData* d, double dt);
  void reset();

  double position_gain() const { return position_gain_; }
  const Eigen::VectorXd& velocity_gain() const { return kv_; }
  const Eigen::VectorXd& integral_gain() const { return ki_; }
  const Eigen::VectorXd& target() const { return target_; }

 private:
  const RobotModel& plant_;
  DriveParams params_;
  double position_gain_ = 0.0;
  Eigen::VectorXd kv_, ki_, torque_limit_;
  Eigen::VectorXi actuator_;  // actuator id per plant joint
  Eigen::VectorXd target_, target_rate_, integral_;
  bool has_target_ = false;
};

}  // namespace biped
