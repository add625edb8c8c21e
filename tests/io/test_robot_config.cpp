#include "io/robot_config.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "io/yaml_reader.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

TEST(RobotConfig, BothRobotsHaveParameterFiles) {
  const auto robots = known_robots();
  EXPECT_NE(std::find(robots.begin(), robots.end(), "lola"), robots.end());
  EXPECT_NE(std::find(robots.begin(), robots.end(), "johnnie"), robots.end());
  for (const auto& name : robots) {
    const RunConfig c = make_run_config(test::robot_scenario(name));
    EXPECT_TRUE(std::filesystem::exists(c.sim.world.robot_mjcf));
    EXPECT_EQ(c.controller.model_path, c.sim.world.robot_mjcf);
    EXPECT_GE(c.sim.drives.bandwidth_hz, 15.0);
    EXPECT_LE(c.sim.drives.bandwidth_hz, 25.0);
  }
}

TEST(RobotConfig, UnknownRobotListsTheKnownOnes) {
  try {
    make_run_config(test::robot_scenario("asimo"));
    FAIL();
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("test.yaml: key 'robot': unknown robot 'asimo'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("lola"), std::string::npos);
  }
}

TEST(RobotConfig, ScenarioOverridesControllerAndSimulationKeys) {
  Scenario s = test::robot_scenario("lola");
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
  Scenario s = test::robot_scenario("lola");
  s.controller = YAML::Load("{stabilization: {force_integral_gain: 80, stiffness_adaptation: true}, "
                            "sensor_limits: {frozen_cycles: 0}}");
  const RunConfig c = make_run_config(s);
  const StabilizerParams& p = c.controller.walking.stabilization;
  EXPECT_DOUBLE_EQ(p.force_integral_gain, 80.0);
  EXPECT_TRUE(p.stiffness_adaptation);
  EXPECT_DOUBLE_EQ(p.tilt_gain, make_run_config(test::robot_scenario("lola")).controller.walking.stabilization.tilt_gain);
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

TEST(RobotConfig, ScenarioValuesReachEveryControllerSection) {
  Scenario s = test::robot_scenario("lola");
  s.controller = YAML::Load("{software_limit_margin_deg: 2, step_time: 0.9, task_gain: 0.5, ramp_time: 2, "
                            "limits: {vx_rate: 0.3}, sensor_limits: {frozen_cycles: 7, max_force: 900}, "
                            "terrain_adaptation: {enabled: false, cop_band: 0.05}}");
  const RunConfig c = make_run_config(s);
  const WalkingControllerParams& w = c.controller.walking;
  EXPECT_EQ(c.controller.software_limit_margin_rad, 2.0 * (M_PI / 180.0));
  EXPECT_EQ(c.sim.software_limit_margin_rad, c.controller.software_limit_margin_rad);
  EXPECT_EQ(w.plan.step.step_time, 0.9);
  EXPECT_EQ(w.rmrc.task_gain, 0.5);
  EXPECT_EQ(c.controller.weight_shift.rmrc.task_gain, 0.5);
  EXPECT_EQ(c.controller.standing.ramp_time, 2.0);
  EXPECT_EQ(w.plan.limits.vx_rate, 0.3);
  EXPECT_EQ(w.sensor_limits.frozen_cycles, 7);
  EXPECT_EQ(w.sensor_limits.max_force, 900.0);
  EXPECT_FALSE(w.terrain.enabled);
  EXPECT_EQ(w.terrain.cop_band, 0.05);
}

std::string config_error(const char* section, const char* yaml) {
  Scenario s = test::robot_scenario("lola");
  (std::string(section) == "controller" ? s.controller : s.simulation) = YAML::Load(yaml);
  try {
    make_run_config(s);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(RobotConfig, SingleAndCrossKeyChecksKeepTheirMessages) {
  EXPECT_EQ(config_error("controller", "{double_support_ratio: 0.9}"),
            "test.yaml:1: key 'controller.double_support_ratio': must be below 0.8");
  EXPECT_EQ(config_error("controller", "{task_gain: 1.5}"),
            "test.yaml:1: key 'controller.task_gain': must be at most 1 (fraction of the error per cycle)");
  EXPECT_EQ(config_error("controller", "{stabilization: {heel_stiffness_share: 1}}"),
            "test.yaml:1: key 'controller.stabilization.heel_stiffness_share': must be below 1 (the toe elements need "
            "stiffness)");
  EXPECT_EQ(config_error("controller", "{stabilization: {adaptation_min_scale: 2}}"),
            "test.yaml:1: key 'controller.stabilization': adaptation_min_scale must be at most 1 and "
            "adaptation_max_scale at least 1");
  EXPECT_EQ(config_error("controller", "{stabilization: {contact_force_high: 20}}"),
            "test.yaml:1: key 'controller.stabilization.contact_force_high': must be above contact_force_low");
  EXPECT_EQ(config_error("simulation", "{contact_timeconst: 0.001}"),
            "test.yaml:1: key 'simulation.contact_timeconst': must be at least twice simulation.timestep for a stable "
            "contact");
  EXPECT_EQ(config_error("simulation", "{control_period: 0.0015}"),
            "test.yaml:1: key 'simulation.control_period': must be a whole multiple of simulation.timestep");
  EXPECT_EQ(config_error("controller", "{limits: {vx_max: -1}}"),
            "test.yaml:1: key 'controller.limits.vx_max': must not be negative (got -1)");
  EXPECT_EQ(config_error("controller", "{limits: {vx_min: 0.2}}"),
            "test.yaml:1: key 'controller.limits.vx_min': must be at most 0 (a zero command must stay standing, not be "
            "saturated to walking)");
  EXPECT_EQ(config_error("controller", "{limits: {lateral_vx_share: 1.5}}"),
            "test.yaml:1: key 'controller.limits.lateral_vx_share': must be at most 1 (a share)");
  EXPECT_EQ(config_error("controller", "{limits: {min_zmp_margin: -0.01}}"),
            "test.yaml:1: key 'controller.limits.min_zmp_margin': must not be negative (got -0.01)");
  EXPECT_EQ(config_error("controller", "{upper_body_lean: {max_angle: -0.1}}"),
            "test.yaml:1: key 'controller.upper_body_lean.max_angle': must not be negative (got -0.1)");
  EXPECT_EQ(config_error("controller", "{upper_body_lean: {return_frequency: 0}}"),
            "test.yaml:1: key 'controller.upper_body_lean.return_frequency': must be positive (got 0)");
  EXPECT_NE(config_error("controller", "{upper_body_lean: {enabled: maybe}}").find("controller.upper_body_lean.enabled"),
            std::string::npos);
  EXPECT_EQ(config_error("controller", "{sensor_limits: {frozen_cycles: 2.5}}"),
            "test.yaml:1: key 'controller.sensor_limits.frozen_cycles': expected an integer");
  EXPECT_NE(config_error("controller", "{limits: {vz_max: 1}}").find("test.yaml:1: key 'controller.limits.vz_max': unknown key"),
            std::string::npos);
}

// Every key of the reference is read from a scenario, and its default passes its check.
TEST(RobotConfig, EveryReferenceKeyOfTheScenarioSectionsIsReadWithItsDefault) {
  YAML::Node root;
  int overridden = 0;
  for (const ParameterDoc& row : parameter_reference()) {
    if (row.key.rfind("controller.", 0) != 0 && row.key.rfind("simulation.", 0) != 0) continue;
    apply_override(root, row.key + "=" + row.default_value);
    ++overridden;
  }
  EXPECT_GT(overridden, 50);
  Scenario s = test::robot_scenario(test::model_path("johnnie"));
  s.controller = root["controller"];
  s.simulation = root["simulation"];
  const RunConfig c = make_run_config(s);
  EXPECT_EQ(c.controller.walking.stabilization.tilt_gain, StabilizerParams{}.tilt_gain);
  EXPECT_EQ(c.sim.world.timestep, WorldSpec{}.timestep);
}

// Keys only robot files hold (drives, encoders, sensor_noise): a robot file of its own, in a data
// directory of its own.
class CustomRobotFile : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto dir = test::fresh_dir("robot-config");
    std::filesystem::create_directories(dir / "config" / "robots");
    file_ = (dir / "config" / "robots" / "custom.yaml").string();
    setenv("BIPED_DATA_DIR", dir.c_str(), 1);
  }
  void TearDown() override { unsetenv("BIPED_DATA_DIR"); }

  RunConfig read(const std::string& body) {
    std::ofstream(file_) << "model: " << test::model_path("lola") << "\n" << body;
    return make_run_config(test::robot_scenario("custom"));
  }
  std::string error_of(const std::string& body) {
    try {
      read(body);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
  std::string file_;
};

TEST_F(CustomRobotFile, ValuesApplyAndDegreesConvert) {
  const RunConfig c = read("drives: {bandwidth_hz: 18}\nencoders: {bits: 16, bits_of: {left_toe: 14}}\n"
                           "sensor_noise: {imu_misalignment_deg: 0.5, gyro_noise_rad_s: 0.01}\n");
  EXPECT_EQ(c.sim.drives.bandwidth_hz, 18.0);
  EXPECT_EQ(c.sim.drives.integral_ratio, DriveParams{}.integral_ratio);
  EXPECT_EQ(c.sim.encoder_bits, 16);
  EXPECT_EQ(c.sim.encoder_bits_of.at("left_toe"), 14);
  EXPECT_EQ(c.sim.noise_levels.imu_misalignment_rad, 0.5 * (M_PI / 180.0));
  EXPECT_EQ(c.sim.noise_levels.accel_bias_m_s2, SensorNoiseParams{}.accel_bias_m_s2);
  EXPECT_EQ(c.sim.noise_levels.gyro_noise_rad_s, 0.01);
}

TEST_F(CustomRobotFile, ErrorsNameFileKeyAndLine) {
  EXPECT_EQ(error_of("drives:\n  bandwidth_hz: fast\n"), file_ + ":3: key 'drives.bandwidth_hz': expected a number");
  EXPECT_EQ(error_of("sensor_noise:\n  gyro_bias_rad_s: -1\n"),
            file_ + ":3: key 'sensor_noise.gyro_bias_rad_s': must not be negative (got -1)");
  EXPECT_EQ(error_of("sensor_noise:\n  imu_misalignment_deg: .nan\n"),
            file_ + ":3: key 'sensor_noise.imu_misalignment_deg': must be a finite number (got '.nan')");
  EXPECT_EQ(error_of("encoders:\n  bits_of: {left_toe: 0}\n"),
            file_ + ":3: key 'encoders.bits_of.left_toe': must be positive (got 0)");
  EXPECT_EQ(error_of("encoders:\n  bit: 16\n").find(file_ + ":3: key 'encoders.bit': unknown key"), 0u);
}

// A robot file anywhere (a robot being brought in), by its path.
TEST(RobotConfig, RobotFileByPath) {
  const RunConfig c = make_run_config(test::robot_scenario(test::source_path("config/robots/jvrc1.yaml")));
  EXPECT_EQ(c.robot, "jvrc1");
  EXPECT_EQ(c.robot_file, test::source_path("config/robots/jvrc1.yaml"));
  EXPECT_EQ(c.sim.world.model_map.root_body, "PELVIS_S");
  try {
    make_run_config(test::robot_scenario("/nonexistent/robot.yaml"));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "test.yaml: key 'robot': no such robot file: /nonexistent/robot.yaml");
  }
}

// `include:` files override the robot file's own values, in order; their paths are relative to the
// robot file; a missing file or an unknown key is one line naming the file and the key.
TEST_F(CustomRobotFile, IncludesOverrideTheRobotFileInOrder) {
  const std::filesystem::path dir = std::filesystem::path(file_).parent_path();
  std::filesystem::create_directories(dir / "gains");
  std::ofstream(dir / "gains" / "a.yaml") << "controller:\n  stabilization: {tilt_gain: 700, com_gain: 200}\n"
                                           << "drives: {bandwidth_hz: 22}\nsimulation: {ground_friction: 0.6}\n";
  std::ofstream(dir / "gains" / "b.yaml") << "controller:\n  stabilization: {com_gain: 250}\n";
  const std::string own = "controller:\n  stabilization: {tilt_gain: 500, com_gain: 100, tilt_rate_gain: 40}\n";
  RunConfig c = read("include: gains/a.yaml\n" + own);
  const StabilizerParams& s = c.controller.walking.stabilization;
  EXPECT_EQ(s.tilt_gain, 700.0);
  EXPECT_EQ(s.com_gain, 200.0);
  EXPECT_EQ(s.tilt_rate_gain, 40.0);
  EXPECT_EQ(c.sim.drives.bandwidth_hz, 22.0);
  EXPECT_EQ(c.sim.world.ground_friction, 0.6);
  c = read("include: [gains/a.yaml, gains/b.yaml]\n" + own);
  EXPECT_EQ(c.controller.walking.stabilization.tilt_gain, 700.0);
  EXPECT_EQ(c.controller.walking.stabilization.com_gain, 250.0);

  const std::string missing = (dir / "gains" / "c.yaml").string();
  EXPECT_EQ(error_of("include: [gains/a.yaml, gains/c.yaml]\n"), file_ + ":2: key 'include.1': no such file: " + missing);
  std::ofstream(missing) << "controller:\n  stabilization: {tilt_gian: 700}\n";
  EXPECT_EQ(error_of("include: gains/c.yaml\n").find(missing + ":2: key 'controller.stabilization.tilt_gian': unknown key"), 0u);
  std::ofstream(missing) << "sensors: {noise: false}\n";
  EXPECT_EQ(error_of("include: gains/c.yaml\n").find(missing + ":1: key 'sensors': unknown key"), 0u);
  EXPECT_EQ(error_of("include: {a: 1}\n"), file_ + ":2: key 'include': expected a path or a list of paths");
}

TEST(RobotConfig, BareMjcfPathUsesDefaults) {
  const RunConfig c = make_run_config(test::robot_scenario(test::model_path("johnnie")));
  EXPECT_EQ(c.robot, "johnnie");
  EXPECT_TRUE(c.robot_file.empty());
  EXPECT_THROW(make_run_config(test::robot_scenario("/nonexistent/robot.xml")), InputError);
}

TEST(RobotConfig, ModelMapOfJvrc1ReachesTheSimulationAndIsChecked) {
  const RunConfig config = make_run_config(test::robot_scenario("jvrc1"));
  const ModelMap& map = config.sim.world.model_map;
  EXPECT_EQ(map.root_body, "PELVIS_S");
  EXPECT_EQ(map.imu_orientation, "");  // `none`
  EXPECT_EQ(map.legs[index_of(Side::Left)].toe_joint, "");
  ASSERT_TRUE(map.legs[index_of(Side::Right)].sole.has_value());
  EXPECT_LT(map.legs[index_of(Side::Right)].sole->z, 0.0);
  EXPECT_NEAR(map.stand_pose.at("L_KNEE"), 44.0 * M_PI / 180.0, 1e-12);
  EXPECT_EQ(map.passive_joints.size(), 10u);
  EXPECT_GT(map.torque_limits.at("R_HIP_P"), 0.0);
  EXPECT_EQ(make_run_config(test::robot_scenario("lola")).sim.world.model_map.root_body, "pelvis");  // the contract
}

TEST_F(CustomRobotFile, ModelMapErrorsNameFileAndKey) {
  const auto expect_error = [&](const std::string& model_map, const std::string& key) {
    const std::string error = error_of("model_map:\n" + model_map);
    EXPECT_EQ(error.find(file_ + ":"), 0u) << error;
    EXPECT_NE(error.find("key '" + key + "'"), std::string::npos) << error;
  };
  expect_error("  bodies: {}\n", "model_map.bodies");
  expect_error("  legs: {left: {sole: {x: [-0.1, 0.2], y: [-0.05, 0.05], z: 0.01}}}\n", "model_map.legs.left.sole.z");
  expect_error("  legs: {right: {sole: {x: [0.1, 0.2], y: [-0.05, 0.05], z: -0.1}}}\n", "model_map.legs.right.sole");
  expect_error("  legs: {left: {sole: {x: [0.2, -0.1], y: [-0.05, 0.05], z: -0.1}}}\n", "model_map.legs.left.sole.x");
  expect_error("  torque_limits: {left_knee: -3}\n", "model_map.torque_limits.left_knee");
  expect_error("  passive_joints: {a: 1}\n", "model_map.passive_joints");
}

}  // namespace
}  // namespace biped
