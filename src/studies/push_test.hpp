#pragma once
// `biped push-test`: the largest impulse of a 0.1 s push on the upper body, at a phase of a single
// support (by default its middle), that the robot survives in a scenario: the first fall is
// bracketed by stepping up the impulse, then found by bisection to 1 N·s. The push is timed by the
// ground truth's gait events (sim/disturbances.hpp): the first single support that starts after
// `earliest`, so no dry run is needed. Each trial runs to the scenario's end: surviving means
// walking on, stopping and standing without a fall.
#include <iosfwd>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "io/robot_config.hpp"
#include "io/scenario.hpp"

namespace biped {

struct PushTestOptions {
  // forward | backward | left | right, or an angle in the robot's heading frame (0 forward, 90 left).
  std::string direction = "forward";
  std::optional<double> direction_deg;  // when set, overrides `direction`
  double phase = 0.5;                 // share of the single support at the push's start
  // When set, the push starts at this time [s] instead of at a gait phase (a robot that stands
  // has no single support).
  std::optional<double> at_time;
  double earliest = 4.0;              // [s] push in the first single support that starts after this
  double max_impulse = 100.0;         // [N·s] upper end of the search
  double bracket_step = 4.0;          // [N·s] the search steps up by this until the first fall
  double resolution = 1.0;            // [N·s]
  double push_duration = 0.1;         // [s]
  std::ostream* progress = nullptr;   // one line per trial, when given
};

// The heading-frame angle of a named direction; throws InputError for an unknown name.
double direction_angle_deg(const std::string& name);

// Throws InputError for an unknown direction, a phase outside [0, 1], or a scenario in which the
// robot has no single support after `earliest`.
nlohmann::json run_push_test(const Scenario& scenario, const RunConfig& config, const PushTestOptions& options);

}  // namespace biped
