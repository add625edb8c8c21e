// `biped robot import` on the example URDF (models/examples/small_biped.urdf) and on URDFs it
// cannot use.
#include "io/urdf_import.hpp"

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>
#include <yaml-cpp/yaml.h>

#include <fstream>
#include <memory>

#include "io/yaml_reader.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

namespace fs = std::filesystem;

const std::string kUrdf = test::source_path("models/examples/small_biped.urdf");

struct Imported {
  fs::path dir;
  UrdfImport result;
  std::unique_ptr<mjModel, void (*)(mjModel*)> model{nullptr, mj_deleteModel};
};

Imported import_example(const char* name) {
  Imported i;
  i.dir = test::fresh_dir(name);
  i.result = import_urdf(kUrdf, (i.dir / "robot.xml").string(), {"", (i.dir / "robot.yaml").string()});
  char error[1000] = "";
  i.model.reset(mj_loadXML((i.dir / "robot.xml").c_str(), nullptr, error, sizeof(error)));
  EXPECT_TRUE(i.model) << error;
  return i;
}

TEST(UrdfImport, AddsWhatAUrdfCannotSay) {
  const Imported i = import_example("urdf-import");
  ASSERT_TRUE(i.model);
  const mjModel* m = i.model.get();
  EXPECT_EQ(m->jnt_type[0], mjJNT_FREE);
  EXPECT_EQ(m->jnt_bodyid[0], 1);
  EXPECT_STREQ(mj_id2name(m, mjOBJ_BODY, 1), "pelvis");
  EXPECT_EQ(m->nu, m->njnt - 1) << "a motor on every hinge";
  const int knee = mj_name2id(m, mjOBJ_ACTUATOR, "l_knee");
  ASSERT_GE(knee, 0);
  EXPECT_TRUE(m->actuator_ctrllimited[knee]);
  EXPECT_DOUBLE_EQ(m->actuator_ctrlrange[2 * knee + 1], 150.0) << "the URDF's effort limit";
  const int imu = mj_name2id(m, mjOBJ_SITE, "imu");
  const int left_ft = mj_name2id(m, mjOBJ_SITE, "left_ft");
  ASSERT_GE(imu, 0);
  ASSERT_GE(left_ft, 0);
  EXPECT_STREQ(mj_id2name(m, mjOBJ_BODY, m->site_bodyid[left_ft]), "l_foot");
  const int force = mj_name2id(m, mjOBJ_SENSOR, "left_ft_force");
  const int gyro = mj_name2id(m, mjOBJ_SENSOR, "imu_gyro");
  ASSERT_GE(force, 0);
  ASSERT_GE(gyro, 0);
  EXPECT_EQ(m->sensor_type[force], mjSENS_FORCE);
  EXPECT_EQ(m->sensor_objid[force], left_ft);
  EXPECT_EQ(m->sensor_type[gyro], mjSENS_GYRO);
  // The URDF's mass, all of it carried (fixed links kept as bodies).
  double mass = 0.0;
  for (int b = 1; b < m->nbody; ++b) mass += m->body_mass[b];
  EXPECT_NEAR(mass, 36.85, 1e-9);
}

TEST(UrdfImport, GuessesTheModelMap) {
  const Imported i = import_example("urdf-guess");
  const YAML::Node robot = YAML::Load(i.result.robot_file);
  EXPECT_EQ(robot["model"].as<std::string>(), "robot.xml") << "relative to the robot file";
  const YAML::Node map = robot["model_map"];
  EXPECT_EQ(map["root_body"].as<std::string>(), "pelvis");
  EXPECT_EQ(map["legs"]["left"]["root_joint"].as<std::string>(), "l_hip_yaw");
  EXPECT_EQ(map["legs"]["right"]["foot_body"].as<std::string>(), "r_foot");
  EXPECT_EQ(map["arms"]["left"].as<std::string>(), "l_shoulder_pitch");
  // The foot's box (0.22 x 0.11, centre 3 cm ahead of and 7 cm below the ankle, 2 cm thick).
  const YAML::Node sole = map["legs"]["left"]["sole"];
  EXPECT_NEAR(sole["x"][0].as<double>(), -0.08, 1e-9);
  EXPECT_NEAR(sole["x"][1].as<double>(), 0.14, 1e-9);
  EXPECT_NEAR(sole["y"][1].as<double>(), 0.055, 1e-9);
  EXPECT_NEAR(sole["z"].as<double>(), -0.08, 1e-9);
  EXPECT_EQ(map["stand_pose_deg"]["l_knee"].as<double>(), 40.0) << "knees bent the way their range allows";
  EXPECT_EQ(map["stand_pose_deg"]["l_elbow"].as<double>(), -10.0) << "zero is outside the elbow's software limits (0° - 5°)";
}

std::string error_of(const std::string& urdf_text, const char* name) {
  const fs::path dir = test::fresh_dir(name);
  std::ofstream(dir / "bad.urdf") << urdf_text;
  try {
    import_urdf((dir / "bad.urdf").string(), (dir / "bad.xml").string());
  } catch (const InputError& e) {
    EXPECT_FALSE(fs::exists(dir / "bad.xml")) << "nothing written";
    return e.what();
  }
  return "";
}

TEST(UrdfImport, OneLineForAUrdfItCannotUse) {
  EXPECT_NE(error_of("<robot name='x'", "urdf-xml").find("bad.urdf: cannot read the URDF"), std::string::npos);
  EXPECT_NE(error_of("<mujoco/>", "urdf-robot").find("bad.urdf: not a URDF file"), std::string::npos);
  const std::string mesh = error_of(
      "<robot name='x'><link name='a'><visual><geometry><box size='1 1 1'/></geometry></visual>"
      "<collision><geometry><mesh filename='package://x/meshes/foot.stl'/></geometry></collision></link></robot>",
      "urdf-mesh");
  EXPECT_NE(mesh.find("bad.urdf: MuJoCo cannot compile it"), std::string::npos) << mesh;
  EXPECT_EQ(mesh.find('\n'), std::string::npos);
}

}  // namespace
}  // namespace biped
