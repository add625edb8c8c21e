// The robot checks on the shipped models, on a small biped built here, and on deliberately broken
// maps and models: every problem found, each under its robot-file key.
#include "model/model_check.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <memory>

#include "test_support.hpp"

namespace biped {
namespace {

constexpr double kMargin = 5.0 * M_PI / 180.0;

struct MjModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
using ModelPtr = std::unique_ptr<mjModel, MjModelDeleter>;

ModelPtr load(const std::string& path) {
  char error[1000] = "";
  ModelPtr m(mj_loadXML(path.c_str(), nullptr, error, sizeof(error)));
  EXPECT_TRUE(m) << error;
  return m;
}

// A small biped in the naming contract of models/README.md: a free-floating pelvis, a `hips` body
// on a roll joint carrying both legs (6 hinges each, a box sole and an F/T site in the foot), an
// upper body with the IMU and one-joint arms, and `extra_world` added to <worldbody>.
ModelPtr small_biped(const std::string& extra_world = "") {
  auto leg = [](const std::string& s, double y) {
    return "<body name='" + s + "_thigh' pos='0 " + std::to_string(y) + " -0.05'>"
           "<joint name='" + s + "_hip_yaw' axis='0 0 1'/><joint name='" + s + "_hip_roll' axis='1 0 0'/>"
           "<joint name='" + s + "_hip_pitch' axis='0 1 0'/><geom type='capsule' fromto='0 0 0 0 0 -0.4' size='0.04'/>"
           "<body name='" + s + "_shank' pos='0 0 -0.4'><joint name='" + s + "_knee' axis='0 1 0'/>"
           "<geom type='capsule' fromto='0 0 0 0 0 -0.4' size='0.04'/>"
           "<body name='" + s + "_foot' pos='0 0 -0.4'><joint name='" + s + "_ankle_pitch' axis='0 1 0'/>"
           "<joint name='" + s + "_ankle_roll' axis='1 0 0'/><site name='" + s + "_ft' pos='0 0 -0.03'/>"
           "<geom name='" + s + "_sole' type='box' pos='0.03 0 -0.07' size='0.1 0.05 0.01'/></body></body></body>";
  };
  std::string motors, sensors = "<framequat name='imu_quat' objtype='site' objname='imu'/>"
                                "<gyro name='imu_gyro' site='imu'/><accelerometer name='imu_accel' site='imu'/>";
  std::vector<std::string> joints = {"hips_roll", "waist", "left_shoulder_pitch", "right_shoulder_pitch"};
  for (const char* s : {"left", "right"}) {
    for (const char* j : {"_hip_yaw", "_hip_roll", "_hip_pitch", "_knee", "_ankle_pitch", "_ankle_roll"}) {
      joints.push_back(s + std::string(j));
    }
    sensors += "<force name='" + std::string(s) + "_ft_force' site='" + s + "_ft'/><torque name='" + s + "_ft_torque' site='" + s + "_ft'/>";
  }
  for (const std::string& j : joints) motors += "<motor name='" + j + "' joint='" + j + "'/>";
  const std::string xml =
      "<mujoco model='small'><compiler angle='degree'/>"
      "<default><joint limited='true' range='-60 60'/><motor ctrllimited='true' ctrlrange='-100 100'/>"
      "<geom mass='1'/></default><worldbody>" + extra_world +
      "<body name='pelvis' pos='0 0 1'><freejoint name='root'/><geom type='box' size='0.1 0.15 0.05'/>"
      "<body name='hips'><joint name='hips_roll' axis='1 0 0'/><geom type='sphere' size='0.05'/>" +
      leg("left", 0.1) + leg("right", -0.1) +
      "</body><body name='upper_body'><joint name='waist' axis='0 0 1'/><geom type='box' pos='0 0 0.3' size='0.1 0.15 0.2'/>"
      "<site name='imu' pos='0 0 0.1'/>"
      "<body name='left_arm' pos='0 0.2 0.4'><joint name='left_shoulder_pitch' axis='0 1 0'/>"
      "<geom type='capsule' fromto='0 0 0 0 0 -0.4' size='0.03'/></body>"
      "<body name='right_arm' pos='0 -0.2 0.4'><joint name='right_shoulder_pitch' axis='0 1 0'/>"
      "<geom type='capsule' fromto='0 0 0 0 0 -0.4' size='0.03'/></body></body></body></worldbody>"
      "<actuator>" + motors + "</actuator><sensor>" + sensors + "</sensor></mujoco>";
  const std::filesystem::path file = test::fresh_dir("model-check") / "small.xml";
  std::ofstream(file) << xml;
  return load(file.string());
}

ModelMap small_biped_map() {
  ModelMap map;
  map.stand_pose = {{"left_hip_pitch", -0.3}, {"left_knee", 0.6}, {"left_ankle_pitch", -0.3},
                    {"right_hip_pitch", -0.3}, {"right_knee", 0.6}, {"right_ankle_pitch", -0.3}};
  return map;
}

std::vector<std::string> keys(const std::vector<ModelProblem>& problems) {
  std::vector<std::string> k;
  for (const ModelProblem& p : problems) k.push_back(p.key);
  return k;
}

std::string all(const std::vector<ModelProblem>& problems) {
  std::string text;
  for (const ModelProblem& p : problems) text += "[" + p.key + "] " + p.message + "\n";
  return text;
}

TEST(ModelCheck, ShippedModelsPass) {
  for (const char* robot : {"lola", "johnnie"}) {
    const ModelPtr m = load(test::model_path(robot));
    EXPECT_TRUE(check_model_map(m.get(), ModelMap{}, kMargin).empty()) << robot << "\n" << all(check_model_map(m.get(), ModelMap{}, kMargin));
    const RobotModel model = test::load_model(robot);
    EXPECT_TRUE(check_robot_geometry(model).empty()) << robot << "\n" << all(check_robot_geometry(model));
  }
  const ModelPtr small = small_biped();
  EXPECT_TRUE(check_model_map(small.get(), small_biped_map(), kMargin).empty())
      << all(check_model_map(small.get(), small_biped_map(), kMargin));
}

TEST(ModelCheck, EveryMissingNameUnderItsKey) {
  const ModelPtr m = load(test::model_path("lola"));
  ModelMap map;
  map.legs[0].ft_site = "left_ft_typo";
  map.legs[1].root_joint = "right_hip_yaww";
  map.imu_gyro = "imu_gyroscope";
  map.legs[0].arm_root_joint = "left_shoulder";
  map.legs[1].foot_body = "right_feet";
  const std::vector<ModelProblem> problems = check_model_map(m.get(), map, kMargin);
  const std::vector<std::string> k = keys(problems);
  for (const char* key : {"model_map.legs.left.ft_site", "model_map.legs.right.root_joint", "model_map.imu.gyro",
                          "model_map.arms.left", "model_map.legs.right.foot_body"}) {
    EXPECT_EQ(std::count(k.begin(), k.end(), key), 1) << key << "\n" << all(problems);
  }
  EXPECT_EQ(problems.size(), 5u) << "a missing part is reported once, not again by the checks that need it\n" << all(problems);
  const auto site = std::find(k.begin(), k.end(), "model_map.legs.left.ft_site") - k.begin();
  EXPECT_EQ(problems[site].message, "the model has no site named 'left_ft_typo'");
}

TEST(ModelCheck, WrongKindsAndPlaces) {
  const ModelPtr m = load(test::model_path("lola"));
  ModelMap map;
  map.imu_gyro = "imu_accel";                   // an accelerometer
  map.legs[0].ft_force = "right_ft_force";      // on the other foot's site
  map.legs[1].ft_site = "left_ft";              // the same site as the left foot's, in another body
  map.imu_site = "left_ft";                     // not in the upper body
  const std::vector<std::string> k = keys(check_model_map(m.get(), map, kMargin));
  for (const char* key : {"model_map.imu.gyro", "model_map.legs.left.ft_force", "model_map.legs.right.ft_site",
                          "model_map.imu.site"}) {
    EXPECT_NE(std::find(k.begin(), k.end(), key), k.end()) << key;
  }
}

TEST(ModelCheck, LegsAreChainsOfTheirOwn) {
  const ModelPtr m = load(test::model_path("lola"));
  ModelMap map;
  map.legs[0].root_joint = "right_hip_yaw";  // not above the left foot
  std::vector<ModelProblem> problems = check_model_map(m.get(), map, kMargin);
  ASSERT_EQ(problems.size(), 1u) << all(problems);
  EXPECT_EQ(problems[0].key, "model_map.legs.left.root_joint");
  EXPECT_NE(problems[0].message.find("not above the foot"), std::string::npos);

  map = ModelMap{};
  map.legs[0].root_joint = "left_knee";  // 3 joints to the foot
  problems = check_model_map(m.get(), map, kMargin);
  ASSERT_EQ(problems.size(), 1u) << all(problems);
  EXPECT_NE(problems[0].message.find("3 driven joints (left_knee, left_ankle_pitch, left_ankle_roll)"), std::string::npos)
      << problems[0].message;

  map = ModelMap{};
  map.passive_joints = {"left_knee"};  // and it still has its motor
  problems = check_model_map(m.get(), map, kMargin);
  EXPECT_EQ(keys(problems), (std::vector<std::string>{"model_map.passive_joints", "model_map.passive_joints",
                                                       "model_map.legs.left.root_joint"})) << all(problems);
  EXPECT_EQ(problems[1].message, "joint 'left_knee' is in the left leg: every leg joint needs a drive");

  map = ModelMap{};
  map.locked_joints = {"right_ankle_roll", "head_pann"};
  EXPECT_EQ(keys(check_model_map(m.get(), map, kMargin)),
            (std::vector<std::string>{"model_map.locked_joints", "model_map.locked_joints", "model_map.legs.right.root_joint"}));

  // A joint above both legs is not a leg's first joint.
  const ModelPtr small = small_biped();
  map = small_biped_map();
  map.legs[0].root_joint = "hips_roll";
  problems = check_model_map(small.get(), map, kMargin);
  ASSERT_EQ(problems.size(), 1u) << all(problems);
  EXPECT_EQ(problems[0].key, "model_map.legs.left.root_joint");
  EXPECT_NE(problems[0].message.find("also holds the right foot"), std::string::npos) << problems[0].message;

  map = small_biped_map();
  map.legs[1].arm_root_joint = "left_shoulder_pitch";
  EXPECT_EQ(keys(check_model_map(small.get(), map, kMargin)), std::vector<std::string>{"model_map.arms.right"});
}

TEST(ModelCheck, DrivesLimitsAndTorques) {
  const ModelPtr m = load(test::model_path("lola"));
  const int knee = mj_name2id(m.get(), mjOBJ_ACTUATOR, "left_knee");
  m->actuator_ctrllimited[knee] = 0;
  ModelMap map;
  std::vector<ModelProblem> problems = check_model_map(m.get(), map, kMargin);
  ASSERT_EQ(problems.size(), 1u) << all(problems);
  EXPECT_EQ(problems[0].key, "model_map.torque_limits");
  EXPECT_NE(problems[0].message.find("'left_knee' has no torque limit"), std::string::npos);
  map.torque_limits["left_knee"] = 300.0;
  EXPECT_TRUE(check_model_map(m.get(), map, kMargin).empty());
  map.torque_limits["left_kneee"] = 300.0;
  EXPECT_EQ(keys(check_model_map(m.get(), map, kMargin)), std::vector<std::string>{"model_map.torque_limits.left_kneee"});

  // A joint without range, an actuator that is not a torque motor: problems of the MJCF itself.
  const ModelPtr n = load(test::model_path("lola"));
  n->jnt_limited[mj_name2id(n.get(), mjOBJ_JOINT, "head_pan")] = 0;
  n->actuator_biastype[mj_name2id(n.get(), mjOBJ_ACTUATOR, "head_tilt")] = mjBIAS_AFFINE;
  problems = check_model_map(n.get(), ModelMap{}, kMargin);
  EXPECT_EQ(keys(problems), (std::vector<std::string>{"", ""})) << all(problems);

  // A passive joint that keeps a motor and is coupled to nothing.
  ModelMap passive;
  passive.passive_joints = {"head_pan"};
  EXPECT_EQ(keys(check_model_map(m.get(), passive, kMargin)).back(), "model_map.passive_joints");
}

TEST(ModelCheck, StandPoseInsideSoftwareLimits) {
  const ModelPtr m = load(test::model_path("lola"));
  ModelMap map;
  map.stand_pose = {{"left_knee", -2.0 * M_PI / 180.0}, {"left_kneecap", 0.0}};  // knee range starts at -4.5°
  const std::vector<std::string> k = keys(check_model_map(m.get(), map, kMargin));
  for (const char* key : {"model_map.stand_pose_deg.left_knee", "model_map.stand_pose_deg.left_kneecap",
                          "model_map.stand_pose_deg"}) {  // the last: joints left at zero, e.g. the right knee
    EXPECT_NE(std::find(k.begin(), k.end(), key), k.end()) << key;
  }
  map.stand_pose = {};
  map.stand_keyframe = "sit";
  EXPECT_EQ(keys(check_model_map(m.get(), map, kMargin)), std::vector<std::string>{"model_map.stand_keyframe"});
}

TEST(ModelCheck, NoGroundOfItsOwn) {
  const ModelPtr m = small_biped("<geom name='floor' type='plane' size='5 5 0.1'/>");
  const std::vector<ModelProblem> problems = check_model_map(m.get(), small_biped_map(), kMargin);
  ASSERT_EQ(problems.size(), 1u) << all(problems);
  EXPECT_EQ(problems[0].key, "");
  EXPECT_NE(problems[0].message.find("'floor' is fixed to the world"), std::string::npos);
}

// Soles measured from the box geoms: below the sensor and around the point below it; the standing
// pose puts them level.
TEST(ModelCheck, SolesBelowTheSensorAndLevel) {
  const ModelPtr m = load(test::model_path("lola"));
  const int left_ft = mj_name2id(m.get(), mjOBJ_SITE, "left_ft");
  const int right_ft = mj_name2id(m.get(), mjOBJ_SITE, "right_ft");
  m->site_pos[3 * left_ft + 2] = -0.2;   // below the sole (z = -0.09 in the foot frame)
  m->site_pos[3 * right_ft + 0] = 0.25;  // ahead of the toe (x = 0.19)
  const RobotModel model = RobotModel::adopt(mj_copyModel(nullptr, m.get()), "lola.xml", kMargin);
  const std::vector<ModelProblem> problems = check_robot_geometry(model);
  ASSERT_EQ(problems.size(), 3u) << all(problems);  // both segments of the left sole, the right sole's outline
  EXPECT_NE(problems[0].message.find("must lie below the F/T sensor 'left_ft'"), std::string::npos) << all(problems);
  EXPECT_NE(problems[2].message.find("must surround the point below the F/T sensor 'right_ft'"), std::string::npos);

  ModelMap tilted;
  tilted.stand_pose = {{"left_ankle_roll", 3.0 * M_PI / 180.0}};
  const std::vector<ModelProblem> level =
      check_robot_geometry(RobotModel::load(test::model_path("lola"), kMargin, tilted));
  ASSERT_EQ(level.size(), 1u) << all(level);
  EXPECT_EQ(level[0].key, "model_map.stand_pose_deg");
  EXPECT_NE(level[0].message.find("tilts the left sole by roll 3.0°"), std::string::npos) << level[0].message;
}

TEST(ModelCheck, DescribesTheRobot) {
  const RobotDescription d = describe_robot(test::load_model("lola"));
  EXPECT_EQ(d.actuated, 24);
  EXPECT_EQ(d.passive, 0);
  for (Side side : kSides) {
    const int k = index_of(side);
    const std::string s = name_of(side);
    EXPECT_EQ(d.leg_joints[k], (std::vector<std::string>{s + "_hip_yaw", s + "_hip_roll", s + "_hip_pitch", s + "_knee",
                                                         s + "_ankle_pitch", s + "_ankle_roll"}));
    EXPECT_EQ(d.toe_joints[k], s + "_toe");
    EXPECT_EQ(d.arm_dof[k], 3);
    EXPECT_NEAR(d.leg_length_stretched[k], 0.88, 1e-9) << "thigh and shank 0.44 m (models/README.md)";
    EXPECT_LT(d.leg_length_stand[k], d.leg_length_stretched[k]) << "knees bent";
    EXPECT_NEAR(d.sole_length[k], 0.28, 1e-9);
  }
  EXPECT_NEAR(d.com_height_stand, 0.909, 0.005) << "models/README.md";
  EXPECT_EQ(describe_robot(test::load_model("johnnie")).toe_joints[0], "");
}

}  // namespace
}  // namespace biped
