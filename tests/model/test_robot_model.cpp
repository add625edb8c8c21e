// The two robot models against the data sheet (shared/robots.md) and the naming contract.
#include "model/robot_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "test_support.hpp"

namespace biped {
namespace {

constexpr double kDeg = M_PI / 180.0;

struct Range {
  double lower, upper;  // [deg], data sheet
};

// robots.md, right leg and arm; both sides use the same numbers (mirrored axes, see the model header).
const std::map<std::string, Range> kLolaRanges = {
    {"hip_yaw", {-26.1, 24.7}},   {"hip_roll", {-34.5, 40.4}},   {"hip_pitch", {-92.0, 44.9}},
    {"knee", {-4.5, 120.0}},      {"ankle_roll", {-23.5, 23.9}}, {"ankle_pitch", {-49.0, 43.8}},
    {"toe", {-49.5, 14.3}},       {"shoulder_pitch", {-170.0, 60.0}}, {"shoulder_roll", {-120.0, 1.5}},
    {"elbow", {-120.0, 5.0}},     {"pelvis_yaw", {-19.4, 19.4}}, {"pelvis_roll", {-15.1, 14.7}},
    {"head_pan", {-113.0, 113.0}}, {"head_tilt", {-51.0, 11.0}}, {"trunk_yaw", {-19.4, 19.4}}};

std::string range_key(const std::string& joint) {
  for (const char* prefix : {"left_", "right_"}) {
    if (joint.rfind(prefix, 0) == 0) return joint.substr(std::string(prefix).size());
  }
  return joint;
}

struct Expected {
  std::string robot;
  int joints;
  double mass;  // data sheet [kg]
  double sole_length, sole_width;
  std::vector<std::string> names;
};

class ModelTest : public ::testing::TestWithParam<Expected> {};

TEST_P(ModelTest, MatchesDataSheet) {
  const Expected& e = GetParam();
  const RobotModel model = test::load_model(e.robot);
  EXPECT_EQ(model.num_joints(), e.joints);
  EXPECT_EQ(model.mj()->nv, e.joints + 6);
  for (const std::string& name : e.names) EXPECT_GE(model.joint_index(name), 0) << name;
  EXPECT_NEAR(model.total_mass(), e.mass, 0.03 * e.mass);

  for (const JointInfo& j : model.joints()) {
    const auto it = kLolaRanges.find(range_key(j.name));
    ASSERT_NE(it, kLolaRanges.end()) << "no data-sheet range for " << j.name;
    EXPECT_NEAR(j.lower, it->second.lower * kDeg, 1e-6) << j.name;
    EXPECT_NEAR(j.upper, it->second.upper * kDeg, 1e-6) << j.name;
    EXPECT_NEAR(j.soft_lower, j.lower + 5 * kDeg, 1e-9);
    EXPECT_NEAR(j.soft_upper, j.upper - 5 * kDeg, 1e-9);
    EXPECT_GT(j.torque_limit, 0.0) << j.name;
    const double q = model.stand_pose()[model.joint_index(j.name)];
    EXPECT_GT(q, j.soft_lower) << j.name;
    EXPECT_LT(q, j.soft_upper) << j.name;
  }
  for (Side side : kSides) {
    const FootInfo& foot = model.foot(side);
    EXPECT_NEAR(foot.sole_x_max - foot.sole_x_min, e.sole_length, 1e-6);
    EXPECT_NEAR(foot.sole_y_max - foot.sole_y_min, e.sole_width, 1e-6);
    EXPECT_LT(foot.sole_z, 0.0) << "the sole lies below the F/T sensor";
    EXPECT_GT(foot.mass_below_sensor, 0.0);
    EXPECT_LT(foot.mass_below_sensor, 2.0);
  }
  EXPECT_NEAR(model.weight_above_sensors(),
              (model.total_mass() - model.foot(Side::Left).mass_below_sensor -
               model.foot(Side::Right).mass_below_sensor) * 9.81,
              1e-9);
}

// The sole segments (robots.md): LOLA's heel segment rigid with the sensor and a 0.08 m toe segment
// on the toe joint 0.20 m ahead of the heel edge (axis along y); JOHNNIE's one rigid sole.
TEST(RobotModel, SoleSegments) {
  const RobotModel lola = test::load_model("lola");
  for (Side side : kSides) {
    const FootInfo& foot = lola.foot(side);
    ASSERT_EQ(foot.num_segments, 2);
    const SoleSegment &heel = foot.segments[0], &toe = foot.segments[1];
    EXPECT_EQ(heel.joint, -1);
    EXPECT_EQ(lola.joints()[toe.joint].name, std::string(name_of(side)) + "_toe");
    EXPECT_NEAR(heel.x_min, foot.sole_x_min, 1e-9);
    EXPECT_NEAR(toe.x_max, foot.sole_x_max, 1e-9);
    EXPECT_NEAR(toe.x_max - toe.x_min, 0.08, 1e-6);
    EXPECT_NEAR(toe.axis_point.x() - heel.x_min, 0.20, 1e-6);
    EXPECT_NEAR(heel.x_max, toe.x_min, 1e-6);
    EXPECT_NEAR(std::abs(toe.axis.y()), 1.0, 1e-9);
    EXPECT_NEAR(heel.z, toe.z, 1e-9) << "one flat sole at toe angle zero";
  }
  const RobotModel johnnie = test::load_model("johnnie");
  for (Side side : kSides) {
    const FootInfo& foot = johnnie.foot(side);
    ASSERT_EQ(foot.num_segments, 1);
    EXPECT_EQ(foot.segments[0].joint, -1);
    EXPECT_EQ(foot.segments[0].x_min, foot.sole_x_min);
    EXPECT_EQ(foot.segments[0].y_max, foot.sole_y_max);
  }
}

const std::vector<std::string> kLegJoints = {"hip_yaw", "hip_roll", "hip_pitch", "knee", "ankle_pitch", "ankle_roll"};

std::vector<std::string> sided(const std::vector<std::string>& joints) {
  std::vector<std::string> out;
  for (const char* side : {"left_", "right_"}) {
    for (const auto& j : joints) out.push_back(side + j);
  }
  return out;
}

std::vector<std::string> lola_names() {
  auto legs = kLegJoints;
  legs.push_back("toe");
  auto names = sided(legs);
  for (const auto& j : sided({"shoulder_pitch", "shoulder_roll", "elbow"})) names.push_back(j);
  for (const char* j : {"pelvis_yaw", "pelvis_roll", "head_pan", "head_tilt"}) names.push_back(j);
  return names;
}

std::vector<std::string> johnnie_names() {
  auto names = sided(kLegJoints);
  for (const auto& j : sided({"shoulder_pitch", "shoulder_roll"})) names.push_back(j);
  names.push_back("trunk_yaw");
  return names;
}

INSTANTIATE_TEST_SUITE_P(Robots, ModelTest,
                         ::testing::Values(Expected{"lola", 24, 55.0, 0.28, 0.14, lola_names()},
                                           Expected{"johnnie", 17, 40.0, 0.24, 0.12, johnnie_names()}),
                         [](const auto& info) { return info.param.robot; });

TEST(RobotModel, MissingFileNamesTheFile) {
  try {
    RobotModel::load("/nonexistent/robot.xml", 0.0);
    FAIL() << "expected ModelError";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/robot.xml"), std::string::npos);
  }
}

TEST(RobotModel, JointIndexOfUnknownNameIsMinusOne) {
  const RobotModel model = test::load_model("johnnie");
  EXPECT_EQ(model.joint_index("left_toe"), -1);
  EXPECT_EQ(model.joint_index("left_knee"), 3);
}

}  // namespace
}  // namespace biped
