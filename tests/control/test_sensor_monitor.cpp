// The sensor monitor: every signal checked every cycle, each failure reported once and latched,
// encoder jumps and freezes told apart from joints that rightly stand still.
#include "control/sensor_monitor.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "test_support.hpp"

namespace biped {
namespace {

class SensorMonitorTest : public ::testing::Test {
 protected:
  RobotModel model = test::load_model("lola");
  SensorLimits limits;
  SensorMonitor monitor{model, limits};
  FaultList faults;
  SensorData s{model.num_joints()};
  Eigen::VectorXd setpoint = model.stand_pose();

  SensorMonitorTest() {
    s.joint_position = model.stand_pose();
    s.imu_acceleration = Eigen::Vector3d(0, 0, 9.81);
    for (Wrench& w : s.foot_wrench) w.force.z() = 300.0;
    monitor.reset(s);
  }
  // One cycle with live F/T and IMU channels (they change a little, as noisy sensors do).
  void cycle() {
    s.time += 0.001;
    for (Wrench& w : s.foot_wrench) w.force.x() = 1e-3 * std::sin(1e3 * s.time);
    s.imu_angular_rate.x() = 1e-4 * std::sin(1e3 * s.time);
    monitor.update(s, setpoint, faults);
  }
};

// A second and a third fault are reported when they happen, each once, and stay failed.
TEST_F(SensorMonitorTest, EachFailureIsReportedOnceAndLatched) {
  cycle();
  EXPECT_EQ(faults.count, 0);
  EXPECT_TRUE(monitor.health().all_good());
  s.foot_wrench[0].force.z() = std::numeric_limits<double>::quiet_NaN();
  cycle();
  ASSERT_EQ(faults.count, 1);
  EXPECT_EQ(faults.items[0].signal, FaultSignal::ForceTorque);
  EXPECT_EQ(faults.items[0].index, 0);
  EXPECT_NEAR(faults.items[0].time, s.time, 1e-12);
  s.foot_wrench[0].force.z() = 300.0;  // the reading recovers: the sensor stays failed
  cycle();
  EXPECT_EQ(faults.count, 0);
  EXPECT_FALSE(monitor.health().force_torque[0]);
  EXPECT_TRUE(monitor.health().force_torque[1]);
  s.joint_position[4] = std::numeric_limits<double>::infinity();
  s.imu_angular_rate.y() = 100.0;
  cycle();
  ASSERT_EQ(faults.count, 2) << "two new faults in one reading";
  EXPECT_EQ(faults.items[0].signal, FaultSignal::JointEncoder);
  EXPECT_EQ(faults.items[0].index, 4);
  EXPECT_EQ(faults.items[1].signal, FaultSignal::ImuAngularRate);
  EXPECT_EQ(monitor.health().encoder_failed[4], 1);
  EXPECT_FALSE(monitor.health().imu);
  cycle();
  EXPECT_EQ(faults.count, 0) << "reported once";
}

TEST_F(SensorMonitorTest, EncoderJumpIsDetected) {
  for (int i = 0; i < 5; ++i) {
    s.joint_position[2] += 0.5 * limits.encoder_jump;  // fast but possible
    cycle();
    EXPECT_EQ(faults.count, 0);
  }
  s.joint_position[2] += 2.0 * limits.encoder_jump;
  cycle();
  ASSERT_EQ(faults.count, 1);
  EXPECT_EQ(faults.items[0].check, FaultCheck::Jump);
  EXPECT_EQ(faults.items[0].index, 2);
  EXPECT_STREQ(describe(faults.items[0]), "joint encoder jump");
}

// A joint that stands still with its set-point repeats its reading rightly; one whose set-point
// moves while the reading stays bit-identical is frozen.
TEST_F(SensorMonitorTest, FrozenEncoderIsToldFromAJointStandingStill) {
  for (int i = 0; i < 3 * limits.frozen_cycles; ++i) cycle();
  EXPECT_TRUE(monitor.health().all_good()) << "standing still is not frozen";
  for (int i = 0; i < 2 * limits.frozen_cycles && faults.count == 0; ++i) {
    setpoint[7] += 0.001;  // 1 rad/s: the joint should follow
    for (int j = 0; j < model.num_joints(); ++j) {
      if (j != 7) s.joint_position[j] = setpoint[j];
    }
    cycle();
  }
  ASSERT_EQ(faults.count, 1);
  EXPECT_EQ(faults.items[0].signal, FaultSignal::JointEncoder);
  EXPECT_EQ(faults.items[0].check, FaultCheck::Frozen);
  EXPECT_EQ(faults.items[0].index, 7);
}

}  // namespace
}  // namespace biped
