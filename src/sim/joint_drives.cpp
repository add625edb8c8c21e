#include "sim/joint_drives.hpp"

#include <algorithm>
#include <cmath>

namespace biped {

JointDrives::JointDrives(const RobotModel& plant, const DriveParams& params)
    : plant_(plant),
      kp_(plant.num_joints()),
      kd_(plant.num_joints()),
      torque_limit_(plant.num_joints()),
      actuator_(plant.num_joints()),
      target_(plant.stand_pose()),
      target_rate_(Eigen::VectorXd::Zero(plant.num_joints())) {
  const mjModel* m = plant.mj();
  RobotData data(plant);
  mjData* d = data.mj();
  Eigen::Map<Eigen::VectorXd>(d->qpos, m->nq) = plant.stand_qpos();
  mj_forward(m, d);  // fills qM (rotor inertia included through armature)
  const double omega = 2.0 * M_PI * params.bandwidth_hz;
  for (int i = 0; i < plant.num_joints(); ++i) {
    const JointInfo& j = plant.joints()[i];
    const double inertia = d->qM[m->dof_Madr[j.dof_adr]];
    kp_[i] = inertia * omega * omega;
    kd_[i] = 2.0 * params.damping_ratio * inertia * omega;
    torque_limit_[i] = j.torque_limit;
    actuator_[i] = -1;
    for (int a = 0; a < m->nu; ++a) {
      if (m->actuator_trntype[a] == mjTRN_JOINT && m->actuator_trnid[2 * a] == j.mj_joint) actuator_[i] = a;
    }
    if (actuator_[i] < 0) throw ModelError(plant.path() + ": joint '" + j.name + "' has no motor actuator");
  }
}

void JointDrives::set_targets(const Eigen::VectorXd& position, double control_period) {
  if (has_target_) {
    target_rate_ = (position - target_) / control_period;
  }
  target_ = position;
  has_target_ = true;
}

void JointDrives::apply(const mjModel* m, mjData* d) const {
  const auto& joints = plant_.joints();
  for (int i = 0; i < static_cast<int>(joints.size()); ++i) {
    const double q = d->qpos[joints[i].qpos_adr];
    const double qd = d->qvel[joints[i].dof_adr];
    double tau = kp_[i] * (target_[i] - q) + kd_[i] * (target_rate_[i] - qd);
    if (torque_limit_[i] > 0.0) tau = std::clamp(tau, -torque_limit_[i], torque_limit_[i]);
    d->ctrl[actuator_[i]] = tau / m->actuator_gear[6 * actuator_[i]];
  }
}

}  // namespace biped
