#include "sim/joint_drives.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/LU>

namespace biped {

JointDrives::JointDrives(const RobotModel& plant, const DriveParams& params)
    : plant_(plant),
      params_(params),
      kv_(plant.num_joints()),
      ki_(plant.num_joints()),
      torque_limit_(plant.num_joints()),
      actuator_(plant.num_joints()),
      target_(plant.stand_pose()),
      target_rate_(Eigen::VectorXd::Zero(plant.num_joints())),
      integral_(Eigen::VectorXd::Zero(plant.num_joints())) {
  const mjModel* m = plant.mj();
  RobotData data(plant);
  mjData* d = data.mj();
  Eigen::Map<Eigen::VectorXd>(d->qpos, m->nq) = plant.stand_qpos();
  mj_forward(m, d);  // fills qM (rotor inertia included through armature)
  // The inertia a joint's drive accelerates when everything else is free to move (floating base):
  // 1/(M⁻¹)_ii. It is the smallest the drive ever sees, so the velocity loop stays stable at the
  // physics step; in stance the robot's mass adds to it and the integrator holds the load.
  Eigen::MatrixXd M(m->nv, m->nv);
  mj_fullM(m, M.data(), d->qM);
  const Eigen::MatrixXd M_inverse = M.inverse();
  const double omega_p = 2.0 * M_PI * params.bandwidth_hz;
  const double omega_v = params.velocity_loop_ratio * omega_p;
  position_gain_ = omega_p;
  for (int i = 0; i < plant.num_joints(); ++i) {
    const JointInfo& j = plant.joints()[i];
    const double inertia = 1.0 / M_inverse(j.dof_adr, j.dof_adr);
    kv_[i] = inertia * omega_v;
    ki_[i] = kv_[i] * params.integral_ratio * omega_v;
    torque_limit_[i] = j.torque_limit;
    actuator_[i] = -1;
    for (int a = 0; a < m->nu; ++a) {
      if (m->actuator_trntype[a] == mjTRN_JOINT && m->actuator_trnid[2 * a] == j.mj_joint) actuator_[i] = a;
    }
    if (j.passive) actuator_[i] = -1;  // no drive, whatever the model's actuators
    else if (actuator_[i] < 0) throw ModelError(plant.path() + ": joint '" + j.name + "' has no motor actuator");
  }
}

double available_torque(double torque, double velocity, double peak_torque, const DriveParams& params) {
  if (torque * velocity <= 0.0) return peak_torque;
  const double voltage_limit =
      params.voltage_stall_ratio * peak_torque * std::max(0.0, 1.0 - std::abs(velocity) / params.no_load_speed);
  return std::min(peak_torque, voltage_limit);
}

void JointDrives::reset() {
  integral_.setZero();
  target_rate_.setZero();
  has_target_ = false;
}

void JointDrives::set_targets(const Eigen::VectorXd& position, double control_period) {
  if (has_target_) {
    target_rate_ = (position - target_) / control_period;
  }
  target_ = position;
  has_target_ = true;
}

void JointDrives::apply(const mjModel* m, mjData* d, double dt) {
  const auto& joints = plant_.joints();
  for (int i = 0; i < static_cast<int>(joints.size()); ++i) {
    if (actuator_[i] < 0) continue;
    const double q = d->qpos[joints[i].qpos_adr];
    const double qd = d->qvel[joints[i].dof_adr];
    const double velocity_error = position_gain_ * (target_[i] - q) + target_rate_[i] - qd;
    const double unsaturated = kv_[i] * velocity_error + ki_[i] * integral_[i];
    const double limit = torque_limit_[i] > 0.0 ? available_torque(unsaturated, qd, torque_limit_[i], params_)
                                                : std::abs(unsaturated);
    const double tau = std::clamp(unsaturated, -limit, limit);
    // Anti-windup: the integrator holds while the drive is saturated.
    if (tau == unsaturated) integral_[i] += velocity_error * dt;
    d->ctrl[actuator_[i]] = tau / m->actuator_gear[6 * actuator_[i]];
  }
}

}  // namespace biped
