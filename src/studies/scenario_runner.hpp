#pragma once
// Runs one scenario end to end: the controller's model, the controller, the simulation, the
// closed loop, and the output files.
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "interface/controller.hpp"
#include "io/robot_config.hpp"
#include "io/scenario.hpp"
#include "io/video_recorder.hpp"
#include "sim/closed_loop.hpp"

namespace biped {

// The controller's own model, loaded from the configured MJCF (throws ModelError).
RobotModel load_controller_model(const RunConfig& config);
// The controller that takes the slot of Fig. 3 for this configuration.
std::unique_ptr<Controller> make_controller(const RunConfig& config, const RobotModel& model);
// Checks names in the scenario that only the model can resolve (fault sensors, pushed bodies).
void check_scenario_against_model(const Scenario& scenario, const RobotModel& model);
// Checks the terrain against where the simulation stands the robot at the start: every sole on the
// level ground, no step, slope or box under it (a robot cannot start with a sole in the ground).
void check_scenario_against_simulation(const Scenario& scenario, const Simulation& sim);

struct ScenarioResult {
  nlohmann::json summary;
  RunResult run;
  std::string previous_run_dir;  // where an earlier run's files were moved (keep_previous), or ""
};

// How many earlier runs `keep_previous` keeps.
inline constexpr int kPreviousRunsKept = 5;

// Runs the scenario. With a non-empty `out_dir`, writes summary.json, log.csv and report.html there,
// each whole or not at all; with `keep_previous`, an earlier run's files there are first moved into
// out_dir/previous/1/ (keep_previous_run()), once the new ones are complete. With `video`, also renders
// the run to that .mp4 (whole or not at all; the summary then has a "video" entry). Throws InputError /
// ModelError for bad input and VideoError when the video cannot be made, before anything is simulated
// and before any file is created.
ScenarioResult run_scenario(const Scenario& scenario, const RunConfig& config, const std::string& out_dir,
                            RunObserver* extra_observer = nullptr, const VideoOptions* video = nullptr,
                            bool keep_previous = false);

}  // namespace biped
