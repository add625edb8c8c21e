#include "studies/scenario_runner.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <utility>
#include <vector>

#include "control/standing_controller.hpp"
#include "io/output_files.hpp"
#include "io/report.hpp"
#include "io/run_recorder.hpp"
#include "io/video_recorder.hpp"
#include "io/yaml_reader.hpp"

namespace biped {
namespace {

// Forwards the loop's calls to several observers.
class Observers final : public RunObserver {
 public:
  explicit Observers(std::vector<RunObserver*> all) : all_(std::move(all)) {}
  void record(const Simulation& sim, const SensorData& s, const JointCommand& c, const ControllerStatus& st,
              double us) override {
    for (RunObserver* o : all_) {
      if (o) o->record(sim, s, c, st, us);
    }
  }
  void cycle_start(const Simulation& sim) override {
    for (RunObserver* o : all_) {
      if (o) o->cycle_start(sim);
    }
  }

 private:
  std::vector<RunObserver*> all_;
};

// The axes of the walk command beyond the limits (vx_max: the step table's fastest row): the most
// extreme commanded value and the limit it was clamped to, e.g. {"vx": {"commanded": 1.1, "limit":
// 1.0}}; empty when the commands stay inside.
nlohmann::json commands_beyond_limits(const std::vector<TimedCommand>& commands, const CommandLimits& limits) {
  nlohmann::json beyond = nlohmann::json::object();
  auto check = [&](const char* axis, double commanded, double limit, bool exceeded) {
    if (!exceeded) return;
    if (!beyond.contains(axis) || std::abs(commanded) > std::abs(beyond[axis]["commanded"].get<double>())) {
      beyond[axis] = {{"commanded", commanded}, {"limit", limit}};
    }
  };
  for (const TimedCommand& c : commands) {
    if (c.command.stop) continue;
    check("vx", c.command.vx, limits.vx_max, c.command.vx > limits.vx_max);
    check("vx", c.command.vx, limits.vx_min, c.command.vx < limits.vx_min);
    check("vy", c.command.vy, std::copysign(limits.vy_max, c.command.vy), std::abs(c.command.vy) > limits.vy_max);
    check("omega", c.command.omega, std::copysign(limits.omega_max, c.command.omega),
          std::abs(c.command.omega) > limits.omega_max);
  }
  return beyond;
}

}  // namespace

RobotModel load_controller_model(const RunConfig& config) {
  return RobotModel::load(config.controller.model_path, config.controller.software_limit_margin_rad,
                          config.sim.world.model_map);
}

std::unique_ptr<Controller> make_controller(const RunConfig& config, const RobotModel& model) {
  if (config.controller.type == "standing") return std::make_unique<StandingController>(model, config.controller.standing);
  if (config.controller.type == "weight_shift") return std::make_unique<WeightShiftController>(model, config.controller.weight_shift);
  return std::make_unique<WalkingController>(model, config.controller.walking);
}

void check_scenario_against_model(const Scenario& s, const RobotModel& model) {
  for (std::size_t i = 0; i < s.faults.size(); ++i) {
    const std::string& name = s.faults[i].sensor;
    const bool known = std::find(kNonJointSensors.begin(), kNonJointSensors.end(), name) != kNonJointSensors.end();
    if (!known && model.joint_index(name) < 0) {
      throw InputError(s.file + ": key 'sensors.faults." + std::to_string(i) + ".sensor': unknown sensor '" + name +
                       "' (ft_left, ft_right, imu, imu_orientation, imu_gyro, imu_accel, or a joint name)");
    }
  }
  // Absent keys give invalid nodes, which only say false.
  const YAML::Node encoders = s.sensors && s.sensors.IsMap() ? s.sensors["encoders"] : YAML::Node();
  const YAML::Node offsets = encoders && encoders.IsMap() ? encoders["offset_deg"] : YAML::Node();
  for (const auto& entry : offsets) {
    const std::string joint = entry.first.Scalar();
    if (model.joint_index(joint) < 0) {
      throw InputError(s.file + ": key 'sensors.encoders.offset_deg." + joint + "': unknown joint '" + joint + "'");
    }
  }
  for (std::size_t i = 0; i < s.pushes.size(); ++i) {
    if (model.body_named(s.pushes[i].body) < 0) {
      throw InputError(s.file + ": key 'disturbances." + std::to_string(i) + ".body': unknown body '" +
                       s.pushes[i].body + "'");
    }
  }
}

void check_scenario_against_simulation(const Scenario& s, const Simulation& sim) {
  static const char* const kKind[] = {"step", "slope", "box", "friction patch"};
  for (std::size_t i = 0; i < s.terrain.size(); ++i) {
    for (const Simulation::SoleOutline& sole : sim.sole_outlines()) {
      if (!Terrain::reshapes_ground_within(s.terrain[i], sole.corners)) continue;
      const Eigen::Vector2d centre = 0.25 * (sole.corners[0] + sole.corners[1] + sole.corners[2] + sole.corners[3]);
      char where[96];
      std::snprintf(where, sizeof where, "(x %.2f, y %.2f m)", centre.x(), centre.y());
      const std::string kind = kKind[static_cast<int>(s.terrain[i].kind)];
      throw InputError(s.file + ": key 'terrain." + std::to_string(i) + "': the " + kind +
                       " reaches under the robot's " + name_of(sole.side) + " sole " + where +
                       ": the robot starts standing on level ground at height 0; move the " + kind +
                       " clear of its feet");
    }
  }
}

ScenarioResult run_scenario(const Scenario& scenario, const RunConfig& config, const std::string& out_dir,
                            RunObserver* extra_observer, const VideoOptions* video, bool keep_previous) {
  const RobotModel model = load_controller_model(config);
  check_scenario_against_model(scenario, model);
  Simulation sim(config.sim, model);
  check_scenario_against_simulation(scenario, sim);
  std::unique_ptr<Controller> controller = make_controller(config, model);
  // First, so that a machine that cannot render fails before any output file exists.
  std::unique_ptr<VideoRecorder> video_recorder = video ? std::make_unique<VideoRecorder>(sim, *video) : nullptr;

  std::unique_ptr<AtomicOutputFile> log_file, summary_file, report_file;
  std::unique_ptr<ReportWriter> report;
  if (!out_dir.empty()) {
    prepare_output_directory(out_dir);
    const std::filesystem::path dir(out_dir);
    log_file = std::make_unique<AtomicOutputFile>((dir / "log.csv").string());
    summary_file = std::make_unique<AtomicOutputFile>((dir / "summary.json").string());
    report_file = std::make_unique<AtomicOutputFile>((dir / "report.html").string());
    report = std::make_unique<ReportWriter>(sim);
  }
  RunRecorder recorder(sim, log_file ? &log_file->stream() : nullptr);
  Observers observers({&recorder, report.get(), extra_observer, video_recorder.get()});

  RunOptions options;
  options.duration = scenario.duration;
  options.log_period = 1.0 / scenario.log_rate_hz;
  ScenarioResult result;
  result.run = run_closed_loop(sim, *controller, scenario.commands, options, &observers);
  result.summary = recorder.summary(config.robot, scenario.name, result.run, controller->status());
  result.summary["seed"] = scenario.seed;
  result.summary["controller"] = config.controller.type;
  if (config.controller.type == "walking") {
    result.summary["command_beyond_limits"] = commands_beyond_limits(scenario.commands, config.controller.walking.plan.limits);
  }
  if (video_recorder) {
    video_recorder->commit();
    result.summary["video"] = {{"file", video->path},
                               {"frames", video_recorder->frames()},
                               {"fps", video->fps},
                               {"size", {video->width, video->height}},
                               {"codec", video_recorder->codec()},
                               {"render_s", video_recorder->render_seconds()}};
  }
  if (summary_file) {
    summary_file->stream() << result.summary.dump(2) << '\n';
    report->write_html(report_file->stream(), result.summary, result.run.cycle_us);
    if (keep_previous) {
      result.previous_run_dir = keep_previous_run(out_dir, {"summary.json", "log.csv", "report.html"}, kPreviousRunsKept);
    }
    log_file->commit();
    summary_file->commit();
    report_file->commit();
  }
  return result;
}

}  // namespace biped
