#include "io/scenario.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "io/robot_config.hpp"
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
  const RunConfig c = make_run_config(s);
  EXPECT_TRUE(c.sim.sensor_noise);
  EXPECT_EQ(c.sim.sensor_delay_cycles, 1);
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

const char* kPlain = "robot: lola\nduration: 1\n";

// The robot file's `sensors` section: noise, per-run errors, one cycle of delay, the attitude filter.
TEST(Scenario, SensorsAreRealisticByDefaultAndIdealTurnsEveryErrorOff) {
  const RunConfig realistic = make_run_config(load_scenario(write_scenario("plain", kPlain)));
  EXPECT_TRUE(realistic.sim.sensor_noise);
  EXPECT_EQ(realistic.sim.sensor_delay_cycles, 1);
  EXPECT_TRUE(realistic.sim.sensor_errors.imu.attitude_filter);
  EXPECT_GT(realistic.sim.sensor_errors.imu.bandwidth_hz, 0.0);

  // ideal wins over every other key, the robot file's and the scenario's own; faults stay.
  const std::string file = write_scenario("ideal", std::string(kPlain) +
                                                       "sensors:\n  noise: true\n  delay_cycles: 3\n"
                                                       "  imu: {gyro_bias: [0, 0, 0.01]}\n"
                                                       "  ft: {left: {offset: [5, 0, 0, 0, 0, 0]}}\n"
                                                       "  encoders: {offset_deg: {left_knee: 0.5}}\n"
                                                       "  faults: [{t: 1, sensor: imu, value: nan}]\n");
  const Scenario ideal = load_scenario(file, {"sensors.ideal=true"});
  const RunConfig c = make_run_config(ideal);
  EXPECT_FALSE(c.sim.sensor_noise);
  EXPECT_EQ(c.sim.sensor_delay_cycles, 0);
  EXPECT_FALSE(c.sim.sensor_errors.imu.attitude_filter);
  EXPECT_EQ(c.sim.sensor_errors.imu.bandwidth_hz, 0.0);
  EXPECT_FALSE(c.sim.sensor_errors.imu.gyro_bias);
  EXPECT_FALSE(c.sim.sensor_errors.ft[0].offset);
  EXPECT_TRUE(c.sim.sensor_errors.encoder_offset_rad.empty());
  EXPECT_EQ(c.sim.faults.size(), 1u);
  EXPECT_EQ(make_run_config(load_scenario(file)).sim.sensor_delay_cycles, 3) << "without ideal the keys apply";
}

TEST(Scenario, ReadsEverySensorErrorOverTheRobotFile) {
  const std::string text = std::string(kPlain) + R"(sensors:
  noise: false
  imu: {misalignment_deg: [0.5, -0.3, 1.0], gyro_bias: [0.001, 0.002, 0.003], gyro_bias_walk: 0.0001,
        accel_bias: [0.1, 0, -0.1], filter_time_s: 2.0}
  ft:
    right: {offset: [6, -4, 15, 0.4, -0.3, 0], scale: [1.02, 1, 0.98, 1, 1, 1.01],
            drift_walk: [0.1, 0.1, 0.1, 0.01, 0.01, 0.01], thermal_drift: [0, 0, 8, 0, 0.5, 0], thermal_time_s: 300}
  encoders: {offset_deg: {left_knee: 0.3, right_hip_pitch: -0.1}}
)";
  const RunConfig c = make_run_config(load_scenario(write_scenario("errors", text)));
  const SensorErrorSpec& e = c.sim.sensor_errors;
  EXPECT_FALSE(c.sim.sensor_noise);
  EXPECT_EQ(c.sim.sensor_delay_cycles, 1) << "the robot file's, not given here";
  EXPECT_TRUE(e.imu.attitude_filter) << "the robot file's, not given here";
  EXPECT_DOUBLE_EQ(e.imu.filter_time_s, 2.0);
  ASSERT_TRUE(e.imu.misalignment_rad);
  EXPECT_NEAR(e.imu.misalignment_rad->z(), M_PI / 180.0, 1e-15);
  EXPECT_DOUBLE_EQ(e.imu.gyro_bias->y(), 0.002);
  EXPECT_DOUBLE_EQ(*e.imu.gyro_bias_walk, 1e-4);
  EXPECT_DOUBLE_EQ(e.imu.accel_bias->x(), 0.1);
  EXPECT_FALSE(e.ft[0].offset) << "left not given";
  EXPECT_DOUBLE_EQ((*e.ft[1].offset)[2], 15.0);
  EXPECT_DOUBLE_EQ((*e.ft[1].scale)[0], 1.02);
  EXPECT_DOUBLE_EQ((*e.ft[1].drift_walk)[5], 0.01);
  EXPECT_DOUBLE_EQ((*e.ft[1].thermal_drift)[2], 8.0);
  EXPECT_DOUBLE_EQ(*e.ft[1].thermal_time_s, 300.0);
  EXPECT_NEAR(e.encoder_offset_rad.at("left_knee"), 0.3 * M_PI / 180.0, 1e-15);
  EXPECT_NEAR(e.encoder_offset_rad.at("right_hip_pitch"), -0.1 * M_PI / 180.0, 1e-15);
}

TEST(Scenario, ReadsSeveralFaultsOfEveryKind) {
  const std::string text = std::string(kPlain) + R"(sensors:
  faults:
    - {t: 1.0, sensor: left_knee, value: freeze, duration: 2}
    - {t: 1.5, sensor: right_knee, jump_deg: 0.5, duration: 10}
    - {t: 1.5, sensor: imu_gyro, value: nan}
    - {t: 2.0, sensor: imu_accel, value: 3.5, duration: 0.1}
    - {t: 2.0, sensor: imu_orientation, value: freeze, duration: 0.1}
    - {t: 0.5, sensor: ft_right, value: .nan}
)";
  const Scenario s = load_scenario(write_scenario("faults", text));
  ASSERT_EQ(s.faults.size(), 6u);
  EXPECT_EQ(s.faults[0].mode, SensorFault::Mode::Freeze);
  EXPECT_EQ(s.faults[1].mode, SensorFault::Mode::Jump);
  EXPECT_NEAR(s.faults[1].value, 0.5 * M_PI / 180.0, 1e-15);
  EXPECT_EQ(s.faults[2].sensor, "imu_gyro");
  EXPECT_EQ(s.faults[3].mode, SensorFault::Mode::Value);
  EXPECT_DOUBLE_EQ(s.faults[3].value, 3.5);
  EXPECT_EQ(s.faults[5].mode, SensorFault::Mode::NaN);
}

// Every sensor key: one line naming the file and the key.
TEST(Scenario, BadSensorInputNamesFileAndKey) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"ideal: maybe", "sensors.ideal"},
      {"noise: 2", "sensors.noise"},
      {"imu: [1, 2]", "sensors.imu"},
      {"imu: {misalignment: [0, 0, 0]}", "sensors.imu.misalignment"},
      {"imu: {misalignment_deg: [0, 0]}", "sensors.imu.misalignment_deg"},
      {"imu: {misalignment_deg: [0, .nan, 0]}", "sensors.imu.misalignment_deg"},
      {"imu: {gyro_bias: 0.01}", "sensors.imu.gyro_bias"},
      {"imu: {gyro_bias_walk: -1}", "sensors.imu.gyro_bias_walk"},
      {"imu: {accel_bias: [0, 0, x]}", "sensors.imu.accel_bias"},
      {"imu: {attitude_filter: 3}", "sensors.imu.attitude_filter"},
      {"imu: {filter_time_s: 0}", "sensors.imu.filter_time_s"},
      {"imu: {bandwidth_hz: -5}", "sensors.imu.bandwidth_hz"},
      {"ft: {middle: {}}", "sensors.ft.middle"},
      {"ft: {left: {offset: [1, 2, 3]}}", "sensors.ft.left.offset"},
      {"ft: {left: {ofset: [1, 2, 3, 4, 5, 6]}}", "sensors.ft.left.ofset"},
      {"ft: {right: {scale: [1, 1, 0, 1, 1, 1]}}", "sensors.ft.right.scale"},
      {"ft: {right: {drift_walk: [0, 0, -1, 0, 0, 0]}}", "sensors.ft.right.drift_walk"},
      {"ft: {right: {thermal_drift: [0, 0, .inf, 0, 0, 0]}}", "sensors.ft.right.thermal_drift"},
      {"ft: {right: {thermal_time_s: -60}}", "sensors.ft.right.thermal_time_s"},
      {"encoders: {offset: {left_knee: 1}}", "sensors.encoders.offset"},
      {"encoders: {offset_deg: [1, 2]}", "sensors.encoders.offset_deg"},
      {"encoders: {offset_deg: {left_knee: big}}", "sensors.encoders.offset_deg.left_knee"},
      {"faults: [{t: 1, sensor: left_knee}]", "sensors.faults.0.value"},
      {"faults: [{t: 1, sensor: left_knee, jump_deg: x}]", "sensors.faults.0.jump_deg"},
      {"faults: [{t: 1, sensor: ft_left, jump_deg: 1}]", "sensors.faults.0.jump_deg"},
      {"faults: [{t: 1, sensor: left_knee, jump_deg: 1, value: 2}]", "sensors.faults.0.jump_deg"},
      {"faults: [{t: 1, sensor: imu, value: nan}, {t: -1, sensor: imu, value: nan}]", "sensors.faults.1.t"},
  };
  for (const auto& [section, key] : cases) {
    const std::string message = error_of(std::string(kPlain) + "sensors: {" + section + "}\n");
    EXPECT_NE(message.find("bad-"), std::string::npos) << section << ": " << message;
    EXPECT_NE(message.find("key '" + key + "'"), std::string::npos) << section << ": " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

// A robot file's `sensors` section is read with the same rules, without `ideal` and `faults`.
TEST(Scenario, RobotFileSensorsSectionIsChecked) {
  const auto dir = std::filesystem::temp_directory_path() / ("biped-robot-sensors-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir / "config" / "robots");
  const std::string robot = (dir / "config" / "robots" / "custom.yaml").string();
  setenv("BIPED_DATA_DIR", dir.c_str(), 1);
  const std::string scenario = write_scenario("custom", "robot: custom\nduration: 1\n");
  auto error_with = [&](const std::string& sensors) {
    std::ofstream(robot) << "model: " << BIPED_SOURCE_DIR << "/models/lola/lola.xml\nsensors: " << sensors << "\n";
    try {
      make_run_config(load_scenario(scenario));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(error_with("{noise: true, imu: {attitude_filter: true}}"), "");
  EXPECT_NE(error_with("{ideal: true}").find(robot + ":2: key 'sensors.ideal': unknown key"), std::string::npos);
  EXPECT_NE(error_with("{faults: []}").find("key 'sensors.faults': unknown key"), std::string::npos);
  EXPECT_NE(error_with("{imu: {gyro_bias: [1]}}").find(robot + ":2: key 'sensors.imu.gyro_bias'"), std::string::npos);
  unsetenv("BIPED_DATA_DIR");
  std::filesystem::remove_all(dir);
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
