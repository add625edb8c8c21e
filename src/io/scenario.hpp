#pragma once
// Scenario files (DESIGN.md "Scenario file"): what to simulate, for how long, with which commands,
// disturbances, terrain, model and sensor errors.
#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "sim/closed_loop.hpp"
#include "sim/simulation.hpp"
#include "sim/world.hpp"

namespace biped {

struct Scenario {
  std::string file;  // path of the scenario file
  std::string name;
  std::string robot;  // as written: a robot name, a path to a robot file (.yaml) or to an MJCF file (.xml)
  double duration = 0.0;
  unsigned long long seed = 1;
  double log_rate_hz = 100.0;
  std::vector<TimedCommand> commands;
  std::vector<Push> pushes;
  std::vector<TerrainFeature> terrain;
  ModelErrorSpec model_error;
  YAML::Node sensors;  // its `sensors` section, applied over the robot file's (read_sensor_settings)
  bool ideal_sensors = false;  // sensors.ideal: every sensor error off, whatever else is set
  std::vector<SensorFault> faults;
  YAML::Node controller;  // overrides of the robot parameter file's `controller` section
  YAML::Node simulation;  // overrides of its `simulation` section
};

class YamlReader;

// Reads a `sensors` section (a scenario's, `scenario`, or a robot file's, which has no `ideal` and no
// `faults`): the keys given replace those in `into`, the others stay. Throws InputError naming the
// file and the key.
void read_sensor_settings(const YamlReader& r, const YAML::Node& sensors, bool scenario, SimulationParams& into);

// Reads and checks a scenario file after applying the `--set KEY=VALUE` overrides; throws
// InputError with one line naming the file and the key (and line) at fault.
Scenario load_scenario(const std::string& path, const std::vector<std::string>& overrides = {});

}  // namespace biped
