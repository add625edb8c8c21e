#pragma once
// The simulated world: the robot's MJCF plus ground, terrain the controller is not told about,
// and deliberate errors of the simulated robot against the controller's model.
#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <string>

#include "model/model_map.hpp"
#include <vector>

#include "sim/terrain.hpp"

namespace biped {

struct ModelErrorSpec {
  double upper_body_mass_scale = 1.0;
  Eigen::Vector3d upper_body_com_offset = Eigen::Vector3d::Zero();  // [m] in the upper-body frame
};

struct WorldSpec {
  std::string robot_mjcf;
  double timestep = 0.001;
  double ground_friction = 0.8;
  // Soft-contact time constant and damping ratio of MuJoCo's contacts (solref), for every geom.
  // 0.03 s gives a sole deflection of about 0.7 mm per foot standing on both feet (LOLA), i.e. a
  // per-foot stiffness of about 4e5 N/m as in robots.md.
  double contact_timeconst = 0.03;
  double contact_dampratio = 1.0;
  std::vector<TerrainFeature> terrain;
  ModelErrorSpec model_error;
  ModelMap model_map;  // names of the robot's parts in robot_mjcf
};

// Compiles the world; throws ModelError naming the robot file on failure. The caller owns the result
// (free with mj_deleteModel).
mjModel* build_world(const WorldSpec& spec);

}  // namespace biped
