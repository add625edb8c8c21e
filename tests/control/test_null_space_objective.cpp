// The null-space objective H of Fig. 5: comfort term plus a joint-limit term active only near limits.
#include "control/null_space_objective.hpp"

#include <gtest/gtest.h>

#include <random>

namespace biped {
namespace {

constexpr double kMargin = 5.0 * M_PI / 180.0;

class NullSpaceObjectiveTest : public ::testing::TestWithParam<const char*> {
 protected:
  NullSpaceObjectiveTest() : model(RobotModel::load(GetParam(), kMargin)) {}

  // A configuration with every joint at the centre of its range, comfort pose there too, so only
  // the joint under test contributes.
  Eigen::VectorXd centred() const {
    Eigen::VectorXd q = model.stand_qpos();
    for (const JointInfo& j : model.joints()) q[j.qpos_adr] = 0.5 * (j.soft_lower + j.soft_upper);
    return q;
  }
  Eigen::VectorXd centre_pose() const {
    Eigen::VectorXd pose(model.num_joints());
    for (int i = 0; i < model.num_joints(); ++i) {
      pose[i] = 0.5 * (model.joints()[i].soft_lower + model.joints()[i].soft_upper);
    }
    return pose;
  }

  RobotModel model;
};

TEST_P(NullSpaceObjectiveTest, LimitTermIsZeroInTheMiddleOfTheRange) {
  NullSpaceObjectiveParams params;
  params.comfort_weight = 0.0;
  const NullSpaceObjective objective(model, params);
  std::mt19937 rng(1);
  Eigen::VectorXd gradient;
  for (int trial = 0; trial < 50; ++trial) {
    Eigen::VectorXd q = model.stand_qpos();
    for (const JointInfo& j : model.joints()) {
      const double zone = params.activation_fraction * (j.soft_upper - j.soft_lower);
      q[j.qpos_adr] = std::uniform_real_distribution<double>(j.soft_lower + zone, j.soft_upper - zone)(rng);
    }
    EXPECT_EQ(objective.value(q), 0.0);
    objective.gradient(q, gradient);
    ASSERT_EQ(gradient.size(), model.mj()->nv);
    EXPECT_EQ(gradient.cwiseAbs().maxCoeff(), 0.0);
  }
}

TEST_P(NullSpaceObjectiveTest, LimitTermActivatesOnlyInTheZonesAndPushesInward) {
  NullSpaceObjectiveParams params;
  params.comfort_pose = centre_pose();
  const NullSpaceObjective objective(model, params);
  Eigen::VectorXd gradient;
  for (int i = 0; i < model.num_joints(); ++i) {
    const JointInfo& j = model.joints()[i];
    const double zone = params.activation_fraction * (j.soft_upper - j.soft_lower);
    Eigen::VectorXd q = centred();
    const double comfort_only = [&] {
      q[j.qpos_adr] = j.soft_lower + 1.01 * zone;  // just outside the lower zone
      return objective.value(q);
    }();
    EXPECT_NEAR(comfort_only, 0.5 * params.comfort_weight * std::pow(0.5 * (j.soft_upper - j.soft_lower) - 1.01 * zone, 2),
                1e-12);
    EXPECT_EQ(objective.limit_zone_depth(i, q[j.qpos_adr]), 0.0);

    q[j.qpos_adr] = j.soft_lower + 0.5 * zone;  // inside the lower zone: pushed up
    EXPECT_NEAR(objective.limit_zone_depth(i, q[j.qpos_adr]), -0.5 * zone, 1e-12);
    objective.gradient(q, gradient);
    EXPECT_LT(gradient[j.dof_adr], -params.comfort_weight * (0.5 * (j.soft_upper - j.soft_lower) - 0.5 * zone));

    q[j.qpos_adr] = j.soft_upper - 0.5 * zone;  // inside the upper zone: pushed down
    EXPECT_NEAR(objective.limit_zone_depth(i, q[j.qpos_adr]), 0.5 * zone, 1e-12);
    objective.gradient(q, gradient);
    EXPECT_GT(gradient[j.dof_adr], params.comfort_weight * (0.5 * (j.soft_upper - j.soft_lower) - 0.5 * zone));
  }
}

TEST_P(NullSpaceObjectiveTest, GradientMatchesFiniteDifferences) {
  const NullSpaceObjective objective(model, NullSpaceObjectiveParams{});
  std::mt19937 rng(2);
  Eigen::VectorXd gradient;
  constexpr double h = 1e-6;
  for (int trial = 0; trial < 10; ++trial) {
    Eigen::VectorXd q = model.stand_qpos();
    for (const JointInfo& j : model.joints()) {
      // Beyond the software limits too: the limit term keeps growing there.
      q[j.qpos_adr] = std::uniform_real_distribution<double>(j.lower, j.upper)(rng);
    }
    objective.gradient(q, gradient);
    for (int k = 0; k < model.mj()->nv; ++k) {
      Eigen::VectorXd direction = Eigen::VectorXd::Zero(model.mj()->nv);
      direction[k] = 1.0;
      Eigen::VectorXd q_plus = q, q_minus = q;
      mj_integratePos(model.mj(), q_plus.data(), direction.data(), h);
      mj_integratePos(model.mj(), q_minus.data(), direction.data(), -h);
      const double fd = (objective.value(q_plus) - objective.value(q_minus)) / (2.0 * h);
      EXPECT_NEAR(gradient[k], fd, 1e-6 * std::max(1.0, std::abs(fd))) << "velocity " << k;
    }
    EXPECT_EQ(gradient.head<6>().cwiseAbs().maxCoeff(), 0.0);  // floating base
  }
}

TEST_P(NullSpaceObjectiveTest, AtTheComfortPoseOnlyTheLimitTermRemains) {
  // Default comfort pose = stand pose. Some stand angles lie in a zone (shoulder roll −10° is
  // within 10 % of its range from the upper limit), so ∇H there is the limit term alone.
  const NullSpaceObjectiveParams params;
  const NullSpaceObjective objective(model, params);
  Eigen::VectorXd gradient;
  const Eigen::VectorXd& q = model.stand_qpos();
  objective.gradient(q, gradient);
  for (int i = 0; i < model.num_joints(); ++i) {
    const JointInfo& j = model.joints()[i];
    EXPECT_DOUBLE_EQ(gradient[j.dof_adr], params.limit_weight * objective.limit_zone_depth(i, q[j.qpos_adr])) << j.name;
  }
}

TEST_P(NullSpaceObjectiveTest, RejectsBadParameters) {
  NullSpaceObjectiveParams params;
  params.comfort_pose = Eigen::VectorXd::Zero(3);
  EXPECT_THROW(NullSpaceObjective(model, params), std::invalid_argument);
  params = NullSpaceObjectiveParams{};
  params.activation_fraction = 0.6;
  EXPECT_THROW(NullSpaceObjective(model, params), std::invalid_argument);
}

INSTANTIATE_TEST_SUITE_P(Robots, NullSpaceObjectiveTest,
                         ::testing::Values(BIPED_SOURCE_DIR "/models/lola/lola.xml",
                                           BIPED_SOURCE_DIR "/models/johnnie/johnnie.xml"),
                         [](const auto& info) {
                           return std::string(info.index == 0 ? "lola" : "johnnie");
                         });

}  // namespace
}  // namespace biped
