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

// JVRC-1's parts under its own names (config/robots/jvrc1.yaml holds the full map).
ModelMap jvrc1_map() {
  ModelMap map;
  map.root_body = "PELVIS_S";
  map.upper_body = "PELVIS_S";
  map.imu_orientation = "";
  map.imu_gyro = "Accelerometer_gyro";
  map.imu_accelerometer = "Accelerometer_accelerometer";
  const SoleRectangle sole{-0.095, 0.155, -0.05, 0.05, -0.1077};
  map.legs[index_of(Side::Left)] = {"L_HIP_P", "", "L_ANKLE_P_S", "lf_force", "LeftFootForceSensor_fsensor",
                                    "LeftFootForceSensor_tsensor", "L_SHOULDER_P", sole};
  map.legs[index_of(Side::Right)] = {"R_HIP_P", "", "R_ANKLE_P_S", "rf_force", "RightFootForceSensor_fsensor",
                                     "RightFootForceSensor_tsensor", "R_SHOULDER_P", sole};
  map.stand_pose = {{"L_HIP_P", -0.4}, {"L_KNEE", 0.8}, {"L_ANKLE_P", -0.4},
                    {"R_HIP_P", -0.4}, {"R_KNEE", 0.8}, {"R_ANKLE_P", -0.4}};
  map.torque_limits = {{"L_KNEE", 340.0}};
  map.passive_joints = {"L_LTHUMB"};
  return map;
}
const std::string kJvrc1 = test::source_path("models/jvrc1/xml/jvrc1.xml");

TEST(RobotModelMap, NamesAnotherModelsPartsAndGivesItsSolesAndPoseAsData) {
  const RobotModel model = RobotModel::load(kJvrc1, 5.0 * kDeg, jvrc1_map());
  EXPECT_EQ(model.joints()[model.leg_root_joint(Side::Left)].name, "L_HIP_P");
  EXPECT_EQ(model.joints()[model.arm_root_joint(Side::Right)].name, "R_SHOULDER_P");
  EXPECT_EQ(model.toe_joint(Side::Left), -1);
  EXPECT_EQ(model.imu_orientation_sensor(), -1);
  EXPECT_EQ(model.body_named("upper_body"), model.upper_body());
  EXPECT_TRUE(model.foot(Side::Left).sole_geoms.empty());
  EXPECT_EQ(model.foot(Side::Left).num_segments, 1);
  EXPECT_DOUBLE_EQ(model.foot(Side::Left).sole_x_max - model.foot(Side::Left).sole_x_min, 0.25);
  EXPECT_DOUBLE_EQ(model.joints()[model.joint_index("L_KNEE")].torque_limit, 340.0);
  EXPECT_TRUE(model.joints()[model.joint_index("L_LTHUMB")].passive);
  EXPECT_FALSE(model.joints()[model.joint_index("L_UTHUMB")].passive);
  EXPECT_DOUBLE_EQ(model.stand_pose()[model.joint_index("L_KNEE")], 0.8);

  // The stand pose's soles rest level on z = 0: every corner of both rectangles at height zero.
  RobotData data(model);
  data.qpos() = model.stand_qpos();
  mj_kinematics(model.mj(), data.mj());
  for (Side side : kSides) {
    const FootInfo& foot = model.foot(side);
    for (double x : {foot.sole_x_min, foot.sole_x_max}) {
      for (double y : {foot.sole_y_min, foot.sole_y_max}) {
        const Eigen::Vector3d corner =
            data.site_position(foot.sensor_site) + data.site_rotation(foot.sensor_site) * Eigen::Vector3d(x, y, foot.sole_z);
        EXPECT_NEAR(corner.z(), 0.0, 1e-9);
      }
    }
  }
}

TEST(RobotModelMap, AMissingPartIsNamedAndTheDefaultsAreTheContract) {
  ModelMap map = jvrc1_map();
  map.legs[index_of(Side::Right)].ft_site = "no_such_site";
  try {
    RobotModel::load(kJvrc1, 5.0 * kDeg, map);
    FAIL() << "expected ModelError";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("'no_such_site'"), std::string::npos) << e.what();
  }
  map = jvrc1_map();
  map.passive_joints = {"NO_JOINT"};
  EXPECT_THROW(RobotModel::load(kJvrc1, 5.0 * kDeg, map), ModelError);
  EXPECT_THROW(RobotModel::load(kJvrc1, 5.0 * kDeg), ModelError);  // JVRC-1 does not follow the contract
  EXPECT_NO_THROW(test::load_model("lola"));                         // LOLA does
}

}  // namespace
}  // namespace biped
