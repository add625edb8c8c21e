#pragma once
// `biped push-map`: the push test (studies/push_test.hpp) over push directions × gait phases, each
// cell an item of the campaign engine (parallel, resumable), into DIR/campaign.sqlite,
// DIR/push_map.json and DIR/report.html (polar figure). A scenario in which the robot only stands
// has no gait phases: its pushes come at a time (`earliest`) and the map has one phase (null).
// The map carries, per direction, the physical bound without a step (docs/campaigns.md): with the
// CoM at height z, ω = √(g/z), a 0.1 s push of impulse I changes the CoM velocity by I/m and moves
// the capture point by I/(m ω); it stays inside the support polygon, with the CoP at its edge at
// distance d in that direction, while I ≤ m ω d.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/robot_config.hpp"
#include "io/scenario.hpp"
#include "studies/campaign_engine.hpp"
#include "studies/push_test.hpp"

namespace biped {

struct PushMapOptions {
  int directions = 16;   // evenly spaced from 0° (forward)
  int phases = 8;        // single-support phases (k + 0.5) / phases
  PushTestOptions test;  // the search per cell (its direction and phase are the cell's)
};

// Whether the scenario's commands ever ask the robot to walk.
bool scenario_walks(const Scenario& scenario);

// The capture-point bound I = m ω d per direction (heading frame) for the robot at its initial
// stance: the support polygon is both soles (standing) or one sole centred under the CoM (walking:
// single support), the CoM at its initial height.
nlohmann::json capture_point_bound(const RunConfig& config, bool standing, int directions);

// Runs (or continues) the map; on the coordinator writes push_map.json and report.html and returns
// the map (other ranks return null).
nlohmann::json run_push_map(const std::string& scenario_path, const std::vector<std::string>& overrides,
                            const std::string& out_dir, const PushMapOptions& options, const MpiSession& mpi,
                            const CampaignEngineOptions& engine);

}  // namespace biped
