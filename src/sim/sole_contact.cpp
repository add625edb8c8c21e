#include "sim/sole_contact.hpp"

#include <cmath>

#include "math/rotations.hpp"

namespace biped {
namespace {

constexpr double kRiserDepth = 0.008;  // [m] a point deeper than this below the surface is under a step edge
constexpr double kRiserReach = 0.05;   // [m] how far from a step edge that can happen

}  // namespace

SoleContact::SoleContact(const RobotModel& plant, std::vector<TerrainFeature> terrain, const SoleContactParams& params)
    : terrain_(std::move(terrain)), params_(params) {
  const mjModel* m = plant.mj();
  for (Side side : kSides) {
    const std::size_t first = points_.size();
    for (int g : plant.foot(side).sole_geoms) {
      const Eigen::Vector3d half(m->geom_size + 3 * g);
      const Eigen::Vector3d center(m->geom_pos + 3 * g);
      const Eigen::Matrix3d rot = math::quat_from_mujoco(m->geom_quat + 4 * g).toRotationMatrix();
      const int nx = 1 + static_cast<int>(std::ceil(2.0 * half.x() / params.max_point_spacing));
      const int ny = 1 + static_cast<int>(std::ceil(2.0 * half.y() / params.max_point_spacing));
      for (int i = 0; i < nx; ++i) {
        for (int j = 0; j < ny; ++j) {
          const Eigen::Vector3d in_geom(half.x() * (-1.0 + 2.0 * i / (nx - 1)), half.y() * (-1.0 + 2.0 * j / (ny - 1)),
                                        -half.z());
          Point p;
          p.body = m->geom_bodyid[g];
          p.local = center + rot * in_geom;
          p.side = index_of(side);
          points_.push_back(p);
        }
      }
    }
    // Each foot's stiffness is shared by its points, so a flat sole has the stated stiffness.
    const double n = static_cast<double>(points_.size() - first);
    for (std::size_t k = first; k < points_.size(); ++k) {
      points_[k].stiffness = params.stiffness_per_foot / n;
      points_[k].damping = params.damping_per_foot / n;
      points_[k].tangential_stiffness = params.tangential_stiffness_per_foot / n;
      points_[k].tangential_damping = params.tangential_damping_per_foot / n;
    }
  }
}

void SoleContact::reset() {
  for (Point& p : points_) {
    p.in_contact = false;
    p.force.setZero();
  }
  normal_force_[0] = normal_force_[1] = 0.0;
}

SoleContact::Ground SoleContact::ground_at(double x) const {
  constexpr double h = 1e-4;
  const double z = terrain_height(terrain_, x);
  const double slope = (terrain_height(terrain_, x + h) - terrain_height(terrain_, x - h)) / (2 * h);
  // A step's discontinuity would give a huge finite-difference slope: steps have vertical risers,
  // handled separately, so clamp the slope to that of the steepest supported ramp.
  const double clamped = std::abs(slope) > 1.0 ? 0.0 : slope;
  return {z, Eigen::Vector3d(-clamped, 0.0, 1.0).normalized()};
}

bool SoleContact::riser_contact(const Eigen::Vector3d& p, Eigen::Vector3d& push, double& depth) const {
  for (const TerrainFeature& f : terrain_) {
    if (f.kind != TerrainFeature::Kind::Step || std::abs(p.x() - f.x) > kRiserReach) continue;
    // The ground is higher on the side of the step the point is on: push it back across the edge.
    const bool upper_is_ahead = f.height > 0.0;
    if (upper_is_ahead && p.x() >= f.x) {
      push = -Eigen::Vector3d::UnitX();
      depth = p.x() - f.x;
      return true;
    }
    if (!upper_is_ahead && p.x() < f.x) {
      push = Eigen::Vector3d::UnitX();
      depth = f.x - p.x();
      return true;
    }
  }
  return false;
}

void SoleContact::apply(const mjModel* m, mjData* d) {
  normal_force_[0] = normal_force_[1] = 0.0;
  for (Point& c : points_) {
    const Eigen::Map<const Eigen::Vector3d> origin(d->xpos + 3 * c.body);
    const Eigen::Matrix3d R = math::mat_from_mujoco(d->xmat + 9 * c.body);
    const Eigen::Vector3d p = origin + R * c.local;
    const Ground ground = ground_at(p.x());
    const double depth = (ground.height - p.z()) * ground.normal.z();
    c.force.setZero();
    if (depth <= 0.0) {
      c.in_contact = false;
      continue;
    }
    mjtNum velocity[6];
    mj_objectVelocity(m, d, mjOBJ_BODY, c.body, velocity, 0);
    const Eigen::Vector3d omega(velocity[0], velocity[1], velocity[2]);
    const Eigen::Vector3d v = Eigen::Vector3d(velocity[3], velocity[4], velocity[5]) + omega.cross(p - origin);

    Eigen::Vector3d push;
    double riser_depth = 0.0;
    if (depth > kRiserDepth && riser_contact(p, push, riser_depth)) {
      // Under a step edge: the riser pushes the point back horizontally, without friction.
      c.force = push * std::max(0.0, c.stiffness * riser_depth - c.damping * v.dot(push));
      c.in_contact = false;
    } else {
      const Eigen::Vector3d& n = ground.normal;
      const double normal = std::max(0.0, c.stiffness * depth - c.damping * v.dot(n));
      // Bristle friction: a tangential spring to the stick point, which slides when the spring
      // force exceeds the Coulomb limit.
      if (!c.in_contact) c.anchor = p;
      c.in_contact = true;
      Eigen::Vector3d stretch = p - c.anchor;
      stretch -= n * n.dot(stretch);
      const Eigen::Vector3d v_t = v - n * n.dot(v);
      Eigen::Vector3d tangential = -c.tangential_stiffness * stretch - c.tangential_damping * v_t;
      const double limit = params_.friction * normal;
      const double magnitude = tangential.norm();
      if (magnitude > limit) {
        tangential *= limit / magnitude;
        const double stretch_norm = stretch.norm();
        if (stretch_norm > 0.0) c.anchor = p - stretch * std::min(1.0, limit / (c.tangential_stiffness * stretch_norm));
      }
      c.force = normal * n + tangential;
      normal_force_[c.side] += normal;
    }
    // xfrc_applied acts at the body's centre of mass.
    const Eigen::Map<const Eigen::Vector3d> com(d->xipos + 3 * c.body);
    const Eigen::Vector3d torque = (p - com).cross(c.force);
    for (int k = 0; k < 3; ++k) {
      d->xfrc_applied[6 * c.body + k] += c.force[k];
      d->xfrc_applied[6 * c.body + 3 + k] += torque[k];
    }
  }
}

}  // namespace biped
