// `biped push-map` (studies/push_map.cpp): the capture-point bound's geometry, and a tiny map of a
// standing robot (pushes timed by the clock, one phase) with a cell per direction.
#include "studies/push_map.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "io/yaml_reader.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

Scenario scenario(const std::string& name, const std::vector<std::string>& overrides = {}) {
  return load_scenario(test::source_path("config/scenarios/" + name + ".yaml"), overrides);
}

TEST(ScenarioWalks, OnlyWhenACommandAsksForMotion) {
  EXPECT_FALSE(scenario_walks(scenario("lola-stand")));
  EXPECT_TRUE(scenario_walks(scenario("lola-push")));
}

TEST(CapturePointBound, BothSolesReachFartherSidewaysThanOneAndTheBoundIsMOmegaD) {
  const RunConfig config = make_run_config(scenario("lola-stand"));
  const nlohmann::json standing = capture_point_bound(config, true, 4);  // 0, 90, 180, -90 degrees
  const nlohmann::json single = capture_point_bound(config, false, 4);
  EXPECT_GT(standing["mass_kg"].get<double>(), 40.0);
  EXPECT_NEAR(standing["omega_per_s"].get<double>(), std::sqrt(9.81 / standing["com_height_m"].get<double>()), 1e-12);
  const auto& s = standing["per_direction"];
  const auto& o = single["per_direction"];
  // Sideways, the other foot's sole widens the support polygon; left and right are symmetric.
  EXPECT_GT(s[1]["distance_m"].get<double>(), 1.5 * o[1]["distance_m"].get<double>());
  EXPECT_NEAR(s[1]["distance_m"].get<double>(), s[3]["distance_m"].get<double>(), 0.01);
  // One sole centred under the CoM: as far forward as backward, farther than sideways.
  EXPECT_NEAR(o[0]["distance_m"].get<double>(), o[2]["distance_m"].get<double>(), 1e-9);
  EXPECT_GT(o[0]["distance_m"].get<double>(), o[1]["distance_m"].get<double>());
  for (int k = 0; k < 4; ++k) {
    EXPECT_GT(o[k]["distance_m"].get<double>(), 0.0);
    EXPECT_NEAR(s[k]["max_impulse_Ns"].get<double>(),
                standing["mass_kg"].get<double>() * standing["omega_per_s"].get<double>() * s[k]["distance_m"].get<double>(),
                1e-9);  // I = m ω d
  }
}

TEST(PushMap, AStandingRobotHasOneCellPerDirectionAndSurvivesSmallPushes) {
  const auto dir = test::fresh_dir("push-map");
  PushMapOptions options;
  options.directions = 2;
  options.phases = 8;  // ignored: a standing robot has no gait phases
  options.test.earliest = 0.5;
  options.test.max_impulse = 8.0;
  options.test.bracket_step = 4.0;
  options.test.resolution = 4.0;
  const MpiSession mpi;
  const std::vector<std::string> overrides = {"duration=2.0"};
  const nlohmann::json map = run_push_map(test::source_path("config/scenarios/lola-stand.yaml"), overrides,
                                          dir.string(), options, mpi, CampaignEngineOptions{2, nullptr, "t"});
  ASSERT_EQ(map["cells"].size(), 2u);
  EXPECT_TRUE(map["standing"].get<bool>());
  for (const auto& cell : map["cells"]) {
    EXPECT_TRUE(cell["phase"].is_null());
    EXPECT_GE(cell["max_impulse_Ns"].get<double>(), 4.0) << cell.dump();
    EXPECT_NE(cell["command"].get<std::string>().find("--at-time 0.5"), std::string::npos);
  }
  EXPECT_EQ(map["cells"][1]["direction_deg"], 180.0);
  EXPECT_TRUE(std::filesystem::exists(dir / "push_map.json"));
  EXPECT_TRUE(std::filesystem::exists(dir / "report.html"));
  EXPECT_THROW(run_push_map(test::source_path("config/scenarios/lola-stand.yaml"), overrides, dir.string(),
                            PushMapOptions{0, 8, {}}, mpi, CampaignEngineOptions{}),
               InputError);
}

}  // namespace
}  // namespace biped
