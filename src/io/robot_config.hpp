#pragma once
// Robot parameter files (config/robots/NAME.yaml): the simulated robot (model, drives, sensors)
// and the controller's parameters. A scenario selects a robot and overrides parts of its file.
#include <string>

#include "control/standing_controller.hpp"
#include "control/walking_controller.hpp"
#include "control/weight_shift_controller.hpp"
#include "io/parameter_table.hpp"
#include "io/scenario.hpp"
#include "sim/simulation.hpp"

namespace biped {

struct ControllerConfig {
  std::string type = "walking";  // walking | standing | weight_shift
  std::string model_path;  // the controller's own MJCF (default: the simulated robot's)
  bool stabilizer = true;  // used by the walking controller; the standing controller has none
  double software_limit_margin_rad = kSoftwareLimitMarginRad;
  // [s] `biped tables`: where no gait passes at a speed by each instant's multibody ZMP, search it
  // again with the ZMP averaged over this window; 0: never (StepTableSearch::relaxed_zmp_window).
  double step_table_relaxed_zmp_window = 0.0;
  // `biped tables`: among gaits with nearly the largest margin, the shortest steps, not the longest.
  bool step_table_prefer_short_steps = false;
  StandingControllerParams standing;
  WalkingControllerParams walking;
  WeightShiftParams weight_shift;
  bool vx_max_given = false;  // a file gave controller.limits.vx_max: the step table does not lower it
};

struct RunConfig {
  std::string robot;        // robot name (or the MJCF file's stem)
  std::string robot_file;   // the parameter file read ("" for a bare MJCF)
  SimulationParams sim;
  ControllerConfig controller;
};

// Directory holding models/ and config/: $BIPED_DATA_DIR, or the source tree it was built from.
std::string data_directory();
// Names of the robots that have a parameter file.
std::vector<std::string> known_robots();

// How a robot file's step table that does not exist (yet) is treated: an error, except for
// `biped tables`, which makes it (the walking plan's default table stands in meanwhile).
enum class MissingStepTable { Error, UseDefault };

// Resolves the scenario's robot, reads its parameter file, and applies the scenario's overrides,
// disturbances, terrain, model error and sensor settings. Throws InputError naming file and key.
RunConfig make_run_config(const Scenario& scenario, MissingStepTable missing = MissingStepTable::Error);

// A file that a robot file includes (`include:`; `biped tune` writes them): its `controller:` keys,
// and optionally `simulation:` and `drives:` keys, override the values in `config`. Throws
// InputError naming the file and the key.
void apply_include_file(const std::string& path, RunConfig& config);

// The parameter reference: every numeric and boolean key of the robot files (and of a scenario's
// `simulation` and `controller` overrides), with the defaults of a default-constructed RunConfig.
std::vector<ParameterDoc> parameter_reference();

}  // namespace biped
