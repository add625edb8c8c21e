#pragma once
// Shared helpers for the tests: source and model paths, the models, a robot's bare scenario, fresh
// output directories.
#include <unistd.h>

#include <filesystem>
#include <string>

#include "io/scenario.hpp"
#include "model/robot_model.hpp"

namespace biped::test {

inline std::string source_path(const std::string& relative) { return std::string(BIPED_SOURCE_DIR) + "/" + relative; }
inline std::string model_path(const std::string& robot) { return source_path("models/" + robot + "/" + robot + ".xml"); }
inline RobotModel load_model(const std::string& robot) {
  return RobotModel::load(model_path(robot), 5.0 * M_PI / 180.0);
}

// A scenario of one second with nothing but the robot: its robot file's configuration.
inline Scenario robot_scenario(const std::string& robot) {
  Scenario s;
  s.file = "test.yaml";
  s.robot = robot;
  s.duration = 1.0;
  return s;
}

// An empty directory under the system's temp directory, unique to this test process.
inline std::filesystem::path fresh_dir(const char* name) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("biped-test-" + std::string(name) + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace biped::test
