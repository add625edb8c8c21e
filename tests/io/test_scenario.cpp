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

TEST(Scenario, MissingFileIsBadInput) {
  EXPECT_THROW(load_scenario("/nonexistent/scenario.yaml"), InputError);
}

}  // namespace
}  // namespace biped
