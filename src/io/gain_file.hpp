#pragma once
// Gain files (`biped tune`'s gains.yaml, config/gains/): `controller:` keys that a robot file
// includes (`include:`, io/robot_config.hpp) over its own values, under a comment header that says
// where they come from.
#include <string>
#include <vector>

#include "io/robot_config.hpp"

namespace biped {

// Writes `assignments` ("controller.stabilization.tilt_gain=812", in this order) as nested YAML
// mappings under `header` (one comment line each), whole or not at all.
void write_gain_file(const std::string& path, const std::vector<std::string>& header,
                     const std::vector<std::string>& assignments);

// The values of a gain file as `--set` assignments of a scenario ("controller.KEY=VALUE"), after
// checking the file as an include of the robot whose configuration is `config`. Only `controller:`
// keys with numbers or booleans are accepted (a path would resolve against another file). Throws
// InputError naming the file and the key.
std::vector<std::string> read_gain_file(const std::string& path, const RunConfig& config);

}  // namespace biped
