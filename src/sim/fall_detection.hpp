#pragma once
// Fall definition of DESIGN.md, evaluated on the simulator's ground truth: the upper body tilts
// more than 45° from vertical, the pelvis drops below 60 % of its standing height above the ground,
// or any body other than the feet touches the ground.
#include <mujoco/mujoco.h>

#include <vector>

#include "model/robot_model.hpp"
#include "sim/terrain.hpp"

namespace biped {

class FallDetector {
 public:
  FallDetector(const RobotModel& plant, Terrain terrain, double standing_pelvis_height);
  // nullptr while standing or walking; otherwise what made it a fall.
  const char* check(const mjData* d) const;

  static constexpr double kMaxTiltRad = 45.0 * M_PI / 180.0;
  static constexpr double kMinPelvisHeightRatio = 0.6;

 private:
  const RobotModel* plant_;
  Terrain terrain_;
  double standing_pelvis_height_;
  std::vector<char> is_foot_body_;
};

}  // namespace biped
