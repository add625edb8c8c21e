// Terrain adaptation: the early-contact latch, the late-contact search and the turn of a partly
// supported foot on constructed samples, and the closed loop over terrain the controller is not
// told about, adaptation on against off.
#include "control/terrain_adaptation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <utility>

#include "foothold_observer.hpp"
#include "io/robot_config.hpp"
#include "io/scenario.hpp"
#include "studies/scenario_runner.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

constexpr double kDt = 0.001;
const std::array<Eigen::Vector2d, 2> kNoTurn = {Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};

std::array<Wrench, 2> loads(double left, double right) {
  std::array<Wrench, 2> w;
  w[0].force.z() = left;
  w[1].force.z() = right;
  return w;
}

// The left foot's plan descending at 0.2 m/s from 5 cm above its ground, the right foot standing.
struct LeftFootDescending {
  PatternSample sample;
  double planned = 0.05;
  LeftFootDescending() {
    sample.feet[0].in_contact = false;
    sample.feet[0].velocity.z() = -0.2;
  }
  // `cycles` control cycles of the descent with these normal forces measured.
  void descend(TerrainAdaptation& terrain, int cycles, double left_force, double right_force) {
    for (int i = 0; i < cycles; ++i) {
      sample.feet[0].position.z() = planned -= 0.2 * kDt;
      terrain.step(kDt, sample, loads(left_force, right_force));
    }
  }
};

// The left foot swings down onto ground that is higher than planned: from the moment its sensor
// feels the ground, its commanded height (plan + offset) stays where it met the ground.
TEST(TerrainAdaptation, EarlyContactHoldsTheFootWhereItMetTheGround) {
  TerrainAdaptationParams params;
  TerrainAdaptation terrain(test::load_model("lola"), params);
  LeftFootDescending left;
  left.descend(terrain, 100, -10.0, 500.0);  // in the air
  EXPECT_DOUBLE_EQ(terrain.foot_offset(0), 0.0);
  const double met_at = left.planned;
  left.descend(terrain, 100, 200.0, 300.0);  // on the ground, 2 cm above the plan's
  EXPECT_NEAR(left.planned + terrain.foot_offset(0), met_at, 0.2 * kDt * 5) << "holds within the filter's few cycles";
  left.sample.feet[0].in_contact = true;
  terrain.step(kDt, left.sample, loads(250.0, 250.0));
  EXPECT_NEAR(terrain.ground_height(0), terrain.foot_offset(0), 1e-12) << "touchdown records the foothold's height";
  EXPECT_GT(terrain.ground_height(0), 0.0);
}

// The plan says touchdown but the sensor feels nothing: after search_delay (the time a foot
// landing on time needs to take load) the foot descends at the search speed until it feels the
// ground, and no further than max_step below the other foot.
TEST(TerrainAdaptation, LateContactSearchesDownForTheGround) {
  TerrainAdaptationParams params;
  TerrainAdaptation terrain(test::load_model("lola"), params);
  PatternSample s;
  s.feet[0].in_contact = false;
  terrain.step(kDt, s, loads(-10.0, 500.0));
  s.feet[0].in_contact = true;
  const int delay = static_cast<int>(std::lround(params.search_delay / kDt));
  for (int i = 0; i < delay - 1; ++i) terrain.step(kDt, s, loads(-10.0, 500.0));
  EXPECT_DOUBLE_EQ(terrain.foot_offset(0), 0.0) << "no search within the delay";
  for (int i = 0; i < 41; ++i) terrain.step(kDt, s, loads(-10.0, 500.0));
  EXPECT_NEAR(terrain.foot_offset(0), -40 * params.search_speed * kDt, params.search_speed * kDt + 1e-9);
  EXPECT_NEAR(terrain.foot_offset_rate(0), -params.search_speed, 1e-9);
  for (int i = 0; i < 20; ++i) terrain.step(kDt, s, loads(300.0, 200.0));
  const double found = terrain.ground_height(0);
  EXPECT_LT(found, -0.01);
  EXPECT_DOUBLE_EQ(terrain.foot_offset_rate(0), 0.0) << "stops once the ground is felt";
  for (int i = 0; i < 2000; ++i) terrain.step(kDt, s, loads(300.0, 200.0));
  EXPECT_NEAR(terrain.com_offset(), 0.5 * found, 1e-3) << "the CoM follows the mean foothold height";

  TerrainAdaptation bounded(test::load_model("lola"), params);
  s.feet[0].in_contact = false;
  bounded.step(kDt, s, loads(-10.0, 500.0));
  s.feet[0].in_contact = true;
  for (int i = 0; i < 2000; ++i) bounded.step(kDt, s, loads(-10.0, 500.0));
  EXPECT_NEAR(bounded.foot_offset(0), -params.max_step, 1e-12);
}

// The robot leans back at a touchdown: the front (left) foot hangs 3 mm above where its command
// puts it, finds no ground at the planned touchdown and searches, so its foothold is found 3 mm
// low (on a 1 cm step down, 1.3 cm). In the double support the encoders and the IMU measure the
// step (`measured_ground`: flat, or 1 cm down): the foothold's height becomes the measured one,
// and every height the adaptation commands moves by the same amount, so the feet keep the offsets
// the search gave them against each other and the CoM keeps following their mean.
TEST(TerrainAdaptation, TheMeasuredStepSetsTheFootholdsLevel) {
  for (const double step_down : {0.0, 0.01}) {
    for (const bool measure : {true, false}) {
      TerrainAdaptationParams params;
      params.measure_step_height = measure;
      TerrainAdaptation terrain(test::load_model("lola"), params);
      const std::array<double, 2> measured = {-0.9 - step_down, -0.9};  // the soles' ground against the pelvis
      auto step = [&](const PatternSample& s, double left, double right) {
        terrain.step(kDt, s, loads(left, right), {}, {0.0, 0.0}, {true, true}, kNoTurn, measured);
      };
      PatternSample s;
      s.feet[0].in_contact = false;
      step(s, -10.0, 500.0);
      s.feet[0].in_contact = true;
      const double search_time = params.search_delay + (0.003 + step_down) / params.search_speed;
      for (int i = 0; i < static_cast<int>(std::lround(search_time / kDt)); ++i) step(s, -10.0, 500.0);
      step(s, 300.0, 200.0);
      const double searched = terrain.foot_offset(0) - terrain.foot_offset(1);
      EXPECT_NEAR(searched, -step_down - 0.003, 1e-3);
      for (int i = 0; i < 2000; ++i) step(s, 300.0, 200.0);
      const double expected = measure ? -step_down : -step_down - 0.003;
      EXPECT_NEAR(terrain.ground_height(0), expected, 1e-3) << "step down " << step_down << ", measured " << measure;
      EXPECT_NEAR(terrain.foot_offset(0) - terrain.foot_offset(1), searched, 1e-9) << "one shift for all";
      EXPECT_NEAR(terrain.com_offset(), 0.5 * (terrain.ground_height(0) + terrain.ground_height(1)), 1e-3);
    }
  }
  // Not measured where one sole does not lie flat (its centre of pressure at the toe): it may be
  // rolling over its edge, above the ground under its sensor.
  TerrainAdaptationParams params;
  TerrainAdaptation terrain(test::load_model("lola"), params);
  const double toe = test::load_model("lola").foot(Side::Right).sole_x_max;
  std::array<Wrench, 2> on_toe = loads(300.0, 200.0);
  on_toe[1].torque.y() = -toe * 200.0;  // T_y = −x_CoP F_z
  PatternSample s;
  for (int i = 0; i < 100; ++i) terrain.step(kDt, s, on_toe, {}, {0.0, 0.0}, {true, true}, kNoTurn, {-0.95, -0.9});
  s.feet[0].in_contact = false;
  terrain.step(kDt, s, on_toe, {}, {0.0, 0.0}, {true, true}, kNoTurn, {-0.95, -0.9});
  s.feet[0].in_contact = true;
  for (int i = 0; i < 2000; ++i) terrain.step(kDt, s, on_toe, {}, {0.0, 0.0}, {true, true}, kNoTurn, {-0.95, -0.9});
  EXPECT_NEAR(terrain.ground_height(0), 0.0, 1e-9);
}

// The measured step takes its samples from the plan's half of the load transfer on, where the
// soles' sinks agree best with the contact model: 50 early samples that say 4 mm up give way to
// 100 later ones that say flat (their mean together would be 1.3 mm up); with no later sample the
// early ones are the measurement (the level of every height, which the right foot's starts at).
TEST(TerrainAdaptation, TheMeasuredStepTakesTheLaterHalfOfTheLoadTransfer) {
  for (const bool later : {true, false}) {
    TerrainAdaptation terrain(test::load_model("lola"), TerrainAdaptationParams{});
    PatternSample s;
    s.feet[0].in_contact = false;
    terrain.step(kDt, s, loads(-10.0, 500.0));
    s.feet[0].in_contact = true;
    s.load_share = {0.2, 0.8};
    for (int i = 0; i < 50; ++i)
      terrain.step(kDt, s, loads(300.0, 200.0), {}, {0.0, 0.0}, {true, true}, kNoTurn, {-0.896, -0.9});
    s.load_share = {0.6, 0.4};
    const std::array<double, 2> flat = {-0.9, -0.9}, none = {NAN, NAN};
    for (int i = 0; i < 100; ++i)
      terrain.step(kDt, s, loads(300.0, 200.0), {}, {0.0, 0.0}, {true, true}, kNoTurn, later ? flat : none);
    for (int i = 0; i < 2000; ++i) terrain.step(kDt, s, loads(300.0, 200.0), {}, {0.0, 0.0}, {true, true}, kNoTurn, none);
    EXPECT_NEAR(terrain.ground_height(0), later ? 0.0 : 0.004, 1e-4) << later;
  }
}

// The left foot latched 2 cm high (the robot rolled towards it as it landed), on flat ground:
// standing, the feet's heights against each other follow the measured step between them (flat) to
// within the dead band, each foot half of the way, their mean kept. Not while a sole is on its
// edge, nor switched off.
TEST(TerrainAdaptation, StandingTheFeetTakeTheMeasuredStepBetweenThem) {
  const RobotModel model = test::load_model("lola");
  for (const int variant : {0, 1, 2}) {  // levelled; the right sole on its toe; switched off
    TerrainAdaptationParams params;
    params.measure_step_height = false;  // the latched step stays as the walk left it
    params.level_standing_feet = variant != 2;
    TerrainAdaptation terrain(model, params);
    LeftFootDescending left;
    left.descend(terrain, 100, -10.0, 500.0);
    left.descend(terrain, 100, 250.0, 300.0);  // meets the ground 2 cm above the plan's
    left.sample.feet[0].in_contact = true;
    left.sample.feet[0].position.z() = 0.0;
    std::array<Wrench, 2> standing = loads(250.0, 250.0);
    if (variant == 1) standing[1].torque.y() = -model.foot(Side::Right).sole_x_max * 250.0;  // T_y = −x_CoP F_z
    for (int i = 0; i < 100; ++i) terrain.step(kDt, left.sample, standing);
    const double latched = terrain.ground_height(0) - terrain.ground_height(1);
    ASSERT_NEAR(latched, 0.02, 2e-3);
    const double mean = 0.5 * (terrain.foot_offset(0) + terrain.foot_offset(1));
    for (int i = 0; i < 3000; ++i) {
      terrain.step(kDt, left.sample, standing);
      terrain.level_standing_feet(kDt, {-0.9, -0.9});
    }
    const double now = terrain.ground_height(0) - terrain.ground_height(1);
    if (variant == 0) {
      EXPECT_LT(std::abs(now), params.standing_level_dead_band + 1e-4);
      EXPECT_GT(std::abs(now), params.standing_level_dead_band - 1e-4) << "the dead band is left";
    } else {
      EXPECT_NEAR(now, latched, 1e-9) << variant;
    }
    EXPECT_NEAR(0.5 * (terrain.foot_offset(0) + terrain.foot_offset(1)), mean, 1e-9) << variant;
  }
}

// A foot that touches the ground on its way down but has lost it again by the planned touchdown
// (its toe brushed the ground) is not standing where it touched: it searches like a late foot
// instead of taking the touch for its foothold.
TEST(TerrainAdaptation, ABrushOfTheGroundIsNotAFoothold) {
  TerrainAdaptationParams params;
  TerrainAdaptation terrain(test::load_model("lola"), params);
  LeftFootDescending left;
  left.descend(terrain, 50, -10.0, 500.0);
  left.descend(terrain, 50, 200.0, 500.0);  // the touch, 2.5 cm above the plan's ground
  for (int i = 0; i < 30; ++i) terrain.step(kDt, left.sample, loads(-10.0, 500.0));  // gone again
  const double held = terrain.foot_offset(0);
  EXPECT_GT(held, 0.005) << "held where it touched while it touched";
  left.sample.feet[0].in_contact = true;
  const int delay = static_cast<int>(std::lround(params.search_delay / kDt));
  for (int i = 0; i < delay + 20; ++i) terrain.step(kDt, left.sample, loads(-10.0, 500.0));
  EXPECT_LT(terrain.foot_offset(0), held - 0.004) << "searching down from there";
  EXPECT_NEAR(terrain.foot_offset_rate(0), -params.search_speed, 1e-9);
}

// A foot that meets the ground on one edge of its sole (its toe, on an uphill slope) just before the
// planned touchdown, is held there and bounces off: while the plan shifts load onto it, it searches
// down again from where it touched; without load asked of it, it waits. So does a foot that landed
// on time and bounced off.
TEST(TerrainAdaptation, AFootThatBouncesOffBeforeItFoundItsSupportSearchesAgain) {
  TerrainAdaptationParams params;
  const int delay = static_cast<int>(std::lround(params.search_delay / kDt));
  struct Case {
    bool early;
    double asked;
    bool searches;
  };
  for (const Case c : {Case{true, 0.0, false}, Case{true, 300.0, true}, Case{false, 300.0, true}}) {
    TerrainAdaptation terrain(test::load_model("lola"), params);
    LeftFootDescending left;
    left.descend(terrain, c.early ? 50 : 100, -10.0, 500.0);
    if (c.early) left.descend(terrain, 50, 200.0, 500.0);  // the touch, 2.5 cm above the plan's ground
    left.sample.feet[0].in_contact = true;
    left.sample.load_share = {0.0, 1.0};
    for (int i = 0; i < 5; ++i) terrain.step(kDt, left.sample, loads(200.0, 500.0));  // touchdown, the sole on the ground
    const double held = terrain.foot_offset(0);
    if (c.early) {
      EXPECT_GT(held, 0.005);
    }
    // The double support after touchdown: the plan's share of the load on the left foot grows.
    std::array<Wrench, 2> desired = loads(c.asked, 500.0 - c.asked);
    for (int i = 0; i < delay + 30; ++i) {
      left.sample.load_share = {std::min(1.0, 0.01 * (i + 1)), std::max(0.0, 1.0 - 0.01 * (i + 1))};
      terrain.step(kDt, left.sample, loads(-10.0, 500.0), desired);
    }
    if (c.searches) {
      EXPECT_LT(terrain.foot_offset(0), held - 0.004) << "searching down from where it touched";
      EXPECT_NEAR(terrain.foot_offset_rate(0), -params.search_speed, 1e-9);
      for (int i = 0; i < 20; ++i) terrain.step(kDt, left.sample, loads(300.0, 200.0), desired);
      EXPECT_DOUBLE_EQ(terrain.foot_offset_rate(0), 0.0) << "stops once the ground is felt";
      EXPECT_LT(terrain.ground_height(0), held - 0.004);
    } else {
      EXPECT_DOUBLE_EQ(terrain.foot_offset(0), held) << "early " << c.early << ", asked " << c.asked << " N: no search";
    }
  }
}

// A foot lands with the front of its sole over a lower level: while the load shifts onto it, the
// measured centre of pressure stays behind the desired one, so the foot turns toes down about it
// until it is found; a foot whose centre of pressure follows (flat ground) does not turn.
TEST(TerrainAdaptation, PartialSupportTurnsTheFootAboutItsCentreOfPressure) {
  const RobotModel model = test::load_model("lola");
  TerrainAdaptationParams params;
  PatternSample s;
  Wrench desired;
  desired.force.z() = 400.0;
  desired.torque.y() = -0.05 * 400.0;  // desired CoP 5 cm ahead of the ankle
  std::array<Wrench, 2> measured = loads(400.0, 400.0);
  for (bool supported : {true, false}) {
    TerrainAdaptation terrain(model, params);
    s.feet[0].in_contact = false;
    s.load_share = {0.0, 1.0};
    terrain.step(kDt, s, measured, {desired, desired});
    s.feet[0].in_contact = true;
    measured[0].torque.y() = supported ? desired.torque.y() : 0.08 * 400.0;  // 8 cm behind the ankle
    for (int i = 0; i < 100; ++i) {  // the double support after touchdown: load shifts onto it
      s.load_share = {0.005 * (i + 1), 1.0 - 0.005 * (i + 1)};
      terrain.step(kDt, s, measured, {desired, desired});
    }
    if (supported) {
      EXPECT_DOUBLE_EQ(terrain.foot_tilt(0), 0.0);
      continue;
    }
    EXPECT_GT(terrain.foot_tilt(0), 0.02) << "toes down";
    EXPECT_NEAR(terrain.foot_offset(0) / terrain.foot_tilt(0), -0.08, 0.005) << "the ankle follows the turn about the CoP";
    measured[0].torque.y() = desired.torque.y();  // the toe has found the ground
    for (int i = 0; i < 200; ++i) terrain.step(kDt, s, measured, {desired, desired});
    const double found = terrain.foot_tilt(0);
    EXPECT_LE(found, params.max_tilt);
    s.feet[1].in_contact = false;  // single support: the tilt holds
    for (int i = 0; i < 200; ++i) terrain.step(kDt, s, measured, {desired, desired});
    EXPECT_DOUBLE_EQ(terrain.foot_tilt(0), found);
  }
}

// A foot whose toe met a step's top early (latched, loaded before the planned touchdown) with its
// heel over the lower level: at the planned touchdown its centre of pressure sits at the edge under
// the sole, 8 cm ahead of the desired one, from the first cycle, in which the plan's load share has
// not risen yet. The search must not end before its filtered error has built: the sole turns heel
// down about the edge. A foot fully on the step (the CoP where desired) does not turn.
TEST(TerrainAdaptation, AFootThatMetAStepTopEarlyStillTurnsOntoItsSupport) {
  const RobotModel model = test::load_model("lola");
  for (bool supported : {true, false}) {
    TerrainAdaptation terrain(model, TerrainAdaptationParams{});
    LeftFootDescending left;
    left.descend(terrain, 50, -10.0, 600.0);
    left.descend(terrain, 20, 200.0, 400.0);  // the toe on the step: latched
    Wrench desired;
    desired.force.z() = 300.0;
    std::array<Wrench, 2> measured = loads(300.0, 300.0);
    measured[0].torque.y() = supported ? 0.0 : -0.08 * 300.0;  // T_y = −x_CoP F_z: the CoP 8 cm ahead
    left.sample.feet[0].in_contact = true;
    left.sample.feet[0].velocity.z() = 0.0;
    left.sample.load_share = {0.0, 1.0};
    for (int i = 0; i < 100; ++i) {
      if (i > 0) left.sample.load_share = {0.005 * i, 1.0 - 0.005 * i};
      terrain.step(kDt, left.sample, measured, {desired, desired});
    }
    if (supported) {
      EXPECT_DOUBLE_EQ(terrain.foot_tilt(0), 0.0);
    } else {
      EXPECT_LT(terrain.foot_tilt(0), -0.02) << "heel down about the edge";
    }
  }
}

// A foot landing across an edge crossed at an angle, 2 cm above the other foot: its supported part
// lies behind and to the left, the desired centre of pressure ahead and to the right. The turn
// lowers the sole towards the desired one (toes down and its right edge down, in the proportion of
// the error), about the present centre of pressure, whose height the ankle keeps. Without the roll,
// or on level ground (the same centres of pressure from a push), only about the lateral axis.
TEST(TerrainAdaptation, AcrossAnObliqueEdgeTheFootAlsoRollsTowardsTheDesiredCentreOfPressure) {
  const RobotModel model = test::load_model("lola");
  const Eigen::Vector2d desired_cop(0.05, -0.02), measured_cop(-0.05, 0.06);
  const Eigen::Vector2d error = desired_cop - measured_cop;
  for (const auto& [roll, step] : {std::pair{true, 0.02}, std::pair{false, 0.02}, std::pair{true, 0.0}}) {
    TerrainAdaptationParams params;
    params.tilt_search_roll = roll;
    const std::array<double, 2> ground_above_command = {step, 0.0};
    TerrainAdaptation terrain(model, params);
    PatternSample s;
    Wrench desired;
    desired.force.z() = 400.0;
    desired.torque = Eigen::Vector3d(desired_cop.y(), -desired_cop.x(), 0.0) * 400.0;  // T_x = y F_z, T_y = −x F_z
    std::array<Wrench, 2> measured = loads(400.0, 400.0);
    s.feet[0].in_contact = false;
    s.load_share = {0.0, 1.0};
    terrain.step(kDt, s, measured, {desired, desired});
    s.feet[0].in_contact = true;
    measured[0].torque = Eigen::Vector3d(measured_cop.y(), -measured_cop.x(), 0.0) * 400.0;
    for (int i = 0; i < 100; ++i) {
      s.load_share = {0.005 * (i + 1), 1.0 - 0.005 * (i + 1)};
      terrain.step(kDt, s, measured, {desired, desired}, ground_above_command);
    }
    const double pitch = terrain.foot_tilt(0), roll_angle = terrain.foot_roll(0);
    ASSERT_GT(pitch, 0.02) << "toes down";
    EXPECT_LE(std::hypot(pitch, roll_angle), params.max_tilt + 1e-12);
    if (!roll || step == 0.0) {
      EXPECT_DOUBLE_EQ(roll_angle, 0.0) << roll << " " << step;
      continue;
    }
    EXPECT_GT(roll_angle, 0.0) << "the right edge down";
    // The direction is the filtered error's when the turn began, the filters still settling.
    EXPECT_NEAR(roll_angle / pitch, -error.y() / error.x(), 0.05) << "turned in the error's direction";
    // The pivot (the centre of pressure when the turn began, within the 5 ms force filter's lag)
    // stays at its height: the ankle at (0, 0) lies at −pivot from it.
    EXPECT_NEAR(terrain.foot_offset(0), measured_cop.x() * pitch - measured_cop.y() * roll_angle,
                0.005 * std::hypot(pitch, roll_angle));
    EXPECT_NEAR(terrain.foot_roll_rate(0) / terrain.foot_tilt_rate(0), roll_angle / pitch, 1e-9);
  }
}
// A turn that has started goes on while the centre-of-pressure error is still more than half the
// band (inside the band that started it), and stops below that.
TEST(TerrainAdaptation, AStartedTurnGoesOnToHalfTheBand) {
  TerrainAdaptationParams params;
  TerrainAdaptation terrain(test::load_model("lola"), params);
  PatternSample s;
  Wrench desired;
  desired.force.z() = 400.0;
  desired.torque.y() = -0.05 * 400.0;
  std::array<Wrench, 2> measured = loads(400.0, 400.0);
  const auto with_error = [&](double error) { measured[0].torque.y() = -(0.05 - error) * 400.0; };
  s.feet[0].in_contact = false;
  s.load_share = {0.0, 1.0};
  terrain.step(kDt, s, measured, {desired, desired});
  s.feet[0].in_contact = true;
  with_error(2.0 * params.cop_band);
  int i = 0;
  for (; terrain.foot_tilt(0) == 0.0 && i < 200; ++i) {
    s.load_share = {0.005 * (i + 1), 1.0 - 0.005 * (i + 1)};
    terrain.step(kDt, s, measured, {desired, desired});
  }
  ASSERT_GT(terrain.foot_tilt(0), 0.0) << "the turn has started";
  const auto turn_for = [&](int cycles) {
    const double before = terrain.foot_tilt(0);
    for (int j = 0; j < cycles; ++j, ++i) {
      s.load_share = {0.005 * (i + 1), 1.0 - 0.005 * (i + 1)};
      terrain.step(kDt, s, measured, {desired, desired});
    }
    return terrain.foot_tilt(0) - before;
  };
  with_error(0.75 * params.cop_band);
  turn_for(100);  // the filtered error settles inside the band
  EXPECT_GT(turn_for(40), 0.0) << "inside the band, above half of it: turning on";
  with_error(0.25 * params.cop_band);
  turn_for(100);  // and below half of it
  EXPECT_DOUBLE_EQ(turn_for(40), 0.0) << "stopped";
}

// A foot whose F/T sensor has failed (not trusted) finds no ground of its own: in the air it goes
// to the other foot's ground. At a planned touchdown it searches down only while the other foot,
// trusted, still carries the whole weight (the failed foot's load is what the other gives up), and
// stands where it is once the other foot has given up some of it, or when neither reading is
// trusted. Trusted again, in the air, it lands like any foot. The other foot goes on finding its
// ground.
TEST(TerrainAdaptation, AFootWithoutATrustedReadingFindsLateGroundByTheOtherFootsLoad) {
  TerrainAdaptationParams params;
  const RobotModel model = test::load_model("lola");
  const double weight = model.weight_above_sensors();
  TerrainAdaptation terrain(model, params);
  const std::array<bool, 2> left_failed{false, true}, both_failed{false, false};
  const std::array<double, 2> standing{0.0, 0.0};
  PatternSample s;
  s.feet[0].in_contact = false;
  // The right foot stands 1.5 cm above the plan's ground (found from its trusted reading).
  for (int i = 0; i < 100; ++i) terrain.step(kDt, s, loads(-10.0, weight), {}, {0.0, 0.015}, left_failed);
  EXPECT_NEAR(terrain.ground_height(1), 0.015, 1e-12);
  EXPECT_NEAR(terrain.foot_offset(0), 0.015, 1e-9) << "in the air: to the other foot's ground";
  // Touchdown planned, the right foot still carrying all the weight: the left one is in the air.
  s.feet[0].in_contact = true;
  for (int i = 0; i < 100; ++i) terrain.step(kDt, s, loads(-10.0, weight), {}, standing, left_failed);
  const double searched = terrain.foot_offset(0);
  EXPECT_LT(searched, 0.015 - 0.01) << "searching down";
  EXPECT_NEAR(terrain.foot_offset_rate(0), -params.search_speed, 1e-9);
  // The right foot gives up half the weight: the left one carries it, the search stops there.
  for (int i = 0; i < 100; ++i) terrain.step(kDt, s, loads(-10.0, 0.5 * weight), {}, standing, left_failed);
  EXPECT_LT(terrain.foot_offset(0), searched);
  EXPECT_GT(terrain.foot_offset(0), searched - 0.01) << "stopped within the force filter's few cycles";
  EXPECT_DOUBLE_EQ(terrain.foot_offset_rate(0), 0.0);
  EXPECT_NEAR(terrain.ground_height(0), terrain.foot_offset(0), 1e-12);

  // Neither reading trusted: no search, the foot stands where planned.
  TerrainAdaptation blind(model, params);
  s.feet[0].in_contact = false;
  for (int i = 0; i < 100; ++i) blind.step(kDt, s, loads(-10.0, weight), {}, {0.0, 0.015}, left_failed);
  s.feet[0].in_contact = true;
  for (int i = 0; i < 500; ++i) blind.step(kDt, s, loads(-10.0, weight), {}, standing, both_failed);
  EXPECT_NEAR(blind.foot_offset(0), 0.015, 1e-9) << "no search without any trusted reading";

  // Trusted again, in the air over ground 1 cm lower than it thinks: a late contact searches.
  s.feet[0].in_contact = false;
  for (int i = 0; i < 50; ++i) blind.step(kDt, s, loads(-10.0, weight), {}, {0.0, 0.015});
  s.feet[0].in_contact = true;
  for (int i = 0; i < 200; ++i) blind.step(kDt, s, loads(-10.0, weight), {}, standing);
  EXPECT_LT(blind.foot_offset(0), 0.015 - 0.01) << "searching again";
}

// Both feet stand 0.1 s, the right one on `right_ground`, both turned by force control by `turn`
// (roll, pitch); then the left foot lifts 5 cm and comes down again at x = 0.4 m while the right one
// stands. `loaded(left, right)`: the feet's wrenches for those normal forces.
template <typename Loads>
void stand_then_swing_the_left_foot(TerrainAdaptation& terrain, PatternSample& s, double right_ground,
                                    const Eigen::Vector2d& turn, Loads loaded) {
  for (int i = 0; i < 100; ++i) {
    terrain.step(kDt, s, loaded(400.0, 400.0), {}, {0.0, right_ground}, {true, true}, {turn, turn});
  }
  s.feet[0].in_contact = false;
  s.feet[0].position.x() = 0.4;
  for (int i = 0; i < 1000; ++i) {
    s.feet[0].velocity.z() = i < 500 ? 0.1 : -0.1;
    s.feet[0].position.z() += s.feet[0].velocity.z() * kDt;
    terrain.step(kDt, s, loaded(0.0, 800.0), {}, {0.0, right_ground}, {true, true}, {Eigen::Vector2d::Zero(), turn});
  }
}

// Slopes: the right foot stands with its sole flat (centre of pressure inside it) where force
// control has turned it toes down by 0.05 rad and its left edge up by 0.03 rad, its foothold as
// much lower than the left one's as that slope gives; the left foot swings 0.2 m past it and 0.2 m
// to its left. On that downhill ground it lands turned the same and aims at the height the slope
// gives there. The same slope uphill (toes up): only its roll is taken (the side slope), not its
// pitch or height; the same with the downhill prediction off. Not taken at all: a slope measured
// with the centre of pressure at the toe (a sole rolling off its ground), a turned sole whose
// foothold is not lower (a step's edge under it), both options off.
TEST(TerrainAdaptation, DownhillTheSwingFootTakesTheSlopeTheStanceFootStandsOn) {
  const RobotModel model = test::load_model("lola");
  enum class Case { Downhill, Uphill, DownhillRollOnly, CopAtTheToe, StepEdge, Off };
  for (Case c : {Case::Downhill, Case::Uphill, Case::DownhillRollOnly, Case::CopAtTheToe, Case::StepEdge, Case::Off}) {
    TerrainAdaptationParams params;
    params.predict_slope = c != Case::Off && c != Case::DownhillRollOnly;
    params.take_side_slope = c != Case::Off;
    TerrainAdaptation terrain(model, params);
    const Eigen::Vector2d turn(0.03, c == Case::Uphill ? -0.05 : 0.05);  // (roll, pitch)
    const Eigen::Vector2d slope(-std::tan(turn.y()), std::tan(turn.x()));  // ∂z/∂x, ∂z/∂y
    PatternSample s;
    s.feet[0].position << 0.0, 0.1, 0.0;
    s.feet[1].position << 0.2, -0.1, 0.0;
    const double right_ground = c == Case::StepEdge ? 0.0 : slope.dot(Eigen::Vector2d(0.2, -0.2));
    const double toe = model.foot(Side::Right).sole_x_max - 0.005;
    auto loaded = [&](double left, double right) {
      std::array<Wrench, 2> w = loads(left, right);
      if (c == Case::CopAtTheToe) w[1].torque.y() = -toe * right;
      return w;
    };
    stand_then_swing_the_left_foot(terrain, s, right_ground, turn, loaded);
    const Eigen::Vector2d measured = terrain.ground_gradient(1);
    if (c == Case::CopAtTheToe) {
      EXPECT_EQ(measured, Eigen::Vector2d::Zero()) << "not measured";
    } else {
      EXPECT_NEAR((measured - slope).norm(), 0.0, 1e-9) << static_cast<int>(c);
    }
    if (c != Case::Downhill) {
      const bool rolls = c == Case::Uphill || c == Case::DownhillRollOnly;
      EXPECT_NEAR(terrain.foot_tilt(0), 0.0, 1e-9) << static_cast<int>(c);
      EXPECT_NEAR(terrain.foot_roll(0), rolls ? turn.x() : 0.0, rolls ? 1e-4 : 1e-9) << static_cast<int>(c);
      EXPECT_NEAR(terrain.foot_offset(0), right_ground, 1e-6) << "the stance foot's ground " << static_cast<int>(c);
      continue;
    }
    EXPECT_NEAR(terrain.foot_tilt(0), turn.y(), 1e-4);
    EXPECT_NEAR(terrain.foot_roll(0), turn.x(), 1e-4);
    EXPECT_NEAR(terrain.foot_offset(0), right_ground + slope.dot(Eigen::Vector2d(0.2, 0.2)), 1e-3);
  }
}

// Without the downhill prediction (JVRC-1's robot file), on ground that descends forward and to the
// left, the left foot swinging 0.2 m past the right stance foot and 0.2 m to its left (its last
// foothold lower than the stance foot's) rolls to the side slope and aims at the drop the side slope
// gives over those 0.2 m sideways, not the whole descent (the pitch's part stays out, as the pitch
// does). Switched off, at the stance foot's ground. On level footholds a roll of 1.4° (force
// control's turn following the sway reads as such) is taken as a roll only: aiming lower by it
// walked the footholds down; a steeper one (2.9°) is a side slope the footholds do not show yet
// (the first step onto it), and its drop is taken.
TEST(TerrainAdaptation, WithoutTheDownhillPredictionTheFootStillAimsAtTheSideSlopesDrop) {
  const RobotModel model = test::load_model("lola");
  enum class Case { SideSlope, Off, LevelFootholds, SteepOnLevelFootholds };
  for (Case c : {Case::SideSlope, Case::Off, Case::LevelFootholds, Case::SteepOnLevelFootholds}) {
    TerrainAdaptationParams params;
    params.predict_slope = false;
    params.side_slope_height = c != Case::Off;
    TerrainAdaptation terrain(model, params);
    const Eigen::Vector2d turn = c == Case::LevelFootholds ? Eigen::Vector2d(-0.025, 0.0) : Eigen::Vector2d(-0.05, 0.01);
    const Eigen::Vector2d slope(-std::tan(turn.y()), std::tan(turn.x()));  // ∂z/∂x, ∂z/∂y
    PatternSample s;
    s.feet[0].position << 0.0, 0.1, 0.0;
    s.feet[1].position << 0.2, -0.1, 0.0;
    const bool level = c == Case::LevelFootholds || c == Case::SteepOnLevelFootholds;
    const double right_ground = level ? 0.0 : slope.dot(Eigen::Vector2d(0.2, -0.2));
    stand_then_swing_the_left_foot(terrain, s, right_ground, turn, loads);
    const int k = static_cast<int>(c);
    EXPECT_NEAR(terrain.foot_tilt(0), 0.0, 1e-9) << k;
    EXPECT_NEAR(terrain.foot_roll(0), turn.x(), 1e-4) << k;
    const bool drop = c == Case::SideSlope || c == Case::SteepOnLevelFootholds;
    EXPECT_NEAR(terrain.foot_offset(0), right_ground + (drop ? slope.y() * 0.2 : 0.0), 1e-6) << k;
  }
}

// On flat ground the footholds' estimated heights stay at the ground's: no step may add a bias
// (a foot landing on time takes load only some 25 ms after the planned touchdown; a loaded sole is
// deflected). LOLA walks 20 s at 0.6 m/s; a bias of 1 mm per step, as before these were accounted
// for, ends 2 cm off (measured: 2.2 cm after 10 s). Ideal sensors, and the controller set up for an
// exactly mounted IMU that reports the exact orientation (as JVRC-1's robot file is): no attitude
// estimate, no model of an attitude filter's bias error, and no start-up misalignment estimate
// under 0.3° applied: the measured steps that set the footholds' level turn with the orientation's
// error (before them, the estimate's own error, RMS 0.06° here, moved these footholds by 1.5 cm;
// docs/stabilizer.md "Known limitations").
// On the long-step table (0.8 s steps at 0.6 m/s, about 22 footholds) within 5 mm (measured
// 2.8 mm). On the shipped table (0.5 s, about 36) within 8 mm, which a bias of 0.25 mm per step
// would exceed (measured 7.1 mm: each landing foot searches some 4 mm below the ground, as the
// robot leans back at touchdown, and the level's shift that answers it lifts the foot in swing
// too; the standing footholds 5.2 mm; docs/walking.md "Short steps").
TEST(TerrainAdaptation, FlatGroundFootholdsStayAtTheGroundsHeight) {
  for (const auto& [table, bound] : {std::pair<std::string, double>{"lola-long-steps.csv", 0.005}, {"lola.csv", 0.008}}) {
    const Scenario s = load_scenario(test::source_path("config/scenarios/lola-walk.yaml"),
                                     {"sensors.ideal=true", "controller.attitude_estimation.enabled=false",
                                      "controller.calibration.ahrs_time_constant=0",
                                      "controller.calibration.min_misalignment_deg=0.3",
                                      "controller.step_table=" + test::source_path("config/tables/" + table)});
    test::LargestFootholdOffset observer;
    const ScenarioResult result = run_scenario(s, make_run_config(s), "", &observer);
    ASSERT_FALSE(result.run.fell) << table;
    EXPECT_LT(observer.largest, bound) << table;
  }
}

// The measured steps on against off, in the default configuration (realistic sensor errors, the
// attitude estimate): JVRC-1, which walks 0.4 s steps and leans at every touchdown, 20 s at
// 0.5 m/s on flat ground. Measured: the footholds end at most 0.7 cm off measured, 5.2 cm without.
TEST(TerrainAdaptation, TheMeasuredStepsKeepTheFootholdsAtTheGround) {
  double largest[2] = {0.0, 0.0};
  for (const bool measure : {true, false}) {
    const Scenario s = load_scenario(test::source_path("config/scenarios/jvrc1-straight.yaml"),
                                     {"duration=20", std::string("controller.terrain_adaptation.measure_step_height=") +
                                                         (measure ? "true" : "false")});
    test::LargestFootholdOffset observer;
    const ScenarioResult result = run_scenario(s, make_run_config(s), "", &observer);
    ASSERT_FALSE(result.run.fell) << measure;
    largest[measure ? 0 : 1] = observer.largest;
  }
  EXPECT_LT(largest[0], 0.025);
  EXPECT_GT(largest[1], 2.0 * largest[0]);
}

// A run of LOLA's user campaign (seed 89, run 796, values rounded) with its push re-timed: a
// 16 N·s push from the left (80°) halfway through the last step of a stop, just as the robot comes
// to stand. The upper body tilts 16°; with the standing feet levelled it is back to 2.6° by the
// restart at 9.25 s and the robot walks on; without, the two feet's height offsets sink on together
// (by 1.5 cm), the tilt grows to 38° and the robot falls at 9.2 s. Measured, the stop's last
// touchdowns 9-11 at phases 0.1-0.9, 30-90°, 12-18 N·s: 23 situations walk only with the feet
// levelled, none only without; here also at phase 0.4 and 0.6 and at 70° and 85°. Without the
// balance steps before a stop: with them the pushed stop steps on, stands balanced and walks
// either way.
TEST(TerrainAdaptation, AStopPushedSidewaysWalksOnOnlyWithTheStandingFeetLevelled) {
  for (const bool level : {true, false}) {
    const Scenario s = load_scenario(
        test::source_path("config/scenarios/lola-walk.yaml"),
        {"duration=12", "seed=1813263936", "sensors.noise=false", "sensors.delay_cycles=0",
         "model_error.upper_body_mass_scale=1.093", "model_error.upper_body_com_offset=[-0.0166, 0.004, 0]",
         "commands=[{t: 0, vx: 0}, {t: 1, vx: 0.511, vy: 0.042, omega: -0.089}, {t: 3.49, vx: 0.273, vy: -0.041, "
         "omega: 0.141}, {t: 5.61, stop: true}, {t: 9.25, vx: 0.588, vy: -0.033, omega: 0.105}, {t: 10.86, stop: true}]",
         "disturbances=[{type: push, at: {touchdown: 11, phase: 0.5}, direction_deg: 80, impulse_Ns: 16, "
         "duration: 0.1}]",
         "terrain=[{type: step, x: 2.515, height: -0.0172}]", "controller.step_adaptation.balance_steps=0",
         std::string("controller.terrain_adaptation.level_standing_feet=") + (level ? "true" : "false")});
    const ScenarioResult result = run_scenario(s, make_run_config(s), "");
    EXPECT_EQ(result.run.fell, !level) << level;
  }
}

// Records the terrain adaptation's height offsets of the feet (the last ones logged).
class FootHeightOffsets : public RunObserver {
 public:
  void record(const Simulation&, const SensorData&, const JointCommand&, const ControllerStatus& status,
              double) override {
    offsets = status.foot_height_offset;
    state = status.state;
  }
  std::array<double, 2> offsets{};
  std::string state;
};

// JVRC-1 walking slowly: a transient NaN of the right F/T sensor (0.5 s) starts a safe stop, in
// whose steps the left foothold was latched 1.1 cm high and the right 0.9 cm low; the feet were
// levelled only after a stop, not after a safe stop, and standing on, the robot leaned onto its
// left foot by 12–15° and fell at 15.9 s. Now the feet stand level at the end and it stands. (Its
// campaign's run 1 of seed 109, the values as drawn: rounded to 4 digits the run stands either way.)
TEST(TerrainAdaptation, AfterASafeStopTheStandingFeetAreLevelledToo) {
  const Scenario s = load_scenario(
      test::source_path("config/scenarios/jvrc1-straight.yaml"),
      {"duration=17", "seed=1829560331", "sensors.noise=false", "sensors.delay_cycles=1",
       "model_error.upper_body_mass_scale=0.9837763317095958",
       "model_error.upper_body_com_offset=[0.008430606395790064, 0.005438961927762068, 0]",
       "commands=[{t: 0, vx: 0, vy: 0, omega: 0}, {t: 1, vx: 0.06315245273412648, vy: -0.0013670998994899652, "
       "omega: -0.12241087740695962}, {t: 3.924237296561108, vx: -0.06724677804905764, vy: 0.014061498617787063, "
       "omega: 0.1730367196060169}, {t: 6.054055087214433, stop: true}]",
       "sensors.faults=[{t: 4.833386723628545, sensor: ft_right, value: nan, duration: 0.5}]"});
  FootHeightOffsets offsets;
  const ScenarioResult result = run_scenario(s, make_run_config(s), "", &offsets);
  EXPECT_EQ(result.summary["fault"], "right F/T sensor");
  EXPECT_EQ(offsets.state, "safe_stop");
  EXPECT_FALSE(result.run.fell);
  EXPECT_LT(std::abs(offsets.offsets[0] - offsets.offsets[1]), 0.005);
}

// With ideal sensors: the adaptation's own effect. (With the robot files' realistic sensor errors
// and the sole contact across step edges, LOLA falls at the 1.25 m step down even with the
// adaptation: docs/simulation.md; the controller's robustness is another issue's.)
bool falls(const char* scenario, double x, bool adaptation, const std::string& terrain) {
  const Scenario s = load_scenario(test::source_path(std::string("config/scenarios/") + scenario + ".yaml"),
                                   {"terrain.0.x=" + std::to_string(x), terrain, "duration=10", "sensors.ideal=true",
                                    std::string("controller.terrain_adaptation.enabled=") + (adaptation ? "true" : "false")});
  return run_scenario(s, make_run_config(s), "").run.fell;
}

// LOLA at 0.4 m/s onto a 2.5 cm step up and a 6° slope it is not told about: with the adaptation it
// walks on (the slope up to 8° measured); without it (force control alone, bounded to ±2 cm and
// returning to zero in swing) it falls. With the swing foot that travels first and comes down
// vertically (the shipped tables since 2026-12-07) the 5° slope of the robustness issue's uphill goal
// walks without the adaptation too; 6°, 7° and 8° fall without it. History: with the earlier
// whole-swing table of 0.4 s steps 3° and 4° walked without it, 5° fell; with 1 s steps 3° fell.
TEST(TerrainAdaptation, UnexpectedStepUpAndSlopeAreWalkedOnlyWithTheAdaptation) {
  for (const auto& [scenario, terrain] : {std::pair<const char*, const char*>{"lola-terrain-step-up", "terrain.0.height=0.025"},
                                          {"lola-terrain-slope", "terrain.0.angle_deg=6"}}) {
    EXPECT_FALSE(falls(scenario, 1.0, true, terrain)) << scenario;
    EXPECT_TRUE(falls(scenario, 1.0, false, terrain)) << scenario;
  }
}

// The same onto a 3 cm step down (the robustness issue's ±3 cm): at x = 1.0 m the foot lands wholly
// on the lower level (late contact); at 1.2 and 1.25 m only the rear of its heel is on the upper
// level and the toe over the edge (partial support). With the adaptation all three walk. Without
// it the partly supported landings fall; the late contact at 1.0 m, met by a foot that comes down
// vertically, walks without it since the shipped tables set the foot down (2026-12-07: it fell with
// the whole-swing table at 5.6 s, and a 4 cm step there falls without the adaptation).
TEST(TerrainAdaptation, UnexpectedStepDownIsWalkedOnlyWithTheAdaptation) {
  for (double x : {1.0, 1.2, 1.25}) EXPECT_FALSE(falls("lola-terrain-step-down", x, true, "terrain.0.height=-0.03")) << x;
  for (double x : {1.2, 1.25}) EXPECT_TRUE(falls("lola-terrain-step-down", x, false, "terrain.0.height=-0.03")) << x;
}

// LOLA walking straight onto a 4.5° slope that rises or falls mostly sideways (its gradient at 65°
// or 75° from the walking direction, 4 m long), the robot file's realistic sensor errors: with the
// swing foot rolled to the side slope the stance foot stands on it walks; without, each foot landed
// level on it, on its uphill edge, and the robot drifted downhill touchdown by touchdown. Scanned
// (2026-12-07): 65° and 75°, ±4.5°, 0.3 and 0.5 m/s: none of the 8 falls with the roll, 4 without
// (the others tilt 7-24°); these are the 4. "Without" means the partial support's roll off as
// well: its feet 1-2 cm apart in height, the robot finds a step between them, and that roll alone
// walks the first of the 4 (measured 2026-12-07).
TEST(TerrainAdaptation, ASideSlopeIsWalkedOnlyWithTheFootRolledToIt) {
  for (const auto& [heading, angle, speed] : {std::tuple<double, double, double>{65.0, 4.5, 0.5},
                                              {65.0, -4.5, 0.5}, {75.0, -4.5, 0.3}, {75.0, -4.5, 0.5}}) {
    for (const bool roll : {true, false}) {
      const Scenario s = load_scenario(
          test::source_path("config/scenarios/lola-walk.yaml"),
          {"duration=14", "commands=[{t: 0, vx: 0}, {t: 1, vx: " + std::to_string(speed) + "}, {t: 11, stop: true}]",
           "terrain=[{type: slope, x: 1.2, heading_deg: " + std::to_string(heading) +
               ", angle_deg: " + std::to_string(angle) + ", length: 4}]",
           std::string("controller.terrain_adaptation.take_side_slope=") + (roll ? "true" : "false"),
           std::string("controller.terrain_adaptation.tilt_search_roll=") + (roll ? "true" : "false")});
      EXPECT_EQ(run_scenario(s, make_run_config(s), "").run.fell, !roll)
          << heading << "° " << angle << "° " << speed << " m/s, roll " << roll;
    }
  }
}

}  // namespace
}  // namespace biped
