#include "sim/fall_detection.hpp"

#include <gtest/gtest.h>

#include "sim/simulation.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

// With joint servos far too soft to carry the body, the robot collapses and the fall is detected.
TEST(FallDetection, CollapseIsAFall) {
  const RobotModel model = test::load_model("johnnie");
  SimulationParams p;
  p.world.robot_mjcf = test::model_path("johnnie");
  p.drives.bandwidth_hz = 0.3;
  Simulation sim(p, model);
  JointCommand hold(model.num_joints());
  hold.position = model.stand_pose();
  for (int i = 0; i < 4000 && !sim.fall_reason(); ++i) {
    sim.command(hold);
    sim.advance();
  }
  ASSERT_NE(sim.fall_reason(), nullptr);
  EXPECT_GT(sim.fall_time(), 0.05);
}

TEST(FallDetection, StandingIsNoFall) {
  const RobotModel model = test::load_model("johnnie");
  SimulationParams p;
  p.world.robot_mjcf = test::model_path("johnnie");
  Simulation sim(p, model);
  FallDetector detector(sim.plant(), {}, sim.standing_pelvis_height());
  EXPECT_EQ(detector.check(sim.data()), nullptr);
  // The same posture judged against a standing height twice as high: the pelvis is "too low".
  FallDetector strict(sim.plant(), {}, 2.0 * sim.standing_pelvis_height());
  EXPECT_NE(strict.check(sim.data()), nullptr);
}

}  // namespace
}  // namespace biped
