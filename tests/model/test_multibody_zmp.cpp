#include "model/multibody_zmp.hpp"

#include <gtest/gtest.h>

#include "test_support.hpp"

namespace biped {
namespace {

// Standing still, the ZMP is the ground projection of the CoM.
TEST(MultibodyZmp, StaticPoseGivesTheCoMProjection) {
  const RobotModel model = test::load_model("lola");
  RobotData data(model);
  const Eigen::VectorXd q = model.stand_qpos();
  const Eigen::Vector2d zmp = multibody_zmp(model, data, q, q, q, 0.001);
  mjData* d = data.mj();
  mj_forward(model.mj(), d);
  EXPECT_NEAR(zmp.x(), d->subtree_com[3 * model.pelvis_body()], 1e-9);
  EXPECT_NEAR(zmp.y(), d->subtree_com[3 * model.pelvis_body() + 1], 1e-9);
}

// Accelerating the whole robot forward (base translation only) shifts the ZMP back by z_CoM·a/g.
TEST(MultibodyZmp, ForwardAccelerationShiftsTheZmpBack) {
  const RobotModel model = test::load_model("johnnie");
  RobotData data(model);
  const double dt = 0.01, a = 1.0;
  Eigen::VectorXd q0 = model.stand_qpos(), q1 = q0, q2 = q0;
  q0[0] -= 0.0;
  q1[0] += 0.5 * a * dt * dt;
  q2[0] += 0.5 * a * 4 * dt * dt;  // x(t) = a t²/2 at t = 0, dt, 2 dt
  const Eigen::Vector2d zmp = multibody_zmp(model, data, q0, q1, q2, dt);
  mjData* d = data.mj();
  const double com_x = d->subtree_com[3 * model.pelvis_body()], com_z = d->subtree_com[3 * model.pelvis_body() + 2];
  EXPECT_NEAR(zmp.x(), com_x - com_z * a / 9.81, 1e-6);
}

}  // namespace
}  // namespace biped
