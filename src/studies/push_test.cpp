#include "studies/push_test.hpp"

#include <cmath>
#include <ostream>

#include "io/yaml_reader.hpp"
#include "studies/scenario_runner.hpp"

namespace biped {
namespace {

struct Trial {
  bool fell = false;
  double push_start = std::nan("");  // [s]; NaN: the gait moment never came
};

// Survived: no fall until the scenario's end, i.e. the robot walks on, stops and stands. (Falls
// come up to several seconds after a push, when the disturbed gait diverges step by step.)
Trial run_trial(const Scenario& scenario, const RunConfig& base, const Push& push) {
  RunConfig config = base;
  config.sim.pushes.push_back(push);
  const RobotModel model = load_controller_model(config);
  Simulation sim(config.sim, model);
  check_scenario_against_simulation(scenario, sim);
  std::unique_ptr<Controller> controller = make_controller(config, model);
  RunOptions options;
  options.duration = scenario.duration;
  options.run_on_after_fall = 0.0;
  Trial trial;
  trial.fell = run_closed_loop(sim, *controller, scenario.commands, options, nullptr).fell;
  trial.push_start = sim.pushes().start_times().back();
  return trial;
}

}  // namespace

double direction_angle_deg(const std::string& name) {
  if (name == "forward") return 0.0;
  if (name == "left") return 90.0;
  if (name == "backward") return 180.0;
  if (name == "right") return -90.0;
  throw InputError("--direction: unknown direction '" + name + "' (forward, backward, left, right)");
}

nlohmann::json run_push_test(const Scenario& scenario, const RunConfig& config, const PushTestOptions& options) {
  const double angle = options.direction_deg ? *options.direction_deg : direction_angle_deg(options.direction);
  if (!(options.phase >= 0.0 && options.phase <= 1.0)) throw InputError("--phase: must be between 0 and 1");
  Push push;
  push.at_gait_moment = !options.at_time;
  push.t = options.at_time.value_or(0.0);
  push.moment.after_time = options.earliest;
  push.moment.phase = options.phase;
  push.duration = options.push_duration;
  push.body = "upper_body";
  push.heading_frame = true;
  const Eigen::Vector3d direction(std::cos(angle * M_PI / 180.0), std::sin(angle * M_PI / 180.0), 0.0);

  double push_time = std::nan("");
  auto survives = [&](double impulse) {
    push.force = direction * impulse / options.push_duration;
    const Trial trial = run_trial(scenario, config, push);
    if (impulse > 0.0 && std::isnan(trial.push_start)) {
      throw InputError(scenario.file + ": the robot has no single support after t = " +
                       std::to_string(options.earliest) + " s to push in");
    }
    if (!std::isnan(trial.push_start)) push_time = trial.push_start;
    if (options.progress) {
      *options.progress << "push-test: " << impulse << " N·s at " << angle << " deg: "
                        << (trial.fell ? "falls" : "survives") << std::endl;
    }
    return !trial.fell;
  };
  // Survival is not monotonic in the impulse: a push can shift a diverging gait's phase so that a
  // larger one happens to be survived. Hence the first fall is bracketed by stepping up from zero,
  // and only that bracket is bisected: the result is the largest impulse below which every tried
  // push was survived.
  double survived = 0.0, failed = 0.0;
  bool survived_every_impulse = false;
  if (survives(0.0)) {
    failed = -1.0;
    for (double impulse = options.bracket_step; impulse <= options.max_impulse + 1e-9; impulse += options.bracket_step) {
      if (!survives(impulse)) {
        failed = impulse;
        break;
      }
      survived = impulse;
    }
    if (failed < 0.0) {
      failed = survived;
      survived_every_impulse = true;
    }
  }
  while (failed - survived > options.resolution) {
    const double mid = 0.5 * (survived + failed);
    (survives(mid) ? survived : failed) = mid;
  }
  return {{"direction", options.direction_deg ? std::to_string(angle) : options.direction},
          {"direction_deg", angle},
          {"phase", options.at_time ? nlohmann::json(nullptr) : nlohmann::json(options.phase)},
          {"max_impulse_Ns", survived},
          {"push_time_s", std::isnan(push_time) ? nlohmann::json(nullptr) : nlohmann::json(push_time)},
          {"push_duration_s", options.push_duration},
          {"falls_without_push", failed == 0.0},
          {"survived_every_impulse_tried", survived_every_impulse},
          {"largest_impulse_tried_Ns", options.max_impulse},
          {"scenario", scenario.name},
          {"robot", config.robot},
          {"stabilizer", config.controller.stabilizer}};
}

}  // namespace biped
