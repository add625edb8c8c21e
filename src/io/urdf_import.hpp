#pragma once
// `biped robot import`: a URDF robot into the MJCF this project simulates (docs/new-robot.md).
// MuJoCo 2.2.2 compiles the URDF (mj_loadXML, fixed links kept as bodies of their own) and writes
// it back as MJCF (mj_saveLastXML). A URDF has no free joint, no actuators, no sites and no sensors:
// the import adds a free joint to the root link, a torque motor to every hinge (ctrlrange = the
// URDF's effort limit), and an IMU site and two F/T sites with their sensors where it guesses them
// to be. It also guesses the robot file's model_map (legs, feet, soles, arms, a standing pose) from
// the model's structure and names, for the user to check with `biped robot check`.
#include <string>
#include <vector>

namespace biped {

struct UrdfImportOptions {
  std::string meshdir;     // where the mesh files are ("": as the URDF's <mujoco> block says, else its folder)
  std::string robot_file;  // the robot file the skeleton is meant for ("": paths absolute)
};

struct UrdfImport {
  std::vector<std::string> notes;  // what was carried, added and guessed, and what was not carried
  std::string robot_file;          // the skeleton robot file (YAML): model and model_map, commented
};

// Reads `urdf_path`, writes the MJCF to `mjcf_path` (whole or not at all) and returns the notes and
// the skeleton. Throws InputError with one line naming the file for a URDF it cannot use.
UrdfImport import_urdf(const std::string& urdf_path, const std::string& mjcf_path, const UrdfImportOptions& options = {});

}  // namespace biped
