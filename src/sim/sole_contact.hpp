#pragma once
// Compliant, unilateral foot-ground contact: spring-damper point contacts distributed over each sole
// (as in the paper's own simulation), with an elasto-plastic (bristle) Coulomb friction model.
// Stiffness is physical (N/m per foot, robots.md: 3-5·10⁵) instead of MuJoCo's acceleration-level
// soft constraints, and the contact costs a few microseconds instead of a constraint solve.
// Bodies other than the soles still touch the ground through MuJoCo's own contacts.
#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <vector>

#include "model/robot_model.hpp"
#include "sim/world.hpp"

namespace biped {

struct SoleContactParams {
  double stiffness_per_foot = 4.0e5;  // [N/m] normal, whole flat sole
  double damping_per_foot = 1500.0;   // [N·s/m] normal
  double tangential_stiffness_per_foot = 4.0e5;  // [N/m] bristle stiffness
  double tangential_damping_per_foot = 1500.0;   // [N·s/m]
  double friction = 0.8;              // Coulomb coefficient
  double max_point_spacing = 0.1;     // [m] contact points along each sole edge at most this far apart
};

class SoleContact {
 public:
  SoleContact(const RobotModel& plant, std::vector<TerrainFeature> terrain, const SoleContactParams& params);

  // Adds the contact wrenches to d->xfrc_applied of the sole bodies (kinematics and velocities of d
  // must be current, i.e. after mj_step1).
  void apply(const mjModel* m, mjData* d);
  void reset();

  struct Point {
    int body = -1;            // body the point belongs to
    Eigen::Vector3d local;    // position in the body frame
    int side = 0;             // foot index (Side)
    double stiffness = 0.0, damping = 0.0, tangential_stiffness = 0.0, tangential_damping = 0.0;
    bool in_contact = false;
    Eigen::Vector3d anchor = Eigen::Vector3d::Zero();  // stick point of the friction bristle (world)
    Eigen::Vector3d force = Eigen::Vector3d::Zero();   // last force on the robot (world)
  };
  const std::vector<Point>& points() const { return points_; }
  // Normal force on each foot from the last apply() [N].
  double normal_force(Side side) const { return normal_force_[index_of(side)]; }

 private:
  struct Ground {
    double height;
    Eigen::Vector3d normal;
  };
  Ground ground_at(double x) const;
  // The riser of a step a point has gone under, if any: direction pushing it out, and depth.
  bool riser_contact(const Eigen::Vector3d& p, Eigen::Vector3d& push, double& depth) const;

  std::vector<TerrainFeature> terrain_;
  SoleContactParams params_;
  std::vector<Point> points_;
  double normal_force_[2] = {0.0, 0.0};
};

}  // namespace biped
