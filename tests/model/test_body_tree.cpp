// The controller's own forward kinematics and Jacobians against MuJoCo's (mj_kinematics,
// mj_comPos, mj_jac*), on random configurations of both robots.
#include "model/body_tree.hpp"

#include <gtest/gtest.h>

#include <mujoco/mujoco.h>

#include <random>

#include "test_support.hpp"

namespace biped {
namespace {

class BodyTreeTest : public ::testing::TestWithParam<const char*> {
 protected:
  RobotModel model = test::load_model(GetParam());
  const mjModel* m = model.mj();
  RobotData mujoco{model};
  BodyFrames frames{model.tree()};
  std::mt19937 rng{11};

  // Hinges uniform in their ranges, a random base position and orientation.
  Eigen::VectorXd random_configuration() {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    Eigen::VectorXd q = model.stand_qpos();
    for (const JointInfo& j : model.joints()) {
      q[j.qpos_adr] = j.lower + 0.5 * (u(rng) + 1.0) * (j.upper - j.lower);
    }
    q.head<3>() = Eigen::Vector3d(u(rng), u(rng), 1.0 + u(rng));
    const Eigen::Quaterniond r = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized();
    q.segment<4>(3) << r.w(), r.x(), r.y(), r.z();
    return q;
  }

  // Both kinematics at q.
  void compute(const Eigen::VectorXd& q) {
    mujoco.qpos() = q;
    mj_kinematics(m, mujoco.mj());
    mj_comPos(m, mujoco.mj());
    forward_kinematics(model.tree(), q, frames);
    subtree_coms(model.tree(), frames);
  }
};

TEST_P(BodyTreeTest, FramesMatchMujoco) {
  for (int trial = 0; trial < 20; ++trial) {
    compute(random_configuration());
    const mjData* d = mujoco.mj();
    for (int b = 1; b < m->nbody; ++b) {
      EXPECT_LT((frames.position[b] - Eigen::Vector3d(d->xpos + 3 * b)).norm(), 1e-12) << "body " << b;
      EXPECT_LT((frames.rotation[b] - mujoco.body_rotation(b)).norm(), 1e-12) << "body " << b;
      EXPECT_LT((frames.com[b] - Eigen::Vector3d(d->xipos + 3 * b)).norm(), 1e-12) << "body " << b;
      EXPECT_LT((frames.subtree_com[b] - Eigen::Vector3d(d->subtree_com + 3 * b)).norm(), 1e-12) << "body " << b;
    }
    for (int i = 0; i < model.num_joints(); ++i) {
      const int j = model.joints()[i].mj_joint;
      EXPECT_LT((frames.joint_axis[i] - Eigen::Vector3d(d->xaxis + 3 * j)).norm(), 1e-12) << model.joints()[i].name;
      EXPECT_LT((frames.joint_anchor[i] - Eigen::Vector3d(d->xanchor + 3 * j)).norm(), 1e-12) << model.joints()[i].name;
    }
  }
}

TEST_P(BodyTreeTest, JacobiansMatchMujoco) {
  using RowMajor3 = Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::RowMajor>;
  RowMajor3 expected(3, m->nv), expected_rot(3, m->nv);
  Eigen::Matrix<double, 3, Eigen::Dynamic> J(3, m->nv);
  for (int trial = 0; trial < 20; ++trial) {
    compute(random_configuration());
    mjData* d = mujoco.mj();
    for (int b = 1; b < m->nbody; ++b) {
      const double scale = 1.0 + frames.position[b].norm();
      mj_jacBody(m, d, expected.data(), expected_rot.data(), b);
      point_jacobian(model.tree(), frames, b, frames.position[b], J);
      EXPECT_LT((J - expected).cwiseAbs().maxCoeff(), 1e-12 * scale) << "body " << b;
      angular_jacobian(model.tree(), frames, b, J);
      EXPECT_LT((J - expected_rot).cwiseAbs().maxCoeff(), 1e-12) << "body " << b;
      mj_jacSubtreeCom(m, d, expected.data(), b);
      subtree_com_jacobian(model.tree(), frames, b, J);
      EXPECT_LT((J - expected).cwiseAbs().maxCoeff(), 1e-12 * scale) << "subtree of body " << b;
    }
    // The whole robot's CoM, the subtree of the world body.
    mj_jacSubtreeCom(m, d, expected.data(), 0);
    subtree_com_jacobian(model.tree(), frames, 0, J);
    EXPECT_LT((J - expected).cwiseAbs().maxCoeff(), 1e-11);
  }
}

// The Jacobian of a point against central differences of its position along each velocity
// direction (the free joint's rotation in the body frame, as mj_integratePos integrates it).
TEST_P(BodyTreeTest, PointJacobianMatchesFiniteDifferences) {
  const Eigen::VectorXd q = random_configuration();
  const int body = model.foot(Side::Left).body;
  const Eigen::Vector3d local(0.05, -0.02, 0.03);
  auto point_at = [&](const Eigen::VectorXd& qq) {
    forward_kinematics(model.tree(), qq, frames);
    return Eigen::Vector3d(frames.position[body] + frames.rotation[body] * local);
  };
  const Eigen::Vector3d p = point_at(q);
  Eigen::Matrix<double, 3, Eigen::Dynamic> J(3, m->nv);
  point_jacobian(model.tree(), frames, body, p, J);
  constexpr double h = 1e-6;
  for (int i = 0; i < m->nv; ++i) {
    Eigen::VectorXd direction = Eigen::VectorXd::Zero(m->nv);
    direction[i] = 1.0;
    Eigen::VectorXd plus = q, minus = q;
    mj_integratePos(m, plus.data(), direction.data(), h);
    mj_integratePos(m, minus.data(), direction.data(), -h);
    const Eigen::Vector3d fd = (point_at(plus) - point_at(minus)) / (2.0 * h);
    EXPECT_LT((J.col(i) - fd).norm(), 1e-7) << "velocity " << i;
  }
}

TEST_P(BodyTreeTest, SubtreesAreContiguousAndMassesAddUp) {
  const BodyTree& t = model.tree();
  ASSERT_EQ(t.hinges.size(), static_cast<std::size_t>(model.num_joints()));
  for (int i = 0; i < model.num_joints(); ++i) EXPECT_EQ(t.hinges[i].joint, model.joints()[i].mj_joint) << "joints() order";
  EXPECT_EQ(t.subtree_last[0], t.num_bodies() - 1);
  for (int b = 1; b < t.num_bodies(); ++b) {
    double mass = 0.0;
    for (int c = b; c <= t.subtree_last[b]; ++c) {
      int a = c;
      while (a != b && a != 0) a = t.parent[a];
      EXPECT_EQ(a, b) << "body " << c << " is in the subtree of " << b;
      mass += t.mass[c];
    }
    EXPECT_NEAR(mass, t.subtree_mass[b], 1e-12);
  }
}

INSTANTIATE_TEST_SUITE_P(Robots, BodyTreeTest, ::testing::Values("lola", "johnnie"),
                         [](const auto& info) { return std::string(info.param); });

}  // namespace
}  // namespace biped
