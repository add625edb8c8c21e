// The push test: the stabilizer (eq. 10 with eq. 20) survives at least twice the push impulse of
// the open-loop baseline, sideways (both ways) and forward, in LOLA's push scenario (a slow walk that the
// open loop walks through unpushed, so that both sides of the comparison are measured).
#include "studies/push_test.hpp"

#include <gtest/gtest.h>

#include "io/yaml_reader.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

struct OnOff {
  nlohmann::json on, off;
};

OnOff push_on_and_off(const std::string& direction) {
  PushTestOptions options;
  options.direction = direction;
  const std::string file = test::source_path("config/scenarios/lola-push.yaml");
  OnOff r;
  for (bool stabilizer : {true, false}) {
    // Ideal sensors: the comparison is of the stabilizer, on a plant whose sensors do not differ.
    const Scenario scenario =
        load_scenario(file, {std::string("controller.stabilizer=") + (stabilizer ? "true" : "false"), "sensors.ideal=true"});
    (stabilizer ? r.on : r.off) = run_push_test(scenario, make_run_config(scenario), options);
  }
  return r;
}

void expect_twice(const OnOff& r) {
  EXPECT_TRUE(r.on["stabilizer"].get<bool>());
  EXPECT_FALSE(r.off["stabilizer"].get<bool>());
  ASSERT_FALSE(r.off["falls_without_push"].get<bool>()) << r.off.dump();
  ASSERT_FALSE(r.on["falls_without_push"].get<bool>()) << r.on.dump();
  // Each push lands in the middle of a single support of its own gait, after t = 4 s.
  EXPECT_GT(r.on["push_time_s"].get<double>(), 4.0);
  EXPECT_GT(r.off["push_time_s"].get<double>(), 4.0);
  EXPECT_NEAR(r.on["push_time_s"].get<double>(), r.off["push_time_s"].get<double>(), 0.5) << "the same step";
  EXPECT_GE(r.on["max_impulse_Ns"].get<double>(), 2.0 * r.off["max_impulse_Ns"].get<double>())
      << "on " << r.on.dump() << "\noff " << r.off.dump();
  EXPECT_GT(r.on["max_impulse_Ns"].get<double>(), r.off["max_impulse_Ns"].get<double>()) << "also where the open loop survives nothing";
  EXPECT_FALSE(r.on["survived_every_impulse_tried"].get<bool>());
  EXPECT_NEAR(r.on["phase"].get<double>(), 0.5, 1e-12);
}

TEST(PushTest, StabilizerSurvivesTwiceTheOpenLoopLateralPush) { expect_twice(push_on_and_off("left")); }

// Towards the swinging foot, which the open loop catches with its next step.
TEST(PushTest, StabilizerSurvivesTwiceTheOpenLoopPushTowardsTheSwingFoot) { expect_twice(push_on_and_off("right")); }

TEST(PushTest, StabilizerSurvivesTwiceTheOpenLoopSagittalPush) { expect_twice(push_on_and_off("forward")); }

TEST(PushTest, RejectsAnUnknownDirection) {
  const Scenario scenario = load_scenario(test::source_path("config/scenarios/lola-push.yaml"));
  PushTestOptions options;
  options.direction = "up";
  EXPECT_THROW(run_push_test(scenario, make_run_config(scenario), options), InputError);
}

}  // namespace
}  // namespace biped
