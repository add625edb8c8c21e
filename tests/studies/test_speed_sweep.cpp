// The speed sweep: one straight walk per commanded speed; a speed beyond the step table's limit is
// reported as saturated and not counted as walked.
#include "studies/speed_sweep.hpp"

#include <gtest/gtest.h>

#include "io/yaml_reader.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

TEST(SpeedSweep, ReportsEachSpeedAndTheFastestUnsaturatedWalk) {
  const Scenario scenario = load_scenario(test::source_path("config/scenarios/johnnie-walk.yaml"));
  const RunConfig config = make_run_config(scenario);
  const double limit = config.controller.walking.plan.limits.vx_max;
  SpeedSweepOptions options;
  options.from = 0.3;
  options.step = limit + 0.2 - 0.3;
  options.to = limit + 0.2;
  options.hold = 3.0;
  const nlohmann::json r = run_speed_sweep(scenario, config, options);
  ASSERT_EQ(r["runs"].size(), 2u);
  const auto& slow = r["runs"][0];
  const auto& fast = r["runs"][1];
  EXPECT_FALSE(slow["fell"].get<bool>());
  EXPECT_FALSE(slow["command_saturated"].get<bool>());
  EXPECT_NEAR(slow["walked_mps"].get<double>(), 0.3, 0.05);
  EXPECT_TRUE(fast["command_saturated"].get<bool>());
  if (!fast["fell"].get<bool>()) {
    EXPECT_LT(fast["walked_mps"].get<double>(), limit + 0.05);
  }
  EXPECT_DOUBLE_EQ(r["fastest_without_fall_mps"].get<double>(), 0.3);

  options.to = 0.1;
  EXPECT_THROW(run_speed_sweep(scenario, config, options), InputError);
}

}  // namespace
}  // namespace biped
