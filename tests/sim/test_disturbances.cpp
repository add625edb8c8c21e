// Pushes: where the force acts and when, by the clock and by the ground truth's gait events.
#include "sim/disturbances.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "control/walking_controller.hpp"
#include "io/robot_config.hpp"
#include "math/rotations.hpp"
#include "sim/closed_loop.hpp"
#include "sim/simulation.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

// Feeds the gait events each foot's normal force [N], held for a duration [s], one update per
// physics step of `dt`.
struct SyntheticGait {
  explicit SyntheticGait(double dt) : dt(dt) { g.reset(); }
  void hold(double left, double right, double duration) {
    for (double end = t + duration; t < end - 1e-9; t += dt) g.update(t, {left, right});
  }
  GaitEvents g;
  double dt;
  double t = 0.0;
};

// A synthetic gait: both feet down, the left lifts, lands, the right lifts, lands.
TEST(GaitEvents, CountsTouchdownsAndTimesSingleSupports) {
  SyntheticGait gait(0.001);
  const GaitEvents& g = gait.g;
  gait.hold(300, 300, 0.2);
  EXPECT_FALSE(g.single_support());
  gait.hold(5, 600, 0.5);  // left swing
  EXPECT_TRUE(g.single_support());
  EXPECT_EQ(g.touchdowns(), 0);
  EXPECT_NEAR(g.single_support_start(), 0.2, 1e-9);
  gait.hold(30, 570, 0.01);  // between the thresholds: still in the air
  EXPECT_EQ(g.touchdowns(), 0);
  gait.hold(300, 300, 0.2);  // left lands
  EXPECT_EQ(g.touchdowns(), 1);
  EXPECT_NEAR(g.last_single_support_duration(), 0.51, 1e-9);
  gait.hold(600, 5, 0.4);  // right swing
  EXPECT_EQ(g.touchdowns_before_current_support(), 1);
  EXPECT_EQ(g.single_supports_started(), 2);
  EXPECT_NEAR(g.single_support_start(), 0.91, 1e-9) << "dated to the lift-off's start, not its confirmation";
}

// A foot that bounces off the ground for a few milliseconds makes no touchdown and no single
// support; a contact that holds counts, dated to its start.
TEST(GaitEvents, BouncesShorterThanTheConfirmationTimeAreNotEvents) {
  SyntheticGait gait(0.0005);
  const GaitEvents& g = gait.g;
  gait.hold(300, 300, 0.2);
  gait.hold(300, 2, 0.003);  // the right foot leaves the ground for 3 ms
  gait.hold(300, 300, 0.1);
  EXPECT_EQ(g.single_supports_started(), 0);
  EXPECT_EQ(g.touchdowns(), 0);
  gait.hold(5, 600, 0.4);  // left swing
  EXPECT_EQ(g.single_supports_started(), 1);
  EXPECT_NEAR(g.single_support_start(), 0.303, 1e-9);
  gait.hold(300, 300, 0.004);  // the swing foot touches for 4 ms, and swings on
  gait.hold(5, 600, 0.05);
  EXPECT_EQ(g.touchdowns(), 0);
  EXPECT_TRUE(g.single_support());
  gait.hold(300, 300, 0.02);  // lands
  gait.hold(2, 600, 0.002);   // and bounces
  gait.hold(300, 300, 0.2);
  EXPECT_EQ(g.touchdowns(), 1);
  EXPECT_FALSE(g.single_support());
  EXPECT_NEAR(g.last_single_support_duration(), 0.454, 1e-9);
}

class PushOnPlant : public ::testing::Test {
 protected:
  RobotModel plant = test::load_model("lola");
  mjData* d = mj_makeData(plant.mj());
  ~PushOnPlant() override { mj_deleteData(d); }
  void pose(double yaw) {
    Eigen::Map<Eigen::VectorXd>(d->qpos, plant.mj()->nq) = plant.stand_qpos();
    const Eigen::Quaterniond q(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
    d->qpos[3] = q.w();
    d->qpos[4] = q.x();
    d->qpos[5] = q.y();
    d->qpos[6] = q.z();
    mj_kinematics(plant.mj(), d);
  }
};

// A force at a point off the body's CoM adds its moment about the CoM; a heading-frame force turns
// with the robot; the push acts for its duration only.
TEST_F(PushOnPlant, ForceActsAtItsPointInItsFrameForItsDuration) {
  Push push;
  push.t = 0.5;
  push.duration = 0.1;
  push.body = "upper_body";
  push.force = Eigen::Vector3d(100.0, 0.0, 0.0);
  push.heading_frame = true;
  push.at_point = true;
  push.point = Eigen::Vector3d(0.0, 0.0, 0.3);
  PushSchedule schedule(plant, {push});
  GaitEvents gait;
  pose(M_PI / 2.0);
  const int b = plant.upper_body();
  auto applied = [&](double t) {
    d->time = t;
    mju_zero(d->xfrc_applied, 6 * plant.mj()->nbody);
    schedule.apply(d, gait);
    return Eigen::Matrix<double, 6, 1>(d->xfrc_applied + 6 * b);
  };
  EXPECT_EQ(applied(0.49).norm(), 0.0) << "not yet";
  const Eigen::Matrix<double, 6, 1> w = applied(0.5);
  EXPECT_NEAR((w.head<3>() - Eigen::Vector3d(0.0, 100.0, 0.0)).norm(), 0.0, 1e-9) << "forward is +y at 90 deg yaw";
  const Eigen::Vector3d point = Eigen::Vector3d(d->xpos + 3 * b) + math::mat_from_mujoco(d->xmat + 9 * b) * push.point;
  const Eigen::Vector3d moment = (point - Eigen::Vector3d(d->xipos + 3 * b)).cross(w.head<3>());
  EXPECT_NEAR((w.tail<3>() - moment).norm(), 0.0, 1e-9);
  EXPECT_GT(w.tail<3>().norm(), 1.0) << "the point lies well off the CoM";
  EXPECT_NEAR(schedule.start_times()[0], 0.5, 1e-12);
  pose(0.0);  // the heading frame is fixed at the push's start
  EXPECT_NEAR((applied(0.55).head<3>() - Eigen::Vector3d(0.0, 100.0, 0.0)).norm(), 0.0, 1e-9);
  EXPECT_EQ(applied(0.6).norm(), 0.0) << "over after its duration";
}

// In a closed-loop walk, a push timed `at: {touchdown: 2, phase: 0.5}` starts after the second
// touchdown's single support has begun, half the previous single support later (at the first physics
// step from then on). A foot that lifts may touch the ground again for a few milliseconds (the
// whole-swing gait's did, 3 ms after the first touchdown): such a bounce is neither a touchdown nor a
// single support of its own.
TEST(PushTiming, GaitMomentPushLandsInTheSingleSupportAfterTheTouchdown) {
  Scenario s;
  s.file = "test";
  s.robot = "lola";
  s.duration = 6.0;
  s.ideal_sensors = true;
  RunConfig config = make_run_config(s);
  Push push;
  push.at_gait_moment = true;
  push.moment.touchdown = 2;
  push.moment.phase = 0.5;
  push.duration = 0.1;
  push.heading_frame = true;
  push.force = Eigen::Vector3d(0.0, 40.0, 0.0);
  config.sim.pushes = {push};
  const RobotModel model = RobotModel::load(config.controller.model_path, config.controller.software_limit_margin_rad);
  Simulation sim(config.sim, model);
  WalkingController controller(model, config.controller.walking);

  // Watches the ground-truth single supports around the push.
  struct Watch final : RunObserver {
    double support_start_at_push = NAN, previous_duration_at_push = NAN;
    int touchdowns_at_push = -1;
    void record(const Simulation&, const SensorData&, const JointCommand&, const ControllerStatus&, double) override {}
    void cycle_start(const Simulation& sim) override {
      const double start = sim.pushes().start_times()[0];
      if (std::isnan(start) || !std::isnan(support_start_at_push)) return;
      support_start_at_push = sim.gait_events().single_support_start();
      previous_duration_at_push = sim.gait_events().last_single_support_duration();
      touchdowns_at_push = sim.gait_events().touchdowns_before_current_support();
    }
  } watch;
  RunOptions options;
  options.duration = s.duration;
  run_closed_loop(sim, controller, {TimedCommand{}, TimedCommand{0.5, WalkCommand{0.3, 0.0, 0.0, false}}}, options,
                  &watch);
  const double start = sim.pushes().start_times()[0];
  ASSERT_FALSE(std::isnan(start)) << "the push came";
  EXPECT_EQ(watch.touchdowns_at_push, 2);
  // At the first physics step at or after that moment (half a support may end between two steps).
  const double moment = watch.support_start_at_push + 0.5 * watch.previous_duration_at_push;
  EXPECT_GE(start, moment - 1e-9);
  EXPECT_LT(start, moment + sim.plant().mj()->opt.timestep - 1e-9);
  EXPECT_GT(watch.previous_duration_at_push, 0.2) << "a real single support was measured";
}

}  // namespace
}  // namespace biped
