#include "io/robot_config.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "io/yaml_reader.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

Scenario scenario_with(const std::string& robot) {
  Scenario s;
  s.file = "test.yaml";
  s.robot = robot;
  s.duration = 1.0;
  return s;
}

TEST(RobotConfig, BothRobotsHaveParameterFiles) {
  const auto robots = known_robots();
  EXPECT_NE(std::find(robots.begin(), robots.end(), "lola"), robots.end());
  EXPECT_NE(std::find(robots.begin(), robots.end(), "johnnie"), robots.end());
  for (const auto& name : robots) {
    const RunConfig c = make_run_config(scenario_with(name));
    EXPECT_TRUE(std::filesystem::exists(c.sim.world.robot_mjcf));
    EXPECT_EQ(c.controller.model_path, c.sim.world.robot_mjcf);
    EXPECT_GE(c.sim.drives.bandwidth_hz, 15.0);
    EXPECT_LE(c.sim.drives.bandwidth_hz, 25.0);
  }
}

TEST(RobotConfig, UnknownRobotListsTheKnownOnes) {
  try {
    make_run_config(scenario_with("asimo"));
    FAIL();
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("test.yaml: key 'robot': unknown robot 'asimo'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("lola"), std::string::npos);
  }
}

TEST(RobotConfig, ScenarioOverridesControllerAndSimulationKeys) {
  Scenario s = scenario_with("lola");
  s.controller = YAML::Load("{stabilizer: false, ramp_time: 0.5}");
  s.simulation = YAML::Load("{timestep: 0.0005, control_period: 0.001}");
  const RunConfig c = make_run_config(s);
  EXPECT_FALSE(c.controller.stabilizer);
  EXPECT_DOUBLE_EQ(c.controller.standing.ramp_time, 0.5);
  EXPECT_DOUBLE_EQ(c.sim.world.timestep, 0.0005);

  s.controller = YAML::Load("{stabiliser: false}");
  EXPECT_THROW(make_run_config(s), InputError);
  s.controller = YAML::Node();
  s.simulation = YAML::Load("{timestep: 0.0007}");
  EXPECT_THROW(make_run_config(s), InputError);
}

// The stabilizer's gains and extensions are read from the robot's file; a scenario overrides single
// keys and keeps the rest; inconsistent values name the key.
TEST(RobotConfig, StabilizationKeysMergeAndAreChecked) {
  Scenario s = scenario_with("lola");
  s.controller = YAML::Load("{stabilization: {force_integral_gain: 80, stiffness_adaptation: true}, "
                            "sensor_limits: {frozen_cycles: 0}}");
  const RunConfig c = make_run_config(s);
  const StabilizerParams& p = c.controller.walking.stabilization;
  EXPECT_DOUBLE_EQ(p.force_integral_gain, 80.0);
  EXPECT_TRUE(p.stiffness_adaptation);
  EXPECT_DOUBLE_EQ(p.tilt_gain, make_run_config(scenario_with("lola")).controller.walking.stabilization.tilt_gain);
  EXPECT_EQ(c.controller.walking.sensor_limits.frozen_cycles, 0);

  s.controller = YAML::Load("{stabilization: {contact_force_low: 200, contact_force_high: 100}}");
  try {
    make_run_config(s);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("controller.stabilization.contact_force_high"), std::string::npos) << e.what();
  }
  for (const char* bad : {"{stabilization: {heel_stiffness_share: 1.0}}", "{stabilization: {heel_stiffness_share: 0}}",
                          "{stabilization: {contact_tolerance: -0.001}}", "{stabilization: {toe_contact: 3}}"}) {
    s.controller = YAML::Load(bad);
    try {
      make_run_config(s);
      FAIL() << bad;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("controller.stabilization."), std::string::npos) << e.what();
    }
  }
  s.controller = YAML::Load("{stabilization: {tilt_gian: 1}}");
  EXPECT_THROW(make_run_config(s), InputError);
  s.controller = YAML::Load("{sensor_limits: {frozen_cycles: -1}}");
  EXPECT_THROW(make_run_config(s), InputError);
}

TEST(RobotConfig, BareMjcfPathUsesDefaults) {
  const RunConfig c = make_run_config(scenario_with(test::model_path("johnnie")));
  EXPECT_EQ(c.robot, "johnnie");
  EXPECT_TRUE(c.robot_file.empty());
  EXPECT_THROW(make_run_config(scenario_with("/nonexistent/robot.xml")), InputError);
}

}  // namespace
}  // namespace biped
