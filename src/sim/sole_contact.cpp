#include "sim/sole_contact.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "math/rotations.hpp"

namespace biped {
namespace {

// A convex polygon in a face's (u, v) coordinates with a value per vertex that is linear over it.
struct Polygon {
  static constexpr int kMax = 16;
  std::array<Eigen::Vector2d, kMax> vertex;
  std::array<double, kMax> value;
  int size = 0;
  void add(const Eigen::Vector2d& p, double v) {
    if (size < kMax) {
      vertex[size] = p;
      value[size++] = v;
    }
  }
};

// The part of `in` where the linear function f (given at its vertices) is >= 0, with f carried along.
Polygon clip(const Polygon& in, const std::array<double, Polygon::kMax>& f) {
  Polygon out;
  for (int i = 0; i < in.size; ++i) {
    const int j = (i + 1) % in.size;
    if (f[i] >= 0.0) out.add(in.vertex[i], in.value[i]);
    if ((f[i] >= 0.0) != (f[j] >= 0.0)) {
      const double t = f[i] / (f[i] - f[j]);
      out.add(in.vertex[i] + t * (in.vertex[j] - in.vertex[i]), in.value[i] + t * (in.value[j] - in.value[i]));
    }
  }
  return out;
}

double area_of(const Polygon& p) {
  double twice = 0.0;
  for (int i = 0; i < p.size; ++i) {
    const int j = (i + 1) % p.size;
    twice += p.vertex[i].x() * p.vertex[j].y() - p.vertex[j].x() * p.vertex[i].y();
  }
  return 0.5 * twice;
}

// Exact integrals over a polygon of 1, r, the linear value δ and δ·r (fan of triangles; over a
// triangle ∫δ dA = A·Σδ_i/3 and ∫δ r dA = A/12·(Σδ_i r_i + Σδ_i·Σr_i)).
struct Integrals {
  double area = 0.0, value = 0.0;
  Eigen::Vector2d moment = Eigen::Vector2d::Zero(), value_moment = Eigen::Vector2d::Zero();
};
Integrals integrate(const Polygon& p) {
  Integrals s;
  for (int i = 1; i + 1 < p.size; ++i) {
    const Eigen::Vector2d& r0 = p.vertex[0];
    const Eigen::Vector2d& r1 = p.vertex[i];
    const Eigen::Vector2d& r2 = p.vertex[i + 1];
    const double a = 0.5 * ((r1 - r0).x() * (r2 - r0).y() - (r1 - r0).y() * (r2 - r0).x());
    const double d0 = p.value[0], d1 = p.value[i], d2 = p.value[i + 1];
    s.area += a;
    s.moment += a * (r0 + r1 + r2) / 3.0;
    s.value += a * (d0 + d1 + d2) / 3.0;
    s.value_moment += a / 12.0 * (d0 * r0 + d1 * r1 + d2 * r2 + (d0 + d1 + d2) * (r0 + r1 + r2));
  }
  return s;
}

void add_force(mjData* d, int body, const Eigen::Vector3d& force, const Eigen::Vector3d& point) {
  // xfrc_applied acts at the body's centre of mass.
  const Eigen::Vector3d torque = (point - Eigen::Vector3d(d->xipos + 3 * body)).cross(force);
  for (int k = 0; k < 3; ++k) {
    d->xfrc_applied[6 * body + k] += force[k];
    d->xfrc_applied[6 * body + 3 + k] += torque[k];
  }
}

constexpr double kTinyArea = 1e-12;  // [m²] pieces smaller than this carry nothing

}  // namespace

std::vector<SoleFace> sole_faces(const RobotModel& plant) {
  const mjModel* m = plant.mj();
  std::vector<SoleFace> faces;
  for (Side side : kSides) {
    const FootInfo& foot = plant.foot(side);
    if (foot.sole_geoms.empty()) {  // a sole given as data: one rectangle in the sensor frame
      const SoleSegment& r = foot.segments[0];
      const Eigen::Matrix3d site = math::quat_from_mujoco(m->site_quat + 4 * foot.sensor_site).toRotationMatrix();
      SoleFace f;
      f.body = foot.body;
      f.side = index_of(side);
      f.center = foot.sensor_position + site * Eigen::Vector3d(0.5 * (r.x_min + r.x_max), 0.5 * (r.y_min + r.y_max), r.z);
      f.axes << site.col(0), site.col(1), -site.col(2);
      f.half_u = 0.5 * (r.x_max - r.x_min);
      f.half_v = 0.5 * (r.y_max - r.y_min);
      faces.push_back(f);
      continue;
    }
    for (int g : foot.sole_geoms) {
      SoleFace f;
      f.body = m->geom_bodyid[g];
      f.side = index_of(side);
      const Eigen::Matrix3d rot = math::quat_from_mujoco(m->geom_quat + 4 * g).toRotationMatrix();
      f.center = Eigen::Vector3d(m->geom_pos + 3 * g) - m->geom_size[3 * g + 2] * rot.col(2);
      f.axes << rot.col(0), rot.col(1), -rot.col(2);
      f.half_u = m->geom_size[3 * g];
      f.half_v = m->geom_size[3 * g + 1];
      faces.push_back(f);
    }
  }
  return faces;
}

SoleContact::SoleContact(const RobotModel& plant, Terrain terrain, const SoleContactParams& params)
    : SoleContact(sole_faces(plant), std::move(terrain), params) {}

SoleContact::SoleContact(std::vector<SoleFace> faces, Terrain terrain, const SoleContactParams& params)
    : faces_(std::move(faces)), terrain_(std::move(terrain)), params_(params) {
  // Grid points on each face, corners and edges included; each patch reaches halfway to the next.
  for (int i = 0; i < static_cast<int>(faces_.size()); ++i) {
    const SoleFace& f = faces_[i];
    const int nu = 1 + static_cast<int>(std::ceil(2.0 * f.half_u / params.max_point_spacing));
    const int nv = 1 + static_cast<int>(std::ceil(2.0 * f.half_v / params.max_point_spacing));
    const double du = 2.0 * f.half_u / (nu - 1), dv = 2.0 * f.half_v / (nv - 1);
    for (int a = 0; a < nu; ++a) {
      for (int b = 0; b < nv; ++b) {
        Patch p;
        p.face = i;
        p.point = Eigen::Vector2d(-f.half_u + a * du, -f.half_v + b * dv);
        p.u0 = std::max(-f.half_u, p.point.x() - 0.5 * du);
        p.u1 = std::min(f.half_u, p.point.x() + 0.5 * du);
        p.v0 = std::max(-f.half_v, p.point.y() - 0.5 * dv);
        p.v1 = std::min(f.half_v, p.point.y() + 0.5 * dv);
        p.area = (p.u1 - p.u0) * (p.v1 - p.v0);
        patches_.push_back(p);
      }
    }
  }
  // Each foot's stiffness is shared by its points so that a flat sole has the stated stiffness:
  // equally, or by the area of each point's patch.
  double foot_area[2] = {0.0, 0.0};
  int foot_points[2] = {0, 0};
  for (const Patch& p : patches_) {
    foot_area[faces_[p.face].side] += p.area;
    ++foot_points[faces_[p.face].side];
  }
  for (Patch& p : patches_) {
    const int side = faces_[p.face].side;
    const double n = params.stiffness_by_point_area ? foot_area[side] / p.area : foot_points[side];
    p.stiffness = params.stiffness_per_foot / n;
    p.damping = params.damping_per_foot / n;
    p.tangential_stiffness = params.tangential_stiffness_per_foot / n;
    p.tangential_damping = params.tangential_damping_per_foot / n;
  }
}

void SoleContact::reset() {
  for (Patch& p : patches_) {
    p.in_contact = false;
    p.force.setZero();
  }
  normal_force_[0] = normal_force_[1] = 0.0;
}

struct SoleContact::Pose {
  int body;
  int side;
  Eigen::Vector3d center, u, v;  // the face's centre and axes (world)
  Eigen::Vector3d origin, linear, angular;  // the body frame's origin, its velocity, the body's angular velocity
  Eigen::Vector3d at(const Eigen::Vector2d& uv) const { return center + uv.x() * u + uv.y() * v; }
  Eigen::Vector3d velocity(const Eigen::Vector3d& p) const { return linear + angular.cross(p - origin); }
};

void SoleContact::apply(const mjModel* m, mjData* d) {
  normal_force_[0] = normal_force_[1] = 0.0;
  int current = -1;
  Pose pose{};
  for (Patch& patch : patches_) {
    if (patch.face != current) {
      current = patch.face;
      const SoleFace& f = faces_[current];
      const Eigen::Matrix3d R = math::mat_from_mujoco(d->xmat + 9 * f.body);
      mjtNum velocity[6];
      // At the body frame's origin (mjOBJ_XBODY), where Pose::velocity measures its lever arm from.
      mj_objectVelocity(m, d, mjOBJ_XBODY, f.body, velocity, 0);
      pose.body = f.body;
      pose.side = f.side;
      pose.origin = Eigen::Vector3d(d->xpos + 3 * f.body);
      pose.center = pose.origin + R * f.center;
      pose.u = R * f.axes.col(0);
      pose.v = R * f.axes.col(1);
      pose.angular = Eigen::Vector3d(velocity[0], velocity[1], velocity[2]);
      pose.linear = Eigen::Vector3d(velocity[3], velocity[4], velocity[5]);
    }
    apply_patch(pose, patch, d);
  }
}

void SoleContact::apply_patch(const Pose& face, Patch& patch, mjData* d) {
  // The patch, split by the terrain lines that cross it into pieces on which the ground is one plane.
  struct Piece {
    Polygon polygon;
    unsigned sides = 0;  // bit k: on the positive side of the k-th cutting line
  };
  constexpr int kMaxCuts = 4;
  std::array<Piece, 1 << kMaxCuts> pieces;
  std::array<int, kMaxCuts> cut_line{};
  int num_pieces = 1, num_cuts = 0;
  Polygon& rect = pieces[0].polygon;
  rect.add({patch.u0, patch.v0}, 0.0);
  rect.add({patch.u1, patch.v0}, 0.0);
  rect.add({patch.u1, patch.v1}, 0.0);
  rect.add({patch.u0, patch.v1}, 0.0);
  const Eigen::Vector2d mid(0.5 * (patch.u0 + patch.u1), 0.5 * (patch.v0 + patch.v1));
  const Eigen::Vector3d mid_world = face.at(mid);
  const double reach = 0.5 * std::hypot(patch.u1 - patch.u0, patch.v1 - patch.v0);
  const auto& lines = terrain_.lines();
  for (int l = 0; l < static_cast<int>(lines.size()) && num_cuts < kMaxCuts; ++l) {
    const Terrain::Line& line = lines[l];
    if (std::abs(line.normal.dot(mid_world.head<2>()) - line.offset) >= reach) continue;
    // Signed horizontal distance from the line, linear in (u, v).
    const double a = line.normal.dot(face.u.head<2>()), b = line.normal.dot(face.v.head<2>());
    const double e = line.normal.dot(face.center.head<2>()) - line.offset;
    std::array<Piece, 1 << kMaxCuts> split;
    int n = 0;
    bool cuts = false;
    for (int k = 0; k < num_pieces; ++k) {
      const Polygon& p = pieces[k].polygon;
      std::array<double, Polygon::kMax> above{}, below{};
      for (int i = 0; i < p.size; ++i) {
        above[i] = a * p.vertex[i].x() + b * p.vertex[i].y() + e;
        below[i] = -above[i];
      }
      const Polygon positive = clip(p, above), negative = clip(p, below);
      const bool has_positive = std::abs(area_of(positive)) > kTinyArea;
      const bool has_negative = std::abs(area_of(negative)) > kTinyArea;
      cuts = cuts || (has_positive && has_negative);
      if (has_positive) split[n++] = {positive, pieces[k].sides | (1u << num_cuts)};
      if (has_negative) split[n++] = {negative, pieces[k].sides};
    }
    if (!cuts) continue;  // the patch lies on one side: the line does not matter here
    pieces = split;
    num_pieces = n;
    cut_line[num_cuts++] = l;
  }

  Eigen::Vector3d normal_sum = Eigen::Vector3d::Zero(), moment_sum = Eigen::Vector3d::Zero();
  double normal_total = 0.0;
  patch.force.setZero();
  if (num_cuts == 0) {
    // One ground plane under the whole patch: a point contact at the grid point with the patch's
    // share of the foot's stiffness.
    const Eigen::Vector3d p = face.at(patch.point);
    const Terrain::Surface ground = terrain_.surface(p.head<2>());
    const Eigen::Vector3d n = ground.normal();
    const double depth = (ground.height - p.z()) * n.z();
    const double f = depth > 0.0 ? std::max(0.0, patch.stiffness * depth - patch.damping * face.velocity(p).dot(n)) : 0.0;
    if (f > 0.0) {
      normal_sum = f * n;
      moment_sum = f * p;
      normal_total = f;
    }
  }
  for (int k = 0; num_cuts > 0 && k < num_pieces; ++k) {
    const Polygon& piece = pieces[k].polygon;
    // The ground's plane under this piece, from its centroid.
    Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
    for (int i = 0; i < piece.size; ++i) centroid += piece.vertex[i];
    centroid /= piece.size;
    const Eigen::Vector2d ground_xy = face.at(centroid).head<2>();
    const Terrain::Surface ground = terrain_.surface(ground_xy);
    const Eigen::Vector3d n = ground.normal();
    // Depth below the ground plane at the vertices, vertical and along the normal.
    Polygon depth = piece;
    for (int i = 0; i < piece.size; ++i) {
      const Eigen::Vector3d w = face.at(piece.vertex[i]);
      depth.value[i] = (ground.height + ground.gradient.dot(w.head<2>() - ground_xy) - w.z()) * n.z();
    }
    const Polygon contact = clip(depth, depth.value);
    if (contact.size < 3) continue;
    const Integrals s = integrate(contact);
    if (s.area <= kTinyArea || s.value <= 0.0) continue;
    const Eigen::Vector3d area_centre = face.at(s.moment / s.area);
    const Eigen::Vector3d velocity = face.velocity(area_centre);

    // Against a riser: the piece is on the upper side of a step edge and overlaps it horizontally
    // by less than it is below the upper level.
    double deepest = 0.0;
    for (int i = 0; i < contact.size; ++i) deepest = std::max(deepest, contact.value[i] / n.z());
    double overlap = deepest;
    Eigen::Vector3d push = Eigen::Vector3d::Zero();
    for (int c = 0; c < num_cuts; ++c) {
      const Terrain::Line& line = lines[cut_line[c]];
      if (!line.jump) continue;
      const double sign = (pieces[k].sides >> c) & 1u ? 1.0 : -1.0;
      const Eigen::Vector2d on_line = ground_xy - (line.normal.dot(ground_xy) - line.offset) * line.normal;
      constexpr double kSide = 1e-6;  // [m]
      const double rise = terrain_.height(on_line + sign * kSide * line.normal) -
                          terrain_.height(on_line - sign * kSide * line.normal);
      if (rise <= 1e-9) continue;
      double beyond = 0.0;
      for (int i = 0; i < contact.size; ++i) {
        beyond = std::max(beyond, sign * (line.normal.dot(face.at(contact.vertex[i]).head<2>()) - line.offset));
      }
      if (beyond < overlap) {
        overlap = beyond;
        push = Eigen::Vector3d(-sign * line.normal.x(), -sign * line.normal.y(), 0.0);
      }
    }
    if (!push.isZero()) {
      const double f = std::max(0.0, patch.stiffness * overlap - patch.damping * velocity.dot(push));
      add_force(d, face.body, f * push, area_centre);
      patch.force += f * push;
      continue;
    }
    // The patch's stiffness and damping spread evenly over it.
    const double spring = patch.stiffness / patch.area * s.value;
    const double damper = -patch.damping / patch.area * s.area * velocity.dot(n);
    const double f = std::max(0.0, spring + damper);
    if (f <= 0.0) continue;
    const Eigen::Vector3d cop = face.at(s.value_moment / s.value);
    normal_sum += f * n;
    moment_sum += f * cop;
    normal_total += f;
  }

  if (normal_total <= 0.0) {
    patch.in_contact = false;
    patch.centre_of_pressure = face.at(patch.point);
    return;
  }
  const Eigen::Vector3d cop = moment_sum / normal_total;
  const double normal = normal_sum.norm();
  const Eigen::Vector3d n = normal_sum / normal;
  // Bristle friction: a tangential spring from the grid point to the stick point, which slides when
  // the spring force exceeds the Coulomb limit.
  const Eigen::Vector3d p = face.at(patch.point);
  if (!patch.in_contact) patch.anchor = p;
  patch.in_contact = true;
  Eigen::Vector3d stretch = p - patch.anchor;
  stretch -= n * n.dot(stretch);
  Eigen::Vector3d v_t = face.velocity(p);
  v_t -= n * n.dot(v_t);
  Eigen::Vector3d tangential = -patch.tangential_stiffness * stretch - patch.tangential_damping * v_t;
  const double limit = terrain_.friction(p.head<2>(), params_.friction) * normal;
  const double magnitude = tangential.norm();
  if (magnitude > limit) {
    tangential *= limit / magnitude;
    const double stretch_norm = stretch.norm();
    if (stretch_norm > 0.0) patch.anchor = p - stretch * std::min(1.0, limit / (patch.tangential_stiffness * stretch_norm));
  }
  const Eigen::Vector3d force = normal_sum + tangential;
  add_force(d, face.body, force, cop);
  patch.force += force;
  patch.centre_of_pressure = cop;
  normal_force_[face.side] += normal;
}

}  // namespace biped
