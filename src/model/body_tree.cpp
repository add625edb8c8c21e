#include "model/body_tree.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <string>

#include "model/robot_model.hpp"

namespace biped {

BodyTree make_body_tree(const mjModel* m, const char* origin) {
  BodyTree t;
  t.nq = m->nq;
  t.nv = m->nv;
  const int n = m->nbody;
  t.parent.assign(m->body_parentid, m->body_parentid + n);
  t.subtree_last.resize(n);
  for (int b = 0; b < n; ++b) t.subtree_last[b] = b;
  for (int b = n - 1; b > 0; --b) t.subtree_last[t.parent[b]] = std::max(t.subtree_last[t.parent[b]], t.subtree_last[b]);
  t.offset.resize(n);
  t.rotation_offset.resize(n);
  t.com_offset.resize(n);
  t.mass.assign(m->body_mass, m->body_mass + n);
  t.subtree_mass.assign(m->body_subtreemass, m->body_subtreemass + n);
  t.first_hinge.assign(n, 0);
  t.num_hinges.assign(n, 0);
  for (int b = 0; b < n; ++b) {
    t.offset[b] = Eigen::Vector3d(m->body_pos + 3 * b);
    const mjtNum* q = m->body_quat + 4 * b;
    t.rotation_offset[b] = Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
    t.com_offset[b] = Eigen::Vector3d(m->body_ipos + 3 * b);
    t.first_hinge[b] = static_cast<int>(t.hinges.size());
    for (int j = m->body_jntadr[b]; j >= 0 && j < m->body_jntadr[b] + m->body_jntnum[b]; ++j) {
      const char* name = mj_id2name(m, mjOBJ_JOINT, j);
      if (m->jnt_type[j] == mjJNT_FREE) {
        if (t.parent[b] != 0 || t.free_body >= 0) {
          throw ModelError(std::string(origin) + ": free joint '" + (name ? name : "") + "' not on the root body");
        }
        t.free_body = b;
        t.free_qpos = m->jnt_qposadr[j];
        t.free_dof = m->jnt_dofadr[j];
        continue;
      }
      if (m->jnt_type[j] != mjJNT_HINGE) {
        throw ModelError(std::string(origin) + ": joint '" + (name ? name : "") + "' is neither a hinge nor a free joint");
      }
      BodyTree::Hinge h;
      h.joint = j;
      h.qpos = m->jnt_qposadr[j];
      h.dof = m->jnt_dofadr[j];
      h.qpos0 = m->qpos0[h.qpos];
      h.axis = Eigen::Vector3d(m->jnt_axis + 3 * j).normalized();
      h.anchor = Eigen::Vector3d(m->jnt_pos + 3 * j);
      t.hinges.push_back(h);
      ++t.num_hinges[b];
    }
  }
  return t;
}

BodyFrames::BodyFrames(const BodyTree& tree)
    : position(tree.num_bodies(), Eigen::Vector3d::Zero()),
      orientation(tree.num_bodies(), Eigen::Quaterniond::Identity()),
      rotation(tree.num_bodies(), Eigen::Matrix3d::Identity()),
      com(tree.num_bodies(), Eigen::Vector3d::Zero()),
      subtree_com(tree.num_bodies(), Eigen::Vector3d::Zero()),
      joint_axis(tree.hinges.size(), Eigen::Vector3d::UnitZ()),
      joint_anchor(tree.hinges.size(), Eigen::Vector3d::Zero()) {}

void forward_kinematics(const BodyTree& tree, const Eigen::VectorXd& qpos, BodyFrames& f) {
  for (int b = 1; b < tree.num_bodies(); ++b) {
    const int p = tree.parent[b];
    Eigen::Vector3d position;
    Eigen::Quaterniond orientation;
    if (b == tree.free_body) {
      position = qpos.segment<3>(tree.free_qpos);
      const Eigen::Vector4d wxyz = qpos.segment<4>(tree.free_qpos + 3);
      orientation = Eigen::Quaterniond(wxyz[0], wxyz[1], wxyz[2], wxyz[3]).normalized();
    } else {
      position = f.position[p] + f.rotation[p] * tree.offset[b];
      orientation = f.orientation[p] * tree.rotation_offset[b];
    }
    // Each hinge turns the body about its axis through its anchor, which stays in place.
    for (int k = tree.first_hinge[b]; k < tree.first_hinge[b] + tree.num_hinges[b]; ++k) {
      const BodyTree::Hinge& h = tree.hinges[k];
      const Eigen::Vector3d anchor = position + orientation * h.anchor;
      f.joint_axis[k] = orientation * h.axis;
      f.joint_anchor[k] = anchor;
      orientation = orientation * Eigen::Quaterniond(Eigen::AngleAxisd(qpos[h.qpos] - h.qpos0, h.axis));
      position = anchor - orientation * h.anchor;
    }
    f.position[b] = position;
    f.orientation[b] = orientation.normalized();
    f.rotation[b] = f.orientation[b].toRotationMatrix();
    f.com[b] = position + f.rotation[b] * tree.com_offset[b];
  }
}

void subtree_coms(const BodyTree& tree, BodyFrames& f) {
  const int n = tree.num_bodies();
  for (int b = 0; b < n; ++b) f.subtree_com[b] = tree.mass[b] * f.com[b];
  for (int b = n - 1; b > 0; --b) f.subtree_com[tree.parent[b]] += f.subtree_com[b];
  for (int b = 0; b < n; ++b) {
    if (tree.subtree_mass[b] > 0.0) f.subtree_com[b] /= tree.subtree_mass[b];
    else f.subtree_com[b] = f.position[b];
  }
}

namespace {

// The free joint's columns for the velocity of `point` (times `share`): v = v_root + (R_root ω_local) × (p − p_root).
void free_joint_columns(const BodyTree& tree, const BodyFrames& f, const Eigen::Vector3d& point, double share,
                        JacobianBlock J) {
  J.middleCols<3>(tree.free_dof) = share * Eigen::Matrix3d::Identity();
  const Eigen::Vector3d r = point - f.position[tree.free_body];
  for (int k = 0; k < 3; ++k) J.col(tree.free_dof + 3 + k) = share * f.rotation[tree.free_body].col(k).cross(r);
}

}  // namespace

void point_jacobian(const BodyTree& tree, const BodyFrames& f, int body, const Eigen::Vector3d& point, JacobianBlock J) {
  J.setZero();
  for (int b = body; b > 0; b = tree.parent[b]) {
    for (int k = tree.first_hinge[b]; k < tree.first_hinge[b] + tree.num_hinges[b]; ++k) {
      const BodyTree::Hinge& h = tree.hinges[k];
      J.col(h.dof) = f.joint_axis[k].cross(point - f.joint_anchor[k]);
    }
    if (b == tree.free_body) free_joint_columns(tree, f, point, 1.0, J);
  }
}

void angular_jacobian(const BodyTree& tree, const BodyFrames& f, int body, JacobianBlock J) {
  J.setZero();
  for (int b = body; b > 0; b = tree.parent[b]) {
    for (int k = tree.first_hinge[b]; k < tree.first_hinge[b] + tree.num_hinges[b]; ++k) {
      const BodyTree::Hinge& h = tree.hinges[k];
      J.col(h.dof) = f.joint_axis[k];
    }
    if (b == tree.free_body) J.middleCols<3>(tree.free_dof + 3) = f.rotation[b];
  }
}

void subtree_com_jacobian(const BodyTree& tree, const BodyFrames& f, int body, JacobianBlock J) {
  J.setZero();
  const Eigen::Vector3d& c = f.subtree_com[body];
  // A hinge inside the subtree moves the part of it below the hinge: its mass share times the
  // velocity of that part's CoM.
  const double total = tree.subtree_mass[body];
  for (int b = body; b <= tree.subtree_last[body]; ++b) {
    const double share = tree.subtree_mass[b] / total;
    for (int k = tree.first_hinge[b]; k < tree.first_hinge[b] + tree.num_hinges[b]; ++k) {
      const BodyTree::Hinge& h = tree.hinges[k];
      J.col(h.dof) = share * f.joint_axis[k].cross(f.subtree_com[b] - f.joint_anchor[k]);
    }
  }
  // A joint above the subtree moves all of it.
  for (int b = tree.parent[body]; b > 0; b = tree.parent[b]) {
    for (int k = tree.first_hinge[b]; k < tree.first_hinge[b] + tree.num_hinges[b]; ++k) {
      const BodyTree::Hinge& h = tree.hinges[k];
      J.col(h.dof) = f.joint_axis[k].cross(c - f.joint_anchor[k]);
    }
  }
  if (tree.free_body >= body && tree.free_body <= tree.subtree_last[body]) {
    free_joint_columns(tree, f, f.subtree_com[tree.free_body], tree.subtree_mass[tree.free_body] / total, J);
  } else if (tree.free_body >= 0 && body >= tree.free_body && body <= tree.subtree_last[tree.free_body]) {
    free_joint_columns(tree, f, c, 1.0, J);
  }
}

}  // namespace biped
