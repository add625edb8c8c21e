#pragma once
// Task coordinates x(q) of the paper's Table I and the task Jacobian J = ∇_q x.
// TaskSpace is read-only (body ids, row layout, row names), TaskSpaceData is the preallocated
// workspace; evaluate() fills x and J from MuJoCo's kinematics without allocating.
// q is MuJoCo's full qpos (floating base included); J has one column per generalized velocity (nv).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <string>
#include <vector>

#include "model/robot_model.hpp"

namespace biped {

// Which rows of x hold what. Built in one place (TaskSpace's constructor) from the model:
//   foot position (world frame) − robot CoM         3 per foot   right, left
//   foot orientation relative to the upper body      3 per foot   right, left
//   arm CoM − robot CoM (world frame)                3 per arm    right, left (2: x, y only for
//                                                                 arms with fewer than 3 joints)
//   upper-body orientation relative to R_ref         3
//   robot CoM (world frame)                          3
struct TaskLayout {
  std::array<int, 2> foot_position{};     // first row, indexed by index_of(Side)
  std::array<int, 2> foot_orientation{};
  std::array<int, 2> arm_com{};
  int arm_com_rows = 3;
  int upper_body_orientation = 0;
  int com = 0;
  int dim = 0;
  bool has_toes = false;  // toe joints (LOLA) are not tasks: they are resolved in the null space
};

class TaskSpace {
 public:
  // Throws ModelError when the model lacks the arms' root joints (ModelMap) or has more task rows
  // than generalized velocities.
  explicit TaskSpace(const RobotModel& model);

  const RobotModel& model() const { return *model_; }
  const TaskLayout& layout() const { return layout_; }
  int dim() const { return layout_.dim; }
  int nq() const { return model_->mj()->nq; }
  int nv() const { return model_->mj()->nv; }
  // One name per row, e.g. "right_foot_x", "left_foot_phi_y", "com_z" (for logs).
  const std::vector<std::string>& row_names() const { return row_names_; }

  int foot_body(Side s) const { return foot_body_[index_of(s)]; }
  int arm_body(Side s) const { return arm_body_[index_of(s)]; }  // first body of the arm's subtree
  int upper_body() const { return model_->upper_body(); }
  int root_body() const { return model_->pelvis_body(); }
  // Velocity addresses of the passive and locked joints, whose Jacobian columns evaluate() zeroes.
  const std::vector<int>& held_dofs() const { return held_dofs_; }

 private:
  const RobotModel* model_;
  TaskLayout layout_;
  std::array<int, 2> foot_body_{};
  std::array<int, 2> arm_body_{};
  std::vector<std::string> row_names_;
  std::vector<int> held_dofs_;
};

// Workspace of evaluate(); everything is sized at construction.
class TaskSpaceData {
 public:
  explicit TaskSpaceData(const TaskSpace& space);

  Eigen::VectorXd x;  // task coordinates (dim)
  Eigen::MatrixXd J;  // ∇_q x (dim × nv)
  Eigen::Vector3d com = Eigen::Vector3d::Zero();          // robot CoM, world frame
  std::array<Eigen::Vector3d, 2> foot_position{};          // world frame, by Side
  Eigen::Matrix3d upper_body_rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d upper_body_position = Eigen::Vector3d::Zero();  // body origin, world frame

  // Every body's and joint's frame at the last evaluate()'s configuration, subtree CoMs included.
  const BodyFrames& frames() const { return frames_; }

 private:
  friend void evaluate(const TaskSpace&, const Eigen::VectorXd&, const Eigen::Matrix3d&, TaskSpaceData&);
  using Jacobian3 = Eigen::Matrix<double, 3, Eigen::Dynamic>;
  BodyFrames frames_;
  Jacobian3 jac_com_, jac_upper_body_rot_, jac_tmp_;
};

// x(q) and J(q) at the full configuration qpos (size nq). R_ref is the reference frame of the
// upper-body orientation (the planner's heading frame). Allocation-free.
void evaluate(const TaskSpace& space, const Eigen::VectorXd& qpos, const Eigen::Matrix3d& R_ref,
              TaskSpaceData& data);

// Task-space error x_d ⊖ x. All rows are coordinates (positions and rotation vectors), and J is the
// derivative of exactly these coordinates, so the plain difference is the consistent error for
// the rate loop; it assumes no rotation vector wraps around |φ| = π (R_ref keeps φ_UB small; feet
// never turn by π against the upper body). Allocation-free when `error` has the right size.
void task_error(const Eigen::VectorXd& x_d, const Eigen::VectorXd& x, Eigen::VectorXd& error);

// The robot CoM relative to a foot, r_CoM − r_foot (world frame): the negated foot-position block.
// With the stance foot this is the r_CoM of the stabilizer's x_IN (eq. (10)).
inline Eigen::Vector3d com_from_foot(const TaskSpace& space, const TaskSpaceData& data, Side foot) {
  return -data.x.segment<3>(space.layout().foot_position[index_of(foot)]);
}

}  // namespace biped
