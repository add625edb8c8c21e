#include "control/com_estimator.hpp"

#include <gtest/gtest.h>

#include "math/rotations.hpp"
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
  JointCommand hold(model.num_joints());
  hold.position = model.stand_pose();
  SensorData s(model.num_joints());
  double worst = 0.0;
  for (int i = 0; i < 1000; ++i) {
    sim.command(hold);
    sim.advance();
    sim.read_sensors(s);
    const mjData* d = sim.data();
    for (Side side : kSides) {
      const Eigen::Vector3d estimate = estimator.com_from_foot(s.joint_position, s.imu_orientation, side);
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

}  // namespace
}  // namespace biped
