#pragma once
// `biped push-test`: the largest impulse of a 0.1 s push on the upper body, at the middle of a
// single-support phase, that the robot survives in a scenario: the first fall is bracketed by
// stepping up the impulse, then found by bisection to 1 N·s.
// Each trial runs to the scenario's end: surviving means walking on, stopping and standing
// without a fall.
#include <nlohmann/json.hpp>
#include <string>

#include "io/robot_config.hpp"
#include "io/scenario.hpp"

namespace biped {

struct PushTestOptions {
  std::string direction = "forward";  // forward | backward | left | right (world frame x / y)
  double earliest = 4.0;              // [s] push in the first single support after this time
  double max_impulse = 100.0;         // [N·s] upper end of the search
  double bracket_step = 4.0;          // [N·s] the search steps up by this until the first fall
  double resolution = 1.0;            // [N·s]
  double push_duration = 0.1;         // [s]
};

// Throws InputError for an unknown direction or a scenario in which the robot never reaches a
// single support after `earliest`.
nlohmann::json run_push_test(const Scenario& scenario, const RunConfig& config, const PushTestOptions& options);

}  // namespace biped
