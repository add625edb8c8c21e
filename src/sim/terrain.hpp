#pragma once
// The ground the simulated robot walks on, unknown to the controller: a level plane at height 0 to
// which every terrain feature adds its own height. A step adds `height` beyond its edge line; a slope
// adds a ramp rising at `angle` beyond its start line, level again after `length`; a box (a plank,
// a block) adds `height` on a rectangle. Features that overlap add up (a step on a slope is a step in
// the slope, a plank on a box stands on it). A friction patch changes the friction coefficient on a
// rectangle; friction patches must not overlap each other (check_overlaps). One description for
// everything that touches the ground: the soles (height, normal, friction and the lines where the
// ground jumps or bends), MuJoCo's geoms for the other bodies and the drawing, fall detection and
// the collision gate.
#include <Eigen/Core>
#include <array>
#include <vector>

namespace biped {

struct TerrainFeature {
  enum class Kind { Step, Slope, Box, Friction };
  Kind kind = Kind::Step;
  // Step: a point of its edge; slope: of its start line; box and friction patch: the centre.
  Eigen::Vector2d at = Eigen::Vector2d::Zero();
  // Step and slope: direction in which they rise, the edge's normal (0: +x, 90: +y); box and
  // friction patch: direction of their length.
  double heading_deg = 0.0;
  double height = 0.0;       // step: change of ground level beyond the edge; box: its height [m] (negative: down)
  double angle_deg = 0.0;    // slope: inclination, positive rising along the heading
  double length = 2.0;       // slope: horizontal run [m], level again beyond it; box, friction patch: length [m]
  double width = 1.0;        // box, friction patch: width across the heading [m]
  double friction = 0.8;     // friction patch: Coulomb coefficient on it

  // Edges across the x axis, as the scenario keys {type: step, x, height} and {type: slope, x, ...}.
  static TerrainFeature step(double x, double height);
  static TerrainFeature slope(double x, double angle_deg, double length);
};

class Terrain {
 public:
  Terrain() = default;  // level ground
  explicit Terrain(const std::vector<TerrainFeature>& features);

  const std::vector<TerrainFeature>& features() const { return features_; }
  // Pairs of features that cannot be combined: friction patches that overlap (which friction would
  // hold there?). Empty when the features are fine.
  struct Overlap {
    int first, second;
  };
  static std::vector<Overlap> overlaps(const std::vector<TerrainFeature>& features);
  // Whether feature f changes the ground's height or slope anywhere inside the convex quadrilateral
  // `outline` (a sole seen from above): the far side of a step's edge or a slope's start line
  // reaching into it, a box overlapping it. Touching along an edge does not count; friction patches
  // never do.
  static bool reshapes_ground_within(const TerrainFeature& f, const std::array<Eigen::Vector2d, 4>& outline);

  // Friction coefficient at p: a patch's, or `elsewhere`.
  double friction(const Eigen::Vector2d& p, double elsewhere) const;
  // The corners of a box's or friction patch's rectangle (counter-clockwise).
  static std::array<Eigen::Vector2d, 4> corners(const TerrainFeature& f);

  // Ground height [m] at p = (x, y) and its gradient (∂z/∂x, ∂z/∂y); on an edge, the side beyond it.
  struct Surface {
    double height = 0.0;
    Eigen::Vector2d gradient = Eigen::Vector2d::Zero();
    Eigen::Vector3d normal() const { return Eigen::Vector3d(-gradient.x(), -gradient.y(), 1.0).normalized(); }
  };
  Surface surface(const Eigen::Vector2d& p) const;
  double height(const Eigen::Vector2d& p) const { return surface(p).height; }
  // No ground within `radius` of p (horizontally) is higher than this.
  double max_height_within(const Eigen::Vector2d& p, double radius) const;

  // A line across which the ground is not one plane, {p : normal·p = offset} (normal a unit vector):
  // an edge where its height jumps, or a kink where its slope changes (a box's four edges are whole
  // lines here: beyond the box they cross level ground, which is one plane on both sides).
  struct Line {
    Eigen::Vector2d normal;
    double offset;
    bool jump;
  };
  const std::vector<Line>& lines() const { return lines_; }

 private:
  struct Placed {
    Eigen::Vector2d direction;  // unit vector of the heading
    double offset;              // direction·at
    TerrainFeature feature;
    double rise_per_metre;      // slope: tan(angle)
    // Box, friction patch: whether p lies on the rectangle (edges included).
    bool covers(const Eigen::Vector2d& p) const;
  };
  std::vector<TerrainFeature> features_;
  std::vector<Placed> placed_;
  std::vector<Line> lines_;
};

}  // namespace biped
