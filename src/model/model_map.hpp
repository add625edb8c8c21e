#pragma once
// ModelMap: where the controller finds its parts in a robot's MJCF file. The defaults are the
// naming contract of the project's own models (models/README.md); a robot file's `model_map:`
// section (docs/new-robot.md) names the parts of any other model, so that a new biped needs data,
// not code.
#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace biped {

// A sole given as data where the model has no box geoms for it: a rectangle in the F/T sensor
// frame, at height z below the sensor (negative), every joint at zero.
struct SoleRectangle {
  double x_min = 0.0, x_max = 0.0;  // [m] along the sensor's x (forward)
  double y_min = 0.0, y_max = 0.0;  // [m] along the sensor's y (left)
  double z = 0.0;                   // [m] sole plane in the sensor frame
};

struct LegMap {
  std::string root_joint;    // first joint of the leg (the one nearest the pelvis)
  std::string toe_joint;     // "" when the foot has no toe joint
  std::string foot_body;     // the body below the F/T sensor
  std::string ft_site;       // F/T sensor frame (a site in foot_body)
  std::string ft_force;      // force sensor on ft_site
  std::string ft_torque;     // torque sensor on ft_site
  std::string arm_root_joint;  // first joint of the arm on this side
  std::optional<SoleRectangle> sole;  // unset: the box geoms named "*<sole_suffix>" below the sensor
};

struct ModelMap {
  std::string root_body = "pelvis";    // the floating base
  std::string upper_body = "upper_body";  // the body whose orientation the IMU measures
  std::string imu_site = "imu";        // in upper_body
  std::string imu_orientation = "imu_quat";  // framequat sensor; "" when the model has none (the
                                             // simulator then reads the site's frame)
  std::string imu_gyro = "imu_gyro";
  std::string imu_accelerometer = "imu_accel";
  std::string sole_suffix = "_sole";   // box geoms that make up a sole
  std::array<LegMap, 2> legs = {         // [left, right] as math/side.hpp indexes them
      LegMap{"left_hip_yaw", "left_toe", "left_foot", "left_ft", "left_ft_force", "left_ft_torque",
             "left_shoulder_pitch", std::nullopt},
      LegMap{"right_hip_yaw", "right_toe", "right_foot", "right_ft", "right_ft_force", "right_ft_torque",
             "right_shoulder_pitch", std::nullopt}};
  std::string stand_keyframe = "stand";  // keyframe of the standing pose
  // The standing pose as data [rad] where the model has no such keyframe: joints not named stay at
  // zero; the base is placed so that the soles rest level at z = 0.
  std::map<std::string, double> stand_pose;
  // Peak torque of each joint's drive [N·m] where the model's actuator has no ctrlrange.
  std::map<std::string, double> torque_limits;
  // Joints without a drive of their own (e.g. finger joints coupled to another by an equality
  // constraint): the controller keeps them out of its tasks and the simulator drives nothing there.
  std::vector<std::string> passive_joints;
  // Joints the controller holds at the stand pose (their drives keep them there): e.g. a waist or
  // neck that the paper's task space (Table I) has no use for.
  std::vector<std::string> locked_joints;
};

}  // namespace biped
