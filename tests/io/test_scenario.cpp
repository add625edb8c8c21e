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

// Terrain in the plane: every feature kind placed and turned anywhere; bad values and overlapping
// friction patches name the feature's key.
TEST(Scenario, TerrainFeaturesInThePlane) {
  const Scenario s = load_scenario(write_scenario("plane", R"(robot: lola
duration: 1
terrain:
  - {type: step, x: 1, y: 0.5, heading_deg: 30, height: 0.02}
  - {type: slope, x: 0, y: -1, heading_deg: 90, angle_deg: -4, length: 1}
  - {type: box, x: 2, y: 0.2, heading_deg: 15, length: 1.2, width: 0.3, height: 0.03}
  - {type: friction, x: 3, length: 1, width: 2, mu: 0.2}
)"));
  ASSERT_EQ(s.terrain.size(), 4u);
  EXPECT_EQ(s.terrain[0].at, Eigen::Vector2d(1.0, 0.5));
  EXPECT_DOUBLE_EQ(s.terrain[0].heading_deg, 30.0);
  EXPECT_DOUBLE_EQ(s.terrain[1].heading_deg, 90.0);
  EXPECT_EQ(s.terrain[2].kind, TerrainFeature::Kind::Box);
  EXPECT_DOUBLE_EQ(s.terrain[2].width, 0.3);
  EXPECT_EQ(s.terrain[3].kind, TerrainFeature::Kind::Friction);
  EXPECT_DOUBLE_EQ(s.terrain[3].friction, 0.2);
  const std::string head = "robot: lola\nduration: 1\nterrain:\n";
  EXPECT_NE(error_of(head + "  - {type: box, x: 1, length: 1, width: -1, height: 0.1}\n").find("key 'terrain.0.width'"),
            std::string::npos);
  EXPECT_NE(error_of(head + "  - {type: box, x: 1, length: 1, height: 0.1}\n").find("key 'terrain.0.width': missing"),
            std::string::npos);
  EXPECT_NE(error_of(head + "  - {type: friction, x: 1, length: 1, width: 1}\n").find("key 'terrain.0.mu': missing"),
            std::string::npos);
  EXPECT_NE(error_of(head + "  - {type: step, x: 1, height: 0.1, heading: 3}\n").find("key 'terrain.0.heading'"),
            std::string::npos);
  const std::string overlap = error_of(head +
                                       "  - {type: friction, x: 1, length: 1, width: 1, mu: 0.2}\n"
                                       "  - {type: step, x: 1, height: 0.02}\n"
                                       "  - {type: friction, x: 1.4, y: 0.4, heading_deg: 45, length: 1, width: 0.2, mu: 0.5}\n");
  EXPECT_NE(overlap.find(":6: key 'terrain.2': friction patch overlaps the one of terrain.0"), std::string::npos)
      << overlap;
  EXPECT_EQ(error_of(head +
                     "  - {type: friction, x: 1, length: 1, width: 1, mu: 0.2}\n"
                     "  - {type: friction, x: 2.01, length: 1, width: 1, mu: 0.5}\n"
                     "  - {type: box, x: 1, length: 1, width: 1, height: 0.05}\n"
                     "  - {type: box, x: 1.2, length: 1, width: 1, height: 0.05}\n"),
            "")
      << "boxes add up; patches side by side do not overlap";
}

TEST(Scenario, MissingFileIsBadInput) {
  EXPECT_THROW(load_scenario("/nonexistent/scenario.yaml"), InputError);
}

}  // namespace
}  // namespace biped
