#pragma once
// Shared helpers for the tests: model paths and a standing closed-loop run.
#include <string>

#include "model/robot_model.hpp"

namespace biped::test {

inline std::string source_path(const std::string& relative) { return std::string(BIPED_SOURCE_DIR) + "/" + relative; }
inline std::string model_path(const std::string& robot) { return source_path("models/" + robot + "/" + robot + ".xml"); }
inline RobotModel load_model(const std::string& robot) {
  return RobotModel::load(model_path(robot), 5.0 * M_PI / 180.0);
}

}  // namespace biped::test
