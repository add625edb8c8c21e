#pragma once
// MuJoCo's collision detection only when it can find something. The soles touch the ground through
// SoleContact; MuJoCo's contacts are for the other bodies (knees, hands, a fallen robot), which are
// far from the ground while the robot stands or walks. Every physics step, before mj_step1, the gate
// checks each robot geom that can collide with the ground: its lowest point against the highest
// ground within its reach. If none is close, MuJoCo's contacts are switched off for the step
// (mjDSBL_CONTACT: no broad or narrow phase, no contact rows), which cannot change a run: a step
// whose collision detection would have found a contact always has it on.
#include <mujoco/mujoco.h>

#include <vector>

#include "sim/terrain.hpp"

namespace biped {

class CollisionGate {
 public:
  CollisionGate(const mjModel* m, Terrain terrain);

  // Switches MuJoCo's contacts on or off for the coming step from the geom poses in d (those of the
  // last mj_step1 or mj_forward: one step old, which the safety margin covers).
  void update(mjModel* m, const mjData* d);
  void reset(const mjModel* m, const mjData* d);
  // Whether the last update left MuJoCo's contacts on.
  bool open() const { return open_; }

  // A geom is close when its clearance is below this plus 3× its descent over the last step.
  static constexpr double kMargin = 0.005;  // [m]

 private:
  // Height of the geom's lowest point above the highest ground within its bounding radius.
  double clearance(const mjModel* m, const mjData* d, int geom) const;

  Terrain terrain_;
  std::vector<int> geoms_;  // robot geoms that can collide with a ground geom
  std::vector<double> last_clearance_;
  bool open_ = true;
};

}  // namespace biped
