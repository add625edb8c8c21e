#pragma once
// `biped campaign`: many variants of a base scenario (io/campaign_spec.hpp) through the campaign
// engine, into DIR/campaign.sqlite, results.csv, summary.json and report.html.
#include <nlohmann/json.hpp>
#include <string>

#include "io/campaign_spec.hpp"
#include "studies/campaign_engine.hpp"

namespace biped {

// Each run of a campaign file: the base scenario with the run's assignments, simulated without
// writing its log. The result is the run's summary.json without its timings (wall time, real-time
// factor, cycle times: they differ between identical runs) plus the time-averaged commanded speed.
class ScenarioCampaign final : public CampaignWork {
 public:
  explicit ScenarioCampaign(CampaignSpec spec) : spec_(std::move(spec)) {}
  long size() const override { return spec_.runs; }
  std::string identity() const override { return spec_.identity; }
  CampaignRow describe(long index) const override;
  void run(long index, CampaignRow& row) const override;

 private:
  CampaignSpec spec_;
};

// Runs (or continues) the campaign into `out_dir`; on the coordinator, writes the outputs and
// returns the summary (other ranks return null).
nlohmann::json run_campaign(const CampaignSpec& spec, const std::string& out_dir, const MpiSession& mpi,
                            const CampaignEngineOptions& options);

}  // namespace biped
