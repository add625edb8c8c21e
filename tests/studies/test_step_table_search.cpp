#include "studies/step_table_search.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include <yaml-cpp/yaml.h>

#include "io/robot_config.hpp"
#include "studies/scenario_runner.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

// The criterion separates a comfortable gait from an overreaching one.
TEST(StepTableSearch, CriterionPrefersFeasibleGaitsWithZmpMargin) {
  const RobotModel model = test::load_model("johnnie");
  WalkingControllerParams base;
  const CandidateResult easy = evaluate_step_candidate(model, base, 0.3, 0.9, 0.2, 4, 2, StepTableSearch{}.zmp_window);
  EXPECT_TRUE(easy.feasible);
  EXPECT_GT(easy.zmp_margin, 0.02);
  const CandidateResult hard = evaluate_step_candidate(model, base, 1.0, 1.0, 0.1, 4, 2, StepTableSearch{}.zmp_window);  // 1 m steps
  EXPECT_FALSE(hard.feasible && hard.zmp_margin > 0.0);
}

// The shipped tables exist for both robots and bound the accepted commands to their fastest row
// with the required ZMP margin; a scenario's own vx_max goes beyond it.
TEST(StepTableSearch, ShippedTablesBoundTheCommands) {
  for (const char* robot : {"lola", "johnnie"}) {
    Scenario s = test::robot_scenario(robot);
    const RunConfig config = make_run_config(s);
    const StepTable& table = config.controller.walking.plan.table;
    ASSERT_FALSE(table.empty()) << robot;
    const CommandLimits& limits = config.controller.walking.plan.limits;
    EXPECT_DOUBLE_EQ(limits.vx_max, fastest_feasible_speed(table, limits.min_zmp_margin));
    EXPECT_GE(limits.vx_max, 0.6) << robot;
    EXPECT_LT(limits.vx_max, fastest_feasible_speed(table)) << robot << ": its fastest row has less margin";
    s.controller["limits"]["vx_max"] = 1.0;
    EXPECT_DOUBLE_EQ(make_run_config(s).controller.walking.plan.limits.vx_max, 1.0) << robot;
  }
}

RunConfig jvrc1_config() { return make_run_config(test::robot_scenario("jvrc1")); }

// Where no gait passes, criterion 2 may average the ZMP over the drives' period
// (`step_table_relaxed_zmp_window`): JVRC-1's swing leg, stopping short before touchdown at 0.7 m/s,
// throws the instantaneous ZMP past the toe for a few milliseconds, which condemns a gait that walks.
TEST(StepTableSearch, AShortZmpExcursionDoesNotCondemnAGaitThatWalks) {
  const RunConfig config = jvrc1_config();
  const RobotModel model = load_controller_model(config);
  // The paper's swing, travelling the whole swing time: its leg stops short just before touchdown.
  WalkingControllerParams base = config.controller.walking;
  base.plan.step.swing_travel_share = 1.0;
  const double speed = 0.7, step_time = 0.45, double_support = 0.2, one_cycle = base.rmrc.dt;
  const CandidateResult instant = evaluate_step_candidate(model, base, speed, step_time, double_support, 6, 2, one_cycle);
  const CandidateResult averaged = evaluate_step_candidate(model, base, speed, step_time, double_support, 6, 2,
                                                           1.0 / config.sim.drives.bandwidth_hz);
  ASSERT_TRUE(instant.feasible && averaged.feasible);
  EXPECT_LT(instant.zmp_margin, 0.0);
  EXPECT_GT(averaged.zmp_margin, 0.0);
  EXPECT_GT(averaged.zmp_margin, instant.zmp_margin + 0.01);
  EXPECT_TRUE(survives_in_simulation(model, base, config.sim, speed, StepTableSearch{}.turn_rate, step_time,
                                     double_support, 8));
}

// The relaxed criterion only adds rows above the fastest row that passed; the rows that passed stay
// exactly as the strict search chose them.
TEST(StepTableSearch, TheRelaxedCriterionOnlyAddsFasterRows) {
  const RunConfig config = jvrc1_config();
  const RobotModel model = load_controller_model(config);
  StepTableSearch search;
  search.speeds = {0.6, 0.7};
  search.step_times = {0.45, 0.5};
  search.double_support_ratios = {0.15, 0.2};
  search.steps = 6;
  const StepTable strict = generate_step_table(model, config.controller.walking, search, nullptr, nullptr);
  search.relaxed_zmp_window = 1.0 / config.sim.drives.bandwidth_hz;
  const StepTable relaxed = generate_step_table(model, config.controller.walking, search, nullptr, nullptr);
  ASSERT_EQ(strict.rows.size(), 2u);
  ASSERT_EQ(relaxed.rows.size(), 2u);
  EXPECT_GT(strict.rows[0].zmp_margin, 0.0);  // 0.6 m/s passes as it is
  EXPECT_DOUBLE_EQ(relaxed.rows[0].step_time, strict.rows[0].step_time);
  EXPECT_DOUBLE_EQ(relaxed.rows[0].double_support_ratio, strict.rows[0].double_support_ratio);
  EXPECT_DOUBLE_EQ(relaxed.rows[0].zmp_margin, strict.rows[0].zmp_margin);
  EXPECT_LE(strict.rows[1].zmp_margin, 0.0);  // 0.7 m/s: no gait by each instant's ZMP
  EXPECT_GT(relaxed.rows[1].zmp_margin, 0.0);
  EXPECT_LE(std::abs(relaxed.rows[1].step_time - relaxed.rows[0].step_time), search.max_step_time_change + 1e-9);
}

// Each row keeps the swing that travels first and comes down vertically (`swing_travel_share`
// 0.8, as the robot file says and config/tables/lola.csv was made) unless travelling the whole
// swing keeps more than the tolerance more ZMP margin: LOLA's slow gait keeps it; at 1.0 m/s the harder leg swing leaves no gait with it.
TEST(StepTableSearch, ARowTravelsTheWholeSwingOnlyWhereItsGaitNeedsIt) {
  const RunConfig config = make_run_config(test::robot_scenario("lola"));
  const RobotModel model = load_controller_model(config);
  const WalkingControllerParams base = config.controller.walking;
  ASSERT_LT(base.plan.step.swing_travel_share, 1.0);
  StepTableSearch search;
  search.speeds = {0.4, 1.0};
  search.step_times = {0.4, 0.5};
  search.double_support_ratios = {0.15};
  search.steps = 6;
  const StepTable table = generate_step_table(model, base, search, nullptr, nullptr);
  ASSERT_EQ(table.rows.size(), 2u);
  for (const StepTableRow& row : table.rows) {
    WalkingControllerParams set_down = base, whole = base;
    whole.plan.step.swing_travel_share = 1.0;
    const double with_set_down = evaluate_step_candidate(model, set_down, row.speed, row.step_time,
                                                         row.double_support_ratio, search.steps,
                                                         search.settle_steps, search.zmp_window).zmp_margin;
    const double with_whole = evaluate_step_candidate(model, whole, row.speed, row.step_time, row.double_support_ratio,
                                                      search.steps, search.settle_steps, search.zmp_window).zmp_margin;
    EXPECT_DOUBLE_EQ(row.zmp_margin, row.swing_travel_share < 1.0 ? with_set_down : with_whole) << row.speed;
  }
  EXPECT_DOUBLE_EQ(table.rows[0].swing_travel_share, base.plan.step.swing_travel_share);
  EXPECT_GT(table.rows[0].zmp_margin, 0.02);
  EXPECT_DOUBLE_EQ(table.rows[1].swing_travel_share, 1.0);
  EXPECT_GT(table.rows[1].zmp_margin, 0.0);
}

}  // namespace
}  // namespace biped
