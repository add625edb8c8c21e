#include "studies/step_table_search.hpp"

#include <gtest/gtest.h>

#include <yaml-cpp/yaml.h>

#include "io/robot_config.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

// The criterion separates a comfortable gait from an overreaching one.
TEST(StepTableSearch, CriterionPrefersFeasibleGaitsWithZmpMargin) {
  const RobotModel model = test::load_model("johnnie");
  WalkingControllerParams base;
  const CandidateResult easy = evaluate_step_candidate(model, base, 0.3, 0.9, 0.2, 4, 2);
  EXPECT_TRUE(easy.feasible);
  EXPECT_GT(easy.zmp_margin, 0.02);
  const CandidateResult hard = evaluate_step_candidate(model, base, 1.0, 1.0, 0.1, 4, 2);  // 1 m steps
  EXPECT_FALSE(hard.feasible && hard.zmp_margin > 0.0);
}

// The shipped tables exist for both robots and bound the accepted commands to their fastest row
// with the required ZMP margin; a scenario's own vx_max goes beyond it.
TEST(StepTableSearch, ShippedTablesBoundTheCommands) {
  for (const char* robot : {"lola", "johnnie"}) {
    Scenario s;
    s.file = "test";
    s.robot = robot;
    s.duration = 1.0;
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

}  // namespace
}  // namespace biped
