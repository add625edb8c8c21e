#pragma once
// `biped speed-sweep`: straight walks at increasing commanded speeds; reports, per speed, whether the
// robot fell, the speed it reached, and whether the command was saturated by the step table's
// limit, and the highest speed walked without a fall.
#include <nlohmann/json.hpp>
#include <ostream>

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
// replaced. With `progress`, one line per speed as it finishes. Throws InputError for an inconsistent
// range. The result's keys:
//   robot, scenario, stabilizer (on or off), hold_s (seconds walked at each speed),
//   fastest_without_fall_mps (the highest commanded speed walked without a fall and unsaturated),
//   runs: one per speed: commanded_mps (the commanded forward speed), fell, fall_time_s (or null),
//     walked_mps (the ground-truth forward speed over the hold; null after a fall),
//     command_saturated (the step table's limit clamped the command), limit_mps (the limit then, or null),
//     upper_body_tilt_deg (as in summary.json).
nlohmann::json run_speed_sweep(const Scenario& scenario, const RunConfig& config, const SpeedSweepOptions& options,
                               std::ostream* progress = nullptr);

}  // namespace biped
