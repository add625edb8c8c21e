#pragma once
// A campaign's outputs beside its database: results.csv (one line per run), summary.json and
// report.html (survival per varied parameter, the failures with their reproduce commands, the
// slowest runs); and a push map's push_map.json and report.html with its polar figure.
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "io/campaign_database.hpp"

namespace biped {

struct CampaignSession {
  std::string name;
  double wall_time_s = 0.0;  // of this session
  int ranks = 1;
  int workers = 1;
  long finished_before = 0;
  double storing_s = 0.0;    // the coordinator's time receiving and storing this session's results
  long ran = 0;              // runs finished in this session
};

// 95 % Wilson score interval of a proportion (successes of trials); [0, 1] for no trials.
std::pair<double, double> wilson_interval(long successes, long trials);

nlohmann::json campaign_summary(const std::vector<CampaignRow>& rows, long total, const CampaignSession& session);
void write_results_csv(const std::vector<CampaignRow>& rows, std::ostream& out);
void write_campaign_report(const std::vector<CampaignRow>& rows, const nlohmann::json& summary, std::ostream& out);

// The push map from its cells' rows (result: a push-test JSON), and its report with a polar figure.
nlohmann::json push_map_json(const std::vector<CampaignRow>& rows, const nlohmann::json& header);
void write_push_map_report(const nlohmann::json& map, std::ostream& out);

// Writes results.csv, summary.json and report.html into `dir`, each whole or not at all; returns the summary.
nlohmann::json write_campaign_outputs(const std::string& dir, const std::vector<CampaignRow>& rows, long total,
                                      const CampaignSession& session);

}  // namespace biped
