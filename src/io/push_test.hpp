#pragma once
// `biped push-test`: the largest impulse of a 0.1 s push on the upper body, at the middle of a
// single-support phase, that the robot survives in a scenario, found by bisection to 1 N·s.
#include <nlohmann/json.hpp>
#include <string>

#include "io/robot_config.hpp"
#include "io/scenario.hpp"

namespace biped {

struct PushTestOptions {
  std::string direction = "forward";  // forward | backward | left | right (world frame x / y)
  double earliest = 4.0;              // [s] push in the first single support after this time
  double max_impulse = 200.0;         // [N·s] upper end of the search
  double resolution = 1.0;            // [N·s]
  double push_duration = 0.1;         // [s]
  double observe_after = 3.0;         // [s] simulated after the push
};

// Throws InputError for an unknown direction or a scenario in which the robot never reaches a
// single support after `earliest`.
nlohmann::json run_push_test(const Scenario& scenario, const RunConfig& config, const PushTestOptions& options);

}  // namespace biped
