#include "model/multibody_zmp.hpp"

#include "math/rotations.hpp"

namespace biped {

Eigen::Vector2d multibody_zmp(const RobotModel& model, RobotData& data, const Eigen::VectorXd& q0,
                              const Eigen::VectorXd& q1, const Eigen::VectorXd& q2, double dt, double* normal_force) {
  const mjModel* m = model.mj();
  mjData* d = data.mj();
  // qvel and qacc as the mean and difference of the two one-sided velocities (mj_differentiatePos
  // handles the free joint's quaternion).
  mj_differentiatePos(m, d->qvel, dt, q0.data(), q1.data());
  mj_differentiatePos(m, d->qacc, dt, q1.data(), q2.data());
  for (int i = 0; i < m->nv; ++i) {
    const double v0 = d->qvel[i], v1 = d->qacc[i];
    d->qvel[i] = 0.5 * (v0 + v1);
    d->qacc[i] = (v1 - v0) / dt;
  }
  mju_copy(d->qpos, q1.data(), m->nq);
  mj_inverse(m, d);
  // The free joint's generalized force: force in the world frame, torque in the root body's frame,
  // both at the root body's origin.
  const int root = model.pelvis_body();
  const Eigen::Vector3d force(d->qfrc_inverse);
  const Eigen::Vector3d torque = math::mat_from_mujoco(d->xmat + 9 * root) * Eigen::Vector3d(d->qfrc_inverse + 3);
  const Eigen::Vector3d origin(d->xpos + 3 * root);
  if (normal_force) *normal_force = force.z();
  return {origin.x() - (torque.y() + origin.z() * force.x()) / force.z(),
          origin.y() + (torque.x() - origin.z() * force.y()) / force.z()};
}

}  // namespace biped
