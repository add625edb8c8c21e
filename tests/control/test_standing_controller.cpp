#include "control/standing_controller.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "test_support.hpp"

namespace biped {
namespace {

SensorData plausible_reading(const RobotModel& model, const Eigen::VectorXd& q, double t) {
  SensorData s(model.num_joints());
  s.time = t;
  s.joint_position = q;
  s.imu_acceleration = Eigen::Vector3d(0, 0, 9.81);
  for (Wrench& w : s.foot_wrench) w.force.z() = 0.5 * model.weight_above_sensors();
  return s;
}

TEST(StandingController, RampsFromTheMeasuredPoseToTheReferencePose) {
  const RobotModel model = test::load_model("lola");
  StandingControllerParams params;
  params.ramp_time = 1.0;
  StandingController controller(model, params);
  const Eigen::VectorXd start = model.stand_pose().array() + 0.05;
  controller.reset(plausible_reading(model, start, 0.0));
  JointCommand out(model.num_joints());
  controller.step(plausible_reading(model, start, 0.0), {}, out);
  EXPECT_LT((out.position - start).norm(), 1e-9);
  controller.step(plausible_reading(model, start, 0.5), {}, out);
  EXPECT_NEAR((out.position - start).norm(), 0.5 * (model.stand_pose() - start).norm(), 1e-9);
  controller.step(plausible_reading(model, start, 1.5), {}, out);
  EXPECT_LT((out.position - model.stand_pose()).norm(), 1e-12);
  EXPECT_STREQ(controller.status().state, "standing");
}

TEST(StandingController, NanSensorValueEntersSafeStopAndHoldsAFiniteSetPoint) {
  const RobotModel model = test::load_model("lola");
  StandingController controller(model, {});
  controller.reset(plausible_reading(model, model.stand_pose(), 0.0));
  JointCommand out(model.num_joints());
  controller.step(plausible_reading(model, model.stand_pose(), 0.001), {}, out);
  const Eigen::VectorXd before = out.position;
  SensorData bad = plausible_reading(model, model.stand_pose(), 0.002);
  bad.foot_wrench[0].force.x() = std::numeric_limits<double>::quiet_NaN();
  controller.step(bad, {}, out);
  EXPECT_TRUE(controller.status().fault);
  EXPECT_STREQ(controller.status().state, "safe_stop");
  EXPECT_EQ(controller.status().first_fault.signal, FaultSignal::ForceTorque);
  EXPECT_EQ(controller.status().first_fault.index, index_of(Side::Left));
  EXPECT_TRUE(out.position.allFinite());
  EXPECT_EQ(out.position, before);
  // It stays in the safe stop even when the signal recovers.
  controller.step(plausible_reading(model, model.stand_pose(), 0.003), {}, out);
  EXPECT_TRUE(controller.status().fault);
}

TEST(StandingController, SetPointsStayInsideTheSoftwareLimits) {
  const RobotModel model = test::load_model("johnnie");
  StandingController controller(model, {});
  Eigen::VectorXd beyond(model.num_joints());
  for (int i = 0; i < model.num_joints(); ++i) beyond[i] = model.joints()[i].upper;
  controller.reset(plausible_reading(model, beyond, 0.0));
  JointCommand out(model.num_joints());
  controller.step(plausible_reading(model, beyond, 0.0), {}, out);
  for (int i = 0; i < model.num_joints(); ++i) EXPECT_LE(out.position[i], model.joints()[i].soft_upper + 1e-12);
}

}  // namespace
}  // namespace biped
