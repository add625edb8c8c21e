#pragma once
// Forward kinematics and Jacobians of the robot's kinematic tree, for the controller's cycle.
// BodyTree is read-only (the tree's structure and offsets, taken from the compiled model once, held
// by RobotModel); BodyFrames is the preallocated workspace; the functions fill it without
// allocating.
//
// They compute what MuJoCo's mj_kinematics, mj_comPos and mj_jac* give for bodies and joints, but
// only that (no geoms, sites, spatial inertias or motion subspaces), which makes the task-space
// evaluation of eq. (21) several times cheaper; tests/model/test_body_tree.cpp checks them against
// MuJoCo. Joints: at most one free joint, on the root body; hinges elsewhere (RobotModel's contract).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

struct mjModel_;

namespace biped {

struct BodyTree {
  struct Hinge {
    int joint = -1;   // MuJoCo joint id
    int qpos = -1, dof = -1;
    double qpos0 = 0.0;  // the angle is qpos − qpos0 (the model's reference configuration)
    Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();      // body frame, unit
    Eigen::Vector3d anchor = Eigen::Vector3d::Zero();     // body frame
  };

  int nq = 0, nv = 0;
  int free_qpos = -1, free_dof = -1;   // the root's free joint (-1: none)
  int free_body = -1;
  // Per body (0: the world). Bodies are numbered depth first: the subtree of b is b .. subtree_last[b].
  std::vector<int> parent, subtree_last;
  std::vector<Eigen::Vector3d> offset;            // origin in the parent's frame
  std::vector<Eigen::Quaterniond> rotation_offset;  // orientation in the parent's frame
  std::vector<Eigen::Vector3d> com_offset;        // CoM in the body's frame
  std::vector<double> mass, subtree_mass;
  std::vector<int> first_hinge, num_hinges;       // into `hinges`
  std::vector<Hinge> hinges;                      // in MuJoCo's joint order: RobotModel::joints() order

  int num_bodies() const { return static_cast<int>(parent.size()); }
};

// Reads the tree of a compiled model; throws ModelError (naming `origin`) for a joint other than a
// hinge or a free joint on the root.
BodyTree make_body_tree(const mjModel_* m, const char* origin);

// Body and joint frames in the world at one configuration.
struct BodyFrames {
  explicit BodyFrames(const BodyTree& tree);
  std::vector<Eigen::Vector3d> position;         // body frame origin
  std::vector<Eigen::Quaterniond> orientation;
  std::vector<Eigen::Matrix3d> rotation;
  std::vector<Eigen::Vector3d> com;              // the body's own CoM
  std::vector<Eigen::Vector3d> subtree_com;      // after subtree_coms()
  std::vector<Eigen::Vector3d> joint_axis;       // hinge axis (unit), by hinge (RobotModel::joints() order)
  std::vector<Eigen::Vector3d> joint_anchor;     // a point on the hinge axis
};

// Frames at the configuration qpos (size nq: free joint position, w-x-y-z quaternion, hinge angles).
void forward_kinematics(const BodyTree& tree, const Eigen::VectorXd& qpos, BodyFrames& frames);
// The CoM of every subtree (the world body's is the robot's CoM), from forward_kinematics' frames.
void subtree_coms(const BodyTree& tree, BodyFrames& frames);

// 3 × nv Jacobians in MuJoCo's velocity coordinates (the free joint's linear velocity in the world,
// its angular velocity in the root body's frame, then hinge rates), written into J (every column).
using JacobianBlock = Eigen::Ref<Eigen::Matrix<double, 3, Eigen::Dynamic>, 0, Eigen::OuterStride<>>;
// Of the world point `point` moving with `body`.
void point_jacobian(const BodyTree& tree, const BodyFrames& frames, int body, const Eigen::Vector3d& point,
                    JacobianBlock J);
// Of `body`'s angular velocity (world frame).
void angular_jacobian(const BodyTree& tree, const BodyFrames& frames, int body, JacobianBlock J);
// Of the CoM of `body`'s subtree (needs subtree_coms()).
void subtree_com_jacobian(const BodyTree& tree, const BodyFrames& frames, int body, JacobianBlock J);

}  // namespace biped
