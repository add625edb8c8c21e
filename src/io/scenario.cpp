#include "io/scenario.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "io/parameter_table.hpp"
#include "io/yaml_reader.hpp"

namespace biped {
namespace {

std::string item(const char* list, std::size_t i) { return std::string(list) + "." + std::to_string(i); }

void read_commands(const YamlReader& r, const YAML::Node& root, Scenario& s) {
  const YAML::Node list = r.sequence(root, "", "commands");
  WalkCommand current;
  double last_t = -1.0;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string where = item("commands", i);
    const YAML::Node c = list[i];
    r.expect_keys(c, where, {"t", "vx", "vy", "omega", "stop"});
    TimedCommand timed;
    timed.t = r.non_negative_or(c, where, "t", 0.0);
    if (!c["t"]) r.fail(c, where + ".t", "missing (required)");
    if (timed.t < last_t) r.fail(c["t"], where + ".t", "commands must be in time order");
    last_t = timed.t;
    // Fields not given keep their previous value: the joystick holds its position.
    current.vx = r.number_or(c, where, "vx", current.vx);
    current.vy = r.number_or(c, where, "vy", current.vy);
    current.omega = r.number_or(c, where, "omega", current.omega);
    current.stop = r.boolean_or(c, where, "stop", false);
    timed.command = current;
    s.commands.push_back(timed);
  }
}

// When: `t` (seconds) or `at` (a gait moment); how hard: `force` (world frame, N) or `direction_deg`
// (heading frame: 0 forward, 90 left) with `impulse_Ns` or `force_N`; where: `body` and `point`.
Push read_push(const YamlReader& r, const YAML::Node& d, const std::string& where) {
  Push push;
  push.duration = r.positive_or(d, where, "duration", 0.1);
  if (d["t"] && d["at"]) r.fail(d["at"], where + ".at", "give either t or at, not both");
  if (d["at"]) {
    const YAML::Node at = r.mapping(d, where, "at");
    const std::string w = where + ".at";
    r.expect_keys(at, w, {"touchdown", "after", "phase"});
    if (at["touchdown"].IsDefined() == at["after"].IsDefined()) {
      r.fail(at, w, "needs exactly one of touchdown (a count) and after (a time)");
    }
    push.at_gait_moment = true;
    if (at["touchdown"]) {
      const long n = r.integer_or(at, w, "touchdown", 1);
      if (n < 1) r.fail(at["touchdown"], w + ".touchdown", "must be at least 1");
      push.moment.touchdown = static_cast<int>(n);
    } else {
      push.moment.after_time = r.non_negative_or(at, w, "after", 0.0);
    }
    push.moment.phase = r.non_negative_or(at, w, "phase", 0.5);
    if (push.moment.phase > 1.0) r.fail(at["phase"], w + ".phase", "must be between 0 and 1 (share of the single support)");
  } else {
    if (!d["t"]) r.fail(d, where + ".t", "missing (required, or a gait moment `at`)");
    push.t = r.non_negative_or(d, where, "t", 0.0);
  }
  push.body = r.text_or(d, where, "body", "upper_body");
  if (d["point"]) {
    push.at_point = true;
    push.point = r.vector3(d, where, "point");
  }
  if (d["force"].IsDefined() == d["direction_deg"].IsDefined()) {
    r.fail(d, where + ".force", "give either force [Fx, Fy, Fz] (world frame) or direction_deg with impulse_Ns or force_N");
  }
  if (d["force"]) {
    if (d["impulse_Ns"] || d["force_N"]) {
      r.fail(d["impulse_Ns"] ? d["impulse_Ns"] : d["force_N"], where + (d["impulse_Ns"] ? ".impulse_Ns" : ".force_N"),
             "goes with direction_deg, not with force");
    }
    push.force = r.vector3(d, where, "force");
    return push;
  }
  if (d["impulse_Ns"].IsDefined() == d["force_N"].IsDefined()) {
    r.fail(d["direction_deg"], where + ".impulse_Ns", "direction_deg needs exactly one of impulse_Ns and force_N");
  }
  const double direction = r.number(d, where, "direction_deg") * M_PI / 180.0;
  const double magnitude = d["impulse_Ns"] ? r.non_negative_or(d, where, "impulse_Ns", 0.0) / push.duration
                                           : r.non_negative_or(d, where, "force_N", 0.0);
  push.heading_frame = true;
  push.force = magnitude * Eigen::Vector3d(std::cos(direction), std::sin(direction), 0.0);
  return push;
}

void read_disturbances(const YamlReader& r, const YAML::Node& root, Scenario& s) {
  const YAML::Node list = r.sequence(root, "", "disturbances");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string where = item("disturbances", i);
    const YAML::Node d = list[i];
    r.expect_keys(d, where, {"type", "t", "at", "body", "point", "force", "direction_deg", "impulse_Ns", "force_N",
                             "duration"});
    const std::string type = r.text(d, where, "type");
    if (type != "push") r.fail(d["type"], where + ".type", "unknown disturbance '" + type + "' (known: push)");
    s.pushes.push_back(read_push(r, d, where));
  }
}

void read_terrain(const YamlReader& r, const YAML::Node& root, Scenario& s) {
  const YAML::Node list = r.sequence(root, "", "terrain");
  std::vector<YAML::Node> nodes;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string where = item("terrain", i);
    const YAML::Node t = list[i];
    nodes.push_back(t);
    const std::string type = r.text(t, where, "type");
    TerrainFeature f;
    // Where the feature is: x (and y, 0 when absent); which way it rises or runs: heading_deg.
    auto place = [&] {
      f.at = Eigen::Vector2d(r.number(t, where, "x"), r.number_or(t, where, "y", 0.0));
      f.heading_deg = r.number_or(t, where, "heading_deg", 0.0);
    };
    auto rectangle = [&] {
      for (const char* key : {"length", "width"}) {
        if (!t[key]) r.fail(t, where + "." + key, "missing (required)");
      }
      f.length = r.positive_or(t, where, "length", 0.0);
      f.width = r.positive_or(t, where, "width", 0.0);
    };
    if (type == "step") {
      r.expect_keys(t, where, {"type", "x", "y", "heading_deg", "height"});
      f.kind = TerrainFeature::Kind::Step;
      place();
      f.height = r.number(t, where, "height");
      if (std::abs(f.height) > 0.3) r.fail(t["height"], where + ".height", "steps higher than 0.3 m are not supported");
    } else if (type == "slope") {
      r.expect_keys(t, where, {"type", "x", "y", "heading_deg", "angle_deg", "length"});
      f.kind = TerrainFeature::Kind::Slope;
      place();
      f.angle_deg = r.number(t, where, "angle_deg");
      if (std::abs(f.angle_deg) > 30.0) r.fail(t["angle_deg"], where + ".angle_deg", "must be within ±30");
      f.length = r.positive_or(t, where, "length", 2.0);
    } else if (type == "box") {
      r.expect_keys(t, where, {"type", "x", "y", "heading_deg", "length", "width", "height"});
      f.kind = TerrainFeature::Kind::Box;
      place();
      rectangle();
      f.height = r.number(t, where, "height");
      if (std::abs(f.height) > 0.3) r.fail(t["height"], where + ".height", "boxes higher than 0.3 m are not supported");
    } else if (type == "friction") {
      r.expect_keys(t, where, {"type", "x", "y", "heading_deg", "length", "width", "mu"});
      f.kind = TerrainFeature::Kind::Friction;
      place();
      rectangle();
      if (!t["mu"]) r.fail(t, where + ".mu", "missing (required)");
      f.friction = r.positive_or(t, where, "mu", 0.0);
    } else {
      r.fail(t["type"], where + ".type", "unknown terrain '" + type + "' (known: step, slope, box, friction)");
    }
    s.terrain.push_back(f);
  }
  for (const Terrain::Overlap& o : Terrain::overlaps(s.terrain)) {
    r.fail(nodes[o.second], item("terrain", o.second),
           "friction patch overlaps the one of " + item("terrain", o.first) + " (friction patches may not overlap)");
  }
}

void read_faults(const YamlReader& r, const YAML::Node& sensors, Scenario& s) {
  const YAML::Node faults = r.sequence(sensors, "sensors", "faults");
  for (std::size_t i = 0; i < faults.size(); ++i) {
    const std::string where = "sensors.faults." + std::to_string(i);
    const YAML::Node f = faults[i];
    r.expect_keys(f, where, {"t", "sensor", "value", "jump_deg", "duration"});
    SensorFault fault;
    fault.t = r.non_negative_or(f, where, "t", 0.0);
    if (!f["t"]) r.fail(f, where + ".t", "missing (required)");
    fault.sensor = r.text(f, where, "sensor");
    fault.duration = r.non_negative_or(f, where, "duration", 0.0);
    if (f["jump_deg"]) {
      if (f["value"]) r.fail(f["jump_deg"], where + ".jump_deg", "give either value or jump_deg, not both");
      const bool joint = std::find(kNonJointSensors.begin(), kNonJointSensors.end(), fault.sensor) == kNonJointSensors.end();
      if (!joint) r.fail(f["jump_deg"], where + ".jump_deg", "only a joint's encoder jumps (sensor is '" + fault.sensor + "')");
      fault.mode = SensorFault::Mode::Jump;
      fault.value = r.number(f, where, "jump_deg") * kRadiansPerDegree;
      s.faults.push_back(fault);
      continue;
    }
    if (!f["value"]) r.fail(f, where + ".value", "missing (required: nan, freeze or a number; or jump_deg)");
    const std::string value = r.text(f, where, "value");
    if (value == "nan" || value == ".nan" || value == "NaN") {
      fault.mode = SensorFault::Mode::NaN;
    } else if (value == "freeze") {
      fault.mode = SensorFault::Mode::Freeze;
    } else {
      fault.mode = SensorFault::Mode::Value;
      fault.value = r.number(f, where, "value");
    }
    s.faults.push_back(fault);
  }
}

Vector6d six(const YamlReader& r, const YAML::Node& map, const std::string& where, const char* key,
             Check::Lower lower) {
  const Vector6d v = r.numbers(map, where, key, 6);
  const bool bad = lower == Check::Lower::Positive ? (v.array() <= 0.0).any() : (v.array() < 0.0).any();
  if (lower != Check::Lower::None && bad) {
    r.fail(map[key], where + "." + key,
           lower == Check::Lower::Positive ? "every value must be positive" : "no value may be negative");
  }
  return v;
}

void read_imu(const YamlReader& r, const YAML::Node& imu, ImuSpec& into) {
  const std::string where = "sensors.imu";
  r.expect_keys(imu, where,
                {"attitude_filter", "filter_time_s", "bandwidth_hz", "misalignment_deg", "gyro_bias",
                 "gyro_bias_walk", "accel_bias"});
  into.attitude_filter = r.boolean_or(imu, where, "attitude_filter", into.attitude_filter);
  into.filter_time_s = r.positive_or(imu, where, "filter_time_s", into.filter_time_s);
  into.bandwidth_hz = r.non_negative_or(imu, where, "bandwidth_hz", into.bandwidth_hz);
  if (imu["misalignment_deg"]) into.misalignment_rad = r.vector3(imu, where, "misalignment_deg") * kRadiansPerDegree;
  if (imu["gyro_bias"]) into.gyro_bias = r.vector3(imu, where, "gyro_bias");
  if (imu["gyro_bias_walk"]) into.gyro_bias_walk = r.non_negative_or(imu, where, "gyro_bias_walk", 0.0);
  if (imu["accel_bias"]) into.accel_bias = r.vector3(imu, where, "accel_bias");
}

void read_force_torque(const YamlReader& r, const YAML::Node& ft, std::array<ForceTorqueSpec, 2>& into) {
  r.expect_keys(ft, "sensors.ft", {"left", "right"});
  for (Side side : kSides) {
    const std::string where = std::string("sensors.ft.") + name_of(side);
    const YAML::Node f = r.mapping(ft, "sensors.ft", name_of(side));
    r.expect_keys(f, where, {"offset", "scale", "drift_walk", "thermal_drift", "thermal_time_s"});
    ForceTorqueSpec& spec = into[index_of(side)];
    if (f["offset"]) spec.offset = six(r, f, where, "offset", Check::Lower::None);
    if (f["scale"]) spec.scale = six(r, f, where, "scale", Check::Lower::Positive);
    if (f["drift_walk"]) spec.drift_walk = six(r, f, where, "drift_walk", Check::Lower::NonNegative);
    if (f["thermal_drift"]) spec.thermal_drift = six(r, f, where, "thermal_drift", Check::Lower::None);
    if (f["thermal_time_s"]) spec.thermal_time_s = r.positive_or(f, where, "thermal_time_s", 1.0);
  }
}

void read_sensors(const YamlReader& r, const YAML::Node& root, Scenario& s) {
  s.sensors = r.mapping(root, "", "sensors");
  SimulationParams checked;  // every key checked here; make_run_config applies them over the robot file's
  read_sensor_settings(r, s.sensors, true, checked);
  s.ideal_sensors = r.boolean_or(s.sensors, "sensors", "ideal", false);
  read_faults(r, s.sensors, s);
}

}  // namespace

void read_sensor_settings(const YamlReader& r, const YAML::Node& sensors, bool scenario, SimulationParams& into) {
  std::vector<std::string> keys = {"noise", "delay_cycles", "imu", "ft", "encoders"};
  if (scenario) keys.insert(keys.end(), {"ideal", "faults"});
  r.expect_keys(sensors, "sensors", keys);
  into.sensor_noise = r.boolean_or(sensors, "sensors", "noise", into.sensor_noise);
  const long delay = r.integer_or(sensors, "sensors", "delay_cycles", into.sensor_delay_cycles);
  if (delay < 0 || delay > 100) r.fail(sensors["delay_cycles"], "sensors.delay_cycles", "must be between 0 and 100");
  into.sensor_delay_cycles = static_cast<int>(delay);
  read_imu(r, r.mapping(sensors, "sensors", "imu"), into.sensor_errors.imu);
  read_force_torque(r, r.mapping(sensors, "sensors", "ft"), into.sensor_errors.ft);
  const YAML::Node encoders = r.mapping(sensors, "sensors", "encoders");
  r.expect_keys(encoders, "sensors.encoders", {"offset_deg"});
  const YAML::Node offsets = r.mapping(encoders, "sensors.encoders", "offset_deg");
  for (const auto& entry : offsets) {
    const std::string joint = entry.first.Scalar();
    into.sensor_errors.encoder_offset_rad[joint] =
        r.number(offsets, "sensors.encoders.offset_deg", joint.c_str()) * kRadiansPerDegree;
  }
}

Scenario load_scenario(const std::string& path, const std::vector<std::string>& overrides) {
  YAML::Node root = load_yaml_file(path);
  if (!root.IsMap()) throw InputError(path + ": expected a mapping of keys to values at the top level");
  for (const std::string& assignment : overrides) apply_override(root, assignment);

  const YamlReader r(path);
  r.expect_keys(root, "", {"name", "robot", "duration", "seed", "log_rate_hz", "controller", "simulation",
                           "commands", "disturbances", "terrain", "model_error", "sensors"});
  Scenario s;
  s.file = path;
  s.name = r.text_or(root, "", "name", std::filesystem::path(path).stem().string());
  if (s.name.find_first_of("/\\") != std::string::npos) r.fail(root["name"], "name", "must not contain '/'");
  s.robot = r.text(root, "", "robot");
  s.duration = r.number(root, "", "duration");
  if (!(s.duration > 0.0)) r.fail(root["duration"], "duration", "must be positive (got " + root["duration"].Scalar() + ")");
  if (s.duration > 3600.0) r.fail(root["duration"], "duration", "must be at most 3600 s");
  const long seed = r.integer_or(root, "", "seed", 1);
  if (seed < 0) r.fail(root["seed"], "seed", "must not be negative");
  s.seed = static_cast<unsigned long long>(seed);
  s.log_rate_hz = r.positive_or(root, "", "log_rate_hz", 100.0);
  s.controller = r.mapping(root, "", "controller");
  s.simulation = r.mapping(root, "", "simulation");
  read_commands(r, root, s);
  read_disturbances(r, root, s);
  read_terrain(r, root, s);
  const YAML::Node error = r.mapping(root, "", "model_error");
  r.expect_keys(error, "model_error", {"upper_body_mass_scale", "upper_body_com_offset"});
  if (error) {
    s.model_error.upper_body_mass_scale = r.positive_or(error, "model_error", "upper_body_mass_scale", 1.0);
    s.model_error.upper_body_com_offset =
        r.vector3_or(error, "model_error", "upper_body_com_offset", Eigen::Vector3d::Zero());
  }
  read_sensors(r, root, s);
  return s;
}

}  // namespace biped
