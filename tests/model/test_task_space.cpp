// Task coordinates x(q) of Table I and their Jacobian.
#include "model/task_space.hpp"

#include <gtest/gtest.h>

#include <Eigen/SVD>

#include <cmath>
#include <ostream>
#include <random>
#include <set>

#include "math/rotations.hpp"
#include "model/kinematics.hpp"

namespace biped {
namespace {

constexpr double kMargin = 5.0 * M_PI / 180.0;

struct Robot {
  const char* name;
  const char* path;
  int expected_dim;
  int expected_arm_rows;
  bool expected_toes;
};
void PrintTo(const Robot& robot, std::ostream* os) { *os << robot.name; }  // readable test names
const Robot kLola{"lola", BIPED_SOURCE_DIR "/models/lola/lola.xml", 24, 3, true};
const Robot kJohnnie{"johnnie", BIPED_SOURCE_DIR "/models/johnnie/johnnie.xml", 22, 2, false};

Eigen::Vector3d random_unit_ball(std::mt19937& rng, double radius) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::Vector3d v;
  do v = Eigen::Vector3d(u(rng), u(rng), u(rng));
  while (v.norm() > 1.0);
  return radius * v;
}

// Joint angles uniform inside the software limits, random base position and orientation.
Eigen::VectorXd random_configuration(const RobotModel& model, std::mt19937& rng) {
  Eigen::VectorXd q = model.stand_qpos();
  for (const JointInfo& j : model.joints()) {
    q[j.qpos_adr] = std::uniform_real_distribution<double>(j.soft_lower, j.soft_upper)(rng);
  }
  q.head<3>() = random_unit_ball(rng, 1.0);
  const Eigen::Quaterniond base = Eigen::Quaterniond::UnitRandom();
  q[3] = base.w();
  q[4] = base.x();
  q[5] = base.y();
  q[6] = base.z();
  return q;
}

class TaskSpaceTest : public ::testing::TestWithParam<Robot> {
 protected:
  TaskSpaceTest() : model(RobotModel::load(GetParam().path, kMargin)), space(model), data(space) {}
  RobotModel model;
  TaskSpace space;
  TaskSpaceData data;
};

TEST_P(TaskSpaceTest, LayoutIsDetectedFromTheModel) {
  const TaskLayout& layout = space.layout();
  EXPECT_EQ(space.dim(), GetParam().expected_dim);
  EXPECT_EQ(layout.arm_com_rows, GetParam().expected_arm_rows);
  EXPECT_EQ(layout.has_toes, GetParam().expected_toes);
  EXPECT_LT(space.dim(), space.nv());
  // Table I's order: right before left, blocks contiguous, CoM last.
  EXPECT_EQ(layout.foot_position[index_of(Side::Right)], 0);
  EXPECT_EQ(layout.foot_position[index_of(Side::Left)], 3);
  EXPECT_EQ(layout.foot_orientation[index_of(Side::Right)], 6);
  EXPECT_EQ(layout.arm_com[index_of(Side::Right)], 12);
  EXPECT_EQ(layout.arm_com[index_of(Side::Left)], 12 + layout.arm_com_rows);
  EXPECT_EQ(layout.upper_body_orientation, 12 + 2 * layout.arm_com_rows);
  EXPECT_EQ(layout.com, space.dim() - 3);

  ASSERT_EQ(static_cast<int>(space.row_names().size()), space.dim());
  const std::set<std::string> unique(space.row_names().begin(), space.row_names().end());
  EXPECT_EQ(static_cast<int>(unique.size()), space.dim());
  EXPECT_EQ(space.row_names()[0], "right_foot_x");
  EXPECT_EQ(space.row_names()[layout.foot_orientation[index_of(Side::Left)] + 1], "left_foot_phi_y");
  EXPECT_EQ(space.row_names()[layout.com + 2], "com_z");
}

TEST_P(TaskSpaceTest, StandPoseValuesMatchTheirDefinitions) {
  evaluate(space, model.stand_qpos(), Eigen::Matrix3d::Identity(), data);
  const TaskLayout& layout = space.layout();
  // MuJoCo's own kinematics, for the foot positions.
  RobotData mujoco(model);
  mujoco.qpos() = model.stand_qpos();
  forward_kinematics(model, mujoco);
  // The stand pose has level feet and an upright upper body: all orientations are zero.
  for (Side s : kSides) {
    EXPECT_LT(data.x.segment<3>(layout.foot_orientation[index_of(s)]).norm(), 1e-9);
    const Eigen::Vector3d foot = mujoco.body_position(space.foot_body(s));
    EXPECT_LT((data.x.segment<3>(layout.foot_position[index_of(s)]) - (foot - data.com)).norm(), 1e-12);
    EXPECT_LT((com_from_foot(space, data, s) - (data.com - foot)).norm(), 1e-12);
  }
  EXPECT_LT(data.x.segment<3>(layout.upper_body_orientation).norm(), 1e-9);
  // Left/right symmetry of the stand pose.
  const Eigen::Vector3d right = data.x.segment<3>(layout.foot_position[index_of(Side::Right)]);
  const Eigen::Vector3d left = data.x.segment<3>(layout.foot_position[index_of(Side::Left)]);
  EXPECT_NEAR(right.y(), -left.y(), 1e-9);
  EXPECT_NEAR(right.z(), left.z(), 1e-9);
  // The robot CoM is the whole-body CoM, 0.909 m (LOLA) / 0.930 m (JOHNNIE) above the soles
  // (models/README.md). The sole is 0.05 m + |sole_z| below the ankle (the F/T site's offset).
  const double sole_below_ankle = 0.05 - model.foot(Side::Right).sole_z;
  EXPECT_NEAR(-right.z() + sole_below_ankle, 0.92, 0.015);
}

// J against central differences of x(q): q is perturbed along each velocity direction with
// mj_integratePos (step 1e-6). Criterion: max_ij |J − J_fd| / max_ij |J| < 1e-6.
TEST_P(TaskSpaceTest, JacobianMatchesFiniteDifferences) {
  const mjModel* m = model.mj();
  std::mt19937 rng(42);
  TaskSpaceData perturbed(space);
  Eigen::MatrixXd J_fd(space.dim(), space.nv());
  constexpr double h = 1e-6;
  for (int trial = 0; trial < 6; ++trial) {
    const Eigen::VectorXd q = random_configuration(model, rng);
    // R_ref up to 1.5 rad away from the upper body, so the rotation-vector rows are tested at
    // large angles too (the inverse left Jacobian is not close to I there).
    evaluate(space, q, Eigen::Matrix3d::Identity(), data);
    const Eigen::Matrix3d R_ref = data.upper_body_rotation * math::so3::exp(random_unit_ball(rng, 1.5));
    evaluate(space, q, R_ref, data);
    for (int k = 0; k < space.nv(); ++k) {
      Eigen::VectorXd direction = Eigen::VectorXd::Zero(space.nv());
      direction[k] = 1.0;
      Eigen::VectorXd q_plus = q, q_minus = q;
      mj_integratePos(m, q_plus.data(), direction.data(), h);
      mj_integratePos(m, q_minus.data(), direction.data(), -h);
      evaluate(space, q_plus, R_ref, perturbed);
      const Eigen::VectorXd x_plus = perturbed.x;
      evaluate(space, q_minus, R_ref, perturbed);
      J_fd.col(k) = (x_plus - perturbed.x) / (2.0 * h);
    }
    const double error = (data.J - J_fd).cwiseAbs().maxCoeff() / data.J.cwiseAbs().maxCoeff();
    EXPECT_LT(error, 1e-6) << GetParam().name << " trial " << trial;
  }
}

// The task coordinates and J as they were computed with MuJoCo's own kinematics (mj_kinematics,
// mj_comPos, mj_jac*) before the controller got its own (model/body_tree): the same to round-off.
TEST_P(TaskSpaceTest, AgreesWithMujocosKinematicsToRoundOff) {
  const mjModel* m = model.mj();
  RobotData mujoco(model);
  mjData* d = mujoco.mj();
  using Jacobian3 = Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::RowMajor>;
  Jacobian3 jac_com(3, m->nv), jac_pos(3, m->nv), jac_rot(3, m->nv), jac_ub(3, m->nv);
  Eigen::VectorXd x(space.dim());
  Eigen::MatrixXd J(space.dim(), space.nv());
  const TaskLayout& L = space.layout();
  std::mt19937 rng(17);
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::VectorXd q = random_configuration(model, rng);
    const Eigen::Matrix3d R_ref = math::so3::exp(random_unit_ball(rng, 1.0));
    evaluate(space, q, R_ref, data);
    mujoco.qpos() = q;
    mj_kinematics(m, d);
    mj_comPos(m, d);
    const Eigen::Vector3d com(d->subtree_com + 3 * space.root_body());
    mj_jacSubtreeCom(m, d, jac_com.data(), space.root_body());
    const Eigen::Quaterniond q_ub = mujoco.body_orientation(space.upper_body());
    mj_jacBody(m, d, nullptr, jac_ub.data(), space.upper_body());
    for (Side side : kSides) {
      const int k = index_of(side), body = space.foot_body(side), arm = space.arm_body(side);
      mj_jacBody(m, d, jac_pos.data(), jac_rot.data(), body);
      x.segment<3>(L.foot_position[k]) = mujoco.body_position(body) - com;
      J.middleRows<3>(L.foot_position[k]) = jac_pos - jac_com;
      const Eigen::Vector3d phi = math::so3::log(q_ub.conjugate() * mujoco.body_orientation(body));
      x.segment<3>(L.foot_orientation[k]) = phi;
      J.middleRows<3>(L.foot_orientation[k]) = math::so3::inverse_left_jacobian(phi) *
                                                mujoco.body_rotation(space.upper_body()).transpose() * (jac_rot - jac_ub);
      mj_jacSubtreeCom(m, d, jac_pos.data(), arm);
      x.segment(L.arm_com[k], L.arm_com_rows) = (mujoco.subtree_com(arm) - com).head(L.arm_com_rows);
      J.middleRows(L.arm_com[k], L.arm_com_rows) = (jac_pos - jac_com).topRows(L.arm_com_rows);
    }
    const Eigen::Vector3d phi_ub = math::so3::log(Eigen::Quaterniond(R_ref).conjugate() * q_ub);
    x.segment<3>(L.upper_body_orientation) = phi_ub;
    J.middleRows<3>(L.upper_body_orientation) = math::so3::inverse_left_jacobian(phi_ub) * R_ref.transpose() * jac_ub;
    x.segment<3>(L.com) = com;
    J.middleRows<3>(L.com) = jac_com;
    EXPECT_LT((data.x - x).cwiseAbs().maxCoeff(), 1e-12) << GetParam().name << " trial " << trial;
    EXPECT_LT((data.J - J).cwiseAbs().maxCoeff(), 1e-12) << GetParam().name << " trial " << trial;
  }
}

TEST_P(TaskSpaceTest, TaskCoordinatesAreTranslationInvariantExceptTheCom) {
  std::mt19937 rng(7);
  const Eigen::VectorXd q = random_configuration(model, rng);
  evaluate(space, q, Eigen::Matrix3d::Identity(), data);
  const Eigen::VectorXd x = data.x;
  Eigen::VectorXd shifted = q;
  shifted.head<3>() += Eigen::Vector3d(0.3, -0.2, 0.1);
  evaluate(space, shifted, Eigen::Matrix3d::Identity(), data);
  const int com = space.layout().com;
  EXPECT_LT((data.x.head(com) - x.head(com)).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((data.x.segment<3>(com) - x.segment<3>(com) - Eigen::Vector3d(0.3, -0.2, 0.1)).norm(), 1e-12);
}

// The task Jacobian has full row rank at the stand pose (the CoM rows anchor the floating base).
TEST_P(TaskSpaceTest, JacobianHasFullRowRankAtStandPose) {
  evaluate(space, model.stand_qpos(), Eigen::Matrix3d::Identity(), data);
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(data.J);
  EXPECT_GT(svd.singularValues().minCoeff(), 1e-3);
}

INSTANTIATE_TEST_SUITE_P(Robots, TaskSpaceTest, ::testing::Values(kLola, kJohnnie),
                         [](const auto& info) { return std::string(info.param.name); });

// A passive joint (no drive: JVRC-1's coupled finger joints) and a locked one are in no task's Jacobian.
TEST(TaskSpaceHeldJoints, HaveZeroColumns) {
  ModelMap map;
  map.passive_joints = {"left_elbow"};
  map.locked_joints = {"head_pan"};
  const RobotModel model = RobotModel::load(kLola.path, kMargin, map);
  const TaskSpace space(model);
  TaskSpaceData data(space);
  evaluate(space, model.stand_qpos(), Eigen::Matrix3d::Identity(), data);
  for (const char* name : {"left_elbow", "head_pan"}) {
    const int dof = model.joints()[model.joint_index(name)].dof_adr;
    EXPECT_EQ(data.J.col(dof).norm(), 0.0) << name;
  }
  const RobotModel driven = RobotModel::load(kLola.path, kMargin);
  const TaskSpace driven_space(driven);
  TaskSpaceData driven_data(driven_space);
  evaluate(driven_space, driven.stand_qpos(), Eigen::Matrix3d::Identity(), driven_data);
  EXPECT_GT(driven_data.J.col(driven.joints()[driven.joint_index("left_elbow")].dof_adr).norm(), 0.0);
}

}  // namespace
}  // namespace biped
