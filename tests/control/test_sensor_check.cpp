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

TEST_F(SensorCheck, PlausibleReadingPasses) { EXPECT_FALSE(check_sensors(model, limits, good())); }

// Each fault names its signal, and the side or joint, as data.
TEST_F(SensorCheck, EachFaultNamesItsSignalSideAndJoint) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto expect = [](const Fault& f, FaultSignal signal, int index, const char* text) {
    EXPECT_EQ(f.signal, signal) << text;
    EXPECT_EQ(f.check, FaultCheck::Implausible) << text;
    EXPECT_EQ(f.index, index) << text;
    EXPECT_STREQ(describe(f), text);
  };
  SensorData s = good();
  s.foot_wrench[1].torque.y() = nan;
  expect(check_sensors(model, limits, s), FaultSignal::ForceTorque, index_of(Side::Right), "right F/T sensor");
  s = good();
  s.foot_wrench[0].force.z() = 1e5;
  expect(check_sensors(model, limits, s), FaultSignal::ForceTorque, index_of(Side::Left), "left F/T sensor");
  s = good();
  s.joint_position[3] = model.joints()[3].upper + 0.2;
  expect(check_sensors(model, limits, s), FaultSignal::JointEncoder, 3, "joint encoder");
  s = good();
  s.imu_angular_rate.x() = nan;
  expect(check_sensors(model, limits, s), FaultSignal::ImuAngularRate, -1, "imu angular rate");
  s = good();
  s.imu_orientation.coeffs() *= 2.0;
  expect(check_sensors(model, limits, s), FaultSignal::ImuOrientation, -1, "imu orientation");
  s = good();
  s.imu_acceleration.z() = std::numeric_limits<double>::infinity();
  expect(check_sensors(model, limits, s), FaultSignal::ImuAcceleration, -1, "imu acceleration");
  s = good();
  s.time = nan;
  expect(check_sensors(model, limits, s), FaultSignal::Time, -1, "time");
}

// An encoder within its margin beyond the hard limit is plausible; beyond it is not.
TEST_F(SensorCheck, EncoderMarginIsHonoured) {
  SensorData s = good();
  s.joint_position[2] = model.joints()[2].lower - 0.5 * limits.encoder_margin;
  EXPECT_FALSE(check_sensors(model, limits, s));
  s.joint_position[2] = model.joints()[2].lower - 2.0 * limits.encoder_margin;
  EXPECT_TRUE(check_sensors(model, limits, s));
}

}  // namespace
}  // namespace biped
