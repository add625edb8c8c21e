#include "sim/world.hpp"

#include <gtest/gtest.h>

#include "model/robot_model.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

TEST(Terrain, StepsAccumulateAndSlopesRiseLinearly) {
  std::vector<TerrainFeature> terrain(3);
  terrain[0] = {TerrainFeature::Kind::Step, 1.0, 0.02, 0.0, 0.0};
  terrain[1] = {TerrainFeature::Kind::Step, 2.0, -0.05, 0.0, 0.0};
  terrain[2] = {TerrainFeature::Kind::Slope, 3.0, 0.0, 3.0, 2.0};
  EXPECT_DOUBLE_EQ(terrain_height(terrain, 0.5), 0.0);
  EXPECT_DOUBLE_EQ(terrain_height(terrain, 1.5), 0.02);
  EXPECT_DOUBLE_EQ(terrain_height(terrain, 2.5), -0.03);
  EXPECT_NEAR(terrain_height(terrain, 4.0), -0.03 + std::tan(3.0 * M_PI / 180.0), 1e-12);
  EXPECT_NEAR(terrain_height(terrain, 8.0), -0.03 + 2.0 * std::tan(3.0 * M_PI / 180.0), 1e-12);
  EXPECT_DOUBLE_EQ(terrain_height({}, 5.0), 0.0);
}

// The compiled terrain blocks' top faces lie on the profile: a ray cast down finds the profile height.
TEST(World, TerrainGeometryMatchesTheProfile) {
  WorldSpec spec;
  spec.robot_mjcf = test::model_path("johnnie");
  spec.terrain = {{TerrainFeature::Kind::Step, 1.0, 0.02, 0.0, 0.0}, {TerrainFeature::Kind::Slope, 2.0, 0.0, 5.0, 1.5}};
  mjModel* m = build_world(spec);
  ASSERT_NE(m, nullptr);
  mjData* d = mj_makeData(m);
  mj_forward(m, d);
  for (double x : {0.5, 1.5, 2.3, 3.2, 4.0}) {
    const mjtNum start[3] = {x, 3.0, 1.0}, down[3] = {0, 0, -1};
    int geom = -1;
    const mjtNum distance = mj_ray(m, d, start, down, nullptr, 1, -1, &geom);
    ASSERT_GE(geom, 0) << x;
    EXPECT_NEAR(1.0 - distance, terrain_height(spec.terrain, x), 1e-9) << x;
  }
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
