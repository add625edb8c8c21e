// Campaign outputs (io/campaign_report.cpp): the survival interval, the summary's counts, one CSV
// line per run with its parameters, the report's failures with reproduce commands, the polar map.
#include "io/campaign_report.hpp"

#include <gtest/gtest.h>

#include <sstream>

namespace biped {
namespace {

std::vector<CampaignRow> rows() {
  std::vector<CampaignRow> rows;
  for (long i = 0; i < 10; ++i) {
    CampaignRow r;
    r.run = i;
    r.status = i == 9 ? "error" : "ok";
    r.error = i == 9 ? "non-finite value in the result: distance_m" : "";
    r.parameters = {{"commands.1.vx", 0.1 * i}, {"sensors.noise", i % 2 ? "true" : "false"}};
    r.command = "build/biped run a.yaml --set seed=" + std::to_string(i);
    if (i != 9) r.result = {{"fell", i >= 6}, {"fall_time_s", i >= 6 ? nlohmann::json(2.0) : nlohmann::json(nullptr)},
                            {"fall_reason", i >= 6 ? "tilt" : ""}, {"distance_m", 1.0}};
    r.wall_time_s = 0.1 * (i + 1);
    r.host = "h";
    rows.push_back(r);
  }
  return rows;
}

TEST(WilsonInterval, ContainsTheRateAndNarrowsWithTrials) {
  const auto [lo, hi] = wilson_interval(90, 100);
  EXPECT_LT(lo, 0.9);
  EXPECT_GT(hi, 0.9);
  const auto [lo2, hi2] = wilson_interval(900, 1000);
  EXPECT_LT(hi2 - lo2, hi - lo);
  const auto [all_lo, all_hi] = wilson_interval(20, 20);
  EXPECT_EQ(all_hi, 1.0);
  EXPECT_LT(all_lo, 1.0);
  EXPECT_EQ(wilson_interval(0, 0), (std::pair<double, double>{0.0, 1.0}));
}

TEST(CampaignSummary, CountsRunsErrorsAndFalls) {
  const nlohmann::json s = campaign_summary(rows(), 12, CampaignSession{"c", 3.0, 2, 4, 1, 0.0, 0});
  EXPECT_EQ(s["runs"], 12);
  EXPECT_EQ(s["finished"], 10);
  EXPECT_EQ(s["completed"], 9);
  EXPECT_EQ(s["errors"], 1);
  EXPECT_EQ(s["falls"], 3);
  EXPECT_DOUBLE_EQ(s["survival_rate"].get<double>(), 6.0 / 9.0);
  EXPECT_LT(s["survival_rate_95ci"][0].get<double>(), 6.0 / 9.0);
  EXPECT_EQ(s["ranks"], 2);
}

TEST(ResultsCsv, OneLinePerRunWithItsParameters) {
  std::ostringstream out;
  write_results_csv(rows(), out);
  const std::string text = out.str();
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 11);
  EXPECT_EQ(text.find("run,status,error,fell,"), 0u);
  EXPECT_NE(text.find("commands.1.vx,sensors.noise,command"), std::string::npos);
  EXPECT_NE(text.find("build/biped run a.yaml --set seed=7"), std::string::npos);
}

TEST(CampaignReport, ListsTheFailuresWithTheirCommandsAndAChartPerParameter) {
  std::ostringstream out;
  const auto r = rows();
  write_campaign_report(r, campaign_summary(r, 10, CampaignSession{"c", 1.0, 1, 2, 0, 0.0, 0}), out);
  const std::string html = out.str();
  for (int i : {6, 7, 8, 9}) EXPECT_NE(html.find("--set seed=" + std::to_string(i) + "</code>"), std::string::npos) << i;
  EXPECT_EQ(html.find("--set seed=2</code></td></tr><tr><td>3"), std::string::npos);  // survivors are no failures
  EXPECT_NE(html.find("non-finite value"), std::string::npos);
  std::size_t charts = 0;
  for (auto p = html.find("<svg"); p != std::string::npos; p = html.find("<svg", p + 1)) ++charts;
  EXPECT_EQ(charts, 2u);
}

TEST(PushMapReport, DrawsOneCurvePerPhaseAndTheBound) {
  std::vector<CampaignRow> cells;
  for (long i = 0; i < 8; ++i) {
    CampaignRow r;
    r.run = i;
    r.status = "ok";
    r.parameters = {{"direction_deg", 90.0 * (i / 2)}, {"phase", i % 2 ? 0.75 : 0.25}};
    r.result = {{"max_impulse_Ns", 10.0 + i}, {"falls_without_push", false}, {"survived_every_impulse_tried", false},
                {"push_time_s", 4.2}};
    r.command = "push-test";
    cells.push_back(r);
  }
  nlohmann::json header = {{"scenario", "s"}, {"capture_point_bound_Ns", nlohmann::json::array()}};
  for (double d : {0.0, 90.0, 180.0, -90.0}) header["capture_point_bound_Ns"].push_back({{"direction_deg", d}, {"max_impulse_Ns", 20.0}});
  const nlohmann::json map = push_map_json(cells, header);
  ASSERT_EQ(map["cells"].size(), 8u);
  EXPECT_EQ(map["cells"][3]["max_impulse_Ns"], 13.0);
  std::ostringstream out;
  write_push_map_report(map, out);
  const std::string html = out.str();
  std::size_t polygons = 0;
  for (auto p = html.find("<polygon"); p != std::string::npos; p = html.find("<polygon", p + 1)) ++polygons;
  EXPECT_EQ(polygons, 3u);  // two phases and the bound
}

}  // namespace
}  // namespace biped
