#include "studies/speed_sweep.hpp"

#include <cmath>
#include <cstdio>
#include <mutex>

#include "io/yaml_reader.hpp"
#include "studies/campaign_engine.hpp"
#include "studies/scenario_runner.hpp"

namespace biped {
namespace {

// The robot's forward progress over the hold phase (ground truth) and whether the controller
// clamped the command.
class HoldPhaseObserver final : public RunObserver {
 public:
  explicit HoldPhaseObserver(double hold_start) : hold_start_(hold_start) {}
  void record(const Simulation& sim, const SensorData&, const JointCommand&, const ControllerStatus& status,
              double) override {
    saturated_ = saturated_ || status.command_saturated;
    const double x = sim.data()->qpos[0];
    if (sim.time() < hold_start_) {
      start_x_ = x;
      start_t_ = sim.time();
    }
    end_x_ = x;
    end_t_ = sim.time();
  }
  double speed() const { return end_t_ > start_t_ ? (end_x_ - start_x_) / (end_t_ - start_t_) : 0.0; }
  bool saturated() const { return saturated_; }

 private:
  double hold_start_;
  double start_x_ = 0.0, start_t_ = 0.0, end_x_ = 0.0, end_t_ = 0.0;
  bool saturated_ = false;
};

}  // namespace

nlohmann::json run_speed_sweep(const Scenario& base, const RunConfig& config, const SpeedSweepOptions& options,
                               std::ostream* progress) {
  if (!(options.step > 0.0) || !(options.from > 0.0) || options.to < options.from) {
    throw InputError("speed-sweep: need 0 < --from <= --to and --step > 0");
  }
  const int count = static_cast<int>(std::floor((options.to - options.from) / options.step + 1e-9)) + 1;
  std::mutex progress_mutex;
  // Each speed is its own simulation: all of them at once on the campaign engine's threads.
  const std::vector<nlohmann::json> results = parallel_map<nlohmann::json>(count, options.jobs, [&](long i) {
    // Rounded to 1 µm/s: 0.1 + 6 × 0.1 is 0.70000000000000007, which a table row of 0.7 saturates.
    const double speed = std::round((options.from + static_cast<double>(i) * options.step) * 1e6) / 1e6;
    Scenario scenario = base;
    scenario.commands.clear();
    const double start = 1.0, ramp = speed / options.ramp_rate;
    for (double t = 0.0; t < ramp; t += 0.1) {
      scenario.commands.push_back({start + t, WalkCommand{speed * t / ramp, 0.0, 0.0, false}});
    }
    scenario.commands.insert(scenario.commands.begin(), {0.0, WalkCommand{}});
    scenario.commands.push_back({start + ramp, WalkCommand{speed, 0.0, 0.0, false}});
    const double hold_start = start + ramp + 2.0;  // the gait settles at the new speed first
    scenario.duration = hold_start + options.hold;
    HoldPhaseObserver observer(hold_start);
    const ScenarioResult r = run_scenario(scenario, config, "", &observer);
    const bool fell = r.summary["fell"].get<bool>();
    const double limit = config.controller.walking.plan.limits.vx_max;
    if (progress) {  // one line per speed as it finishes, numbered by speed (they run in parallel)
      char line[256];
      int n = std::snprintf(line, sizeof(line), "commanded %.2f m/s: ", speed);
      n += fell ? std::snprintf(line + n, sizeof(line) - n, "FELL at %.3f s", r.summary["fall_time_s"].get<double>())
                : std::snprintf(line + n, sizeof(line) - n, "walked %.2f m/s", observer.speed());
      if (observer.saturated()) std::snprintf(line + n, sizeof(line) - n, " (saturated to the limit %.2f m/s)", limit);
      const std::lock_guard<std::mutex> lock(progress_mutex);
      *progress << "speed-sweep " << i + 1 << "/" << count << ": " << line << std::endl;
    }
    return nlohmann::json{{"commanded_mps", speed},
                          {"fell", fell},
                          {"fall_time_s", r.summary["fall_time_s"]},
                          {"walked_mps", fell ? nlohmann::json(nullptr) : nlohmann::json(observer.speed())},
                          {"command_saturated", observer.saturated()},
                          {"limit_mps", observer.saturated() ? nlohmann::json(limit) : nlohmann::json(nullptr)},
                          {"upper_body_tilt_deg", r.summary["upper_body_tilt_deg"]}};
  });
  nlohmann::json runs = nlohmann::json::array();
  double fastest = 0.0;
  for (const nlohmann::json& run : results) {
    runs.push_back(run);
    if (!run["fell"].get<bool>() && !run["command_saturated"].get<bool>()) fastest = run["commanded_mps"].get<double>();
  }
  return {{"robot", config.robot},
          {"scenario", base.name},
          {"stabilizer", config.controller.stabilizer},
          {"hold_s", options.hold},
          {"fastest_without_fall_mps", fastest},
          {"runs", runs}};
}

}  // namespace biped
