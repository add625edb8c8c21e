// Kinematics on the controller's model: integration on the configuration manifold against its
// explicit form, the subtree CoM against the mass-weighted body CoMs, and the leg mass split of the
// pattern generator's simplified model within its physical bounds, for both robots.
#include "model/kinematics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "test_support.hpp"

namespace biped {
namespace {

class KinematicsTest : public ::testing::TestWithParam<std::string> {
 protected:
  KinematicsTest() : model(test::load_model(GetParam())), data(model) {}
  RobotModel model;
  RobotData data;
};

// The stand pose with its joints moved at random inside the software limits and the base turned
// at random.
Eigen::VectorXd random_configuration(const RobotModel& model, std::mt19937& rng) {
  Eigen::VectorXd q = model.stand_qpos();
  for (const JointInfo& j : model.joints()) {
    q[j.qpos_adr] = std::uniform_real_distribution<double>(j.soft_lower, j.soft_upper)(rng);
  }
  const Eigen::Quaterniond base = Eigen::Quaterniond::UnitRandom();
  q.segment<4>(3) << base.w(), base.x(), base.y(), base.z();
  return q;
}

Eigen::Quaterniond base_orientation(const Eigen::VectorXd& q) { return {q[3], q[4], q[5], q[6]}; }

// Each joint advances by its rate × dt; the base moves by its (world-frame) linear velocity × dt
// and turns by exp(ω dt) about its own axes (body-frame angular velocity), its quaternion unit.
TEST_P(KinematicsTest, IntegrateConfigurationMatchesTheExplicitStep) {
  std::mt19937 rng(3);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::VectorXd q = random_configuration(model, rng);
    Eigen::VectorXd qdot(model.nv());
    for (int i = 0; i < model.nv(); ++i) qdot[i] = normal(rng);
    const double dt = 0.02;
    Eigen::VectorXd next = q;
    integrate_configuration(model, qdot, dt, next);

    for (const JointInfo& j : model.joints()) {
      EXPECT_NEAR(next[j.qpos_adr], q[j.qpos_adr] + qdot[j.dof_adr] * dt, 1e-12) << j.name;
    }
    EXPECT_LT((next.head<3>() - (q.head<3>() + dt * qdot.head<3>())).norm(), 1e-12);
    const Eigen::Vector3d omega = qdot.segment<3>(3);
    const Eigen::Quaterniond expected =
        base_orientation(q) * Eigen::Quaterniond(Eigen::AngleAxisd(omega.norm() * dt, omega.normalized()));
    const Eigen::Quaterniond turned = base_orientation(next);
    EXPECT_NEAR(turned.norm(), 1.0, 1e-12);
    EXPECT_LT(turned.angularDistance(expected), 1e-9) << "trial " << trial;
  }
}

// The robot CoM (subtree CoM of the pelvis, the root of the robot) is Σ m_i x_i / Σ m_i over the
// bodies' own CoMs, and the robot's mass is the model's total.
TEST_P(KinematicsTest, ForwardKinematicsWithComGivesTheMassWeightedCom) {
  const mjModel* m = model.mj();
  const mjData* d = data.mj();
  std::mt19937 rng(5);
  for (int trial = 0; trial < 5; ++trial) {
    data.qpos() = random_configuration(model, rng);
    forward_kinematics_with_com(model, data);
    Eigen::Vector3d moment = Eigen::Vector3d::Zero();
    double mass = 0.0;
    for (int b = 1; b < m->nbody; ++b) {
      moment += m->body_mass[b] * Eigen::Vector3d(d->xipos + 3 * b);
      mass += m->body_mass[b];
    }
    EXPECT_NEAR(mass, model.total_mass(), 1e-9);
    EXPECT_LT((data.subtree_com(model.pelvis_body()) - moment / mass).norm(), 1e-12) << "trial " << trial;
  }
}

// Frames follow the configuration: a shifted base carries every body with it, a bent knee moves
// the foot below it and not the pelvis.
TEST_P(KinematicsTest, ForwardKinematicsPlacesTheFramesOfTheConfiguration) {
  data.qpos() = model.stand_qpos();
  forward_kinematics(model, data);
  const Eigen::Vector3d pelvis = data.body_position(model.pelvis_body());
  const Eigen::Vector3d foot = data.body_position(model.foot(Side::Left).body);
  const Eigen::Vector3d shift(0.3, -0.2, 0.1);
  data.qpos().head<3>() += shift;
  forward_kinematics(model, data);
  EXPECT_LT((data.body_position(model.pelvis_body()) - pelvis - shift).norm(), 1e-12);
  EXPECT_LT((data.body_position(model.foot(Side::Left).body) - foot - shift).norm(), 1e-12);
  const int knee = model.joint_index("left_knee");
  ASSERT_GE(knee, 0);
  data.qpos()[model.joints()[knee].qpos_adr] -= 0.3;
  forward_kinematics(model, data);
  EXPECT_LT((data.body_position(model.pelvis_body()) - pelvis - shift).norm(), 1e-12);
  EXPECT_GT((data.body_position(model.foot(Side::Left).body) - foot - shift).norm(), 0.05);
}

// The estimators' kinematics of the encoder angles: the frames and subtree CoMs of MuJoCo's
// kinematics at the same joint angles with the base at the origin, unrotated.
TEST_P(KinematicsTest, EncoderKinematicsIsMuJoCosAtTheOriginWithTheEncoderAngles) {
  EncoderKinematics encoders(model);
  std::mt19937 rng(7);
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::VectorXd q = random_configuration(model, rng);
    Eigen::VectorXd joints(model.num_joints());
    for (int i = 0; i < model.num_joints(); ++i) joints[i] = q[model.joints()[i].qpos_adr];
    encoders.update(joints);
    data.qpos() = q;
    data.qpos().head<3>().setZero();
    data.qpos().segment<4>(3) << 1.0, 0.0, 0.0, 0.0;
    forward_kinematics_with_com(model, data);
    const BodyFrames& frames = encoders.frames();
    for (int b : {model.pelvis_body(), model.upper_body(), model.foot(Side::Left).body, model.foot(Side::Right).body}) {
      EXPECT_LT((frames.position[b] - data.body_position(b)).norm(), 1e-12) << "body " << b;
      EXPECT_LT((frames.subtree_com[b] - data.subtree_com(b)).norm(), 1e-12) << "body " << b;
      EXPECT_LT((frames.rotation[b] - Eigen::Matrix3d(data.body_rotation(b))).norm(), 1e-12) << "body " << b;
    }
  }
}

// Part of each leg moves with its foot: more than nothing, less than both legs; its height lies
// between the ankles and the hips; the ankle sits a few centimetres above the sole.
TEST_P(KinematicsTest, LegMassSplitLiesWithinTheLegs) {
  const LegMassSplit split = leg_mass_split(model);
  const mjModel* m = model.mj();
  data.qpos() = model.stand_qpos();
  forward_kinematics(model, data);
  double legs_mass = 0.0;
  double hip_above_ankle = 1e9;
  for (Side side : kSides) {
    const int root = model.leg_root_joint(side);
    ASSERT_GE(root, 0);
    legs_mass += m->body_subtreemass[m->jnt_bodyid[model.joints()[root].mj_joint]];
    const double hip = data.joint_anchor(root).z() - data.body_position(model.foot(side).body).z();
    hip_above_ankle = std::min(hip_above_ankle, hip);
  }
  EXPECT_GT(split.moving_mass, 0.0);
  EXPECT_LT(split.moving_mass, legs_mass);
  EXPECT_GT(split.moving_height, 0.0);
  EXPECT_LT(split.moving_height, hip_above_ankle);
  EXPECT_GT(split.ankle_height, 0.0);
  EXPECT_LT(split.ankle_height, 0.2);
}

INSTANTIATE_TEST_SUITE_P(Robots, KinematicsTest, ::testing::Values("lola", "johnnie"),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace biped
