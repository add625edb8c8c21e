#include "model/kinematics.hpp"

#include <algorithm>

namespace biped {

void forward_kinematics(const RobotModel& model, RobotData& data) { mj_kinematics(model.mj(), data.mj()); }

void forward_kinematics_with_com(const RobotModel& model, RobotData& data) {
  mj_kinematics(model.mj(), data.mj());
  mj_comPos(model.mj(), data.mj());
}

void kinematics_at_origin(const RobotModel& model, const Eigen::VectorXd& joint_positions, Eigen::VectorXd& qpos,
                          BodyFrames& frames) {
  for (int i = 0; i < 7; ++i) qpos[i] = i == 3 ? 1.0 : 0.0;  // position 0, quaternion (1, 0, 0, 0)
  for (int i = 0; i < model.num_joints(); ++i) qpos[model.joints()[i].qpos_adr] = joint_positions[i];
  forward_kinematics(model.tree(), qpos, frames);
}

EncoderKinematics::EncoderKinematics(const RobotModel& model)
    : model_(model), qpos_(model.stand_qpos()), frames_(model.tree()) {}

void EncoderKinematics::update(const Eigen::VectorXd& joint_positions) {
  kinematics_at_origin(model_, joint_positions, qpos_, frames_);
  subtree_coms(model_.tree(), frames_);
}

void integrate_configuration(const RobotModel& model, const Eigen::VectorXd& qdot, double dt, Eigen::VectorXd& qpos) {
  mj_integratePos(model.mj(), qpos.data(), qdot.data(), dt);
}

LegMassSplit leg_mass_split(const RobotModel& model) {
  const mjModel* m = model.mj();
  RobotData data(model);
  data.qpos() = model.stand_qpos();
  forward_kinematics_with_com(model, data);
  const mjData* d = data.mj();
  double moving = 0.0, moment = 0.0, ankle_height = 0.0;
  for (Side side : kSides) {
    const int joint_index = model.leg_root_joint(side);
    if (joint_index < 0) {
      throw ModelError(model.path() + ": no joint '" + model.map().legs[index_of(side)].root_joint +
                       "' (root of the " + name_of(side) + " leg)");
    }
    const int joint = model.joints()[joint_index].mj_joint;
    const int leg = m->jnt_bodyid[joint];
    const FootInfo& foot = model.foot(side);
    const double hip_z = d->xanchor[3 * joint + 2];
    const double ankle_z = d->xpos[3 * foot.body + 2];
    const double sole_z = d->site_xpos[3 * foot.sensor_site + 2] + foot.sole_z;
    for (int b = leg; b < m->nbody; ++b) {
      int parent = b;
      while (parent != leg && parent != 0) parent = m->body_parentid[parent];
      if (parent != leg) continue;
      const double z = d->xipos[3 * b + 2];
      const double r = std::clamp((hip_z - z) / (hip_z - ankle_z), 0.0, 1.0);
      moving += m->body_mass[b] * r;
      moment += m->body_mass[b] * r * (z - ankle_z);
    }
    ankle_height += 0.5 * (ankle_z - sole_z);
  }
  return {moving, moment / moving, ankle_height};
}

}  // namespace biped
