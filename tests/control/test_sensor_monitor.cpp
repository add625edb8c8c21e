// The sensor monitor: every signal checked every cycle, each failure reported once and latched,
// encoder jumps and freezes told apart from joints that rightly stand still, F/T sensors and the IMU
// trusted again only after a healthy while.
#include "control/sensor_monitor.hpp"

#include <gtest/gtest.h>

#include <cmath>
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
  // One cycle with live F/T and IMU channels (they change a little, as noisy sensors do), but for a
  // right F/T sensor that reads frozen.
  void cycle(bool right_ft_frozen = false) {
    s.time += 0.001;
    for (int k = 0; k < (right_ft_frozen ? 1 : 2); ++k) s.foot_wrench[k].force.x() = 1e-3 * std::sin(1e3 * s.time);
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
  s.foot_wrench[0].force.z() = 300.0;  // the reading recovers: the sensor stays failed for now
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

// A transient F/T fault: the sensor is trusted again once its readings have been healthy for
// recovery_time (not earlier), which is reported once; failing again is a new fault.
TEST_F(SensorMonitorTest, ForceSensorIsTrustedAgainAfterAHealthyWhile) {
  const int recovery_cycles = static_cast<int>(std::lround(limits.recovery_time / 0.001));
  ASSERT_GT(recovery_cycles, limits.frozen_cycles);
  s.foot_wrench[1].torque.y() = std::numeric_limits<double>::quiet_NaN();
  for (int i = 0; i < 300; ++i) cycle();
  EXPECT_FALSE(monitor.health().force_torque[1]);
  s.foot_wrench[1].torque.y() = 5.0;
  int healthy_cycles = 0;
  while (!monitor.health().force_torque[1] && healthy_cycles < 10 * recovery_cycles) {
    cycle();
    ++healthy_cycles;
    if (!monitor.health().force_torque[1]) {
      EXPECT_EQ(monitor.recovered().count, 0);
    }
  }
  EXPECT_NEAR(healthy_cycles, recovery_cycles, 1);
  ASSERT_EQ(monitor.recovered().count, 1);
  EXPECT_EQ(monitor.recovered().items[0].signal, FaultSignal::ForceTorque);
  EXPECT_EQ(monitor.recovered().items[0].index, 1);
  EXPECT_TRUE(monitor.health().all_good());
  cycle();
  EXPECT_EQ(monitor.recovered().count, 0) << "reported once";
  s.foot_wrench[1].torque.y() = std::numeric_limits<double>::quiet_NaN();
  cycle();
  ASSERT_EQ(faults.count, 1) << "failing again is a new fault";
  EXPECT_FALSE(monitor.health().force_torque[1]);
}

// A frozen F/T sensor is never trusted while it stays frozen; once alive again it is.
TEST_F(SensorMonitorTest, FrozenForceSensorIsNotTrustedWhileFrozen) {
  const int recovery_cycles = static_cast<int>(std::lround(limits.recovery_time / 0.001));
  for (int i = 0; i < 10 * recovery_cycles; ++i) cycle(true);
  EXPECT_FALSE(monitor.health().force_torque[1]);
  EXPECT_TRUE(monitor.health().force_torque[0]);
  for (int i = 0; i < recovery_cycles + 2; ++i) cycle();
  EXPECT_TRUE(monitor.health().force_torque[1]);
}

// Encoders are never trusted again (a jumped one may have lost its zero), nor is anything with
// recovery_time 0.
TEST_F(SensorMonitorTest, EncodersAndFaultsWithoutRecoveryTimeStayFailed) {
  SensorLimits latching = limits;
  latching.recovery_time = 0.0;
  SensorMonitor latched{model, latching};
  latched.reset(s);
  s.joint_position[3] += 2.0 * limits.encoder_jump;
  s.imu_angular_rate.z() = std::numeric_limits<double>::quiet_NaN();
  cycle();
  latched.update(s, setpoint, faults);
  s.imu_angular_rate.z() = 0.0;
  for (int i = 0; i < 2000; ++i) {
    cycle();
    latched.update(s, setpoint, faults);
  }
  EXPECT_EQ(monitor.health().encoder_failed[3], 1);
  EXPECT_TRUE(monitor.health().imu) << "the IMU is trusted again";
  EXPECT_EQ(latched.health().encoder_failed[3], 1);
  EXPECT_FALSE(latched.health().imu);
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
