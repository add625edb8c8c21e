#include "io/robot_config.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include "io/step_table_file.hpp"
#include "io/yaml_reader.hpp"

namespace fs = std::filesystem;

namespace biped {
namespace {

constexpr double kDeg = M_PI / 180.0;

std::string resolve(const std::string& path, const std::string& relative_to_file) {
  const fs::path p(path);
  if (p.is_absolute()) return p.string();
  return (fs::path(relative_to_file).parent_path() / p).lexically_normal().string();
}

void read_simulation(const YamlReader& r, const YAML::Node& sim, SimulationParams& p) {
  r.expect_keys(sim, "simulation", {"timestep", "control_period", "ground_friction", "contact_timeconst",
                                    "contact_dampratio", "sole_stiffness_per_foot", "sole_damping_per_foot"});
  if (!sim) return;
  p.world.timestep = r.positive_or(sim, "simulation", "timestep", p.world.timestep);
  p.control_period = r.positive_or(sim, "simulation", "control_period", p.control_period);
  p.world.ground_friction = r.positive_or(sim, "simulation", "ground_friction", p.world.ground_friction);
  p.sole_contact.friction = p.world.ground_friction;
  p.sole_contact.stiffness_per_foot =
      r.positive_or(sim, "simulation", "sole_stiffness_per_foot", p.sole_contact.stiffness_per_foot);
  p.sole_contact.damping_per_foot = r.non_negative_or(sim, "simulation", "sole_damping_per_foot", p.sole_contact.damping_per_foot);
  p.sole_contact.tangential_stiffness_per_foot = p.sole_contact.stiffness_per_foot;
  p.sole_contact.tangential_damping_per_foot = p.sole_contact.damping_per_foot;
  p.world.contact_timeconst = r.positive_or(sim, "simulation", "contact_timeconst", p.world.contact_timeconst);
  p.world.contact_dampratio = r.positive_or(sim, "simulation", "contact_dampratio", p.world.contact_dampratio);
  if (p.world.contact_timeconst < 2.0 * p.world.timestep) {
    r.fail(sim["contact_timeconst"] ? sim["contact_timeconst"] : sim, "simulation.contact_timeconst",
           "must be at least twice simulation.timestep for a stable contact");
  }
  const double ratio = p.control_period / p.world.timestep;
  if (std::abs(ratio - std::round(ratio)) > 1e-9 || ratio < 0.5) {
    r.fail(sim["control_period"] ? sim["control_period"] : sim, "simulation.control_period",
           "must be a whole multiple of simulation.timestep");
  }
}

void read_stabilization(const YamlReader& r, const YAML::Node& n, StabilizerParams& p) {
  const std::string where = "controller.stabilization";
  r.expect_keys(n, where, {"tilt_gain", "tilt_rate_gain", "com_gain", "com_rate_gain", "force_gain", "feedforward_gain",
                           "pitch_gain_scale", "position_gain", "contact_stiffness", "heel_stiffness_share", "contact_tolerance",
                           "toe_contact",
                           "cop_margin", "contact_filter_time",
                           "contact_force_low", "contact_force_high", "max_tilt", "max_height",
                           "force_integral_gain", "stiffness_adaptation", "adaptation_time",
                           "adaptation_min_scale", "adaptation_max_scale"});
  if (!n) return;
  p.tilt_gain = r.non_negative_or(n, where, "tilt_gain", p.tilt_gain);
  p.tilt_rate_gain = r.non_negative_or(n, where, "tilt_rate_gain", p.tilt_rate_gain);
  p.com_gain = r.non_negative_or(n, where, "com_gain", p.com_gain);
  p.com_rate_gain = r.non_negative_or(n, where, "com_rate_gain", p.com_rate_gain);
  p.force_gain = r.non_negative_or(n, where, "force_gain", p.force_gain);
  p.feedforward_gain = r.non_negative_or(n, where, "feedforward_gain", p.feedforward_gain);
  p.pitch_gain_scale = r.non_negative_or(n, where, "pitch_gain_scale", p.pitch_gain_scale);
  p.position_gain = r.positive_or(n, where, "position_gain", p.position_gain);
  p.contact_stiffness = r.positive_or(n, where, "contact_stiffness", p.contact_stiffness);
  p.heel_stiffness_share = r.positive_or(n, where, "heel_stiffness_share", p.heel_stiffness_share);
  if (p.heel_stiffness_share >= 1.0) {
    r.fail(n["heel_stiffness_share"], where + ".heel_stiffness_share", "must be below 1 (the toe elements need stiffness)");
  }
  p.contact_tolerance = r.non_negative_or(n, where, "contact_tolerance", p.contact_tolerance);
  p.toe_contact = r.boolean_or(n, where, "toe_contact", p.toe_contact);
  p.cop_margin = r.non_negative_or(n, where, "cop_margin", p.cop_margin);
  p.contact_filter_time = r.positive_or(n, where, "contact_filter_time", p.contact_filter_time);
  p.contact_force_low = r.non_negative_or(n, where, "contact_force_low", p.contact_force_low);
  p.contact_force_high = r.positive_or(n, where, "contact_force_high", p.contact_force_high);
  if (p.contact_force_high <= p.contact_force_low) {
    r.fail(n["contact_force_high"] ? n["contact_force_high"] : n, where + ".contact_force_high",
           "must be above contact_force_low");
  }
  p.max_tilt = r.positive_or(n, where, "max_tilt", p.max_tilt);
  p.max_height = r.positive_or(n, where, "max_height", p.max_height);
  p.force_integral_gain = r.non_negative_or(n, where, "force_integral_gain", p.force_integral_gain);
  p.stiffness_adaptation = r.boolean_or(n, where, "stiffness_adaptation", p.stiffness_adaptation);
  p.adaptation_time = r.positive_or(n, where, "adaptation_time", p.adaptation_time);
  p.adaptation_min_scale = r.positive_or(n, where, "adaptation_min_scale", p.adaptation_min_scale);
  p.adaptation_max_scale = r.positive_or(n, where, "adaptation_max_scale", p.adaptation_max_scale);
  if (p.adaptation_min_scale > 1.0 || p.adaptation_max_scale < 1.0) {
    r.fail(n, where, "adaptation_min_scale must be at most 1 and adaptation_max_scale at least 1");
  }
}

void read_sensor_limits(const YamlReader& r, const YAML::Node& n, SensorLimits& p) {
  const std::string where = "controller.sensor_limits";
  r.expect_keys(n, where, {"max_force", "max_torque", "max_angular_rate", "max_acceleration", "encoder_margin",
                           "frozen_cycles"});
  if (!n) return;
  p.max_force = r.positive_or(n, where, "max_force", p.max_force);
  p.max_torque = r.positive_or(n, where, "max_torque", p.max_torque);
  p.max_angular_rate = r.positive_or(n, where, "max_angular_rate", p.max_angular_rate);
  p.max_acceleration = r.positive_or(n, where, "max_acceleration", p.max_acceleration);
  p.encoder_margin = r.non_negative_or(n, where, "encoder_margin", p.encoder_margin);
  const long frozen = r.integer_or(n, where, "frozen_cycles", p.frozen_cycles);
  if (frozen < 0) r.fail(n["frozen_cycles"], where + ".frozen_cycles", "must be non-negative (0: off)");
  p.frozen_cycles = static_cast<int>(frozen);
}

void read_terrain_adaptation(const YamlReader& r, const YAML::Node& n, TerrainAdaptationParams& p) {
  const std::string where = "controller.terrain_adaptation";
  r.expect_keys(n, where, {"enabled", "contact_force", "filter_time", "search_speed", "search_delay", "max_step", "com_follow_time",
                           "cop_band", "cop_filter_time", "tilt_search_speed", "max_tilt"});
  if (!n) return;
  p.enabled = r.boolean_or(n, where, "enabled", p.enabled);
  p.contact_force = r.positive_or(n, where, "contact_force", p.contact_force);
  p.filter_time = r.positive_or(n, where, "filter_time", p.filter_time);
  p.search_speed = r.positive_or(n, where, "search_speed", p.search_speed);
  p.search_delay = r.non_negative_or(n, where, "search_delay", p.search_delay);
  p.max_step = r.positive_or(n, where, "max_step", p.max_step);
  p.com_follow_time = r.positive_or(n, where, "com_follow_time", p.com_follow_time);
  p.cop_band = r.positive_or(n, where, "cop_band", p.cop_band);
  p.cop_filter_time = r.positive_or(n, where, "cop_filter_time", p.cop_filter_time);
  p.tilt_search_speed = r.positive_or(n, where, "tilt_search_speed", p.tilt_search_speed);
  p.max_tilt = r.positive_or(n, where, "max_tilt", p.max_tilt);
}

void read_controller(const YamlReader& r, const YAML::Node& c, ControllerConfig& p) {
  r.expect_keys(c, "controller", {"type", "model", "stabilizer", "ramp_time", "software_limit_margin_deg", "step_time",
                                  "double_support_ratio", "clearance", "start_shift", "arm_swing_gain", "task_gain",
                                  "null_space_gain", "joint_velocity_limit", "limits", "stance", "lift_height", "shift_time",
                                  "lift_time", "hold_time", "step_table", "stabilization", "sensor_limits", "terrain_adaptation"});
  if (!c) return;
  p.type = r.text_or(c, "controller", "type", p.type);
  if (p.type != "walking" && p.type != "standing" && p.type != "weight_shift") {
    r.fail(c["type"], "controller.type", "unknown controller '" + p.type + "' (known: walking, standing, weight_shift)");
  }
  WeightShiftParams& ws = p.weight_shift;
  const std::string stance = r.text_or(c, "controller", "stance", ws.stance == Side::Left ? "left" : "right");
  if (stance != "left" && stance != "right") r.fail(c["stance"], "controller.stance", "must be left or right");
  ws.stance = stance == "left" ? Side::Left : Side::Right;
  ws.lift_height = r.non_negative_or(c, "controller", "lift_height", ws.lift_height);
  ws.shift_time = r.positive_or(c, "controller", "shift_time", ws.shift_time);
  ws.lift_time = r.positive_or(c, "controller", "lift_time", ws.lift_time);
  ws.hold_time = r.non_negative_or(c, "controller", "hold_time", ws.hold_time);
  WalkingControllerParams& w = p.walking;
  if (c["step_table"]) {
    const std::string table = resolve(r.text(c, "controller", "step_table"), r.file());
    if (!fs::exists(table)) r.fail(c["step_table"], "controller.step_table", "no such file: " + table);
    w.plan.table = read_step_table(table);
    w.plan.limits.vx_max = std::min(w.plan.limits.vx_max, fastest_feasible_speed(w.plan.table));
  }
  w.plan.step.step_time = r.positive_or(c, "controller", "step_time", w.plan.step.step_time);
  w.plan.step.double_support_ratio = r.positive_or(c, "controller", "double_support_ratio", w.plan.step.double_support_ratio);
  if (w.plan.step.double_support_ratio >= 0.8) r.fail(c["double_support_ratio"], "controller.double_support_ratio", "must be below 0.8");
  w.plan.step.clearance = r.non_negative_or(c, "controller", "clearance", w.plan.step.clearance);
  w.plan.start_shift = r.non_negative_or(c, "controller", "start_shift", w.plan.start_shift);
  w.plan.arm_swing_gain = r.non_negative_or(c, "controller", "arm_swing_gain", w.plan.arm_swing_gain);
  w.rmrc.task_gain = r.positive_or(c, "controller", "task_gain", w.rmrc.task_gain);
  if (w.rmrc.task_gain > 1.0) r.fail(c["task_gain"], "controller.task_gain", "must be at most 1 (fraction of the error per cycle)");
  w.rmrc.null_space_gain = r.non_negative_or(c, "controller", "null_space_gain", w.rmrc.null_space_gain);
  w.rmrc.joint_velocity_limit = r.positive_or(c, "controller", "joint_velocity_limit", w.rmrc.joint_velocity_limit);
  const YAML::Node limits = r.mapping(c, "controller", "limits");
  r.expect_keys(limits, "controller.limits", {"vx_min", "vx_max", "vx_rate", "vy_max", "omega_max"});
  if (limits) {
    w.plan.limits.vx_min = r.number_or(limits, "controller.limits", "vx_min", w.plan.limits.vx_min);
    w.plan.limits.vx_max = r.non_negative_or(limits, "controller.limits", "vx_max", w.plan.limits.vx_max);
    w.plan.limits.vx_rate = r.positive_or(limits, "controller.limits", "vx_rate", w.plan.limits.vx_rate);
    w.plan.limits.vy_max = r.non_negative_or(limits, "controller.limits", "vy_max", w.plan.limits.vy_max);
    w.plan.limits.omega_max = r.non_negative_or(limits, "controller.limits", "omega_max", w.plan.limits.omega_max);
  }
  if (c["model"]) {
    p.model_path = resolve(r.text(c, "controller", "model"), r.file());
    if (!fs::exists(p.model_path)) r.fail(c["model"], "controller.model", "no such file: " + p.model_path);
  }
  p.stabilizer = r.boolean_or(c, "controller", "stabilizer", p.stabilizer);
  p.walking.stabilizer = p.stabilizer;
  read_stabilization(r, r.mapping(c, "controller", "stabilization"), w.stabilization);
  read_sensor_limits(r, r.mapping(c, "controller", "sensor_limits"), w.sensor_limits);
  read_terrain_adaptation(r, r.mapping(c, "controller", "terrain_adaptation"), w.terrain);
  p.standing.ramp_time = r.non_negative_or(c, "controller", "ramp_time", p.standing.ramp_time);
  p.software_limit_margin_rad =
      r.non_negative_or(c, "controller", "software_limit_margin_deg", p.software_limit_margin_rad / kDeg) * kDeg;
}

void read_robot_file(const std::string& file, RunConfig& config) {
  const YAML::Node root = load_yaml_file(file);
  const YamlReader r(file);
  r.expect_keys(root, "", {"model", "simulation", "drives", "encoders", "sensor_noise", "controller"});
  config.sim.world.robot_mjcf = resolve(r.text(root, "", "model"), file);
  if (!fs::exists(config.sim.world.robot_mjcf)) {
    r.fail(root["model"], "model", "no such file: " + config.sim.world.robot_mjcf);
  }
  read_simulation(r, r.mapping(root, "", "simulation"), config.sim);

  const YAML::Node drives = r.mapping(root, "", "drives");
  r.expect_keys(drives, "drives", {"bandwidth_hz", "velocity_loop_ratio", "integral_ratio"});
  if (drives) {
    DriveParams& dp = config.sim.drives;
    dp.bandwidth_hz = r.positive_or(drives, "drives", "bandwidth_hz", dp.bandwidth_hz);
    dp.velocity_loop_ratio = r.positive_or(drives, "drives", "velocity_loop_ratio", dp.velocity_loop_ratio);
    dp.integral_ratio = r.non_negative_or(drives, "drives", "integral_ratio", dp.integral_ratio);
  }

  const YAML::Node encoders = r.mapping(root, "", "encoders");
  r.expect_keys(encoders, "encoders", {"bits", "bits_of"});
  if (encoders) {
    config.sim.encoder_bits = static_cast<int>(r.integer_or(encoders, "encoders", "bits", config.sim.encoder_bits));
    const YAML::Node per_joint = r.mapping(encoders, "encoders", "bits_of");
    if (per_joint) {
      for (const auto& entry : per_joint) {
        const std::string joint = entry.first.Scalar();
        config.sim.encoder_bits_of[joint] = static_cast<int>(r.integer_or(per_joint, "encoders.bits_of", joint.c_str(), 16));
      }
    }
  }

  const YAML::Node noise = r.mapping(root, "", "sensor_noise");
  r.expect_keys(noise, "sensor_noise",
                {"imu_orientation_noise_deg", "imu_orientation_bias_deg", "gyro_noise_rad_s", "gyro_bias_rad_s",
                 "accel_noise_m_s2", "accel_bias_m_s2", "ft_force_noise_n", "ft_force_bias_n", "ft_torque_noise_nm",
                 "ft_torque_bias_nm"});
  if (noise) {
    SensorNoiseParams& n = config.sim.noise_levels;
    const char* w = "sensor_noise";
    n.imu_orientation_noise_rad = r.non_negative_or(noise, w, "imu_orientation_noise_deg", n.imu_orientation_noise_rad / kDeg) * kDeg;
    n.imu_orientation_bias_rad = r.non_negative_or(noise, w, "imu_orientation_bias_deg", n.imu_orientation_bias_rad / kDeg) * kDeg;
    n.gyro_noise_rad_s = r.non_negative_or(noise, w, "gyro_noise_rad_s", n.gyro_noise_rad_s);
    n.gyro_bias_rad_s = r.non_negative_or(noise, w, "gyro_bias_rad_s", n.gyro_bias_rad_s);
    n.accel_noise_m_s2 = r.non_negative_or(noise, w, "accel_noise_m_s2", n.accel_noise_m_s2);
    n.accel_bias_m_s2 = r.non_negative_or(noise, w, "accel_bias_m_s2", n.accel_bias_m_s2);
    n.ft_force_noise_n = r.non_negative_or(noise, w, "ft_force_noise_n", n.ft_force_noise_n);
    n.ft_force_bias_n = r.non_negative_or(noise, w, "ft_force_bias_n", n.ft_force_bias_n);
    n.ft_torque_noise_nm = r.non_negative_or(noise, w, "ft_torque_noise_nm", n.ft_torque_noise_nm);
    n.ft_torque_bias_nm = r.non_negative_or(noise, w, "ft_torque_bias_nm", n.ft_torque_bias_nm);
  }
  read_controller(r, r.mapping(root, "", "controller"), config.controller);
}

}  // namespace

std::string data_directory() {
  if (const char* env = std::getenv("BIPED_DATA_DIR"); env && *env) return env;
  return BIPED_SOURCE_DIR;
}

std::vector<std::string> known_robots() {
  std::vector<std::string> names;
  const fs::path dir = fs::path(data_directory()) / "config" / "robots";
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    if (entry.path().extension() == ".yaml") names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

RunConfig make_run_config(const Scenario& s) {
  RunConfig config;
  const YamlReader r(s.file);
  const bool is_mjcf = s.robot.size() > 4 && s.robot.substr(s.robot.size() - 4) == ".xml";
  if (is_mjcf) {
    config.sim.world.robot_mjcf = resolve(s.robot, s.file);
    if (!fs::exists(config.sim.world.robot_mjcf)) {
      throw InputError(s.file + ": key 'robot': no such model file: " + config.sim.world.robot_mjcf);
    }
    config.robot = fs::path(s.robot).stem().string();
  } else {
    const fs::path file = fs::path(data_directory()) / "config" / "robots" / (s.robot + ".yaml");
    if (s.robot.find('/') != std::string::npos || !fs::exists(file)) {
      std::string list;
      for (const auto& name : known_robots()) list += (list.empty() ? "" : ", ") + name;
      throw InputError(s.file + ": key 'robot': unknown robot '" + s.robot + "' (known: " + list +
                       ", or a path to an MJCF .xml file)");
    }
    config.robot = s.robot;
    config.robot_file = file.string();
    read_robot_file(config.robot_file, config);
  }
  read_simulation(r, s.simulation, config.sim);
  read_controller(r, s.controller, config.controller);
  if (config.controller.model_path.empty()) config.controller.model_path = config.sim.world.robot_mjcf;

  config.sim.world.terrain = s.terrain;
  config.sim.world.model_error = s.model_error;
  config.sim.pushes = s.pushes;
  config.sim.sensor_noise = s.sensor_noise;
  config.sim.sensor_delay_cycles = s.sensor_delay_cycles;
  config.sim.faults = s.faults;
  config.sim.seed = s.seed;
  config.sim.software_limit_margin_rad = config.controller.software_limit_margin_rad;
  config.controller.walking.rmrc.dt = config.sim.control_period;
  config.controller.weight_shift.rmrc = config.controller.walking.rmrc;
  return config;
}

}  // namespace biped
