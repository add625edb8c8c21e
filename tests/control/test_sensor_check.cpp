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

}  // namespace
}  // namespace biped
