#include "io/scenario.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "io/yaml_reader.hpp"

namespace biped {
namespace {

std::string write_scenario(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / (name + "-" + std::to_string(::getpid()) + ".yaml");
  std::ofstream(path) << text;
  return path.string();
}

const char* kFull = R"(name: full
robot: lola
duration: 20.0
seed: 3
controller:
  stabilizer: true
commands:
  - {t: 0.0, vx: 0.0, vy: 0.0, omega: 0.0}
  - {t: 1.0, vx: 0.5}
  - {t: 18.0, stop: true}
disturbances:
  - {type: push, t: 6.3, body: upper_body, force: [0, 80, 0], duration: 0.1}
terrain:
  - {type: step, x: 3.0, height: 0.02}
  - {type: slope, x: 6.0, angle_deg: 3}
model_error: {upper_body_mass_scale: 1.1}
sensors:
  noise: true
  delay_cycles: 1
  faults:
    - {t: 5.0, sensor: ft_left, value: nan}
)";

TEST(Scenario, ReadsTheSchemaOfTheDesign) {
  const Scenario s = load_scenario(write_scenario("full", kFull));
  EXPECT_EQ(s.name, "full");
  EXPECT_EQ(s.robot, "lola");
  EXPECT_DOUBLE_EQ(s.duration, 20.0);
  EXPECT_EQ(s.seed, 3u);
  ASSERT_EQ(s.commands.size(), 3u);
  EXPECT_DOUBLE_EQ(s.commands[1].command.vx, 0.5);
  EXPECT_DOUBLE_EQ(s.commands[2].command.vx, 0.5) << "unspecified fields keep their value";
  EXPECT_TRUE(s.commands[2].command.stop);
  ASSERT_EQ(s.pushes.size(), 1u);
  EXPECT_DOUBLE_EQ(s.pushes[0].force.y(), 80.0);
  ASSERT_EQ(s.terrain.size(), 2u);
  EXPECT_EQ(s.terrain[1].kind, TerrainFeature::Kind::Slope);
  EXPECT_DOUBLE_EQ(s.model_error.upper_body_mass_scale, 1.1);
  EXPECT_TRUE(s.sensor_noise);
  EXPECT_EQ(s.sensor_delay_cycles, 1);
  ASSERT_EQ(s.faults.size(), 1u);
  EXPECT_EQ(s.faults[0].mode, SensorFault::Mode::NaN);
}

TEST(Scenario, OverridesApplyBeforeChecks) {
  const Scenario s = load_scenario(write_scenario("override", kFull), {"duration=2.5", "controller.stabilizer=false"});
  EXPECT_DOUBLE_EQ(s.duration, 2.5);
  EXPECT_FALSE(s.controller["stabilizer"].as<bool>());
}

std::string error_of(const std::string& text, std::vector<std::string> overrides = {}) {
  const std::string path = write_scenario("bad", text);
  try {
    load_scenario(path, overrides);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Scenario, BadInputNamesFileKeyAndLine) {
  EXPECT_NE(error_of("robot: lola\nduration: -1\n").find("bad-"), std::string::npos);
  EXPECT_NE(error_of("robot: lola\nduration: -1\n").find(":2: key 'duration': must be positive"), std::string::npos);
  EXPECT_NE(error_of("robot: lola\nduration: .nan\n").find("key 'duration': must be a finite number"), std::string::npos);
  EXPECT_NE(error_of("robot: lola\nduration: 1\ndurration: 2\n").find(":3: key 'durration': unknown key"),
            std::string::npos);
  EXPECT_NE(error_of("robot: lola\nduration: 1\ncommands:\n  - {t: 0, vz: 1}\n").find("key 'commands.0.vz'"),
            std::string::npos);
  EXPECT_NE(error_of("robot: lola\nduration: [1\n").find("YAML syntax error"), std::string::npos);
  EXPECT_NE(error_of("duration: 1\n").find("key 'robot': missing"), std::string::npos);
  EXPECT_NE(error_of("robot: lola\nduration: 1\nterrain: [{type: hole, x: 1}]\n").find("unknown terrain 'hole'"),
            std::string::npos);
  EXPECT_NE(error_of("robot: lola\nduration: 1\ncommands: [{t: 2}, {t: 1}]\n").find("time order"), std::string::npos);
  EXPECT_NE(error_of("robot: lola\nduration: 1\n", {"sensors.delay_cycles=-3"}).find("(--set)"), std::string::npos);
}

// Pushes in any direction (an angle in the heading frame, or a world-frame vector), on any body and
// point, timed by the clock or by a gait moment.
TEST(Scenario, PushesTakeAnAngleOrAVectorAndATimeOrAGaitMoment) {
  const Scenario s = load_scenario(write_scenario("pushes", R"(robot: lola
duration: 5
disturbances:
  - {type: push, at: {touchdown: 3, phase: 0.25}, direction_deg: 90, impulse_Ns: 12, duration: 0.1}
  - {type: push, at: {after: 2.5}, direction_deg: 180, force_N: 50, body: pelvis, point: [0.1, 0, 0.2]}
  - {type: push, t: 1.5, force: [10, 20, 0]}
)"));
  ASSERT_EQ(s.pushes.size(), 3u);
  const Push& a = s.pushes[0];
  EXPECT_TRUE(a.at_gait_moment);
  EXPECT_EQ(a.moment.touchdown, 3);
  EXPECT_DOUBLE_EQ(a.moment.phase, 0.25);
  EXPECT_TRUE(a.heading_frame);
  EXPECT_NEAR((a.force - Eigen::Vector3d(0.0, 120.0, 0.0)).norm(), 0.0, 1e-12) << "12 N·s over 0.1 s, to the left";
  const Push& b = s.pushes[1];
  EXPECT_DOUBLE_EQ(b.moment.after_time, 2.5);
  EXPECT_DOUBLE_EQ(b.moment.phase, 0.5) << "the middle of the single support by default";
  EXPECT_NEAR((b.force - Eigen::Vector3d(-50.0, 0.0, 0.0)).norm(), 0.0, 1e-12);
  EXPECT_EQ(b.body, "pelvis");
  EXPECT_TRUE(b.at_point);
  EXPECT_EQ(b.point, Eigen::Vector3d(0.1, 0.0, 0.2));
  const Push& c = s.pushes[2];
  EXPECT_FALSE(c.at_gait_moment);
  EXPECT_FALSE(c.heading_frame);
  EXPECT_DOUBLE_EQ(c.t, 1.5);
  EXPECT_FALSE(c.at_point) << "at the body's CoM by default";
}

TEST(Scenario, BadPushesNameTheKey) {
  auto error = [](const std::string& push) { return error_of("robot: lola\nduration: 1\ndisturbances:\n  - " + push + "\n"); };
  EXPECT_NE(error("{type: push, t: 1, at: {touchdown: 1}, force: [1, 0, 0]}").find("key 'disturbances.0.at'"), std::string::npos);
  EXPECT_NE(error("{type: push, force: [1, 0, 0]}").find("key 'disturbances.0.t': missing"), std::string::npos);
  EXPECT_NE(error("{type: push, at: {touchdown: 0}, force: [1, 0, 0]}").find("key 'disturbances.0.at.touchdown'"),
            std::string::npos);
  EXPECT_NE(error("{type: push, at: {touchdown: 1, after: 2}, force: [1, 0, 0]}").find("key 'disturbances.0.at'"),
            std::string::npos);
  EXPECT_NE(error("{type: push, at: {after: 1, phase: 1.5}, force: [1, 0, 0]}").find("key 'disturbances.0.at.phase'"),
            std::string::npos);
  EXPECT_NE(error("{type: push, at: {after: 1, fase: 0.5}, force: [1, 0, 0]}").find("key 'disturbances.0.at.fase'"),
            std::string::npos);
  EXPECT_NE(error("{type: push, t: 1}").find("key 'disturbances.0.force'"), std::string::npos);
  EXPECT_NE(error("{type: push, t: 1, force: [1, 0, 0], direction_deg: 90}").find("key 'disturbances.0.force'"),
            std::string::npos);
  EXPECT_NE(error("{type: push, t: 1, direction_deg: 90}").find("key 'disturbances.0.impulse_Ns'"), std::string::npos);
  EXPECT_NE(error("{type: push, t: 1, direction_deg: 90, impulse_Ns: -3}").find("key 'disturbances.0.impulse_Ns'"),
            std::string::npos);
  EXPECT_NE(error("{type: push, t: 1, force: [1, 0, 0], impulse_Ns: 3}").find("key 'disturbances.0.impulse_Ns'"),
            std::string::npos);
  EXPECT_NE(error("{type: push, t: 1, force: [1, 0, 0], point: [1, 2]}").find("key 'disturbances.0.point'"),
            std::string::npos);
  EXPECT_NE(error("{type: push, t: 1, direction_deg: x, force_N: 3}").find("key 'disturbances.0.direction_deg'"),
            std::string::npos);
}

TEST(Scenario, MissingFileIsBadInput) {
  EXPECT_THROW(load_scenario("/nonexistent/scenario.yaml"), InputError);
}

}  // namespace
}  // namespace biped
