#include "io/scenario.hpp"

#include <filesystem>

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

void read_disturbances(const YamlReader& r, const YAML::Node& root, Scenario& s) {
  const YAML::Node list = r.sequence(root, "", "disturbances");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string where = item("disturbances", i);
    const YAML::Node d = list[i];
    r.expect_keys(d, where, {"type", "t", "body", "force", "duration"});
    const std::string type = r.text(d, where, "type");
    if (type != "push") r.fail(d["type"], where + ".type", "unknown disturbance '" + type + "' (known: push)");
    Push push;
    push.t = r.non_negative_or(d, where, "t", 0.0);
    if (!d["t"]) r.fail(d, where + ".t", "missing (required)");
    push.body = r.text_or(d, where, "body", "upper_body");
    push.force = r.vector3(d, where, "force");
    push.duration = r.positive_or(d, where, "duration", 0.1);
    s.pushes.push_back(push);
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

void read_sensors(const YamlReader& r, const YAML::Node& root, Scenario& s) {
  const YAML::Node sensors = r.mapping(root, "", "sensors");
  r.expect_keys(sensors, "sensors", {"noise", "delay_cycles", "faults"});
  if (!sensors) return;
  s.sensor_noise = r.boolean_or(sensors, "sensors", "noise", false);
  const long delay = r.integer_or(sensors, "sensors", "delay_cycles", 0);
  if (delay < 0 || delay > 100) r.fail(sensors["delay_cycles"], "sensors.delay_cycles", "must be between 0 and 100");
  s.sensor_delay_cycles = static_cast<int>(delay);
  const YAML::Node faults = r.sequence(sensors, "sensors", "faults");
  for (std::size_t i = 0; i < faults.size(); ++i) {
    const std::string where = "sensors.faults." + std::to_string(i);
    const YAML::Node f = faults[i];
    r.expect_keys(f, where, {"t", "sensor", "value", "duration"});
    SensorFault fault;
    fault.t = r.non_negative_or(f, where, "t", 0.0);
    if (!f["t"]) r.fail(f, where + ".t", "missing (required)");
    fault.sensor = r.text(f, where, "sensor");
    fault.duration = r.non_negative_or(f, where, "duration", 0.0);
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

}  // namespace

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
