// The weight-shift scenario in closed loop: eq. (21) and the joint servos move the simulated robot
// onto one foot, lift the other 5 cm and put it down again, without a fall.
#include "control/weight_shift_controller.hpp"

#include <gtest/gtest.h>

#include "io/robot_config.hpp"
#include "io/scenario.hpp"
#include "studies/scenario_runner.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

struct LiftObserver final : public RunObserver {
  double hold_start = 0.0, hold_end = 0.0;
  double max_swing_load = 0.0;     // ground-truth normal force on the lifted foot during the hold
  double min_swing_height = 1.0;   // lowest point of the lifted foot's sole during the hold
  double max_tilt = 0.0;
  void record(const Simulation& sim, const SensorData&, const JointCommand&, const ControllerStatus&, double) override {
    const double t = sim.time();
    const mjData* d = sim.data();
    max_tilt = std::max(max_tilt, std::acos(std::clamp(d->xmat[9 * sim.plant().upper_body() + 8], -1.0, 1.0)));
    if (t < hold_start || t > hold_end) return;
    max_swing_load = std::max(max_swing_load, sim.foot_contact_force(Side::Right));
    const FootInfo& foot = sim.plant().foot(Side::Right);
    min_swing_height = std::min(min_swing_height, d->site_xpos[3 * foot.sensor_site + 2] + foot.sole_z);
  }
};

class WeightShift : public ::testing::TestWithParam<std::string> {};

TEST_P(WeightShift, LiftsTheOtherFootWithoutFalling) {
  const Scenario scenario = load_scenario(test::source_path("config/scenarios/" + GetParam() + "-weight-shift.yaml"));
  const RunConfig config = make_run_config(scenario);
  const WeightShiftParams& p = config.controller.weight_shift;
  ASSERT_EQ(p.stance, Side::Left);
  LiftObserver obs;
  // The middle of the hold phase, when the foot should be at its full height.
  obs.hold_start = p.start_delay + p.shift_time + p.lift_time + 0.2;
  obs.hold_end = obs.hold_start + p.hold_time - 0.4;
  const ScenarioResult result = run_scenario(scenario, config, "", &obs);
  EXPECT_FALSE(result.run.fell) << result.run.fall_reason;
  EXPECT_LT(obs.max_swing_load, 1.0) << "the lifted foot still touched the ground";
  EXPECT_GT(obs.min_swing_height, 0.7 * p.lift_height);
  EXPECT_LT(obs.max_tilt, 10.0 * M_PI / 180.0);
}

INSTANTIATE_TEST_SUITE_P(Robots, WeightShift, ::testing::Values("lola", "johnnie"),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace biped
