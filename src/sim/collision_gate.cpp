#include "sim/collision_gate.hpp"

#include <algorithm>
#include <cmath>

namespace biped {
namespace {

bool can_collide(const mjModel* m, int g1, int g2) {
  return (m->geom_contype[g1] & m->geom_conaffinity[g2]) || (m->geom_contype[g2] & m->geom_conaffinity[g1]);
}

// Lowest point of a geom along world z: the geom's half-extent along z from its pose.
double lowest_point(const mjModel* m, const mjData* d, int g) {
  const double* size = m->geom_size + 3 * g;
  const double* R = d->geom_xmat + 9 * g;  // row-major: R[6 + k] is the z component of local axis k
  const double z = d->geom_xpos[3 * g + 2];
  switch (m->geom_type[g]) {
    case mjGEOM_SPHERE:
      return z - size[0];
    case mjGEOM_CAPSULE:
      return z - std::abs(R[8]) * size[1] - size[0];
    case mjGEOM_CYLINDER:
      return z - std::abs(R[8]) * size[1] - size[0] * std::sqrt(std::max(0.0, 1.0 - R[8] * R[8]));
    case mjGEOM_BOX:
      return z - std::abs(R[6]) * size[0] - std::abs(R[7]) * size[1] - std::abs(R[8]) * size[2];
    case mjGEOM_ELLIPSOID:
      return z - std::hypot(R[6] * size[0], R[7] * size[1], R[8] * size[2]);
    default:
      return z - m->geom_rbound[g];
  }
}

}  // namespace

CollisionGate::CollisionGate(const mjModel* m, Terrain terrain) : terrain_(std::move(terrain)) {
  for (int g = 0; g < m->ngeom; ++g) {
    if (m->geom_bodyid[g] == 0) continue;
    for (int w = 0; w < m->ngeom; ++w) {
      if (m->geom_bodyid[w] == 0 && can_collide(m, g, w)) {
        geoms_.push_back(g);
        break;
      }
    }
  }
  last_clearance_.assign(geoms_.size(), 0.0);
}

double CollisionGate::clearance(const mjModel* m, const mjData* d, int g) const {
  const Eigen::Vector2d xy(d->geom_xpos[3 * g], d->geom_xpos[3 * g + 1]);
  return lowest_point(m, d, g) - terrain_.max_height_within(xy, m->geom_rbound[g]);
}

void CollisionGate::reset(const mjModel* m, const mjData* d) {
  for (std::size_t k = 0; k < geoms_.size(); ++k) last_clearance_[k] = clearance(m, d, geoms_[k]);
  open_ = true;
}

void CollisionGate::update(mjModel* m, const mjData* d) {
  open_ = false;
  for (std::size_t k = 0; k < geoms_.size(); ++k) {
    const double now = clearance(m, d, geoms_[k]);
    const double descent = std::max(0.0, last_clearance_[k] - now);
    last_clearance_[k] = now;
    if (now < kMargin + 3.0 * descent) open_ = true;
  }
  if (open_) {
    m->opt.disableflags &= ~mjDSBL_CONTACT;
  } else {
    m->opt.disableflags |= mjDSBL_CONTACT;
  }
}

}  // namespace biped
