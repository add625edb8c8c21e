#include "sim/world.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "model/robot_model.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

TerrainFeature box(double x, double y, double length, double width, double heading_deg, double height) {
  TerrainFeature f;
  f.kind = TerrainFeature::Kind::Box;
  f.at = {x, y};
  f.length = length;
  f.width = width;
  f.heading_deg = heading_deg;
  f.height = height;
  return f;
}

// The compiled terrain's cells tile the ground area, and each one's top face lies on the terrain's
// surface with the terrain's friction there, features turned any way and on top of each other
// included. (Checked on the meshes' vertices: mj_ray misses mesh geoms in the robot files' default
// class, whose density is 0, on 2.2.2.)
TEST(World, TerrainGeometryMatchesTheSurface) {
  WorldSpec spec;
  spec.robot_mjcf = test::model_path("johnnie");
  TerrainFeature side_slope = TerrainFeature::slope(0.0, 5.0, 1.5);
  side_slope.at = {0.0, -1.0};
  side_slope.heading_deg = 90.0;  // rising towards +y
  TerrainFeature diagonal_step = TerrainFeature::step(2.0, -0.04);
  diagonal_step.heading_deg = 30.0;
  TerrainFeature ice;
  ice.kind = TerrainFeature::Kind::Friction;
  ice.at = {-1.0, 0.0};
  ice.length = 0.8;
  ice.width = 0.6;
  ice.friction = 0.1;
  spec.terrain = {TerrainFeature::step(1.0, 0.02), side_slope, diagonal_step, box(1.5, 0.3, 0.6, 0.3, 45.0, 0.03),
                  box(1.5, 0.3, 0.2, 0.2, 0.0, 0.02), ice};
  const Terrain terrain(spec.terrain);
  mjModel* m = build_world(spec);
  ASSERT_NE(m, nullptr);
  mjData* d = mj_makeData(m);
  mj_forward(m, d);
  double total_area = 0.0;
  int cells = 0, on_ice = 0;
  for (int g = 0; g < m->ngeom; ++g) {
    if (m->geom_bodyid[g] != 0 || m->geom_type[g] != mjGEOM_MESH) continue;
    const int mesh = m->geom_dataid[g];
    const Eigen::Map<const Eigen::Vector3d> origin(d->geom_xpos + 3 * g);
    const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> R(d->geom_xmat + 9 * g);
    std::vector<Eigen::Vector3d> vertices;
    double bottom = INFINITY;
    for (int v = 0; v < m->mesh_vertnum[mesh]; ++v) {
      const float* p = m->mesh_vert + 3 * (m->mesh_vertadr[mesh] + v);
      vertices.push_back(origin + R * Eigen::Vector3d(p[0], p[1], p[2]));
      bottom = std::min(bottom, vertices.back().z());
    }
    std::vector<Eigen::Vector3d> top;
    for (const Eigen::Vector3d& v : vertices) {
      if (v.z() > bottom + 0.25) top.push_back(v);
    }
    ASSERT_GE(top.size(), 3u);
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& v : top) mean += v;
    mean /= static_cast<double>(top.size());
    // The ground is one plane over the cell: its height at the vertices' mean is their mean height.
    EXPECT_NEAR(mean.z(), terrain.height(mean.head<2>()), 1e-5) << mean.transpose();
    EXPECT_NEAR(m->geom_friction[3 * g], terrain.friction(mean.head<2>(), spec.ground_friction), 1e-6);
    if (m->geom_friction[3 * g] < 0.5) ++on_ice;
    std::sort(top.begin(), top.end(), [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
      return std::atan2(a.y() - mean.y(), a.x() - mean.x()) < std::atan2(b.y() - mean.y(), b.x() - mean.x());
    });
    for (std::size_t k = 0; k < top.size(); ++k) {
      const Eigen::Vector3d& a = top[k];
      const Eigen::Vector3d& b = top[(k + 1) % top.size()];
      total_area += 0.5 * (a.x() * b.y() - b.x() * a.y());
    }
    ++cells;
  }
  EXPECT_GT(cells, 6);
  EXPECT_GE(on_ice, 1);
  EXPECT_NEAR(total_area, 120.0 * 40.0, 1e-3) << "the cells tile the ground, without gaps or overlaps";
  mj_deleteData(d);
  mj_deleteModel(m);
}

TEST(World, ModelErrorScalesTheUpperBody) {
  WorldSpec spec;
  spec.robot_mjcf = test::model_path("lola");
  mjModel* nominal = build_world(spec);
  spec.model_error.upper_body_mass_scale = 0.9;
  spec.model_error.upper_body_com_offset = Eigen::Vector3d(0.02, 0, 0);
  mjModel* changed = build_world(spec);
  const int ub = mj_name2id(nominal, mjOBJ_BODY, "upper_body");
  EXPECT_NEAR(changed->body_mass[ub], 0.9 * nominal->body_mass[ub], 1e-12);
  EXPECT_NEAR(changed->body_ipos[3 * ub] - nominal->body_ipos[3 * ub], 0.02, 1e-12);
  mj_deleteModel(nominal);
  mj_deleteModel(changed);
}

TEST(World, MissingRobotFileIsAModelError) {
  WorldSpec spec;
  spec.robot_mjcf = "/nonexistent.xml";
  EXPECT_THROW(build_world(spec), ModelError);
}

}  // namespace
}  // namespace biped
