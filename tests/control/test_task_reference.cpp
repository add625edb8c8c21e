// The reference of eq. (21) in Table I's coordinates: the pattern's feet and CoM in their rows, the
// terrain adaptation's offsets and tilts only in the foot height, foot tilt and CoM height rows, the
// arms where they were at the start when they do not swing, rates that are the references' time
// derivatives, and the stabilizer's modification in the foot rows, turned into the heading frame.
#include "control/task_reference.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "math/rotations.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

constexpr double kDt = 0.001;

std::array<Wrench, 2> loads(double left, double right) {
  std::array<Wrench, 2> w;
  w[0].force.z() = left;
  w[1].force.z() = right;
  return w;
}

// A walking instant: the left foot swinging forward, turned against the upper body's heading.
PatternSample walking_sample() {
  PatternSample s;
  s.com = Eigen::Vector3d(0.05, 0.01, 0.85);
  s.com_velocity = Eigen::Vector3d(0.3, -0.02, 0.01);
  s.feet[0].position = Eigen::Vector3d(0.2, 0.1, 0.12);
  s.feet[0].velocity = Eigen::Vector3d(0.6, 0.01, -0.1);
  s.feet[0].yaw = 0.1;
  s.feet[0].yaw_rate = 0.2;
  s.feet[0].in_contact = false;
  s.feet[1].position = Eigen::Vector3d(-0.1, -0.1, 0.09);
  s.feet[1].yaw = -0.05;
  s.heading = 0.02;
  s.heading_rate = 0.1;
  s.arm_swing = 0.01;
  s.arm_swing_rate = 0.05;
  return s;
}

Eigen::Vector3d yawed(double angle, const Eigen::Vector3d& v) {
  return Eigen::Vector3d(std::cos(angle) * v.x() - std::sin(angle) * v.y(),
                         std::sin(angle) * v.x() + std::cos(angle) * v.y(), v.z());
}

class TaskReferenceTest : public ::testing::TestWithParam<std::string> {
 protected:
  TaskReferenceTest()
      : model(test::load_model(GetParam())), space(model), start(space), L(space.layout()), flat(model, {}) {
    evaluate(space, model.stand_qpos(), Eigen::Matrix3d::Identity(), start);
    flat.reset();
  }
  RobotModel model;
  TaskSpace space;
  TaskSpaceData start;
  const TaskLayout& L;
  TerrainAdaptation flat;  // fresh: zero offsets and tilts
  UpperBodyLean upright{UpperBodyLeanParams{}};  // fresh: no lean
};

TEST_P(TaskReferenceTest, FootAndComRowsAreThePatternsOnFlatGround) {
  TaskReference ref(space);
  ref.reset(start, 0.0);
  const PatternSample s = walking_sample();
  ref.update(s, flat, upright, start);
  const Eigen::VectorXd& x = ref.x();
  const Eigen::VectorXd& xd = ref.rate();
  for (int k = 0; k < 2; ++k) {
    EXPECT_LT((x.segment<3>(L.foot_position[k]) - (s.feet[k].position - s.com)).norm(), 1e-15) << k;
    EXPECT_LT((xd.segment<3>(L.foot_position[k]) - (s.feet[k].velocity - s.com_velocity)).norm(), 1e-15) << k;
    EXPECT_LT((x.segment<3>(L.foot_orientation[k]) - Eigen::Vector3d(0, 0, s.feet[k].yaw - s.heading)).norm(), 1e-15);
    EXPECT_NEAR(xd[L.foot_orientation[k] + 2], s.feet[k].yaw_rate - s.heading_rate, 1e-15);
  }
  EXPECT_LT((x.segment<3>(L.com) - s.com).norm(), 1e-15);
  EXPECT_LT((xd.segment<3>(L.com) - s.com_velocity).norm(), 1e-15);
  EXPECT_EQ(x.segment<3>(L.upper_body_orientation), Eigen::Vector3d::Zero());
  EXPECT_LT((xd.segment<3>(L.upper_body_orientation) - Eigen::Vector3d(0, 0, s.heading_rate)).norm(), 1e-15);
}

// x with the terrain adaptation minus x without it: the foot height offsets (less the CoM's) in the
// foot z rows, the tilts about each foot's lateral axis in its orientation rows, the CoM offset in
// the CoM z row, nothing anywhere else; the same for the rates.
void expect_terrain_only_in_its_rows(const TaskSpace& space, const TerrainAdaptation& flat,
                                     const TerrainAdaptation& terrain, const PatternSample& s,
                                     const TaskSpaceData& start) {
  const TaskLayout& L = space.layout();
  TaskReference with(space), without(space);
  const UpperBodyLean upright{UpperBodyLeanParams{}};
  with.reset(start, 0.0);
  without.reset(start, 0.0);
  with.update(s, terrain, upright, start);
  without.update(s, flat, upright, start);
  Eigen::VectorXd expected = Eigen::VectorXd::Zero(space.dim());
  Eigen::VectorXd expected_rate = Eigen::VectorXd::Zero(space.dim());
  for (int k = 0; k < 2; ++k) {
    expected[L.foot_position[k] + 2] = terrain.foot_offset(k) - terrain.com_offset();
    expected_rate[L.foot_position[k] + 2] = terrain.foot_offset_rate(k) - terrain.com_offset_rate();
    const Eigen::Vector3d lateral = yawed(s.feet[k].yaw - s.heading, Eigen::Vector3d::UnitY());
    expected.segment<3>(L.foot_orientation[k]) = terrain.foot_tilt(k) * lateral;
    expected_rate.segment<3>(L.foot_orientation[k]) = terrain.foot_tilt_rate(k) * lateral;
  }
  expected[L.com + 2] = terrain.com_offset();
  expected_rate[L.com + 2] = terrain.com_offset_rate();
  EXPECT_LT((with.x() - without.x() - expected).cwiseAbs().maxCoeff(), 1e-12)
      << (with.x() - without.x()).transpose() << "\nexpected " << expected.transpose();
  EXPECT_LT((with.rate() - without.rate() - expected_rate).cwiseAbs().maxCoeff(), 1e-12)
      << (with.rate() - without.rate()).transpose() << "\nexpected " << expected_rate.transpose();
}

// A late foot searching down for the ground, found 2 cm low; the CoM height following it.
TEST_P(TaskReferenceTest, TerrainHeightOffsetsEnterOnlyTheHeightRows) {
  TerrainAdaptation terrain(model, {});
  terrain.reset();
  PatternSample s;
  s.feet[0].in_contact = false;
  terrain.step(kDt, s, loads(-10.0, 500.0));
  s.feet[0].in_contact = true;
  for (int i = 0; i < 120; ++i) terrain.step(kDt, s, loads(-10.0, 500.0));
  for (int i = 0; i < 100; ++i) terrain.step(kDt, s, loads(300.0, 200.0));
  ASSERT_LT(terrain.foot_offset(0), -0.01);
  ASSERT_LT(terrain.com_offset(), -0.001);
  ASSERT_LT(terrain.com_offset_rate(), -0.001);
  expect_terrain_only_in_its_rows(space, flat, terrain, walking_sample(), start);
}

// A foot yawed 30° against the heading, tilted toes down about a sole edge after touchdown: the tilt
// is about the foot's own lateral axis, seen from the heading frame.
TEST_P(TaskReferenceTest, TerrainTiltEntersTheFootOrientationRowsAboutTheFootsLateralAxis) {
  TerrainAdaptation terrain(model, {});
  terrain.reset();
  PatternSample s;
  Wrench desired;
  desired.force.z() = 400.0;
  desired.torque.y() = -0.05 * 400.0;  // desired CoP 5 cm ahead of the ankle
  std::array<Wrench, 2> measured = loads(400.0, 400.0);
  s.feet[0].in_contact = false;
  s.load_share = {0.0, 1.0};
  terrain.step(kDt, s, measured, {desired, desired});
  s.feet[0].in_contact = true;
  measured[0].torque.y() = 0.08 * 400.0;  // measured CoP 8 cm behind the ankle: the toe is unsupported
  for (int i = 0; i < 100; ++i) {
    s.load_share = {0.005 * (i + 1), 1.0 - 0.005 * (i + 1)};
    terrain.step(kDt, s, measured, {desired, desired});
  }
  ASSERT_GT(terrain.foot_tilt(0), 0.02);
  ASSERT_GT(terrain.foot_tilt_rate(0), 0.0);
  PatternSample walking = walking_sample();
  walking.feet[0].yaw = walking.heading + M_PI / 6.0;
  expect_terrain_only_in_its_rows(space, flat, terrain, walking, start);
}

// At zero arm swing the arm rows are the arms' CoMs relative to the robot CoM at the start, also
// when the robot starts turned against the world's x axis.
TEST_P(TaskReferenceTest, ArmRowsWithoutSwingAreTheStartOffsets) {
  for (double heading : {0.0, 0.7}) {
    Eigen::VectorXd q = model.stand_qpos();
    const Eigen::Quaterniond turned(Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()) *
                                    Eigen::Quaterniond(q[3], q[4], q[5], q[6]));
    q.segment<4>(3) << turned.w(), turned.x(), turned.y(), turned.z();
    TaskSpaceData turned_start(space);
    evaluate(space, q, Eigen::Matrix3d::Identity(), turned_start);
    TaskReference ref(space);
    ref.reset(turned_start, heading);
    PatternSample s = walking_sample();
    s.heading = heading;
    s.arm_swing = 0.0;
    ref.update(s, flat, upright, turned_start);
    for (int k = 0; k < 2; ++k) {
      const Eigen::VectorXd row = ref.x().segment(L.arm_com[k], L.arm_com_rows);
      const Eigen::VectorXd at_start = turned_start.x.segment(L.arm_com[k], L.arm_com_rows);
      EXPECT_LT((row - at_start).norm(), 1e-12) << "heading " << heading << " arm " << k;
    }
  }
}

// A leaning upper body: its orientation rows are the lean, the feet's (relative to it) turn back so
// that each foot keeps its orientation in the heading frame, and the arms turn with it.
TEST_P(TaskReferenceTest, LeaningUpperBodyKeepsTheFeetAndTurnsTheArms) {
  UpperBodyLeanParams params;
  params.enabled = true;
  UpperBodyLean leaning(params);
  for (int k = 0; k < 3000; ++k) leaning.update(kDt, {0.1, -0.09}, true);
  ASSERT_GT(leaning.angle().cwiseAbs().minCoeff(), 0.1);
  TaskReference with(space), without(space);
  with.reset(start, 0.0);
  without.reset(start, 0.0);
  PatternSample s = walking_sample();
  s.arm_swing = 0.0;
  with.update(s, flat, leaning, start);
  without.update(s, flat, upright, start);
  EXPECT_LT((with.x().segment<3>(L.upper_body_orientation) - leaning.rotation_vector()).norm(), 1e-15);
  const Eigen::Matrix3d lean = math::so3::exp(leaning.rotation_vector());
  for (int k = 0; k < 2; ++k) {
    const Eigen::Matrix3d foot_with = lean * math::so3::exp(with.x().segment<3>(L.foot_orientation[k]));
    const Eigen::Matrix3d foot_without = math::so3::exp(without.x().segment<3>(L.foot_orientation[k]));
    EXPECT_LT((foot_with - foot_without).norm(), 1e-12) << k;
  }
  if (L.arm_com_rows == 3) {
    for (int k = 0; k < 2; ++k) {
      const Eigen::Vector3d from_body = start.com - start.upper_body_position;
      const Eigen::Vector3d arm_with = with.x().segment<3>(L.arm_com[k]) + from_body;
      const Eigen::Vector3d arm_without = without.x().segment<3>(L.arm_com[k]) + from_body;
      // The lean is about the heading frame's axes.
      const Eigen::Matrix3d heading = Eigen::AngleAxisd(s.heading, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      EXPECT_LT((arm_with - heading * lean * heading.transpose() * arm_without).norm(), 1e-12) << k;
    }
  }
}

// ẋ_id is the time derivative of x_id when the sample moves with its own rates (the upper-body
// orientation rows excepted: x holds them at zero in the turning heading frame, ẋ carries that
// frame's turn rate for eq. (21)).
TEST_P(TaskReferenceTest, RatesAreTheTimeDerivativesOfTheReference) {
  const PatternSample s = walking_sample();
  auto at = [&](double h) {
    PatternSample moved = s;
    moved.com += h * s.com_velocity;
    for (int k = 0; k < 2; ++k) {
      moved.feet[k].position += h * s.feet[k].velocity;
      moved.feet[k].yaw += h * s.feet[k].yaw_rate;
    }
    moved.heading += h * s.heading_rate;
    moved.arm_swing += h * s.arm_swing_rate;
    TaskReference ref(space);
    ref.reset(start, 0.0);
    ref.update(moved, flat, upright, start);
    return std::pair<Eigen::VectorXd, Eigen::VectorXd>(ref.x(), ref.rate());
  };
  const double h = 1e-6;
  const Eigen::VectorXd difference = (at(h).first - at(-h).first) / (2.0 * h);
  Eigen::VectorXd rate = at(0.0).second;
  EXPECT_GT(rate.segment(L.arm_com[0], L.arm_com_rows).norm(), 0.01) << "the arms swing";
  rate.segment<3>(L.upper_body_orientation) = difference.segment<3>(L.upper_body_orientation);
  EXPECT_LT((rate - difference).cwiseAbs().maxCoeff(), 1e-7)
      << "rate " << rate.transpose() << "\ndifference " << difference.transpose();
}

// Δx: each foot's height offset in its z row, its tilts (about the foot's own x and y axes) turned
// by the foot's yaw against the heading into the orientation rows; nothing else.
TEST_P(TaskReferenceTest, ModificationGoesIntoTheFootRowsTurnedIntoTheHeadingFrame) {
  TaskReference ref(space);
  ref.reset(start, 0.0);
  PatternSample s = walking_sample();
  s.heading = 0.1;
  s.feet[0].yaw = s.heading + M_PI / 6.0;  // the left foot turned 30° against the heading
  s.feet[1].yaw = s.heading;
  std::array<FootModification, 2> m;
  m[0].offset = Eigen::Vector3d(0.004, 0.02, -0.03);
  m[0].rate = Eigen::Vector3d(0.1, 0.5, -0.2);
  m[1].offset = Eigen::Vector3d(-0.002, -0.01, 0.015);
  m[1].rate = Eigen::Vector3d(-0.05, 0.1, 0.3);
  ref.set_modification(s, m);

  Eigen::VectorXd expected = Eigen::VectorXd::Zero(space.dim());
  Eigen::VectorXd expected_rate = Eigen::VectorXd::Zero(space.dim());
  const double c = std::cos(M_PI / 6.0), sn = std::sin(M_PI / 6.0);
  const int left = L.foot_orientation[0], right = L.foot_orientation[1];
  expected[L.foot_position[0] + 2] = 0.004;
  expected.segment<3>(left) << c * 0.02 - sn * -0.03, sn * 0.02 + c * -0.03, 0.0;
  expected_rate[L.foot_position[0] + 2] = 0.1;
  expected_rate.segment<3>(left) << c * 0.5 - sn * -0.2, sn * 0.5 + c * -0.2, 0.0;
  expected[L.foot_position[1] + 2] = -0.002;
  expected.segment<3>(right) << -0.01, 0.015, 0.0;  // no yaw against the heading: unturned
  expected_rate[L.foot_position[1] + 2] = -0.05;
  expected_rate.segment<3>(right) << 0.1, 0.3, 0.0;
  EXPECT_LT((ref.modification() - expected).cwiseAbs().maxCoeff(), 1e-15) << ref.modification().transpose();
  EXPECT_LT((ref.modification_rate() - expected_rate).cwiseAbs().maxCoeff(), 1e-15)
      << ref.modification_rate().transpose();

  ref.decay_modification(0.25);
  EXPECT_LT((ref.modification() - 0.25 * expected).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_EQ(ref.modification_rate(), Eigen::VectorXd::Zero(space.dim()));

  ref.reset(start, 0.0);
  EXPECT_EQ(ref.modification(), Eigen::VectorXd::Zero(space.dim())) << "reset clears the modification";
}

INSTANTIATE_TEST_SUITE_P(Robots, TaskReferenceTest, ::testing::Values("lola", "johnnie"),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace biped
