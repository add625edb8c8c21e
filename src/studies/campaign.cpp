#include "studies/campaign.hpp"

#include <filesystem>

#include "io/campaign_report.hpp"
#include "io/output_files.hpp"
#include "io/robot_config.hpp"
#include "io/scenario.hpp"
#include "studies/scenario_runner.hpp"

namespace biped {
namespace {

// The mean of the commanded planar speed |(vx, vy)| over the run (stops count as zero).
double mean_commanded_speed(const Scenario& s) {
  double sum = 0.0;
  for (std::size_t i = 0; i < s.commands.size(); ++i) {
    const double from = std::min(s.commands[i].t, s.duration);
    const double to = i + 1 < s.commands.size() ? std::min(s.commands[i + 1].t, s.duration) : s.duration;
    const WalkCommand& c = s.commands[i].command;
    if (!c.stop) sum += std::hypot(c.vx, c.vy) * (to - from);
  }
  return s.duration > 0.0 ? sum / s.duration : 0.0;
}

nlohmann::json parameter_value(const YAML::Node& node) {
  if (node.IsScalar()) {
    double number = 0.0;
    long integer = 0;
    bool flag = false;
    if (YAML::convert<bool>::decode(node, flag)) return node.Scalar();
    if (YAML::convert<long>::decode(node, integer)) return integer;
    if (YAML::convert<double>::decode(node, number)) return number;
    return node.Scalar();
  }
  YAML::Emitter out;
  out.SetMapFormat(YAML::Flow);
  out.SetSeqFormat(YAML::Flow);
  out << node;
  return std::string(out.c_str());
}

}  // namespace

CampaignRow ScenarioCampaign::describe(long index) const {
  const CampaignRun run = campaign_run(spec_, index);
  CampaignRow row;
  row.run = index;
  for (const auto& [key, value] : run.parameters) row.parameters[key] = parameter_value(value);
  row.command = reproduce_command(run.scenario, run.assignments);
  return row;
}

void ScenarioCampaign::run(long index, CampaignRow& row) const {
  const CampaignRun run = campaign_run(spec_, index);
  Scenario scenario = load_scenario(run.scenario, run.assignments);
  scenario.name = run.case_name.empty() ? spec_.name + "-" + std::to_string(index) : run.case_name;
  const RunConfig config = make_run_config(scenario);
  nlohmann::json summary = run_scenario(scenario, config, "").summary;
  for (const char* timing : {"wall_time_s", "realtime_factor", "controller_cycle_us"}) summary.erase(timing);
  summary["commanded_speed_mps"] = mean_commanded_speed(scenario);
  if (!run.expect.empty()) {
    summary["expected"] = run.expect;
    summary["as_expected"] = summary["fell"].get<bool>() == (run.expect == "falls");
  }
  row.result = std::move(summary);
}

nlohmann::json run_campaign(const CampaignSpec& spec, const std::string& out_dir, const MpiSession& mpi,
                            const CampaignEngineOptions& options) {
  if (mpi.rank() == 0) prepare_output_directory(out_dir);
  const ScenarioCampaign work(spec);
  const std::string database = (std::filesystem::path(out_dir) / "campaign.sqlite").string();
  const CampaignEngineOutcome outcome = run_campaign_engine(work, database, mpi, options);
  if (!outcome.coordinator) return nullptr;
  const CampaignDatabase db(database);
  CampaignSession session{spec.name, outcome.wall_time_s, outcome.ranks, outcome.workers, outcome.finished_before,
                          outcome.storing_s, outcome.ran};
  return write_campaign_outputs(out_dir, db.rows(), outcome.total, session);
}

}  // namespace biped
