#include "sim/terrain.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

namespace biped {
namespace {

const double kTan3 = std::tan(3.0 * M_PI / 180.0);

// Features add their heights: steps accumulate, a slope rises over its length and stays level after.
TEST(Terrain, StepsAccumulateAndSlopesRiseLinearly) {
  const Terrain terrain({TerrainFeature::step(1.0, 0.02), TerrainFeature::step(2.0, -0.05),
                         TerrainFeature::slope(3.0, 3.0, 2.0)});
  EXPECT_DOUBLE_EQ(terrain.height({0.5, 0.0}), 0.0);
  EXPECT_DOUBLE_EQ(terrain.height({1.5, 7.0}), 0.02);
  EXPECT_DOUBLE_EQ(terrain.height({2.5, -3.0}), -0.03);
  EXPECT_NEAR(terrain.height({4.0, 0.0}), -0.03 + kTan3, 1e-12);
  EXPECT_NEAR(terrain.height({8.0, 0.0}), -0.03 + 2.0 * kTan3, 1e-12);
  EXPECT_DOUBLE_EQ(Terrain().height({5.0, 1.0}), 0.0);
  // On the slope the normal leans back against the rise; level elsewhere.
  const Eigen::Vector3d n = terrain.surface({4.0, 0.0}).normal();
  EXPECT_NEAR(n.x(), -std::sin(3.0 * M_PI / 180.0), 1e-12);
  EXPECT_NEAR(n.z(), std::cos(3.0 * M_PI / 180.0), 1e-12);
  EXPECT_DOUBLE_EQ(terrain.surface({6.0, 0.0}).normal().z(), 1.0);
  // A step's edge belongs to the side beyond it.
  EXPECT_DOUBLE_EQ(terrain.height({1.0, 0.0}), 0.02);
}

// The lines where the ground is not one plane: one per step (a jump), two per slope (kinks).
TEST(Terrain, LinesAtEdgesAndKinks) {
  const Terrain terrain({TerrainFeature::step(1.0, 0.02), TerrainFeature::slope(3.0, 3.0, 2.0)});
  ASSERT_EQ(terrain.lines().size(), 3u);
  EXPECT_TRUE(terrain.lines()[0].jump);
  EXPECT_DOUBLE_EQ(terrain.lines()[0].offset, 1.0);
  EXPECT_FALSE(terrain.lines()[1].jump);
  EXPECT_DOUBLE_EQ(terrain.lines()[2].offset, 5.0);
}

// The bound on the height near a point is never below the height anywhere within the radius, and
// tight on level ground far from any feature.
TEST(Terrain, MaxHeightWithinBoundsTheHeightsAround) {
  const Terrain terrain({TerrainFeature::step(1.0, 0.05), TerrainFeature::step(1.5, -0.08),
                         TerrainFeature::slope(2.0, -4.0, 1.0)});
  for (double x = -0.5; x < 4.0; x += 0.05) {
    const double radius = 0.2, bound = terrain.max_height_within({x, 0.0}, radius);
    for (double dx = -radius; dx <= radius; dx += 0.01) {
      EXPECT_GE(bound, terrain.height({x + dx, 0.3}) - 1e-12) << x << " " << dx;
    }
  }
  EXPECT_DOUBLE_EQ(terrain.max_height_within({-2.0, 0.0}, 0.5), 0.0);
}

TerrainFeature rectangle(TerrainFeature::Kind kind, Eigen::Vector2d at, double length, double width, double heading_deg) {
  TerrainFeature f;
  f.kind = kind;
  f.at = at;
  f.length = length;
  f.width = width;
  f.heading_deg = heading_deg;
  return f;
}

// Features turned any way in the plane: a step whose edge runs diagonally, a side slope, a box
// turned 90° (its length along y) that stands on the slope, and a friction patch.
TEST(Terrain, FeaturesInThePlaneAddUp) {
  TerrainFeature diagonal = TerrainFeature::step(0.0, 0.05);
  diagonal.at = {1.0, 1.0};
  diagonal.heading_deg = 45.0;  // rises towards +x+y
  TerrainFeature side = TerrainFeature::slope(0.0, 10.0, 1.0);
  side.heading_deg = -90.0;  // rises towards −y from y = 0
  TerrainFeature box = rectangle(TerrainFeature::Kind::Box, {3.0, -0.5}, 1.0, 0.2, 90.0);
  box.height = 0.1;
  TerrainFeature ice = rectangle(TerrainFeature::Kind::Friction, {-2.0, 0.0}, 1.0, 0.5, 0.0);
  ice.friction = 0.1;
  const Terrain terrain({diagonal, side, box, ice});
  EXPECT_NEAR(terrain.height({1.9, 0.0}), 0.0, 1e-12);  // before the diagonal edge (x + y < 2)
  EXPECT_DOUBLE_EQ(terrain.height({0.0, 2.1}), 0.05);
  const double tan10 = std::tan(10.0 * M_PI / 180.0);
  EXPECT_NEAR(terrain.height({-1.0, -0.5}), 0.5 * tan10, 1e-12);
  EXPECT_NEAR(terrain.surface({-1.0, -0.5}).gradient.y(), -tan10, 1e-12);
  // On the box: 1.0 long along y, 0.2 wide along x; on the slope and beyond the diagonal step.
  EXPECT_NEAR(terrain.height({3.05, -0.9}), 0.1 + 0.9 * tan10 + 0.05, 1e-12);
  EXPECT_NEAR(terrain.height({3.15, -0.9}), 0.9 * tan10 + 0.05, 1e-12) << "beyond the box's width";
  EXPECT_DOUBLE_EQ(terrain.friction({-2.4, 0.2}, 0.8), 0.1);
  EXPECT_DOUBLE_EQ(terrain.friction({-2.6, 0.2}, 0.8), 0.8);
  EXPECT_NEAR(terrain.height({-2.4, 0.2}), 0.0, 1e-12) << "a friction patch is level with the ground";
  EXPECT_EQ(terrain.lines().size(), 1u + 2u + 4u);
}

// Friction patches that overlap cannot be combined; ones that only touch, and any other features
// on top of each other, can.
TEST(Terrain, OnlyOverlappingFrictionPatchesConflict) {
  using Kind = TerrainFeature::Kind;
  const TerrainFeature a = rectangle(Kind::Friction, {0.0, 0.0}, 1.0, 1.0, 0.0);
  EXPECT_EQ(Terrain::overlaps({a, rectangle(Kind::Friction, {1.0, 0.0}, 1.0, 1.0, 0.0)}).size(), 0u);
  EXPECT_EQ(Terrain::overlaps({a, rectangle(Kind::Box, {0.2, 0.0}, 1.0, 1.0, 0.0)}).size(), 0u);
  // Turned 45°: its corner reaches into a's square, though their centres are 1.2 m apart in x.
  const auto found = Terrain::overlaps({a, TerrainFeature::step(0.0, 0.1), rectangle(Kind::Friction, {1.2, 0.0}, 1.0, 1.0, 45.0)});
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].first, 0);
  EXPECT_EQ(found[0].second, 2);
  EXPECT_EQ(Terrain::overlaps({a, rectangle(Kind::Friction, {1.3, 0.0}, 1.0, 1.0, 45.0)}).size(), 0u);
  EXPECT_EQ(Terrain::overlaps({a, rectangle(Kind::Friction, {1.25, 0.0}, 0.5, 0.5, 45.0)}).size(), 0u);
}

// A feature reshapes the ground inside an outline where its far side (a step's, a slope's) or its
// rectangle (a box's) reaches into it; touching along an edge, a flat feature or friction does not.
TEST(Terrain, ReshapesGroundWithinAnOutlineWhereItReachesIn) {
  using Kind = TerrainFeature::Kind;
  const std::array<Eigen::Vector2d, 4> sole = {Eigen::Vector2d(-0.1, 0.05), Eigen::Vector2d(0.1, 0.05),
                                               Eigen::Vector2d(0.1, 0.15), Eigen::Vector2d(-0.1, 0.15)};
  EXPECT_TRUE(Terrain::reshapes_ground_within(TerrainFeature::step(0.05, 0.02), sole));
  EXPECT_TRUE(Terrain::reshapes_ground_within(TerrainFeature::step(-0.5, -0.02), sole));
  EXPECT_FALSE(Terrain::reshapes_ground_within(TerrainFeature::step(0.1, 0.02), sole)) << "touching";
  EXPECT_FALSE(Terrain::reshapes_ground_within(TerrainFeature::step(0.05, 0.0), sole)) << "no step";
  EXPECT_FALSE(Terrain::reshapes_ground_within(TerrainFeature::slope(0.3, 5.0, 2.0), sole));
  // A slope starting 1.4 m ahead but rising sideways at 100°: its start line passes y = −0.25 at
  // x = 0, so the sole stands beyond it; at 80° the line passes y = +0.25 and the sole is short of it.
  TerrainFeature side_slope = TerrainFeature::slope(1.4, 3.0, 2.0);
  side_slope.heading_deg = 100.0;
  EXPECT_TRUE(Terrain::reshapes_ground_within(side_slope, sole));
  side_slope.heading_deg = 80.0;
  EXPECT_FALSE(Terrain::reshapes_ground_within(side_slope, sole));
  side_slope.at.x() = 0.6;  // the line passes y = 0.11 at x = 0: through the sole
  EXPECT_TRUE(Terrain::reshapes_ground_within(side_slope, sole));

  TerrainFeature box = rectangle(Kind::Box, {0.2, 0.1}, 0.2, 0.2, 0.0);
  box.height = 0.03;
  EXPECT_FALSE(Terrain::reshapes_ground_within(box, sole)) << "touching at x = 0.1";
  box.at.x() = 0.19;
  EXPECT_TRUE(Terrain::reshapes_ground_within(box, sole));
  box.height = 0.0;
  EXPECT_FALSE(Terrain::reshapes_ground_within(box, sole));
  EXPECT_FALSE(Terrain::reshapes_ground_within(rectangle(Kind::Friction, {0.0, 0.1}, 1.0, 1.0, 0.0), sole));
  // Turned 45°: the square around it overlaps the sole, the box itself does not, until it comes closer.
  TerrainFeature turned = rectangle(Kind::Box, {0.2, 0.25}, 0.2, 0.2, 45.0);
  turned.height = 0.03;
  EXPECT_FALSE(Terrain::reshapes_ground_within(turned, sole));
  turned.at = {0.15, 0.2};
  EXPECT_TRUE(Terrain::reshapes_ground_within(turned, sole));
}

// The height bound near a box: never below the height within the radius, around raised and sunk boxes.
TEST(Terrain, MaxHeightWithinBoundsBoxes) {
  TerrainFeature raised = rectangle(TerrainFeature::Kind::Box, {1.0, 0.0}, 0.6, 0.3, 30.0);
  raised.height = 0.04;
  TerrainFeature pit = rectangle(TerrainFeature::Kind::Box, {2.0, 0.5}, 1.0, 1.0, 0.0);
  pit.height = -0.05;
  const Terrain terrain({raised, pit});
  const double radius = 0.15;
  for (double x = 0.0; x < 3.0; x += 0.05) {
    for (double y = -0.5; y < 1.2; y += 0.05) {
      const double bound = terrain.max_height_within({x, y}, radius);
      for (double a = 0.0; a < 2.0 * M_PI; a += 0.3) {
        for (double r : {0.0, 0.5 * radius, radius}) {
          EXPECT_GE(bound, terrain.height({x + r * std::cos(a), y + r * std::sin(a)}) - 1e-12) << x << " " << y;
        }
      }
    }
  }
  EXPECT_DOUBLE_EQ(terrain.max_height_within({2.0, 0.5}, radius), -0.05);
}

}  // namespace
}  // namespace biped
