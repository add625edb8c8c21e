#include "control/com_estimator.hpp"

#include <gtest/gtest.h>

#include "math/rotations.hpp"
#include "model/kinematics.hpp"
#include "sim/simulation.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

// The estimate from the emulated sensors (quantized encoders, IMU) against the simulator's ground
// truth, while the robot is pushed around on its feet.
TEST(CoMEstimator, MatchesTheGroundTruthFromSensorsOnly) {
  const RobotModel model = test::load_model("lola");
  SimulationParams p;
  p.world.robot_mjcf = test::model_path("lola");
  p.pushes.push_back({0.2, 0.3, "upper_body", Eigen::Vector3d(60.0, -40.0, 0.0)});
  Simulation sim(p, model);
  CoMEstimator estimator(model);
  EncoderKinematics encoders(model);
  JointCommand hold(model.num_joints());
  hold.position = model.stand_pose();
  SensorData s(model.num_joints());
  double worst = 0.0;
  for (int i = 0; i < 1000; ++i) {
    sim.command(hold);
    sim.advance();
    sim.read_sensors(s);
    const mjData* d = sim.data();
    encoders.update(s.joint_position);
    for (Side side : kSides) {
      const Eigen::Vector3d estimate = estimator.com_from_foot(encoders.frames(), s.imu_orientation, side);
      // Sensors describe the state at the start of the last physics step: compare with the ground
      // truth kinematics of that state (xpos, subtree_com are from the same step).
      const Eigen::Vector3d truth_world = Eigen::Vector3d(d->subtree_com + 3 * model.pelvis_body()) -
                                          Eigen::Vector3d(d->xpos + 3 * model.foot(side).body);
      const double heading = math::heading_of(math::mat_from_mujoco(d->xmat + 9 * model.upper_body()));
      const Eigen::Vector3d truth = Eigen::AngleAxisd(-heading, Eigen::Vector3d::UnitZ()) * truth_world;
      worst = std::max(worst, (estimate - truth).norm());
    }
  }
  EXPECT_LT(worst, 0.002);
}

// Encoder readings of LOLA leaning its legs: both hip pitch joints turn at a constant rate from the
// stand pose, so the CoM moves relative to the feet at a nearly constant velocity.
struct LeaningLegs {
  const RobotModel& model;
  SensorData sensors;
  EncoderKinematics encoders;
  static constexpr double kRate = 0.3;  // [rad/s]
  explicit LeaningLegs(const RobotModel& m) : model(m), sensors(m.num_joints()), encoders(m) {
    sensors.joint_position = model.stand_pose();
  }
  const SensorData& at(double t) {
    sensors.time = t;
    sensors.joint_position = model.stand_pose();
    for (const char* hip : {"left_hip_pitch", "right_hip_pitch"}) sensors.joint_position[model.joint_index(hip)] += kRate * t;
    return sensors;
  }
  // One cycle of the estimator on the readings at t, with their encoders' kinematics.
  void step(CoMEstimator& estimator, double t, Side stance, double dt) {
    encoders.update(at(t).joint_position);
    estimator.update(sensors, encoders.frames(), stance, dt);
  }
};

// The rate starts from zero: at the first update, after reset(), and after a change of stance foot
// (the estimate jumps to the other foot: no rate from that jump); the carried rate only at the
// first update and after reset(): it goes on through the change.
TEST(CoMEstimator, RateRestartsFromZeroAtTheFirstUpdateAndAtAStanceChange) {
  const RobotModel model = test::load_model("lola");
  CoMEstimator estimator(model);
  LeaningLegs legs(model);
  const double dt = 0.001;
  legs.step(estimator, 0.0, Side::Left, dt);
  EXPECT_EQ(estimator.rate(), Eigen::Vector2d::Zero());
  for (int i = 1; i <= 20; ++i) legs.step(estimator, i * dt, Side::Left, dt);
  EXPECT_GT(estimator.rate().norm(), 0.01) << "moving";

  const Eigen::Vector2d moving = estimator.carried_rate();
  EXPECT_EQ(moving, estimator.rate()) << "the same rate until a change of stance foot";

  legs.step(estimator, 21 * dt, Side::Right, dt);
  EXPECT_EQ(estimator.rate(), Eigen::Vector2d::Zero());
  EXPECT_EQ(estimator.carried_rate(), moving) << "carried over: the jump to the other foot is no motion";
  EXPECT_LT((estimator.estimate() -
             estimator.com_from_foot(legs.encoders.frames(), legs.sensors.imu_orientation, Side::Right).head<2>())
                .norm(),
            1e-12)
      << "relative to the new stance foot";
  legs.step(estimator, 22 * dt, Side::Right, dt);
  EXPECT_GT(estimator.rate().norm(), 0.0);

  EXPECT_LT((estimator.carried_rate() - moving).norm(), 0.1 * moving.norm()) << "no rate from the jump";

  estimator.reset();
  legs.step(estimator, 23 * dt, Side::Right, dt);
  EXPECT_EQ(estimator.rate(), Eigen::Vector2d::Zero());
  EXPECT_EQ(estimator.carried_rate(), Eigen::Vector2d::Zero());
}

// Once its filter (10 ms) has settled, the rate is the estimate's finite difference: the CoM's
// velocity, here nearly constant. The filter lags it by its time constant, which costs only 10 ms
// of the slow change of that velocity.
TEST(CoMEstimator, RateFollowsACoMMovingAtConstantVelocity) {
  const RobotModel model = test::load_model("lola");
  CoMEstimator estimator(model);
  LeaningLegs legs(model);
  const double dt = 0.001;
  Eigen::Vector2d previous = Eigen::Vector2d::Zero();
  double worst = 0.0, speed = 0.0;
  for (int i = 0; i <= 300; ++i) {
    legs.step(estimator, i * dt, Side::Left, dt);
    const Eigen::Vector2d difference = (estimator.estimate() - previous) / dt;
    previous = estimator.estimate();
    if (i < 150) continue;  // 15 filter time constants
    worst = std::max(worst, (estimator.rate() - difference).norm());
    speed = difference.norm();
  }
  EXPECT_GT(speed, 0.1) << "[m/s] the CoM moves";
  EXPECT_LT(worst, 0.01 * speed);
}

}  // namespace
}  // namespace biped
