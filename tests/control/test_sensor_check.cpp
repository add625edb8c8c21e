#include "control/sensor_check.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "test_support.hpp"

namespace biped {
namespace {

class SensorCheck : public ::testing::Test {
 protected:
  RobotModel model = test::load_model("johnnie");
  SensorLimits limits;
  SensorData good() const {
    SensorData s(model.num_joints());
    s.joint_position = model.stand_pose();
    s.imu_acceleration = Eigen::Vector3d(0, 0, 9.81);
    return s;
  }
};

TEST_F(SensorCheck, PlausibleReadingPasses) { EXPECT_EQ(check_sensors(model, limits, good()), nullptr); }

TEST_F(SensorCheck, EachFaultIsNamed) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  SensorData s = good();
  s.foot_wrench[1].torque.y() = nan;
  EXPECT_STREQ(check_sensors(model, limits, s), "right F/T sensor");
  s = good();
  s.foot_wrench[0].force.z() = 1e5;
  EXPECT_STREQ(check_sensors(model, limits, s), "left F/T sensor");
  s = good();
  s.joint_position[3] = model.joints()[3].upper + 0.2;
  EXPECT_STREQ(check_sensors(model, limits, s), "joint encoder");
  s = good();
  s.imu_angular_rate.x() = nan;
  EXPECT_STREQ(check_sensors(model, limits, s), "imu angular rate");
  s = good();
  s.imu_orientation.coeffs() *= 2.0;
  EXPECT_STREQ(check_sensors(model, limits, s), "imu orientation");
  s = good();
  s.imu_acceleration.z() = std::numeric_limits<double>::infinity();
  EXPECT_STREQ(check_sensors(model, limits, s), "imu acceleration");
}

// A frozen F/T channel is reported after `frozen_cycles` identical readings, not before; a reading
// that changes, however little, restarts the count.
TEST_F(SensorCheck, FrozenSignalIsReportedAfterTheConfiguredNumberOfRepeats) {
  FrozenSignalDetector detector;
  SensorData s = good();
  s.foot_wrench[0].force.z() = 300.0;
  detector.reset(s);
  for (int i = 1; i <= 20; ++i) {
    s.foot_wrench[1].force.z() = 300.0 + 1e-9 * i;  // the right sensor and the IMU stay alive
    s.imu_angular_rate.x() = 1e-9 * i;
    const char* fault = detector.update(s, 5);
    if (i < 5) {
      EXPECT_EQ(fault, nullptr) << i;
    } else {
      EXPECT_STREQ(fault, "left F/T sensor frozen") << i;
    }
  }
  s.foot_wrench[0].force.z() += 1e-9;
  EXPECT_EQ(detector.update(s, 5), nullptr) << "a changing reading restarts the count";
  for (int i = 0; i < 10; ++i) EXPECT_EQ(detector.update(s, 0), nullptr) << "0 switches the check off";
}

TEST_F(SensorCheck, FrozenImuIsReported) {
  FrozenSignalDetector detector;
  SensorData s = good();
  detector.reset(s);
  const char* fault = nullptr;
  for (int i = 1; i <= 3 && !fault; ++i) {
    s.foot_wrench[0].force.z() = i;
    s.foot_wrench[1].force.z() = i;
    fault = detector.update(s, 3);
  }
  EXPECT_STREQ(fault, "imu frozen");
}

}  // namespace
}  // namespace biped
