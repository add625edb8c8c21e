#pragma once
// Checks of a robot's MJCF model against its ModelMap, for `biped robot check` (docs/new-robot.md):
// every problem at once, each tied to the robot-file key it concerns, where RobotModel::load stops at
// the first. Two stages: the names, types and structure on the compiled MJCF alone (a RobotModel
// cannot be built before they pass), then the geometry (soles, standing pose) on the RobotModel.
#include <mujoco/mujoco.h>

#include <array>
#include <string>
#include <vector>

#include "model/model_map.hpp"
#include "model/robot_model.hpp"

namespace biped {

// One problem: `key` is the robot-file key it concerns (e.g. "model_map.legs.left.ft_site"), or ""
// when it lies in the MJCF file itself.
struct ModelProblem {
  std::string key;
  std::string message;
};

// Joints of the leg from `root_joint` (a MuJoCo joint id) down to `foot_body`, in that order: the
// joints of every body on the path, those before root_joint in its own body left out. Empty when
// foot_body is not in the subtree of root_joint's body.
std::vector<int> leg_chain(const mjModel* m, int root_joint, int foot_body);

// Joints in the subtree of `root_joint` (a MuJoCo joint id): root_joint, the joints after it in its
// body and every joint of the bodies below, in MuJoCo's order.
std::vector<int> joints_below(const mjModel* m, int root_joint);

// Stage 1: everything `map` names exists in `m` and has the right type and place (sensors on their
// sites, sites in their bodies, the root body carries the free joint, legs are chains of at least
// six driven, unlocked joints that share nothing with each other, the arms or the upper body), every other
// joint is a hinge with a range wider than twice the margin, every joint has a torque motor and a
// torque limit or is passive (and then has no motor or is coupled by an equality constraint), the
// standing pose names existing joints inside their software limits.
std::vector<ModelProblem> check_model_map(const mjModel* m, const ModelMap& map, double software_limit_margin_rad);

// Stage 2, on a model that passed stage 1: the soles lie below their F/T sensors (z < 0) around the
// point below the sensor, and the standing pose puts both soles level (within `max_sole_tilt_rad`)
// at the same height (within `max_sole_height_difference`).
std::vector<ModelProblem> check_robot_geometry(const RobotModel& model, double max_sole_tilt_rad = M_PI / 180.0,
                                               double max_sole_height_difference = 0.002);

// What a robot is made of, for the report of `biped robot check`.
struct RobotDescription {
  std::string name;
  double mass = 0.0;    // [kg]
  int nq = 0, nv = 0;   // configuration and velocity sizes (floating base included)
  int actuated = 0;     // joints with a drive
  int passive = 0;      // ModelMap::passive_joints
  int locked = 0;       // ModelMap::locked_joints (driven, held at the standing pose)
  std::array<std::vector<std::string>, 2> leg_joints;  // [left, right] from the root joint to the foot
  std::array<std::string, 2> toe_joints;               // "" without
  std::array<int, 2> arm_dof{0, 0};                    // driven, unlocked joints below each arm's root joint
  std::array<double, 2> sole_length{0.0, 0.0}, sole_width{0.0, 0.0};  // [m]
  std::array<double, 2> leg_length_stand{0.0, 0.0};    // [m] leg root joint's axis to the last leg joint's, standing
  std::array<double, 2> leg_length_stretched{0.0, 0.0};  // the same with every joint at zero
  double com_height_stand = 0.0;  // [m] above the soles in the standing pose
  std::array<std::string, 2> ft_sites;
  std::array<std::string, 2> foot_bodies;
  std::string imu_site, upper_body;
};

RobotDescription describe_robot(const RobotModel& model);

}  // namespace biped
