// Contact force modification (eq. 10) and hybrid position/force control (eq. 20): invariants of the
// point-contact model, the saturation, and the closed loop: the same walk with the stabilizer on
// and off.
#include "control/stabilizer.hpp"

#include "control/contact_model.hpp"

#include <gtest/gtest.h>

#include <ostream>

#include "io/robot_config.hpp"
#include "io/scenario.hpp"
#include "studies/scenario_runner.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

// The stabilizer's input for a pattern with the given contact schedule and wrenches, no CoM error.
StabilizerInput input(const std::array<Wrench, 2>& ideal, std::array<bool, 2> contact, std::array<double, 2> share,
                      const std::array<Wrench, 2>& measured,
                      const Eigen::Quaterniond& orientation = Eigen::Quaterniond::Identity()) {
  StabilizerInput in;
  in.ideal = ideal;
  in.planned_contact = contact;
  in.load_share = share;
  in.measured = measured;
  in.imu_orientation = orientation;
  return in;
}

std::array<Wrench, 2> standing_wrenches(double weight) {
  std::array<Wrench, 2> w;
  for (Wrench& x : w) x.force.z() = 0.5 * weight;
  return w;
}

// A leaning upper body moves the desired CoP the way that rights it; the CoP stays in the sole.
TEST(Stabilizer, ContactForceModificationMovesTheCopAgainstTheTiltInsideTheSole) {
  const RobotModel model = test::load_model("lola");
  StabilizerParams params;
  Stabilizer stabilizer(model, params);
  const auto ideal = standing_wrenches(500.0);
  const Eigen::Quaterniond forward(Eigen::AngleAxisd(0.02, Eigen::Vector3d::UnitY()));
  stabilizer.step(0.001, input(ideal, {true, true}, {0.5, 0.5}, ideal, forward));
  for (const Wrench& d : stabilizer.desired()) {
    EXPECT_LT(d.torque.y(), 0.0) << "leaning forward: CoP forward, T_y = −x_CoP F_z < 0";
    EXPECT_NEAR(d.torque.x(), 0.0, 1e-9);
  }
  const Eigen::Quaterniond left(Eigen::AngleAxisd(-0.02, Eigen::Vector3d::UnitX()));
  stabilizer.step(0.001, input(ideal, {true, true}, {0.5, 0.5}, ideal, left));
  for (const Wrench& d : stabilizer.desired()) EXPECT_GT(d.torque.x(), 0.0) << "leaning left: CoP left";
  // A huge tilt saturates at the sole's edge minus the margin.
  const Eigen::Quaterniond far(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitY()));
  stabilizer.step(0.001, input(ideal, {true, false}, {1.0, 0.0}, ideal, far));
  const Wrench& d = stabilizer.desired()[0];
  const double cop_x = -d.torque.y() / d.force.z();
  EXPECT_NEAR(cop_x, model.foot(Side::Left).sole_x_max - params.cop_margin, 1e-9);
  EXPECT_EQ(stabilizer.desired()[1].torque.norm(), 0.0) << "a swing foot carries no torque";
}

// With full contact and a torque error, the foot tilts the way that reduces the error, at the rate
// the point-contact stiffness predicts.
TEST(Stabilizer, ForceControlTiltsTheFootToReduceTheTorqueError) {
  const RobotModel model = test::load_model("johnnie");
  StabilizerParams params;
  params.feedforward_gain = 0.0;
  params.contact_filter_time = 1e-6;
  Stabilizer stabilizer(model, params);
  const auto ideal = standing_wrenches(400.0);
  auto measured = ideal;
  measured[0].torque.y() = -10.0;  // CoP 5 cm ahead of where λ_id wants it
  stabilizer.step(0.001, input(ideal, {true, true}, {0.5, 0.5}, measured));
  const FootModification& m = stabilizer.modification()[0];
  // Tilting about +y moves the CoP forward (T_y decreases): to raise T_y the foot tilts about −y.
  EXPECT_LT(m.rate[2], 0.0);
  EXPECT_NEAR(stabilizer.modification()[1].rate.norm(), 0.0, 1e-12);
  // The rate undone by the contact model gives back the commanded torque change: −K Δẋ = K_λ Δλ.
  const FootInfo& foot = model.foot(Side::Left);
  Eigen::Matrix3d K = Eigen::Matrix3d::Zero();
  for (double x : {foot.sole_x_min, foot.sole_x_max}) {
    for (double y : {foot.sole_y_min, foot.sole_y_max}) {
      const Eigen::Vector3d g(1.0, y, -x);
      K += 0.25 * params.contact_stiffness * g * g.transpose();
    }
  }
  const Eigen::Vector3d torque_rate = -K * m.rate;
  EXPECT_NEAR(torque_rate[2], params.force_gain * 10.0, 1e-6);
  EXPECT_NEAR(torque_rate[0], 0.0, 1e-6);
}

// pitch_gain_scale scales the pitch torque's rate alone.
TEST(Stabilizer, PitchGainScaleActsOnThePitchTorqueOnly) {
  const RobotModel model = test::load_model("johnnie");
  StabilizerParams params;
  params.feedforward_gain = 0.0;
  params.contact_filter_time = 1e-6;
  params.pitch_gain_scale = 0.5;
  Stabilizer stabilizer(model, params);
  const auto ideal = standing_wrenches(400.0);
  auto measured = ideal;
  measured[0].torque.y() = -10.0;
  measured[0].torque.x() = 10.0;
  stabilizer.step(0.001, input(ideal, {true, true}, {0.5, 0.5}, measured));
  const Eigen::Vector3d torque_rate = -stabilizer.contact_stiffness_matrix()[0] * stabilizer.modification()[0].rate;
  EXPECT_NEAR(torque_rate[2], 0.5 * params.force_gain * 10.0, 1e-6);
  EXPECT_NEAR(torque_rate[1], -params.force_gain * 10.0, 1e-6);
}

// A flat foot on a ground of stiffness `true_stiffness` (the point-contact model of eq. 11 with the
// default elements): the measured wrench is the ideal one minus K_true times the foot's modification.
Wrench foot_on_ground(const RobotModel& model, Side side, double true_stiffness, const Wrench& ideal,
                      const FootModification& m) {
  ContactModelParams ground;
  ground.stiffness = true_stiffness;
  const Eigen::Matrix3d K = point_contact_stiffness(model.foot(side), ground);
  const Eigen::Vector3d push = -K * m.offset;
  Wrench w = ideal;
  w.force.z() += push[0];
  w.torque.x() += push[1];
  w.torque.y() += push[2];
  return w;
}

// eq. (11) from the sensors: LOLA's left toe bent up 0.1 rad (encoder) under the load of a flat
// heel: the left foot's K is the heel segment's alone; the right foot, toe at zero, keeps all eight
// elements.
TEST(Stabilizer, MeasuredToeAngleLeavesTheHeelElements) {
  const RobotModel model = test::load_model("lola");
  const StabilizerParams params;
  Stabilizer stabilizer(model, params);
  Eigen::VectorXd joints = model.stand_pose();
  joints[model.foot(Side::Left).segments[1].joint] = -0.1;
  stabilizer.update_contact_model(joints, standing_wrenches(500.0));
  EXPECT_DOUBLE_EQ(stabilizer.contact_stiffness_matrix()[0](0, 0), params.heel_stiffness_share * params.contact_stiffness);
  EXPECT_DOUBLE_EQ(stabilizer.contact_stiffness_matrix()[1](0, 0), params.contact_stiffness);
  const ContactElements& left = stabilizer.contact_elements()[0];
  for (int i = 0; i < left.count; ++i) EXPECT_EQ(left.in_contact[i], left.segment[i] == 0);
}

// sole_deflection inverts eq. (11): LOLA's flat sole pressed 1 mm into the ground under its sensor
// and pitched 2 mrad toes-down (every element still in contact) gives back that sink and that
// pitch, to eq. (11)'s linearization in the angle (1 µm, 1 %); no load, no deflection.
TEST(Stabilizer, SoleDeflectionInvertsThePointContactModel) {
  const RobotModel model = test::load_model("lola");
  const StabilizerParams params;
  Stabilizer stabilizer(model, params);
  const FootInfo& foot = model.foot(Side::Left);
  const Eigen::Vector3d sensor(0.1, 0.2, 0.1);
  const double sink = 0.001, pitch = 0.002;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const double ground = sensor.z() + foot.sole_z + sink;
  const Eigen::Vector3d lambda = point_contact_wrench(foot, stabilizer.contact_params(), 0.0, sensor, R, ground);
  std::array<Wrench, 2> measured = standing_wrenches(0.0);
  measured[0].force.z() = lambda[0];
  measured[0].torque.x() = lambda[1];
  measured[0].torque.y() = lambda[2];
  stabilizer.update_contact_model(model.stand_pose(), measured);
  const Eigen::Vector3d deflection = stabilizer.sole_deflection(Side::Left, measured[0]);
  EXPECT_NEAR(deflection.x(), sink, 1e-6);
  EXPECT_NEAR(deflection.y(), 0.0, 1e-9);
  EXPECT_NEAR(deflection.z(), -pitch, 0.01 * pitch);
  EXPECT_TRUE(stabilizer.sole_deflection(Side::Right, measured[1]).isZero());
}

// Tracks a normal force that ramps up by 200 N/s from the steady state; returns the final error.
double ramp_tracking_error(const StabilizerParams& params) {
  const RobotModel model = test::load_model("lola");
  Stabilizer stabilizer(model, params);
  const double dt = 0.001;
  std::array<Wrench, 2> ideal = standing_wrenches(500.0), measured = ideal;
  for (int i = 0; i < 3000; ++i) {
    if (i >= 1000) ideal[0].force.z() += 200.0 * dt;
    stabilizer.step(dt, input(ideal, {true, true}, {0.5, 0.5}, measured));
    for (Side side : kSides) {
      const int k = index_of(side);
      // The ground answers the modification; the unmodified foot would carry 250 N.
      Wrench unmodified = standing_wrenches(500.0)[k];
      measured[k] = foot_on_ground(model, side, params.contact_stiffness, unmodified, stabilizer.modification()[k]);
    }
  }
  return stabilizer.desired()[0].force.z() - measured[0].force.z();
}

// The integral-action extension of eq. (14): without feed-forward, the proportional force law lags a
// ramp by rate/K_λ; the integral removes that lag.
TEST(Stabilizer, IntegralForceActionRemovesTheRampLag) {
  StabilizerParams params;
  params.feedforward_gain = 0.0;
  params.contact_filter_time = 1e-6;
  const double proportional = ramp_tracking_error(params);
  EXPECT_NEAR(proportional, 200.0 / params.force_gain, 0.5) << "the lag of the proportional law";
  params.force_integral_gain = 100.0;
  const double with_integral = ramp_tracking_error(params);
  EXPECT_LT(std::abs(with_integral), 0.05 * std::abs(proportional));
}

// The stiffness-adaptation extension: both feet stand on a ground twice as stiff as the controller's
// model, under one body that carries the planned load. The load split follows the feet's height
// difference, δF_left = −(C/2)(δz_left − δz_right). While the force controller follows a changing
// split (as λ_id changes in double support), the estimate converges to the true stiffness. Off, the
// configured value stays.
TEST(Stabilizer, ContactStiffnessAdaptationFindsTheGroundStiffness) {
  const RobotModel model = test::load_model("lola");
  for (bool adapt : {false, true}) {
    StabilizerParams params;
    params.contact_filter_time = 1e-6;
    params.stiffness_adaptation = adapt;
    const double true_stiffness = 2.0 * params.contact_stiffness;
    Stabilizer stabilizer(model, params);
    const double dt = 0.001;
    std::array<Wrench, 2> ideal = standing_wrenches(500.0), measured = ideal;
    for (int i = 0; i < 2000; ++i) {
      const double shift = 100.0 * std::sin(2.0 * M_PI * 2.0 * i * dt);
      ideal[0].force.z() = 250.0 + shift;
      ideal[1].force.z() = 250.0 - shift;
      stabilizer.step(dt, input(ideal, {true, true}, {0.5, 0.5}, measured));
      std::array<double, 2> lift;  // each foot's modification as the nominal model's normal force
      for (Side side : kSides) {
        const int k = index_of(side);
        measured[k] = foot_on_ground(model, side, true_stiffness, ideal[k], stabilizer.modification()[k]);
        lift[k] = ideal[k].force.z() - measured[k].force.z();
      }
      for (int k = 0; k < 2; ++k) measured[k].force.z() = ideal[k].force.z() - 0.5 * (lift[k] - lift[1 - k]);
    }
    if (adapt) {
      EXPECT_NEAR(stabilizer.contact_stiffness() / true_stiffness, 1.0, 0.1);
    } else {
      EXPECT_EQ(stabilizer.contact_stiffness(), params.contact_stiffness);
    }
  }
}

struct WalkOutcome {
  bool fell;
  double tilt_rms_x, tilt_rms_y, tilt_max;
};

WalkOutcome walk(bool stabilizer) {
  const Scenario scenario = load_scenario(test::source_path("config/scenarios/lola-walk-open-loop.yaml"),
                                          {"duration=10", "commands.1.vx=0.5",
                                           std::string("controller.stabilizer=") + (stabilizer ? "true" : "false")});
  const ScenarioResult r = run_scenario(scenario, make_run_config(scenario), "");
  const auto& tilt = r.summary["upper_body_tilt_deg"];
  return {r.run.fell, tilt["rms_x"], tilt["rms_y"], tilt["max"]};
}

// The same walk (LOLA, 0.5 m/s), stabilizer on against off: on, the upper body stays within about a
// degree; off, its rocking grows until the robot falls (measured with the swing that comes down
// vertically: falls at 0.4, 0.45, 0.5 and 0.6 m/s; at 0.3 m/s it walks, tilting 3x as much as on).
TEST(Stabilizer, ClosedLoopWalkKeepsTheUpperBodySteadyWhereOpenLoopRocks) {
  const WalkOutcome off = walk(false);
  const WalkOutcome on = walk(true);
  EXPECT_FALSE(on.fell);
  EXPECT_LT(on.tilt_rms_x, 1.0);
  EXPECT_LT(on.tilt_rms_y, 1.0);
  EXPECT_LT(on.tilt_max, 2.0);
  EXPECT_TRUE(off.fell || off.tilt_max > 5.0 * on.tilt_max) << "open loop: max tilt " << off.tilt_max;
}

struct Robustness {
  const char* name;  // of the test instance
  const char* scenario;
  std::vector<std::string> overrides;
};

void PrintTo(const Robustness& r, std::ostream* os) {
  *os << r.scenario;
  for (const std::string& o : r.overrides) *os << " --set " << o;
}

class StabilizerRobustness : public ::testing::TestWithParam<Robustness> {};

// Shortened versions of the shipped robustness scenarios: the stabilizer walks through errors the
// controller is not told about.
TEST_P(StabilizerRobustness, WalksWithoutFalling) {
  std::vector<std::string> overrides = GetParam().overrides;
  overrides.push_back("duration=8");
  const Scenario scenario = load_scenario(test::source_path(std::string("config/scenarios/") + GetParam().scenario + ".yaml"),
                                          overrides);
  const ScenarioResult r = run_scenario(scenario, make_run_config(scenario), "");
  EXPECT_FALSE(r.run.fell) << r.run.fall_reason;
  EXPECT_GT(r.summary["distance_m"].get<double>(), 1.5);
}

INSTANTIATE_TEST_SUITE_P(
    Scenarios, StabilizerRobustness,
    ::testing::Values(Robustness{"SensorNoiseAndDelay", "lola-sensor-noise", {}},
                      Robustness{"UpperBodyMassPlus10Percent", "lola-model-error-mass", {}},
                      Robustness{"UpperBodyMassMinus10Percent", "lola-model-error-mass", {"model_error.upper_body_mass_scale=0.9"}},
                      Robustness{"UpperBodyComForward", "lola-model-error-com", {}},
                      // With the realistic sensor errors it falls (README "Status"): here the model error alone.
                      Robustness{"UpperBodyComSideways", "lola-model-error-com",
                                 {"model_error.upper_body_com_offset=[0,0.02,0]", "sensors.ideal=true"}},
                      Robustness{"HeavierWithComForward", "lola-model-error", {}},
                      Robustness{"LighterWithComForward", "lola-model-error", {"model_error.upper_body_mass_scale=0.9"}}),
    [](const ::testing::TestParamInfo<Robustness>& info) { return std::string(info.param.name); });

// The first scenario in full: LOLA straight at 0.6 m/s for 30 s, no fall, the upper body's
// tilt RMS below 1° about each axis, and the distance of the commanded speed (within 10 %).
TEST(StabilizerRobustness, LolaWalksStraightThirtySecondsWithTheTiltBelowOneDegree) {
  const Scenario scenario = load_scenario(test::source_path("config/scenarios/lola-straight.yaml"));
  const ScenarioResult r = run_scenario(scenario, make_run_config(scenario), "");
  ASSERT_FALSE(r.run.fell) << r.run.fall_reason << " at " << r.run.fall_time;
  const auto& tilt = r.summary["upper_body_tilt_deg"];
  EXPECT_LT(tilt["rms_x"].get<double>(), 1.0);
  EXPECT_LT(tilt["rms_y"].get<double>(), 1.0);
  const double walking_time = scenario.commands[2].t - scenario.commands[1].t;
  EXPECT_GT(r.summary["distance_m"].get<double>(), 0.9 * scenario.commands[1].command.vx * walking_time);
}

// The JOHNNIE scenario: a circle of radius 1.5 m, 60 s, the joystick changing speed
// (0.2–0.5 m/s) and direction. (It fell at 43.6 s before the CoM height followed the footholds.)
TEST(StabilizerRobustness, JohnnieWalksTheSixtySecondCircle) {
  const Scenario scenario = load_scenario(test::source_path("config/scenarios/johnnie-circle.yaml"));
  const ScenarioResult r = run_scenario(scenario, make_run_config(scenario), "");
  EXPECT_FALSE(r.run.fell) << r.run.fall_reason << " at " << r.run.fall_time;
  // It covers most of the joystick's path around the circle (the pelvis path; Σ v·Δt commanded).
  double commanded_path = 0.0;
  for (std::size_t i = 0; i < scenario.commands.size(); ++i) {
    const double until = i + 1 < scenario.commands.size() ? scenario.commands[i + 1].t : scenario.duration;
    if (!scenario.commands[i].command.stop) commanded_path += scenario.commands[i].command.vx * (until - scenario.commands[i].t);
  }
  EXPECT_GT(r.summary["path_length_m"].get<double>(), 0.8 * commanded_path) << "commanded " << commanded_path << " m";
}

// One NaN reading of a force/torque sensor while walking: safe stop, no NaN set-point, no fall.
// The fault comes at several phases of the gait (double support, early and late single support).
TEST(StabilizerRobustness, NanForceReadingGivesASafeStopWithoutAFall) {
  for (const char* t : {"4.8", "5.0", "5.3", "6.0"}) {
    const Scenario scenario =
        load_scenario(test::source_path("config/scenarios/lola-ft-nan.yaml"), {std::string("sensors.faults.0.t=") + t});
    const RunConfig config = make_run_config(scenario);
    const ScenarioResult r = run_scenario(scenario, config, "");
    EXPECT_FALSE(r.run.fell) << "fault at " << t << " s: " << r.run.fall_reason;
    EXPECT_EQ(r.summary["final_state"], "safe_stop");
    EXPECT_EQ(r.summary["fault"], "left F/T sensor");
    // Healthy again after the one reading: trusted again after the recovery time, the stop goes on.
    ASSERT_EQ(r.summary["sensors_recovered"].size(), 1u) << "fault at " << t << " s";
    EXPECT_EQ(r.summary["sensors_recovered"][0]["sensor"], "left F/T sensor");
    EXPECT_GE(r.summary["sensors_recovered"][0]["t"].get<double>(),
              std::stod(t) + config.controller.walking.sensor_limits.recovery_time - 1e-9);
  }
}

// The left F/T sensor freezes at 5 s while walking: the dead signal is noticed within the configured
// number of cycles, the controller stops safely, the robot does not fall.
TEST(StabilizerRobustness, FrozenForceSensorGivesASafeStopWithoutAFall) {
  const Scenario scenario = load_scenario(test::source_path("config/scenarios/lola-ft-frozen.yaml"), {"duration=8"});
  const RunConfig config = make_run_config(scenario);
  const ScenarioResult r = run_scenario(scenario, config, "");
  EXPECT_FALSE(r.run.fell) << r.run.fall_reason;
  EXPECT_EQ(r.summary["final_state"], "safe_stop");
  EXPECT_EQ(r.summary["fault"], "left F/T sensor frozen");
  EXPECT_TRUE(r.summary["sensors_recovered"].empty()) << "frozen to the end: never trusted again";
}

}  // namespace
}  // namespace biped
