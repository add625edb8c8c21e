#include "sim/terrain.hpp"

#include <algorithm>
#include <cmath>

namespace biped {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

}  // namespace

TerrainFeature TerrainFeature::step(double x, double height) {
  TerrainFeature f;
  f.kind = Kind::Step;
  f.at = Eigen::Vector2d(x, 0.0);
  f.height = height;
  return f;
}

TerrainFeature TerrainFeature::slope(double x, double angle_deg, double length) {
  TerrainFeature f;
  f.kind = Kind::Slope;
  f.at = Eigen::Vector2d(x, 0.0);
  f.angle_deg = angle_deg;
  f.length = length;
  return f;
}

std::array<Eigen::Vector2d, 4> Terrain::corners(const TerrainFeature& f) {
  const double heading = f.heading_deg * kDegToRad;
  const Eigen::Vector2d along = 0.5 * f.length * Eigen::Vector2d(std::cos(heading), std::sin(heading));
  const Eigen::Vector2d across = 0.5 * f.width * Eigen::Vector2d(-std::sin(heading), std::cos(heading));
  return {f.at - along - across, f.at + along - across, f.at + along + across, f.at - along + across};
}

bool Terrain::Placed::covers(const Eigen::Vector2d& p) const {
  const Eigen::Vector2d r = p - feature.at;
  const Eigen::Vector2d across(-direction.y(), direction.x());
  return std::abs(direction.dot(r)) <= 0.5 * feature.length && std::abs(across.dot(r)) <= 0.5 * feature.width;
}

namespace {

// Two convex quadrilaterals (corners in order) are apart, or only touch, when an edge direction of
// one of them separates them (separating axes).
bool separated(const std::array<Eigen::Vector2d, 4>& a, const std::array<Eigen::Vector2d, 4>& b) {
  for (const auto* shape : {&a, &b}) {
    for (int e = 0; e < 4; ++e) {
      const Eigen::Vector2d edge = (*shape)[(e + 1) % 4] - (*shape)[e];
      const Eigen::Vector2d axis(-edge.y(), edge.x());
      double a_min = INFINITY, a_max = -INFINITY, b_min = INFINITY, b_max = -INFINITY;
      for (int k = 0; k < 4; ++k) {
        a_min = std::min(a_min, axis.dot(a[k]));
        a_max = std::max(a_max, axis.dot(a[k]));
        b_min = std::min(b_min, axis.dot(b[k]));
        b_max = std::max(b_max, axis.dot(b[k]));
      }
      if (a_max <= b_min || b_max <= a_min) return true;
    }
  }
  return false;
}

}  // namespace

std::vector<Terrain::Overlap> Terrain::overlaps(const std::vector<TerrainFeature>& features) {
  std::vector<Overlap> found;
  for (int i = 0; i < static_cast<int>(features.size()); ++i) {
    for (int j = i + 1; j < static_cast<int>(features.size()); ++j) {
      if (features[i].kind != TerrainFeature::Kind::Friction || features[j].kind != TerrainFeature::Kind::Friction) {
        continue;
      }
      if (!separated(corners(features[i]), corners(features[j]))) found.push_back({i, j});
    }
  }
  return found;
}

bool Terrain::reshapes_ground_within(const TerrainFeature& f, const std::array<Eigen::Vector2d, 4>& outline) {
  switch (f.kind) {
    case TerrainFeature::Kind::Step:
    case TerrainFeature::Kind::Slope: {
      if ((f.kind == TerrainFeature::Kind::Step ? f.height : f.angle_deg) == 0.0) return false;
      const double heading = f.heading_deg * kDegToRad;
      const Eigen::Vector2d rising(std::cos(heading), std::sin(heading));
      const double start = rising.dot(f.at);
      for (const Eigen::Vector2d& corner : outline) {
        if (rising.dot(corner) > start + 1e-9) return true;
      }
      return false;
    }
    case TerrainFeature::Kind::Box:
      return f.height != 0.0 && !separated(corners(f), outline);
    case TerrainFeature::Kind::Friction:
      return false;
  }
  return false;
}

Terrain::Terrain(const std::vector<TerrainFeature>& features) : features_(features) {
  for (const TerrainFeature& f : features) {
    const double heading = f.heading_deg * kDegToRad;
    Placed p{Eigen::Vector2d(std::cos(heading), std::sin(heading)), 0.0, f, std::tan(f.angle_deg * kDegToRad)};
    p.offset = p.direction.dot(f.at);
    placed_.push_back(p);
    switch (f.kind) {
      case TerrainFeature::Kind::Step:
        lines_.push_back({p.direction, p.offset, true});
        break;
      case TerrainFeature::Kind::Slope:
        lines_.push_back({p.direction, p.offset, false});
        lines_.push_back({p.direction, p.offset + f.length, false});
        break;
      case TerrainFeature::Kind::Box: {
        const Eigen::Vector2d across(-p.direction.y(), p.direction.x());
        lines_.push_back({p.direction, p.offset - 0.5 * f.length, true});
        lines_.push_back({p.direction, p.offset + 0.5 * f.length, true});
        lines_.push_back({across, across.dot(f.at) - 0.5 * f.width, true});
        lines_.push_back({across, across.dot(f.at) + 0.5 * f.width, true});
        break;
      }
      case TerrainFeature::Kind::Friction:
        break;
    }
  }
}

double Terrain::friction(const Eigen::Vector2d& point, double elsewhere) const {
  for (const Placed& p : placed_) {
    if (p.feature.kind == TerrainFeature::Kind::Friction && p.covers(point)) return p.feature.friction;
  }
  return elsewhere;
}

Terrain::Surface Terrain::surface(const Eigen::Vector2d& point) const {
  Surface s;
  for (const Placed& p : placed_) {
    const double along = p.direction.dot(point) - p.offset;  // distance beyond the edge or start line
    switch (p.feature.kind) {
      case TerrainFeature::Kind::Step:
        if (along >= 0.0) s.height += p.feature.height;
        break;
      case TerrainFeature::Kind::Slope:
        if (along > 0.0) {
          s.height += p.rise_per_metre * std::min(along, p.feature.length);
          if (along < p.feature.length) s.gradient += p.rise_per_metre * p.direction;
        }
        break;
      case TerrainFeature::Kind::Box:
        if (p.covers(point)) s.height += p.feature.height;
        break;
      case TerrainFeature::Kind::Friction:
        break;
    }
  }
  return s;
}

double Terrain::max_height_within(const Eigen::Vector2d& point, double radius) const {
  // The sum of each feature's highest contribution within the disc bounds the highest sum.
  double highest = 0.0;
  for (const Placed& p : placed_) {
    const double along = p.direction.dot(point) - p.offset;
    switch (p.feature.kind) {
      case TerrainFeature::Kind::Step: {
        const bool reaches_beyond = along + radius >= 0.0, reaches_before = along - radius < 0.0;
        highest += p.feature.height > 0.0 ? (reaches_beyond ? p.feature.height : 0.0)
                                          : (reaches_before ? 0.0 : p.feature.height);
        break;
      }
      case TerrainFeature::Kind::Slope: {
        auto ramp = [&](double s) { return p.rise_per_metre * std::clamp(s, 0.0, p.feature.length); };
        highest += std::max(ramp(along - radius), ramp(along + radius));
        break;
      }
      case TerrainFeature::Kind::Box: {
        // In the box's frame: the disc reaches onto the box, and it lies wholly on it.
        const Eigen::Vector2d r = point - p.feature.at;
        const Eigen::Vector2d local(p.direction.dot(r), p.direction.x() * r.y() - p.direction.y() * r.x());
        const double half_l = 0.5 * p.feature.length, half_w = 0.5 * p.feature.width;
        const double outside = std::hypot(std::max(0.0, std::abs(local.x()) - half_l),
                                          std::max(0.0, std::abs(local.y()) - half_w));
        const bool reaches = outside <= radius;
        const bool within = std::abs(local.x()) + radius <= half_l && std::abs(local.y()) + radius <= half_w;
        highest += p.feature.height > 0.0 ? (reaches ? p.feature.height : 0.0) : (within ? p.feature.height : 0.0);
        break;
      }
      case TerrainFeature::Kind::Friction:
        break;
    }
  }
  return highest;
}

}  // namespace biped
