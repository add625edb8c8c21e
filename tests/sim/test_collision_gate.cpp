#include "sim/collision_gate.hpp"

#include <gtest/gtest.h>

#include "sim/simulation.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

// JOHNNIE with joint servos too soft to carry it: it collapses onto the ground (knees, hands).
SimulationParams collapsing(bool gate) {
  SimulationParams p;
  p.world.robot_mjcf = test::model_path("johnnie");
  p.world.terrain = {TerrainFeature::step(0.3, 0.03)};
  p.drives.bandwidth_hz = 0.1;
  p.pushes.push_back({0.2, 0.3, "upper_body", Eigen::Vector3d(150.0, 0.0, 0.0)});  // forwards, onto the step
  p.collision_gate = gate;
  return p;
}

// The gate only skips collision detection that would find nothing: the same run, bit for bit, with
// MuJoCo's collision detection in every step; and it was shut while the robot stood.
TEST(CollisionGate, ARunIsTheSameWithCollisionDetectionEveryStep) {
  const RobotModel model = test::load_model("johnnie");
  Simulation gated(collapsing(true), model), every_step(collapsing(false), model);
  JointCommand hold(model.num_joints());
  hold.position = model.stand_pose();
  int steps_shut = 0, steps_with_contacts = 0;
  for (int i = 0; i < 2500; ++i) {
    for (Simulation* sim : {&gated, &every_step}) {
      sim->command(hold);
      sim->advance();
    }
    if (!gated.collision_gate().open()) ++steps_shut;
    if (every_step.data()->ncon > 0) ++steps_with_contacts;
    ASSERT_EQ(gated.data()->ncon, every_step.data()->ncon) << "at step " << i;
    for (int k = 0; k < model.mj()->nq; ++k) {
      ASSERT_EQ(gated.data()->qpos[k], every_step.data()->qpos[k]) << "qpos " << k << " at step " << i;
    }
  }
  ASSERT_NE(every_step.fall_reason(), nullptr) << "the robot was meant to collapse";
  EXPECT_GT(steps_with_contacts, 100) << "bodies other than the soles touched the ground";
  EXPECT_GT(steps_shut, 100) << "the gate skipped collision detection while the robot stood";
}

// Standing on flat ground: every robot geom is well above the ground, so MuJoCo's collision detection
// is off; lowered into the ground it is on.
TEST(CollisionGate, ShutWhileStandingOpenNearTheGround) {
  const RobotModel model = test::load_model("lola");
  SimulationParams p;
  p.world.robot_mjcf = test::model_path("lola");
  Simulation sim(p, model);
  mjModel* m = mj_copyModel(nullptr, sim.plant().mj());
  mjData* d = mj_makeData(m);
  mju_copy(d->qpos, sim.data()->qpos, m->nq);
  mj_forward(m, d);
  CollisionGate gate(m, Terrain());
  gate.reset(m, d);
  gate.update(m, d);
  EXPECT_FALSE(gate.open());
  EXPECT_TRUE(m->opt.disableflags & mjDSBL_CONTACT);
  d->qpos[2] -= 0.5;  // knees in the ground
  mj_forward(m, d);
  gate.update(m, d);
  EXPECT_TRUE(gate.open());
  EXPECT_FALSE(m->opt.disableflags & mjDSBL_CONTACT);
  mj_deleteData(d);
  mj_deleteModel(m);
}

}  // namespace
}  // namespace biped
