// `biped robot check` on the shipped robots (each passes and stands) and on broken copies of their
// robot files: the right one-line problem under the right key, and exit status 2 from the CLI.
#include "studies/robot_check.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <yaml-cpp/yaml.h>

#include <cstdio>
#include <fstream>
#include <functional>

#include "io/urdf_import.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

namespace fs = std::filesystem;

RobotCheckOptions short_stand() {
  RobotCheckOptions options;
  options.stand_duration = 1.5;
  return options;
}

std::string all(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) text += line + "\n";
  return text;
}

class ShippedRobot : public ::testing::TestWithParam<const char*> {};

TEST_P(ShippedRobot, PassesAndStands) {
  const RobotCheckReport r = check_robot(resolve_robot_file(GetParam()), short_stand());
  EXPECT_TRUE(r.problems.empty()) << all(r.problems);
  ASSERT_TRUE(r.description.has_value());
  for (const auto& leg : r.description->leg_joints) EXPECT_GE(leg.size(), 6u);
  EXPECT_GT(r.description->mass, 30.0);
  ASSERT_TRUE(r.stand.ran);
  EXPECT_FALSE(r.stand.fell);
  EXPECT_LT(r.stand.max_tilt_deg, 2.0);
  EXPECT_LT(r.stand.com_drift, 0.02);
}

INSTANTIATE_TEST_SUITE_P(Robots, ShippedRobot, ::testing::Values("lola", "johnnie", "jvrc1"),
                         [](const auto& info) { return std::string(info.param); });

// Paths in a robot file (model, step table, included files) made absolute, so that a copy in
// another folder means the same robot.
void absolute_paths(YAML::Node node, const fs::path& dir) {
  if (node.IsMap()) {
    for (auto entry : node) {
      if (entry.second.IsScalar()) {
        const std::string value = entry.second.Scalar();
        if (value.rfind("../", 0) == 0 || value.rfind("./", 0) == 0) {
          entry.second = (dir / value).lexically_normal().string();
        }
      } else {
        absolute_paths(entry.second, dir);
      }
    }
  }
}

// A copy of a shipped robot file, edited by `edit`, in a fresh folder.
std::string broken_copy(const std::string& robot, const std::string& name, const std::function<void(YAML::Node&)>& edit) {
  const fs::path original = test::source_path("config/robots/" + robot + ".yaml");
  YAML::Node root = YAML::LoadFile(original.string());
  absolute_paths(root, original.parent_path());
  edit(root);
  const fs::path file = test::fresh_dir(("robot-check-" + name).c_str()) / (name + ".yaml");
  std::ofstream(file) << root << '\n';
  return file.string();
}

std::vector<std::string> problems_of(const std::string& file) { return check_robot(file, short_stand()).problems; }

TEST(RobotCheck, MissingSite) {
  const std::string file = broken_copy("jvrc1", "missing-site", [](YAML::Node& r) {
    r["model_map"]["legs"]["left"]["ft_site"] = "lf_sensor";
  });
  EXPECT_EQ(problems_of(file), std::vector<std::string>{file + ": key 'model_map.legs.left.ft_site': the model has no "
                                                               "site named 'lf_sensor'"});
}

TEST(RobotCheck, WrongJointNames) {
  const std::string file = broken_copy("jvrc1", "wrong-joint", [](YAML::Node& r) {
    r["model_map"]["legs"]["right"]["root_joint"] = "R_HIP_PITCH";
    r["model_map"]["arms"]["left"] = "L_SHOULDER";
  });
  EXPECT_EQ(problems_of(file),
            (std::vector<std::string>{file + ": key 'model_map.legs.right.root_joint': the model has no joint named 'R_HIP_PITCH'",
                                      file + ": key 'model_map.arms.left': the model has no joint named 'L_SHOULDER'"}));
}

TEST(RobotCheck, BadSole) {
  const std::string above = broken_copy("jvrc1", "sole-above", [](YAML::Node& r) {
    r["model_map"]["legs"]["left"]["sole"]["z"] = 0.01;
  });
  std::vector<std::string> problems = problems_of(above);
  ASSERT_EQ(problems.size(), 1u) << all(problems);
  EXPECT_NE(problems[0].find("key 'model_map.legs.left.sole.z': the sole must be below the F/T sensor"), std::string::npos)
      << problems[0];

  const std::string aside = broken_copy("jvrc1", "sole-aside", [](YAML::Node& r) {
    r["model_map"]["legs"]["right"]["sole"]["y"][0] = 0.01;
  });
  problems = problems_of(aside);
  ASSERT_EQ(problems.size(), 1u) << all(problems);
  EXPECT_NE(problems[0].find("key 'model_map.legs.right.sole': the sole rectangle must lie around the point below the F/T"),
            std::string::npos)
      << problems[0];

  // LOLA's soles are box geoms: a suffix that finds none.
  const std::string none = broken_copy("lola", "sole-none", [](YAML::Node& r) { r["model_map"]["sole_suffix"] = "_plate"; });
  problems = problems_of(none);
  ASSERT_EQ(problems.size(), 2u) << all(problems);
  EXPECT_EQ(problems[0].rfind(none + ": key 'model_map.legs.left.sole': no box geom named '*_plate' below the F/T sensor", 0), 0u)
      << problems[0];
}

TEST(RobotCheck, LegRootNotAboveTheFoot) {
  const std::string file = broken_copy("jvrc1", "leg-root", [](YAML::Node& r) {
    r["model_map"]["legs"]["left"]["root_joint"] = "R_HIP_P";
  });
  EXPECT_EQ(problems_of(file),
            std::vector<std::string>{file + ": key 'model_map.legs.left.root_joint': joint 'R_HIP_P' is not above the foot: "
                                            "body 'L_ANKLE_P_S' is not below its body 'R_HIP_P_S'"});
}

TEST(RobotCheck, MissingTorqueLimit) {
  const std::string file = broken_copy("jvrc1", "torque-limit", [](YAML::Node& r) {
    r["model_map"]["torque_limits"].remove("R_KNEE");
  });
  EXPECT_EQ(problems_of(file),
            std::vector<std::string>{file + ": key 'model_map.torque_limits': joint 'R_KNEE' has no torque limit: its "
                                            "actuator 'R_KNEE_motor' has no ctrlrange; give the drive's peak torque here [N·m]"});
}

TEST(RobotCheck, EveryProblemAtOnce) {
  const std::string file = broken_copy("jvrc1", "several", [](YAML::Node& r) {
    r["model_map"]["imu"]["site"] = "imu_site";
    r["model_map"]["legs"]["right"]["foot_body"] = "R_FOOT";
    r["model_map"]["torque_limits"].remove("L_ANKLE_P");
    r["model_map"]["stand_pose_deg"]["L_KNEE"] = 170;
  });
  EXPECT_EQ(problems_of(file).size(), 4u) << all(problems_of(file));
}

// A standing pose right at a software limit passes, with a warning (the walking controller has no room).
TEST(RobotCheck, StandPoseAtALimitWarns) {
  const std::string file = broken_copy("jvrc1", "pose-at-limit", [](YAML::Node& r) {
    r["model_map"]["stand_pose_deg"]["L_ELBOW_P"] = -5.0;  // range [-145°, 0°], software limit -5°
  });
  const RobotCheckReport r = check_robot(file, short_stand());
  EXPECT_TRUE(r.problems.empty()) << all(r.problems);
  ASSERT_EQ(r.warnings.size(), 1u) << all(r.warnings);
  EXPECT_NE(r.warnings[0].find("holds joint 'L_ELBOW_P' within 1 deg of a software limit"), std::string::npos) << r.warnings[0];
}

// A step table named before `biped tables` made it: a warning, and the robot stands without it.
TEST(RobotCheck, StepTableNotYetMade) {
  const std::string file = broken_copy("jvrc1", "no-table", [](YAML::Node& r) {
    r["controller"]["step_table"] = "jvrc1-new.csv";
  });
  const RobotCheckReport r = check_robot(file, short_stand());
  EXPECT_TRUE(r.problems.empty()) << all(r.problems);
  ASSERT_EQ(r.warnings.size(), 1u) << all(r.warnings);
  EXPECT_NE(r.warnings[0].find("key 'controller.step_table': no such file yet"), std::string::npos) << r.warnings[0];
  EXPECT_TRUE(r.stand.ran);
}

// Drives too soft to carry the robot: every name is right, and it falls standing.
TEST(RobotCheck, FallStanding) {
  const std::string file = broken_copy("jvrc1", "soft-drives", [](YAML::Node& r) { r["drives"]["bandwidth_hz"] = 0.5; });
  const RobotCheckReport r = check_robot(file, short_stand());
  ASSERT_TRUE(r.stand.ran);
  EXPECT_TRUE(r.stand.fell);
  ASSERT_EQ(r.problems.size(), 1u) << all(r.problems);
  EXPECT_EQ(r.problems[0].rfind(file + ": the robot fell at ", 0), 0u) << r.problems[0];
}

// The way of docs/new-robot.md for a URDF: import, give the joints rotor inertia, check, stand.
TEST(RobotCheck, ImportedUrdfPassesAndStands) {
  const fs::path dir = test::fresh_dir("robot-check-urdf");
  const UrdfImport imported = import_urdf(test::source_path("models/examples/small_biped.urdf"),
                                          (dir / "small_biped.xml").string(), {"", (dir / "small_biped.yaml").string()});
  std::ofstream(dir / "small_biped.yaml") << imported.robot_file;
  RobotCheckReport r = check_robot((dir / "small_biped.yaml").string(), short_stand());
  EXPECT_TRUE(r.problems.empty()) << all(r.problems);
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_NE(r.warnings[0].find("have no rotor inertia"), std::string::npos) << r.warnings[0];

  std::ifstream in(dir / "small_biped.xml");
  std::string xml((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto at = xml.find("<default/>");
  ASSERT_NE(at, std::string::npos);
  xml.replace(at, 10, "<default><joint armature=\"0.05\" damping=\"0.5\"/></default>");
  std::ofstream(dir / "small_biped.xml") << xml;
  r = check_robot((dir / "small_biped.yaml").string(), short_stand());
  EXPECT_TRUE(r.problems.empty()) << all(r.problems);
  EXPECT_TRUE(r.warnings.empty()) << all(r.warnings);
  EXPECT_FALSE(r.stand.fell);
  EXPECT_LT(r.stand.com_drift, 0.01);
}

// The command line: exit 2 with the problem lines on stderr; 0 and no problem for a shipped robot.
int run_cli(const std::string& args, std::string& err) {
  const fs::path err_file = test::fresh_dir("robot-check-stderr") / "stderr.txt";
  const std::string command = std::string(BIPED_BINARY) + " robot check " + args + " --stand-time 1 >/dev/null 2>" +
                              err_file.string();
  const int status = std::system(command.c_str());
  std::ifstream in(err_file);
  err.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(RobotCheck, CommandLineExitStatus) {
  const std::string file = broken_copy("jvrc1", "cli", [](YAML::Node& r) {
    r["model_map"]["legs"]["left"]["ft_site"] = "lf_sensor";
  });
  std::string err;
  EXPECT_EQ(run_cli(file, err), 2);
  EXPECT_NE(err.find(file + ": key 'model_map.legs.left.ft_site': the model has no site named 'lf_sensor'\n"), std::string::npos)
      << err;
  EXPECT_EQ(run_cli("jvrc1", err), 0) << err;
  EXPECT_EQ(err, "");
  EXPECT_EQ(run_cli("no_such_robot", err), 2);
  EXPECT_NE(err.find("no_such_robot: no such robot file"), std::string::npos) << err;
}

}  // namespace
}  // namespace biped
