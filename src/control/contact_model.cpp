#include "control/contact_model.hpp"

#include <mujoco/mujoco.h>

#include <Eigen/QR>
#include <algorithm>

namespace biped {
namespace {

// The four sole corners (x, y) in the sensor frame.
std::array<Eigen::Vector2d, 4> sole_corners(const FootInfo& foot) {
  return {Eigen::Vector2d(foot.sole_x_min, foot.sole_y_min), Eigen::Vector2d(foot.sole_x_min, foot.sole_y_max),
          Eigen::Vector2d(foot.sole_x_max, foot.sole_y_min), Eigen::Vector2d(foot.sole_x_max, foot.sole_y_max)};
}

}  // namespace

// Linearization of eq. (11) at a flat foot: a displacement δ = (z, φ_x, φ_y) moves corner (x, y)
// by w = z + y φ_x − x φ_y and the ground pushes back with f = −C/4 · w, so (F_z, T_x, T_y) = −K δ
// with K = Σ C/4 g gᵀ, g = (1, y, −x).
Eigen::Matrix3d point_contact_stiffness(const FootInfo& foot, double contact_stiffness) {
  Eigen::Matrix3d K = Eigen::Matrix3d::Zero();
  for (double x : {foot.sole_x_min, foot.sole_x_max}) {
    for (double y : {foot.sole_y_min, foot.sole_y_max}) {
      const Eigen::Vector3d g(1.0, y, -x);
      K += 0.25 * contact_stiffness * g * g.transpose();
    }
  }
  return K;
}

// eq. (11): F = Σ C_i d_i, T = Σ Δr_i × C_i d_i over the corners in contact; d_i is the corner's
// depth below the ground plane along the world z axis (no friction), Δr_i the corner relative to
// the sensor point. Both are expressed in the sensor frame.
Eigen::Vector3d point_contact_wrench(const FootInfo& foot, double contact_stiffness,
                                     const Eigen::Vector3d& sensor_position, const Eigen::Matrix3d& sensor_rotation,
                                     double ground_height) {
  Eigen::Vector3d force = Eigen::Vector3d::Zero(), torque = Eigen::Vector3d::Zero();
  const Eigen::Vector3d up = sensor_rotation.transpose().col(2);  // world z in the sensor frame
  for (const Eigen::Vector2d& c : sole_corners(foot)) {
    const Eigen::Vector3d r(c.x(), c.y(), foot.sole_z);
    const double depth = ground_height - (sensor_position + sensor_rotation * r).z();
    const Eigen::Vector3d f = 0.25 * contact_stiffness * std::max(depth, 0.0) * up;
    force += f;
    torque += r.cross(f);
  }
  return {force.z(), torque.x(), torque.y()};
}

std::array<Eigen::Vector3d, 2> point_contact_wrenches(const RobotModel& model, RobotData& data,
                                                      const Eigen::VectorXd& qpos, double contact_stiffness,
                                                      double ground_height) {
  const mjModel* m = model.mj();
  mjData* d = data.mj();
  Eigen::Map<Eigen::VectorXd>(d->qpos, m->nq) = qpos;
  mj_kinematics(m, d);
  std::array<Eigen::Vector3d, 2> lambda;
  for (Side side : kSides) {
    const FootInfo& foot = model.foot(side);
    const Eigen::Vector3d position(d->site_xpos + 3 * foot.sensor_site);
    const Eigen::Matrix3d rotation =
        Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(d->site_xmat + 9 * foot.sensor_site);
    lambda[index_of(side)] = point_contact_wrench(foot, contact_stiffness, position, rotation, ground_height);
  }
  return lambda;
}

FootRows contact_jacobian(const RobotModel& model, const Eigen::VectorXd& qpos, double contact_stiffness,
                          double ground_height, double h) {
  const mjModel* m = model.mj();
  RobotData data(model);
  FootRows G(6, m->nv);
  for (int i = 0; i < m->nv; ++i) {
    Eigen::VectorXd direction = Eigen::VectorXd::Zero(m->nv);
    direction[i] = 1.0;
    Eigen::VectorXd q_plus = qpos, q_minus = qpos;
    mj_integratePos(m, q_plus.data(), direction.data(), h);
    mj_integratePos(m, q_minus.data(), direction.data(), -h);
    const auto plus = point_contact_wrenches(model, data, q_plus, contact_stiffness, ground_height);
    const auto minus = point_contact_wrenches(model, data, q_minus, contact_stiffness, ground_height);
    for (int k = 0; k < 2; ++k) G.col(i).segment<3>(3 * k) = (plus[k] - minus[k]) / (2.0 * h);
  }
  return G;
}

FootRows selected_task_rows(const TaskSpace& space, const TaskSpaceData& data) {
  const TaskLayout& L = space.layout();
  FootRows rows(6, space.nv());
  for (Side side : kSides) {
    const int k = index_of(side);
    const Eigen::Vector3d phi = data.x.segment<3>(L.foot_orientation[k]);
    // The x/y rows of the task's rotation vector rates (upper-body frame) are not foot-frame tilts
    // once the foot is yawed against the upper body; this rotates them there (the controller's
    // stabilizer_modification uses yaw(ψ_foot − ψ_heading) for it).
    const Eigen::Matrix3d to_foot = so3::exp(phi).transpose() * so3::inverse_left_jacobian(phi).inverse();
    rows.row(3 * k) = data.J.row(L.foot_position[k] + 2);
    rows.middleRows<2>(3 * k + 1) = (to_foot * data.J.middleRows<3>(L.foot_orientation[k])).topRows<2>();
  }
  return rows;
}

// eq. (20): the map S_λ∇_qλ(S̄_x∇_q x)^† whose pseudo-inverse turns the force law into the
// modification Δẋ_λ. The task rows do not depend on R_ref (only the upper-body rows do).
Eigen::Matrix<double, 6, 6> general_force_position_map(const TaskSpace& space, const Eigen::VectorXd& qpos,
                                                       double contact_stiffness, double ground_height) {
  TaskSpaceData data(space);
  evaluate(space, qpos, Eigen::Matrix3d::Identity(), data);
  const FootRows selected = selected_task_rows(space, data);
  const FootRows G = contact_jacobian(space.model(), qpos, contact_stiffness, ground_height);
  return G * selected.completeOrthogonalDecomposition().pseudoInverse();
}

}  // namespace biped
