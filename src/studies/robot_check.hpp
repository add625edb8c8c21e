#pragma once
// `biped robot check`: a robot file (config/robots/NAME.yaml) against its MJCF model, before anything
// else uses it (docs/new-robot.md). Reads the file, checks every part its model_map names and the
// model's joints, drives and soles (model/model_check.hpp), describes what it found and stands the
// robot for a few seconds with the standing controller.
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "model/model_check.hpp"

namespace biped {

// The robot file a name (config/robots/NAME.yaml) or a path (NAME.yaml) stands for, relative to the
// working directory when it is below it, else absolute; throws InputError when there is no such file.
std::string resolve_robot_file(const std::string& name_or_path);

struct RobotCheckOptions {
  double stand_duration = 3.0;  // [s] simulated with the standing controller
};

// The standing run: the robot moves into its standing pose and holds it.
struct StandTest {
  bool ran = false;
  double duration = 0.0;       // [s]
  bool fell = false;
  double fall_time = 0.0;      // [s]
  std::string fall_reason;
  double max_tilt_deg = 0.0;   // upper body against gravity
  double com_drift = 0.0;      // [m] horizontal CoM displacement from start to end (ground truth)
  double com_height = 0.0;     // [m] at the end
};

struct RobotCheckReport {
  std::string robot_file;
  std::string mjcf;
  // One line per problem: "ROBOT_FILE: key 'KEY': what" or, for problems in the model itself,
  // "MJCF_FILE: what". Empty: the robot is usable.
  std::vector<std::string> problems;
  std::optional<RobotDescription> description;  // when the model could be built
  StandTest stand;                               // run only when nothing else was found
  // What is allowed but looks wrong (one line each, the same form): a standing pose at a software
  // limit, driven joints without rotor inertia, a standing robot that tilts or drifts. They do not make the check fail.
  std::vector<std::string> warnings;
};

// Above these the standing run is reported as a warning.
inline constexpr double kStandTiltWarningDeg = 2.0;
inline constexpr double kStandDriftWarning = 0.02;  // [m]
// A standing pose closer than this to a software limit is reported as a warning.
inline constexpr double kStandPoseLimitWarning = M_PI / 180.0;  // [rad]

// Checks the robot file (a path; see resolve_robot_file). Never throws for bad input: every problem
// becomes a line of the report.
RobotCheckReport check_robot(const std::string& robot_file, const RobotCheckOptions& options = {});

}  // namespace biped
