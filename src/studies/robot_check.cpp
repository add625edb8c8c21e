#include "studies/robot_check.hpp"

#include <filesystem>
#include <iomanip>
#include <sstream>

#include "io/robot_config.hpp"
#include "io/scenario.hpp"
#include "io/yaml_reader.hpp"
#include "studies/scenario_runner.hpp"

namespace fs = std::filesystem;

namespace biped {
namespace {

// The whole robot's centre of mass (ground truth) at the first and the last logged instant.
class ComTrack final : public RunObserver {
 public:
  void record(const Simulation& sim, const SensorData&, const JointCommand&, const ControllerStatus&, double) override {
    last_ = Eigen::Vector3d(sim.data()->subtree_com + 3 * sim.plant().pelvis_body());
    if (!started_) first_ = last_;
    started_ = true;
  }
  const Eigen::Vector3d& first() const { return first_; }
  const Eigen::Vector3d& last() const { return last_; }

 private:
  bool started_ = false;
  Eigen::Vector3d first_ = Eigen::Vector3d::Zero(), last_ = Eigen::Vector3d::Zero();
};

// Stands the robot with the standing controller for `duration` seconds.
StandTest stand(const std::string& robot_file, double duration) {
  Scenario scenario;  // robot_file relative to the working directory, as no scenario file holds it
  scenario.name = "robot-check";
  scenario.robot = robot_file;
  scenario.duration = duration;
  scenario.controller = YAML::Load("{type: standing}");
  scenario.commands = {TimedCommand{}};
  const RunConfig config = make_run_config(scenario, MissingStepTable::UseDefault);
  ComTrack com;
  const ScenarioResult result = run_scenario(scenario, config, "", &com);
  StandTest test;
  test.ran = true;
  test.duration = duration;
  test.fell = result.run.fell;
  test.fall_time = result.run.fall_time;
  test.fall_reason = result.run.fall_reason;
  test.max_tilt_deg = result.summary["upper_body_tilt_deg"]["max"].get<double>();
  test.com_drift = (com.last() - com.first()).head<2>().norm();
  test.com_height = com.last().z();
  return test;
}

}  // namespace

std::string resolve_robot_file(const std::string& name_or_path) {
  const bool is_name = name_or_path.find('/') == std::string::npos && fs::path(name_or_path).extension() != ".yaml";
  const fs::path file = is_name ? fs::path(data_directory()) / "config" / "robots" / (name_or_path + ".yaml")
                                : fs::path(name_or_path);
  if (!fs::is_regular_file(file)) {
    std::string known;
    for (const std::string& robot : known_robots()) known += (known.empty() ? "" : ", ") + robot;
    throw InputError(name_or_path + ": no such robot file (a path to a robot file, or a robot name: " + known + ")");
  }
  // As short as it can be said from here (messages name it).
  const fs::path relative = fs::absolute(file).lexically_relative(fs::current_path());
  const bool below = !relative.empty() && *relative.begin() != "..";
  return (below ? relative : fs::absolute(file)).lexically_normal().string();
}

RobotCheckReport check_robot(const std::string& robot_file, const RobotCheckOptions& options) {
  RobotCheckReport report;
  report.robot_file = robot_file;
  // MuJoCo's messages may span lines; a problem is one.
  auto one_line = [](std::string text) {
    while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
    for (std::size_t at = text.find('\n'); at != std::string::npos; at = text.find('\n', at)) text.replace(at, 1, "; ");
    return text;
  };
  auto add = [&](const std::vector<ModelProblem>& problems) {
    for (const ModelProblem& p : problems) {
      report.problems.push_back(p.key.empty() ? report.mjcf + ": " + p.message
                                              : report.robot_file + ": key '" + p.key + "': " + p.message);
    }
  };

  // The robot file as `biped run` reads it: its own errors come one at a time (strict reader).
  Scenario scenario;
  scenario.robot = robot_file;
  RunConfig config;
  try {
    config = make_run_config(scenario, MissingStepTable::UseDefault);
  } catch (const InputError& e) {
    report.problems.push_back(e.what());
    return report;
  }
  // The step table comes after the check (docs/new-robot.md): a robot file may name it before it exists.
  const YAML::Node root = YAML::LoadFile(robot_file);
  const YAML::Node controller = root["controller"];
  const YAML::Node table = controller && controller.IsMap() ? controller["step_table"] : YAML::Node();
  if (table && table.IsScalar()) {
    const fs::path path = (fs::path(robot_file).parent_path() / table.as<std::string>()).lexically_normal();
    if (!fs::exists(path)) {
      report.warnings.push_back(robot_file + ": key 'controller.step_table': no such file yet: " + path.string() +
                                " (make it: biped tables --robot " + robot_file + ")");
    }
  }
  report.mjcf = config.sim.world.robot_mjcf;
  const ModelMap& map = config.sim.world.model_map;
  const double margin = config.controller.software_limit_margin_rad;

  char error[1000] = "";
  mjModel* compiled = mj_loadXML(report.mjcf.c_str(), nullptr, error, sizeof(error));
  if (!compiled) {
    report.problems.push_back(one_line(robot_file + ": key 'model': MuJoCo cannot load " + report.mjcf + ": " + error));
    return report;
  }
  add(check_model_map(compiled, map, margin));
  if (!report.problems.empty()) {
    mj_deleteModel(compiled);
    return report;
  }
  try {
    const RobotModel model = RobotModel::adopt(compiled, report.mjcf, margin, map);
    add(check_robot_geometry(model));
    report.description = describe_robot(model);
    std::vector<std::string> no_armature;
    for (const JointInfo& j : model.joints()) {
      if (!j.passive && model.mj()->dof_armature[j.dof_adr] <= 0.0) no_armature.push_back(j.name);
    }
    for (const JointInfo& j : model.joints()) {
      const double q = model.stand_pose()[model.joint_index(j.name)];
      if (!j.passive && std::min(q - j.soft_lower, j.soft_upper - q) < kStandPoseLimitWarning) {
        report.warnings.push_back(report.robot_file + ": the standing pose holds joint '" + j.name +
                                  "' within 1 deg of a software limit: the walking controller then has no room "
                                  "(biped tables finds no gait); move it inside");
      }
    }
    if (!no_armature.empty()) {
      std::string names;
      for (std::size_t i = 0; i < std::min<std::size_t>(4, no_armature.size()); ++i) names += (i ? ", " : "") + no_armature[i];
      report.warnings.push_back(report.mjcf + ": " + std::to_string(no_armature.size()) +
                                " driven joints have no rotor inertia (armature): " + names +
                                (no_armature.size() > 4 ? ", ..." : "") +
                                "; drives on light links then oscillate: give the motors' reflected inertia "
                                "(docs/new-robot.md)");
    }
  } catch (const ModelError& e) {
    report.problems.push_back(one_line(e.what()));
  }
  if (!report.problems.empty()) return report;

  try {
    report.stand = stand(robot_file, options.stand_duration);
  } catch (const std::runtime_error& e) {  // InputError, ModelError: what the simulator could not build
    report.problems.push_back(one_line(e.what()));
    return report;
  }
  if (!report.stand.fell && (report.stand.max_tilt_deg > kStandTiltWarningDeg || report.stand.com_drift > kStandDriftWarning)) {
    std::ostringstream line;
    line << std::fixed << std::setprecision(1) << robot_file << ": standing " << report.stand.duration
         << " s, the upper body tilted up to " << report.stand.max_tilt_deg << " deg and the CoM drifted "
         << 1e3 * report.stand.com_drift << " mm: the robot rocks or slides (armature, drives, soles: docs/new-robot.md)";
    report.warnings.push_back(line.str());
  }
  if (report.stand.fell) {
    std::ostringstream line;
    line << std::fixed << std::setprecision(2) << robot_file << ": the robot fell at " << report.stand.fall_time
         << " s standing with the standing controller (" << report.stand.fall_reason
         << "): check the standing pose (model_map), the drives and the soles";
    report.problems.push_back(line.str());
  }
  return report;
}

}  // namespace biped
