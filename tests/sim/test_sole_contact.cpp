#include "sim/sole_contact.hpp"

#include <gtest/gtest.h>

#include "sim/simulation.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

void hold_stand_pose(Simulation& sim, const RobotModel& model, int cycles) {
  JointCommand hold(model.num_joints());
  hold.position = model.stand_pose();
  for (int i = 0; i < cycles; ++i) {
    sim.command(hold);
    sim.advance();
  }
}

// The sole sinks by the load it carries divided by its stiffness (N/m, robots.md).
TEST(SoleContact, DeflectionFollowsThePhysicalStiffness) {
  const RobotModel model = test::load_model("lola");
  for (double stiffness : {3e5, 5e5}) {
    SimulationParams p;
    p.world.robot_mjcf = test::model_path("lola");
    p.sole_contact.stiffness_per_foot = stiffness;
    Simulation sim(p, model);
    hold_stand_pose(sim, model, 1500);
    for (Side side : kSides) {
      double depth_sum = 0.0;
      int n = 0;
      const mjData* d = sim.data();
      for (const auto& c : sim.sole_contact().points()) {
        if (c.side != index_of(side)) continue;
        const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> R(d->xmat + 9 * c.body);
        const Eigen::Vector3d p_world = Eigen::Vector3d(d->xpos + 3 * c.body) + R * c.local;
        depth_sum += -p_world.z();
        ++n;
      }
      const double load = sim.sole_contact().normal_force(side);
      EXPECT_NEAR(load, 0.5 * 9.81 * sim.plant().total_mass(), 0.05 * 9.81 * sim.plant().total_mass());
      EXPECT_NEAR(depth_sum / n, load / stiffness, 0.1 * load / stiffness) << stiffness;
    }
  }
}

// Coulomb friction: a steady 30 N horizontal push on the pelvis of the standing robot (weight ~390 N)
// is held by friction with μ = 0.8, but exceeds μ·W with μ = 0.05 and the feet slide.
TEST(SoleContact, FeetStickInsideTheFrictionConeAndSlideOutside) {
  const RobotModel model = test::load_model("johnnie");
  auto foot_travel = [&](double friction) {
    SimulationParams p;
    p.world.robot_mjcf = test::model_path("johnnie");
    p.sole_contact.friction = friction;
    p.pushes.push_back({0.2, 1.0, "pelvis", Eigen::Vector3d(30.0, 0.0, 0.0)});
    Simulation sim(p, model);
    hold_stand_pose(sim, model, 100);
    const double x0 = sim.data()->xpos[3 * model.foot(Side::Left).body];
    hold_stand_pose(sim, model, 1000);
    return std::abs(sim.data()->xpos[3 * model.foot(Side::Left).body] - x0);
  };
  EXPECT_LT(foot_travel(0.8), 0.001);
  EXPECT_GT(foot_travel(0.05), 0.02);
}

// A swing foot above the ground feels nothing.
TEST(SoleContact, NoForceWithoutPenetration) {
  const RobotModel model = test::load_model("johnnie");
  SimulationParams p;
  p.world.robot_mjcf = test::model_path("johnnie");
  Simulation sim(p, model);
  SoleContact contact(sim.plant(), {{TerrainFeature::Kind::Step, -10.0, -0.1, 0.0, 0.0}}, {});
  mjData* d = mj_makeData(sim.plant().mj());
  mju_copy(d->qpos, sim.data()->qpos, sim.plant().mj()->nq);
  mj_forward(sim.plant().mj(), d);
  contact.apply(sim.plant().mj(), d);
  EXPECT_EQ(contact.normal_force(Side::Left), 0.0);
  for (int i = 0; i < 6 * sim.plant().mj()->nbody; ++i) EXPECT_EQ(d->xfrc_applied[i], 0.0);
  mj_deleteData(d);
}

}  // namespace
}  // namespace biped
