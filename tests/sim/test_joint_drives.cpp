#include "sim/joint_drives.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>

#include "sim/simulation.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

// The torque the drive of MuJoCo joint `joint` applies (its actuator's control times its gear).
double applied_torque(const mjModel* m, const mjData* d, int joint) {
  for (int a = 0; a < m->nu; ++a) {
    if (m->actuator_trnid[2 * a] == joint) return d->ctrl[a] * m->actuator_gear[6 * a];
  }
  ADD_FAILURE() << "no actuator drives joint " << joint;
  return 0.0;
}

// Gains follow from the loop bandwidths and the inertia each joint sees in the stand pose.
TEST(JointDrives, GainsFollowTheLoopBandwidths) {
  const RobotModel model = test::load_model("lola");
  DriveParams params;
  params.bandwidth_hz = 20.0;
  params.velocity_loop_ratio = 5.0;
  params.integral_ratio = 0.2;
  const JointDrives drives(model, params);
  RobotData data(model);
  const mjModel* m = model.mj();
  Eigen::Map<Eigen::VectorXd>(data.mj()->qpos, m->nq) = model.stand_qpos();
  mj_forward(m, data.mj());
  Eigen::MatrixXd M(m->nv, m->nv);
  mj_fullM(m, M.data(), data.mj()->qM);
  const double omega_p = 2 * M_PI * 20.0, omega_v = 5.0 * omega_p;
  EXPECT_NEAR(drives.position_gain(), omega_p, 1e-12);
  const Eigen::MatrixXd M_inverse = M.inverse();
  for (int i = 0; i < model.num_joints(); ++i) {
    const int dof = model.joints()[i].dof_adr;
    const double inertia = 1.0 / M_inverse(dof, dof);
    EXPECT_GT(inertia, m->dof_armature[dof]) << "rotor inertia is part of what the drive moves";
    EXPECT_NEAR(drives.velocity_gain()[i] / inertia, omega_v, 1e-9 * omega_v);
    EXPECT_NEAR(drives.integral_gain()[i] / drives.velocity_gain()[i], 0.2 * omega_v, 1e-9 * omega_v);
  }
}

TEST(JointDrives, TorqueSaturatesAtTheDriveLimit) {
  const RobotModel model = test::load_model("lola");
  JointDrives drives(model, {});
  RobotData data(model);
  const mjModel* m = model.mj();
  Eigen::Map<Eigen::VectorXd>(data.mj()->qpos, m->nq) = model.stand_qpos();
  Eigen::VectorXd far = model.stand_pose().array() + 1.0;
  drives.set_targets(far, 0.001);
  drives.set_targets(far, 0.001);  // same target twice: no velocity reference
  drives.apply(m, data.mj(), 0.001);
  for (int i = 0; i < model.num_joints(); ++i) {
    const JointInfo& j = model.joints()[i];
    EXPECT_NEAR(std::abs(applied_torque(m, data.mj(), j.mj_joint)), j.torque_limit, 1e-9) << j.name;
  }
}

// Step response of one joint of the standing robot: a position loop of bandwidth ω behaves like a
// first-order lag, 10-90 % rise time 2.2/ω, so 15-25 Hz means 14-23 ms.
TEST(JointDrives, StepResponseRiseTimeMatchesTheBandwidth) {
  const RobotModel model = test::load_model("lola");
  SimulationParams p;
  p.world.robot_mjcf = test::model_path("lola");
  p.drives.bandwidth_hz = 20.0;
  Simulation sim(p, model);
  JointCommand cmd(model.num_joints());
  cmd.position = model.stand_pose();
  for (int i = 0; i < 300; ++i) {
    sim.command(cmd);
    sim.advance();
  }
  const int elbow = model.joint_index("left_elbow");
  const int adr = model.joints()[elbow].qpos_adr;
  const double start = sim.data()->qpos[adr];
  const double step = -0.2;
  cmd.position[elbow] += step;
  sim.command(cmd);
  sim.command(cmd);  // a pure position step, no velocity reference
  double t10 = -1, t90 = -1;
  for (int i = 1; i <= 300; ++i) {
    sim.advance();
    const double progress = (sim.data()->qpos[adr] - start) / step;
    if (t10 < 0 && progress >= 0.1) t10 = i * 1e-3;
    if (t90 < 0 && progress >= 0.9) t90 = i * 1e-3;
  }
  ASSERT_GT(t90, 0.0) << "the joint never reached 90 % of the step";
  const double rise = t90 - t10;
  EXPECT_GT(rise, 2.2 / (2 * M_PI * 25.0)) << rise;
  EXPECT_LT(rise, 2.2 / (2 * M_PI * 15.0)) << rise;
}

// The velocity loop's integrator carries a static load without a standing position error.
TEST(JointDrives, NoStaticErrorUnderLoad) {
  const RobotModel model = test::load_model("lola");
  SimulationParams p;
  p.world.robot_mjcf = test::model_path("lola");
  Simulation sim(p, model);
  JointCommand cmd(model.num_joints());
  cmd.position = model.stand_pose();
  for (int i = 0; i < 2000; ++i) {
    sim.command(cmd);
    sim.advance();
  }
  for (const char* joint : {"left_knee", "right_hip_pitch", "left_ankle_pitch"}) {
    const int i = model.joint_index(joint);
    EXPECT_NEAR(sim.data()->qpos[model.joints()[i].qpos_adr], model.stand_pose()[i], 1e-4) << joint;
  }
}

}  // namespace
}  // namespace biped


namespace biped {
namespace {

// The speed–torque envelope: the full peak torque at rest and whenever the drive brakes; while
// motoring, the voltage limit's line from the corner speed down to nothing at the no-load speed.
TEST(JointDrives, SpeedTorqueEnvelope) {
  DriveParams params;
  params.no_load_speed = 10.0;
  params.voltage_stall_ratio = 4.0;
  const double peak = 200.0;
  EXPECT_DOUBLE_EQ(available_torque(1.0, 0.0, peak, params), peak);
  EXPECT_DOUBLE_EQ(available_torque(-1.0, 7.0, peak, params), peak);  // braking
  EXPECT_DOUBLE_EQ(available_torque(1.0, -9.9, peak, params), peak);
  EXPECT_DOUBLE_EQ(available_torque(1.0, 7.5, peak, params), peak);   // the corner: 10·(1 − 1/4)
  EXPECT_NEAR(available_torque(1.0, 9.0, peak, params), 0.4 * peak, 1e-9);
  EXPECT_NEAR(available_torque(-1.0, -9.0, peak, params), 0.4 * peak, 1e-9);
  EXPECT_DOUBLE_EQ(available_torque(1.0, 12.0, peak, params), 0.0);
}

// A joint driven towards a far target runs into the envelope: the servo's torque is cut to the
// voltage limit at speed, but not when the drive brakes.
TEST(JointDrives, ServoTorqueIsCutBeyondTheCornerSpeed) {
  const RobotModel model = test::load_model("lola");
  DriveParams params;
  JointDrives drives(model, params);
  RobotData data(model);
  const mjModel* m = model.mj();
  Eigen::Map<Eigen::VectorXd>(data.mj()->qpos, m->nq) = model.stand_qpos();
  const Eigen::VectorXd far = model.stand_pose().array() + 1.0;
  drives.set_targets(far, 0.001);
  drives.set_targets(far, 0.001);
  const double fast = 0.95 * params.no_load_speed;
  // Even joints move towards the target (motoring), odd ones away from it (braking).
  for (int i = 0; i < model.num_joints(); ++i) data.mj()->qvel[model.joints()[i].dof_adr] = i % 2 ? -fast : fast;
  drives.apply(m, data.mj(), 0.001);
  for (int i = 0; i < model.num_joints(); ++i) {
    const JointInfo& j = model.joints()[i];
    const double tau = applied_torque(m, data.mj(), j.mj_joint);
    if (i % 2 == 0) {
      EXPECT_NEAR(tau, available_torque(1.0, fast, j.torque_limit, params), 1e-9) << j.name;
      EXPECT_LT(tau, 0.5 * j.torque_limit) << j.name;
    } else {
      EXPECT_NEAR(tau, j.torque_limit, 1e-9) << j.name << " brakes with the full torque";
    }
  }
}

}  // namespace
}  // namespace biped
