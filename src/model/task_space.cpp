#include "model/task_space.hpp"

#include "math/rotations.hpp"

#include <algorithm>
#include <cmath>

namespace biped {
namespace {

// All bodies in the subtree of `root` (root included).
bool in_subtree(const mjModel* m, int body, int root) {
  for (int b = body; b > 0; b = m->body_parentid[b]) {
    if (b == root) return true;
  }
  return false;
}

int count_dofs_in_subtree(const mjModel* m, int root) {
  int dofs = 0;
  for (int j = 0; j < m->njnt; ++j) {
    if (in_subtree(m, m->jnt_bodyid[j], root)) dofs += m->jnt_type[j] == mjJNT_HINGE ? 1 : 0;
  }
  return dofs;
}

void add_rows(std::vector<std::string>& names, const std::string& prefix, int count,
              const char* const* suffixes) {
  for (int i = 0; i < count; ++i) names.push_back(prefix + suffixes[i]);
}


}  // namespace

TaskSpace::TaskSpace(const RobotModel& model) : model_(&model) {
  const mjModel* m = model.mj();
  constexpr std::array<Side, 2> kRowOrder = {Side::Right, Side::Left};  // Table I lists right first

  int arm_dofs = 3;
  for (Side side : kSides) {
    foot_body_[index_of(side)] = model.foot(side).body;
    const int j = model.arm_root_joint(side);
    if (j < 0) {
      throw ModelError(model.path() + ": the model has no joint named '" + model.map().legs[index_of(side)].arm_root_joint +
                       "' (root of the " + name_of(side) + " arm)");
    }
    arm_body_[index_of(side)] = m->jnt_bodyid[model.joints()[j].mj_joint];
    arm_dofs = std::min(arm_dofs, count_dofs_in_subtree(m, arm_body_[index_of(side)]));
  }
  if (arm_dofs < 2) throw ModelError(model.path() + ": each arm needs at least two joints");
  // An arm with fewer than three joints cannot place its CoM in 3D: only x and y are tasks.
  layout_.arm_com_rows = arm_dofs >= 3 ? 3 : 2;
  layout_.has_toes = model.toe_joint(Side::Left) >= 0 && model.toe_joint(Side::Right) >= 0;
  for (const JointInfo& joint : model.joints()) {
    if (joint.passive || joint.locked) held_dofs_.push_back(joint.dof_adr);
  }

  static const char* const kXyz[] = {"_x", "_y", "_z"};
  static const char* const kPhi[] = {"_phi_x", "_phi_y", "_phi_z"};
  int row = 0;
  for (Side side : kRowOrder) {
    layout_.foot_position[index_of(side)] = row;
    row += 3;
    add_rows(row_names_, std::string(name_of(side)) + "_foot", 3, kXyz);
  }
  for (Side side : kRowOrder) {
    layout_.foot_orientation[index_of(side)] = row;
    row += 3;
    add_rows(row_names_, std::string(name_of(side)) + "_foot", 3, kPhi);
  }
  for (Side side : kRowOrder) {
    layout_.arm_com[index_of(side)] = row;
    row += layout_.arm_com_rows;
    add_rows(row_names_, std::string(name_of(side)) + "_arm_com", layout_.arm_com_rows, kXyz);
  }
  layout_.upper_body_orientation = row;
  row += 3;
  add_rows(row_names_, "upper_body", 3, kPhi);
  layout_.com = row;
  row += 3;
  add_rows(row_names_, "com", 3, kXyz);
  layout_.dim = row;

  if (layout_.dim > m->nv) {
    throw ModelError(model.path() + ": " + std::to_string(layout_.dim) + " task coordinates but only " +
                     std::to_string(m->nv) + " generalized velocities");
  }
}

TaskSpaceData::TaskSpaceData(const TaskSpace& space)
    : x(Eigen::VectorXd::Zero(space.dim())),
      J(Eigen::MatrixXd::Zero(space.dim(), space.nv())),
      frames_(space.model().tree()),
      jac_com_(3, space.nv()),
      jac_upper_body_rot_(3, space.nv()),
      jac_tmp_(3, space.nv()) {
  foot_position[0].setZero();
  foot_position[1].setZero();
}

void evaluate(const TaskSpace& space, const Eigen::VectorXd& qpos, const Eigen::Matrix3d& R_ref,
              TaskSpaceData& data) {
  const BodyTree& tree = space.model().tree();
  BodyFrames& f = data.frames_;
  const TaskLayout& layout = space.layout();
  Eigen::VectorXd& x = data.x;
  Eigen::MatrixXd& J = data.J;

  forward_kinematics(tree, qpos, f);
  subtree_coms(tree, f);

  const int root = space.root_body();
  data.com = f.subtree_com[root];
  subtree_com_jacobian(tree, f, root, data.jac_com_);

  const int ub = space.upper_body();
  const Eigen::Quaterniond& q_ub = f.orientation[ub];
  data.upper_body_rotation = f.rotation[ub];
  data.upper_body_position = f.position[ub];
  angular_jacobian(tree, f, ub, data.jac_upper_body_rot_);

  for (Side side : kSides) {
    const int s = index_of(side);
    const int body = space.foot_body(side);
    data.foot_position[s] = f.position[body];

    const int p = layout.foot_position[s];
    x.segment<3>(p) = data.foot_position[s] - data.com;
    point_jacobian(tree, f, body, f.position[body], J.middleRows<3>(p));
    J.middleRows<3>(p) -= data.jac_com_;

    // φ = log(R_UBᵀ R_foot); its rate is J_l⁻¹(φ) R_UBᵀ (ω_foot − ω_UB).
    const int o = layout.foot_orientation[s];
    const Eigen::Vector3d phi = math::so3::log(q_ub.conjugate() * f.orientation[body]);
    x.segment<3>(o) = phi;
    const Eigen::Matrix3d map = math::so3::inverse_left_jacobian(phi) * data.upper_body_rotation.transpose();
    angular_jacobian(tree, f, body, data.jac_tmp_);
    data.jac_tmp_ -= data.jac_upper_body_rot_;
    J.middleRows<3>(o).noalias() = map * data.jac_tmp_;

    const int a = layout.arm_com[s];
    const int n = layout.arm_com_rows;
    const int arm = space.arm_body(side);
    subtree_com_jacobian(tree, f, arm, data.jac_tmp_);
    x.segment(a, n) = (f.subtree_com[arm] - data.com).head(n);
    J.middleRows(a, n) = (data.jac_tmp_ - data.jac_com_).topRows(n);
  }

  // φ_UB = log(R_refᵀ R_UB); its rate is J_l⁻¹(φ_UB) R_refᵀ ω_UB.
  const int u = layout.upper_body_orientation;
  const Eigen::Vector3d phi_ub = math::so3::log(Eigen::Quaterniond(R_ref).conjugate() * q_ub);
  x.segment<3>(u) = phi_ub;
  const Eigen::Matrix3d map = math::so3::inverse_left_jacobian(phi_ub) * R_ref.transpose();
  J.middleRows<3>(u).noalias() = map * data.jac_upper_body_rot_;

  const int c = layout.com;
  x.segment<3>(c) = data.com;
  J.middleRows<3>(c) = data.jac_com_;

  // A passive joint has no drive to move it and a locked one stays at the stand pose: no task may
  // ask for either (the null-space objective keeps them at the pose).
  for (int dof : space.held_dofs()) J.col(dof).setZero();
}

void task_error(const Eigen::VectorXd& x_d, const Eigen::VectorXd& x, Eigen::VectorXd& error) {
  error = x_d - x;
}

}  // namespace biped
