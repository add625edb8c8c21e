#pragma once
// Compliant, unilateral foot-ground contact with Coulomb friction, as in the paper's own simulation
// (spring-damper contacts on the sole) with a physical stiffness (N/m per foot, robots.md: 3-5·10⁵)
// instead of MuJoCo's acceleration-level soft constraints, at a few microseconds per physics step
// instead of a constraint solve. Bodies other than the soles touch the ground through MuJoCo.
//
// Each sole face (the bottom of a sole geom) carries a grid of spring-damper points at most
// `max_point_spacing` apart, corners and edges included (LOLA: 3×3 on the heel segment and 2×3 on
// the toe segment per foot, 15 points; JOHNNIE: 4×3 on its one sole). Each foot's stiffness and
// damping are shared by its points, so a flat foot sinks by load/stiffness_per_foot: equally by
// default, by the area each point represents with `stiffness_by_point_area` (which puts less on the
// corners and edges and lowers the sole's tilt stiffness: docs/simulation.md).
// Around each point is its patch, reaching halfway to the next point. Where a terrain edge or kink
// crosses a patch, the patch's stiffness is spread evenly over it and the pressure integrated
// exactly over the part below the ground, piece by piece on each side of the line, so the force
// acts where the sole is supported: at a step's edge under a foot resting half on it. A piece on the
// upper side of a step edge that has gone in sideways (less horizontal overlap than vertical depth:
// the sole is against the riser, not on top) is pushed back horizontally instead, without friction.
// Contact-point velocities are those of the points themselves (the body frame origin's velocity
// plus ω × r), not of the body's centre of mass.
// Friction: per patch an elasto-plastic bristle from its grid point to a stick point, which slides
// when its force exceeds μ times the patch's normal force (μ of the ground under its grid point: a
// terrain friction patch's, or `friction`); it acts at the patch's centre of pressure.
// The forces enter as xfrc_applied on the sole bodies, so MuJoCo's F/T sensors see them.
#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <vector>

#include "model/robot_model.hpp"
#include "sim/terrain.hpp"

namespace biped {

struct SoleContactParams {
  double stiffness_per_foot = 4.0e5;  // [N/m] normal, whole flat sole
  double damping_per_foot = 1500.0;   // [N·s/m] normal
  double tangential_stiffness_per_foot = 4.0e5;  // [N/m] bristle stiffness
  double tangential_damping_per_foot = 1500.0;   // [N·s/m]
  double friction = 0.8;              // Coulomb coefficient (off the terrain's friction patches)
  double max_point_spacing = 0.1;     // [m] grid points along each sole edge at most this far apart
  // Each point's share of the foot's stiffness and damping: its patch's share of the sole area (a
  // uniformly compliant sole), or else an equal share (a sole that is stiffer at its rim).
  bool stiffness_by_point_area = false;
};

// The bottom face of a sole geom: a rectangle fixed in a body.
struct SoleFace {
  int body = -1;
  int side = 0;                                      // foot index (Side)
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  // in the body frame
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  // columns: the face's u and v axes and its outward normal (body frame)
  double half_u = 0.0, half_v = 0.0;                 // [m]
};
// The bottom faces of the model's sole geoms (FootInfo::sole_geoms), or the sole rectangle a
// ModelMap gives in the sensor frame.
std::vector<SoleFace> sole_faces(const RobotModel& plant);

class SoleContact {
 public:
  SoleContact(std::vector<SoleFace> faces, Terrain terrain, const SoleContactParams& params);
  SoleContact(const RobotModel& plant, Terrain terrain, const SoleContactParams& params);

  // Adds the contact wrenches to d->xfrc_applied of the sole bodies (kinematics and velocities of d
  // must be current, i.e. after mj_step1).
  void apply(const mjModel* m, mjData* d);
  void reset();

  struct Patch {
    int face = -1;                                   // index into faces()
    Eigen::Vector2d point = Eigen::Vector2d::Zero();  // grid point (face coordinates u, v)
    double u0 = 0, u1 = 0, v0 = 0, v1 = 0;           // the patch (face coordinates)
    double area = 0.0;                               // [m²]
    double stiffness = 0.0, damping = 0.0;           // [N/m], [N·s/m]
    double tangential_stiffness = 0.0, tangential_damping = 0.0;
    bool in_contact = false;
    Eigen::Vector3d anchor = Eigen::Vector3d::Zero();  // stick point of the friction bristle (world)
    Eigen::Vector3d force = Eigen::Vector3d::Zero();   // last force on the robot (world)
    Eigen::Vector3d centre_of_pressure = Eigen::Vector3d::Zero();  // where it acts (world)
  };
  const std::vector<SoleFace>& faces() const { return faces_; }
  const std::vector<Patch>& patches() const { return patches_; }
  // Normal force on each foot from the last apply() [N].
  double normal_force(Side side) const { return normal_force_[index_of(side)]; }

 private:
  struct Pose;  // a face's placement and velocity in the world in the current step
  void apply_patch(const Pose& face, Patch& patch, mjData* d);

  std::vector<SoleFace> faces_;
  Terrain terrain_;
  SoleContactParams params_;
  std::vector<Patch> patches_;
  double normal_force_[2] = {0.0, 0.0};
};

}  // namespace biped
