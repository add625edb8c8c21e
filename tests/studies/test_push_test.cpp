// The push test: in every direction the stabilizer (eq. 10 with eq. 20) survives at least twice the
// push impulse of the open-loop baseline in the baseline's worst gait phase, in LOLA's push scenario
// (a slow walk that stops early enough for the open loop to walk it through unpushed, so that both
// sides of the comparison are measured). Worst phases, because the open loop's catch depends on the phase: its sideways sway
// makes a push towards the swinging foot at mid-swing survivable (16 N·s) and one at the start of
// the single support not (1 N·s). On the long-step table (1 s steps at 0.1 m/s), the gait of the
// comparison's requirement: with the shipped table's 0.4 s steps the open loop itself catches
// 8–16 N·s and the stabilizer adds 1.5–1.9× (docs/walking.md "Short steps").
#include "studies/push_test.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "io/yaml_reader.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

struct Worst {
  double impulse = 1e9;  // [N·s] the smallest over the phases of the largest survived
  nlohmann::json runs = nlohmann::json::array();
};

Worst worst_phase(const std::string& direction, bool stabilizer) {
  const std::string file = test::source_path("config/scenarios/lola-push.yaml");
  // Ideal sensors: the comparison is of the stabilizer, on a plant whose sensors do not differ.
  const Scenario scenario =
      load_scenario(file, {std::string("controller.stabilizer=") + (stabilizer ? "true" : "false"), "sensors.ideal=true",
                           "commands.2.t=5.5",
                           "controller.step_table=" + test::source_path("config/tables/lola-long-steps.csv")});
  Worst worst;
  for (double phase : {1.0 / 6.0, 0.5, 5.0 / 6.0}) {
    PushTestOptions options;
    options.direction = direction;
    options.phase = phase;
    options.earliest = 3.5;  // the third step's single support, a step before the walk stops
    const nlohmann::json r = run_push_test(scenario, make_run_config(scenario), options);
    EXPECT_EQ(r["stabilizer"].get<bool>(), stabilizer);
    EXPECT_FALSE(r["falls_without_push"].get<bool>()) << r.dump();
    EXPECT_FALSE(r["survived_every_impulse_tried"].get<bool>()) << r.dump();
    EXPECT_GT(r["push_time_s"].get<double>(), 3.5);
    EXPECT_LT(r["push_time_s"].get<double>(), 4.7) << "within the third step";
    worst.impulse = std::min(worst.impulse, r["max_impulse_Ns"].get<double>());
    worst.runs.push_back(r);
  }
  return worst;
}

void expect_twice(const std::string& direction) {
  const Worst on = worst_phase(direction, true), off = worst_phase(direction, false);
  EXPECT_GE(on.impulse, 2.0 * off.impulse) << "on " << on.runs.dump() << "\noff " << off.runs.dump();
  EXPECT_GT(on.impulse, off.impulse) << "also where the open loop survives nothing";
}

TEST(PushTest, StabilizerSurvivesTwiceTheOpenLoopLateralPush) { expect_twice("left"); }

// Towards the swinging foot, which the open loop catches with its next step in some phases.
TEST(PushTest, StabilizerSurvivesTwiceTheOpenLoopPushTowardsTheSwingFoot) { expect_twice("right"); }

TEST(PushTest, StabilizerSurvivesTwiceTheOpenLoopSagittalPush) { expect_twice("forward"); }

TEST(PushTest, RejectsAnUnknownDirection) {
  const Scenario scenario = load_scenario(test::source_path("config/scenarios/lola-push.yaml"));
  PushTestOptions options;
  options.direction = "up";
  EXPECT_THROW(run_push_test(scenario, make_run_config(scenario), options), InputError);
}

}  // namespace
}  // namespace biped
