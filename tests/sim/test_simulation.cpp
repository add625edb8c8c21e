// Closed-loop standing in the MuJoCo simulation, both robots, with the standing controller in the
// controller slot: no fall, the pelvis holds its height, the F/T sensors carry the robot's weight,
// and the centre of pressure stays inside both soles.
#include "sim/simulation.hpp"

#include <gtest/gtest.h>

#include "control/contact_wrench.hpp"
#include "control/standing_controller.hpp"
#include "sim/closed_loop.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

struct StandingObservation final : public RunObserver {
  double first_pelvis_z = -1.0;
  double max_pelvis_drift = 0.0;
  double max_force_error = 0.0;  // relative to the weight above the sensors, after the first second
  double min_cop_margin = 1.0;   // [m] distance of the CoP to the nearest sole edge (negative: outside)
  int samples = 0;
  double weight = 0.0;
  const RobotModel* model = nullptr;

  void record(const Simulation& sim, const SensorData& s, const JointCommand&, const ControllerStatus&,
              double) override {
    const double z = sim.data()->xpos[3 * sim.plant().pelvis_body() + 2];
    if (first_pelvis_z < 0) first_pelvis_z = z;
    max_pelvis_drift = std::max(max_pelvis_drift, std::abs(z - first_pelvis_z));
    if (s.time < 1.0) return;
    ++samples;
    const double fz = s.foot_wrench[0].force.z() + s.foot_wrench[1].force.z();
    max_force_error = std::max(max_force_error, std::abs(fz - weight) / weight);
    for (Side side : kSides) {
      const FootInfo& foot = model->foot(side);
      const Eigen::Vector2d cop = center_of_pressure(s.foot_wrench[index_of(side)], foot.sole_z);
      const double margin = std::min({cop.x() - foot.sole_x_min, foot.sole_x_max - cop.x(),
                                      cop.y() - foot.sole_y_min, foot.sole_y_max - cop.y()});
      min_cop_margin = std::min(min_cop_margin, margin);
    }
  }
};

SimulationParams params_for(const std::string& robot) {
  SimulationParams p;
  p.world.robot_mjcf = test::model_path(robot);
  return p;
}

class Standing : public ::testing::TestWithParam<std::string> {};

TEST_P(Standing, TenSecondsWithoutFallDriftOrLostWeight) {
  const RobotModel model = test::load_model(GetParam());
  Simulation sim(params_for(GetParam()), model);
  StandingController controller(model, {});
  StandingObservation obs;
  obs.weight = model.weight_above_sensors();
  obs.model = &model;
  RunOptions options;
  options.duration = 10.0;
  const RunResult result = run_closed_loop(sim, controller, {}, options, &obs);
  EXPECT_FALSE(result.fell) << result.fall_reason;
  EXPECT_NEAR(result.sim_time, 10.0, 1e-6);
  EXPECT_LT(obs.max_pelvis_drift, 0.005);
  EXPECT_GT(obs.samples, 800);
  EXPECT_LT(obs.max_force_error, 0.03);
  EXPECT_GT(obs.min_cop_margin, 0.0) << "centre of pressure left a sole";
  EXPECT_FALSE(controller.status().fault);
}

INSTANTIATE_TEST_SUITE_P(Robots, Standing, ::testing::Values("lola", "johnnie"),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

// The control period is a whole number of physics steps; set-points are held in between.
TEST(Simulation, ControlPeriodOfSeveralPhysicsSteps) {
  const RobotModel model = test::load_model("johnnie");
  SimulationParams p = params_for("johnnie");
  p.world.timestep = 0.0005;
  p.control_period = 0.002;
  Simulation sim(p, model);
  EXPECT_EQ(sim.physics_steps_per_control_period(), 4);
  JointCommand hold(model.num_joints());
  hold.position = model.stand_pose();
  sim.command(hold);
  sim.advance();
  EXPECT_NEAR(sim.time(), 0.002, 1e-12);
  p.control_period = 0.0012;
  EXPECT_THROW(Simulation(p, model), ModelError);
}

TEST(Simulation, ResetPlacesTheSolesOnTheGround) {
  const RobotModel model = test::load_model("lola");
  Simulation sim(params_for("lola"), model);
  const mjData* d = sim.data();
  double lowest = 1.0;
  for (Side side : kSides) {
    for (int g : sim.plant().foot(side).sole_geoms) {
      lowest = std::min(lowest, d->geom_xpos[3 * g + 2] - sim.plant().mj()->geom_size[3 * g + 2]);
    }
  }
  // Sunk by the static deflection of the two soles carrying the weight.
  const double sink = sim.plant().total_mass() * 9.81 / (2.0 * SoleContactParams{}.stiffness_per_foot);
  EXPECT_NEAR(lowest, -sink, 1e-9);
  EXPECT_GT(sim.standing_pelvis_height(), 0.8);
}

// Standing at the start, each sole seen from above is its full rectangle (the soles are level), on
// its own side of the robot, corners in order around it.
TEST(Simulation, SoleOutlinesAreTheLevelSolesSeenFromAbove) {
  for (const char* robot : {"lola", "johnnie"}) {
    const RobotModel model = test::load_model(robot);
    Simulation sim(params_for(robot), model);
    const auto outlines = sim.sole_outlines();
    ASSERT_EQ(outlines.size(), sim.sole_contact().faces().size()) << robot;
    for (std::size_t i = 0; i < outlines.size(); ++i) {
      const SoleFace& face = sim.sole_contact().faces()[i];
      const auto& c = outlines[i].corners;
      double twice_area = 0.0;  // shoelace formula: positive counter-clockwise
      for (int k = 0; k < 4; ++k) twice_area += c[k].x() * c[(k + 1) % 4].y() - c[(k + 1) % 4].x() * c[k].y();
      EXPECT_NEAR(std::abs(twice_area) / 2.0, 4.0 * face.half_u * face.half_v, 1e-3 * face.half_u * face.half_v) << robot;
      const double y = (c[0] + c[1] + c[2] + c[3]).y() / 4.0;
      EXPECT_EQ(outlines[i].side, face.side == 0 ? Side::Left : Side::Right);
      EXPECT_GT(outlines[i].side == Side::Left ? y : -y, 0.03) << robot;
    }
  }
}

// A push on the upper body is applied for its duration and moves the robot.
TEST(Simulation, PushDisplacesTheUpperBody) {
  const RobotModel model = test::load_model("johnnie");
  SimulationParams p = params_for("johnnie");
  p.pushes.push_back({0.2, 0.1, "upper_body", Eigen::Vector3d(150.0, 0.0, 0.0)});
  Simulation pushed(p, model);
  Simulation quiet(params_for("johnnie"), model);
  JointCommand hold(model.num_joints());
  hold.position = model.stand_pose();
  for (int i = 0; i < 400; ++i) {
    for (Simulation* s : {&pushed, &quiet}) {
      s->command(hold);
      s->advance();
    }
  }
  const int ub = model.upper_body();
  EXPECT_GT(pushed.data()->xpos[3 * ub] - quiet.data()->xpos[3 * ub], 0.002);
}

// A push far beyond the physical blows the physics up; MuJoCo would reset the robot to its rest
// pose and the run would go on as if nothing happened. The simulation says so instead.
TEST(Simulation, DivergedPhysicsIsAnErrorNotARestart) {
  const RobotModel model = test::load_model("johnnie");
  SimulationParams p = params_for("johnnie");
  p.pushes.push_back({0.05, 0.01, "upper_body", Eigen::Vector3d(1e300, 0.0, 0.0)});
  Simulation sim(p, model);
  JointCommand hold(model.num_joints());
  hold.position = model.stand_pose();
  try {
    for (int i = 0; i < 100; ++i) {
      sim.command(hold);
      sim.advance();
    }
    FAIL() << "no SimulationDiverged";
  } catch (const SimulationDiverged& e) {
    EXPECT_NE(std::string(e.what()).find("diverged at t = 0.05"), std::string::npos) << e.what();
  }
}

// Model error: the simulated upper body is heavier than the controller's model says.
TEST(Simulation, ModelErrorChangesTheSimulatedMassOnly) {
  const RobotModel model = test::load_model("lola");
  SimulationParams p = params_for("lola");
  p.world.model_error.upper_body_mass_scale = 1.1;
  Simulation sim(p, model);
  EXPECT_NEAR(sim.plant().total_mass() - model.total_mass(), 0.1 * model.mj()->body_mass[model.upper_body()], 1e-9);
}

}  // namespace
}  // namespace biped
