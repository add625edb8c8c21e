#include "control/initial_configuration.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

#include "test_support.hpp"

namespace biped {
namespace {

// A plausible first reading is where the controller starts, clamped to the software limits.
TEST(InitialConfiguration, StartsFromThePlausibleReadingInsideTheSoftwareLimits) {
  const RobotModel model = test::load_model("lola");
  SensorLimits limits;
  SensorData first(model.num_joints());
  first.joint_position = model.stand_pose();
  first.joint_position[0] += 0.01;
  const JointInfo& j = model.joints()[1];
  first.joint_position[1] = j.upper + 0.5 * limits.encoder_margin;  // plausible, beyond the software limit
  first.imu_acceleration = Eigen::Vector3d(0, 0, 9.81);
  const Eigen::VectorXd q = initial_joint_pose(model, limits, first);
  EXPECT_DOUBLE_EQ(q[0], first.joint_position[0]);
  EXPECT_DOUBLE_EQ(q[1], j.soft_upper);
  const Eigen::VectorXd qpos = initial_configuration(model, limits, first);
  ASSERT_EQ(qpos.size(), model.nq());
  EXPECT_EQ(qpos.head<7>(), model.stand_qpos().head<7>()) << "the floating base of the stand keyframe";
  for (int i = 0; i < model.num_joints(); ++i) EXPECT_DOUBLE_EQ(qpos[model.joints()[i].qpos_adr], q[i]);
}

// An implausible first reading (NaN encoder) falls back to the stand pose.
TEST(InitialConfiguration, ImplausibleReadingFallsBackToTheStandPose) {
  const RobotModel model = test::load_model("johnnie");
  SensorLimits limits;
  SensorData first(model.num_joints());
  first.joint_position = model.stand_pose();
  first.joint_position[4] = std::numeric_limits<double>::quiet_NaN();
  first.imu_acceleration = Eigen::Vector3d(0, 0, 9.81);
  const Eigen::VectorXd q = initial_joint_pose(model, limits, first);
  ASSERT_TRUE(q.allFinite());
  for (int i = 0; i < model.num_joints(); ++i) {
    const JointInfo& j = model.joints()[i];
    EXPECT_DOUBLE_EQ(q[i], std::clamp(model.stand_pose()[i], j.soft_lower, j.soft_upper));
  }
}

}  // namespace
}  // namespace biped
