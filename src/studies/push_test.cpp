#include "studies/push_test.hpp"

#include "io/yaml_reader.hpp"
#include "studies/scenario_runner.hpp"

namespace biped {
namespace {

// Finds the middle of the first single support after `earliest` from the controller's plan: the
// planned swing foot carries no load (its desired normal force is at most the weight of the part
// below its sensor, i.e. ≤ 0).
class SingleSupportFinder final : public RunObserver {
 public:
  explicit SingleSupportFinder(double earliest) : earliest_(earliest) {}
  void record(const Simulation& sim, const SensorData&, const JointCommand&, const ControllerStatus& status,
              double) override {
    const double t = sim.time();
    if (t < earliest_ || end_ > 0.0) return;
    const bool single = status.desired_wrench[0].force.z() <= 0.0 || status.desired_wrench[1].force.z() <= 0.0;
    if (single && start_ < 0.0) start_ = t;
    if (!single && start_ >= 0.0) end_ = t;
  }
  double middle() const { return end_ > 0.0 ? 0.5 * (start_ + end_) : -1.0; }

 private:
  double earliest_;
  double start_ = -1.0, end_ = -1.0;
};

// Survived: no fall until the scenario's end, i.e. the robot walks on, stops and stands. (Falls
// come up to several seconds after a push, when the disturbed gait diverges step by step.)
bool survives(const Scenario& scenario, const RunConfig& base, const Push& push) {
  RunConfig config = base;
  config.sim.pushes.push_back(push);
  const RobotModel model = load_controller_model(config);
  Simulation sim(config.sim, model);
  std::unique_ptr<Controller> controller = make_controller(config, model);
  RunOptions options;
  options.duration = scenario.duration;
  options.run_on_after_fall = 0.0;
  return !run_closed_loop(sim, *controller, scenario.commands, options, nullptr).fell;
}

}  // namespace

nlohmann::json run_push_test(const Scenario& scenario, const RunConfig& config, const PushTestOptions& options) {
  Eigen::Vector3d direction;
  if (options.direction == "forward") direction = Eigen::Vector3d::UnitX();
  else if (options.direction == "backward") direction = -Eigen::Vector3d::UnitX();
  else if (options.direction == "left") direction = Eigen::Vector3d::UnitY();
  else if (options.direction == "right") direction = -Eigen::Vector3d::UnitY();
  else throw InputError("--direction: unknown direction '" + options.direction + "' (forward, backward, left, right)");

  // A dry run finds when to push.
  SingleSupportFinder finder(options.earliest);
  {
    const RobotModel model = load_controller_model(config);
    Simulation sim(config.sim, model);
    std::unique_ptr<Controller> controller = make_controller(config, model);
    RunOptions run;
    run.duration = scenario.duration;
    run.log_period = config.sim.control_period;
    run_closed_loop(sim, *controller, scenario.commands, run, &finder);
  }
  if (finder.middle() < 0.0) {
    throw InputError(scenario.file + ": the robot is never in single support after t = " + std::to_string(options.earliest) + " s");
  }
  Push push;
  push.t = finder.middle();
  push.duration = options.push_duration;
  push.body = "upper_body";
  auto try_impulse = [&](double impulse) {
    push.force = direction * impulse / options.push_duration;
    return survives(scenario, config, push);
  };
  // Survival is not monotonic in the impulse: a push can shift a diverging gait's phase so that a
  // larger one happens to be survived. Hence the first fall is bracketed by stepping up from zero,
  // and only that bracket is bisected: the result is the largest impulse below which every tried
  // push was survived.
  double survived = 0.0, failed = 0.0;
  if (try_impulse(0.0)) {
    failed = -1.0;
    for (double impulse = options.bracket_step; impulse <= options.max_impulse + 1e-9; impulse += options.bracket_step) {
      if (!try_impulse(impulse)) {
        failed = impulse;
        break;
      }
      survived = impulse;
    }
    if (failed < 0.0) failed = survived;  // survives every push up to max_impulse
  }
  while (failed - survived > options.resolution) {
    const double mid = 0.5 * (survived + failed);
    (try_impulse(mid) ? survived : failed) = mid;
  }
  return {{"direction", options.direction},
          {"max_impulse_Ns", survived},
          {"push_time_s", push.t},
          {"push_duration_s", options.push_duration},
          {"falls_without_push", failed == 0.0},
          {"survives_max_impulse", survived >= options.max_impulse},
          {"scenario", scenario.name},
          {"robot", config.robot},
          {"stabilizer", config.controller.stabilizer}};
}

}  // namespace biped
