#include "sim/fall_detection.hpp"

#include "math/rotations.hpp"

namespace biped {

FallDetector::FallDetector(const RobotModel& plant, Terrain terrain,
                           double standing_pelvis_height)
    : plant_(&plant),
      terrain_(std::move(terrain)),
      standing_pelvis_height_(standing_pelvis_height),
      is_foot_body_(plant.mj()->nbody, 0) {
  for (Side side : kSides) {
    for (int b : plant.foot(side).bodies_below_sensor) is_foot_body_[b] = 1;
  }
}

const char* FallDetector::check(const mjData* d) const {
  const mjModel* m = plant_->mj();
  const Eigen::Matrix3d upper_body = math::mat_from_mujoco(d->xmat + 9 * plant_->upper_body());
  if (math::tilt_from_vertical(upper_body) > kMaxTiltRad) return "upper body tilted more than 45 deg";
  const double* pelvis = d->xpos + 3 * plant_->pelvis_body();
  const double height = pelvis[2] - terrain_.height({pelvis[0], pelvis[1]});
  if (height < kMinPelvisHeightRatio * standing_pelvis_height_) return "pelvis below 60% of standing height";
  for (int i = 0; i < d->ncon; ++i) {
    const int b1 = m->geom_bodyid[d->contact[i].geom1];
    const int b2 = m->geom_bodyid[d->contact[i].geom2];
    const int robot_body = b1 == 0 ? b2 : (b2 == 0 ? b1 : -1);
    if (robot_body > 0 && !is_foot_body_[robot_body]) return "a body other than the feet touched the ground";
  }
  return nullptr;
}

}  // namespace biped
