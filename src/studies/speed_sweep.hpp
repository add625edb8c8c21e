#pragma once
// `biped speed-sweep`: straight walks at increasing commanded speeds; reports, per speed, whether the
// robot fell, the speed it reached, and whether the command was saturated by the step table's
// limit, and the highest speed walked without a fall.
#include <nlohmann/json.hpp>

#include "io/robot_config.hpp"
#include "io/scenario.hpp"

namespace biped {

struct SpeedSweepOptions {
  double from = 0.2;         // [m/s] first commanded speed
  double to = 1.2;           // [m/s] last commanded speed
  double step = 0.1;         // [m/s]
  double ramp_rate = 0.2;    // [m/s²] the command rises to the target at this rate, from t = 1 s
  double hold = 10.0;        // [s] walking at the target speed
  int jobs = 0;              // speeds simulated at once (0: every core)
};

// The scenario gives the robot, its parameters and the disturbances; its commands and duration are
// replaced. Throws InputError for an inconsistent range.
nlohmann::json run_speed_sweep(const Scenario& scenario, const RunConfig& config, const SpeedSweepOptions& options);

}  // namespace biped
