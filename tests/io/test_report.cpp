// report.html: the page holds the bundled viewer and the run's data as JSON that parses back with
// consistent series; the data survives hostile strings; a walking run records the planned
// footprints and a measured CoP inside the support polygon.
#include "io/report.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <unistd.h>

#include "io/robot_config.hpp"
#include "io/scenario.hpp"
#include "studies/scenario_runner.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kDataOpen = "<script type=\"application/json\" id=\"report-data\">";

// The JSON between the data element's tags.
json data_of_page(const std::string& html) {
  const std::size_t begin = html.find(kDataOpen);
  EXPECT_NE(begin, std::string::npos);
  const std::size_t from = begin + kDataOpen.size();
  return json::parse(html.substr(from, html.find("</script>", from) - from));
}

void expect_series_length(const json& object, std::size_t n, const std::string& where) {
  for (const auto& [key, value] : object.items()) {
    if (value.is_array() && key != "states") {
      EXPECT_EQ(value.size(), n) << where << "." << key;
    }
  }
}

struct StandingRun : ::testing::Test {
  Scenario scenario = load_scenario(test::source_path("config/scenarios/lola-stand.yaml"), {"duration=0.3"});
  RunConfig config = make_run_config(scenario);
  RobotModel model = load_controller_model(config);
  Simulation sim{config.sim, model};
  ReportWriter report{sim};
  RunResult run;

  void SetUp() override {
    std::unique_ptr<Controller> controller = make_controller(config, model);
    RunOptions options;
    options.duration = 0.3;
    options.log_period = 0.01;
    run = run_closed_loop(sim, *controller, scenario.commands, options, &report);
  }
};

TEST_F(StandingRun, PageHoldsTheBundleAndTheDataParsesBack) {
  ASSERT_GT(report_bundle().size(), 100000u) << "three.js and uPlot are in the bundle";
  const json summary = {{"scenario", "lola-stand"}, {"robot", "lola"}};
  std::ostringstream page;
  report.write_html(page, summary, run.cycle_us);
  const std::string html = page.str();
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(html.find(report_bundle()), std::string::npos);
  EXPECT_EQ(html.find("src=\"http"), std::string::npos) << "nothing is loaded from elsewhere";
  EXPECT_NE(html.find("<title>lola-stand (lola): biped run report</title>"), std::string::npos) << "the scenario names the page";

  const json data = data_of_page(html);
  EXPECT_EQ(data["summary"], summary);
  const std::size_t n = data["log"]["t"].size();
  EXPECT_EQ(n, 30u) << "0.3 s at 100 Hz";
  expect_series_length(data["log"], n, "log");
  for (const char* key : {"phi_x", "phi_y", "com_x", "com_des_x", "zmp_des_y", "cop_x", "support_y_min", "cycle_us"}) {
    EXPECT_TRUE(data["log"].contains(key)) << key;
  }
  EXPECT_EQ(data["log"]["states"], json::array({"standing"}));
  // The longest cycle of each 10 ms log interval: the cycles there, the logged one among them.
  ASSERT_EQ(run.cycle_us.size(), 300u);
  for (std::size_t i = 0; i < n; ++i) {
    const auto interval = run.cycle_us.begin() + 10 * static_cast<long>(i);
    EXPECT_NEAR(data["log"]["cycle_us_max"][i].get<double>(), *std::max_element(interval, interval + 10), 0.051);
    EXPECT_GE(data["log"]["cycle_us_max"][i].get<double>(), data["log"]["cycle_us"][i].get<double>());
  }
  ASSERT_EQ(data["feet"].size(), 2u);
  for (const json& foot : data["feet"]) {
    expect_series_length(foot, n, foot["side"].get<std::string>());
    for (const char* key : {"fz_des", "fz", "tx_des", "tx", "ty_des", "ty", "cop_x", "cop_y"}) {
      EXPECT_TRUE(foot.contains(key)) << key;
    }
    // Standing, each foot carries about half the weight.
    EXPECT_NEAR(foot["fz"].back().get<double>(), 0.5 * model.weight_above_sensors(), 0.15 * model.weight_above_sensors());
  }
  ASSERT_EQ(data["joints"].size(), static_cast<std::size_t>(model.num_joints()));
  for (const json& j : data["joints"]) {
    EXPECT_EQ(j["q"].size(), n);
    EXPECT_LT(j["lower"].get<double>(), j["upper"].get<double>());
    EXPECT_LE(j["lower"].get<double>(), j["q"].front().get<double>());
    EXPECT_GE(j["upper"].get<double>(), j["q"].front().get<double>());
  }

  const json& m = data["model"];
  const std::size_t bodies = m["bodies"].size();
  EXPECT_EQ(m["bodies"][m["pelvis"].get<int>()], "pelvis");
  EXPECT_GT(m["geoms"].size(), 20u);
  for (const json& g : m["geoms"]) EXPECT_LT(g["body"].get<int>(), static_cast<int>(bodies));
  const json& replay = data["replay"];
  EXPECT_EQ(replay["t"].size(), 9u) << "30 Hz over 0.3 s";
  for (const json& frame : replay["frames"]) EXPECT_EQ(frame.size(), 7 * bodies);
}

TEST_F(StandingRun, StringsCannotEndTheDataElement) {
  const std::string hostile = "a</script><script>alert(1)</script><!-- b";
  std::ostringstream page;
  report.write_html(page, {{"scenario", hostile}}, run.cycle_us);
  const std::string html = page.str();
  const std::size_t data_start = html.find(kDataOpen);
  const std::size_t data_end = html.find("</script>", data_start);
  EXPECT_EQ(html.find("<!--"), std::string::npos);
  EXPECT_EQ(data_of_page(html)["summary"]["scenario"], hostile);
  EXPECT_NE(html.find("<title>a&lt;/script&gt;&lt;script&gt;alert(1)"), std::string::npos) << "escaped in the title";
  EXPECT_EQ(html.find("<script>", data_start + kDataOpen.size()), data_end + 10) << "only the viewer script follows";
}

TEST(ReportOfAWalk, FootprintsOfThePlanAndCopInsideTheSupportPolygon) {
  const Scenario scenario = load_scenario(test::source_path("config/scenarios/lola-walk.yaml"), {"duration=6"});
  const fs::path out = fs::temp_directory_path() / ("biped-report-" + std::to_string(::getpid()));
  fs::remove_all(out);
  const ScenarioResult r = run_scenario(scenario, make_run_config(scenario), out.string());
  ASSERT_FALSE(r.run.fell);
  std::ifstream in(out / "report.html");
  std::stringstream page;
  page << in.rdbuf();
  const json data = data_of_page(page.str());
  fs::remove_all(out);

  // The plan reaches three steps ahead; each footprint is listed once; the feet alternate on the
  // footprints stepped on.
  json kept = json::array();
  for (const json& f : data["footprints"]) {
    EXPECT_LE(f["first"].get<double>(), f["last"].get<double>());
    EXPECT_FALSE(f["stepped"].get<bool>() && f["superseded"].get<bool>());
    if (f["stepped"].get<bool>()) kept.push_back(f);
  }
  ASSERT_GE(kept.size(), 4u);
  std::set<std::pair<long, long>> places;
  for (std::size_t i = 0; i < kept.size(); ++i) {
    places.insert({std::lround(kept[i]["x"].get<double>() * 100), std::lround(kept[i]["y"].get<double>() * 100)});
    if (i > 0) {
      EXPECT_NE(kept[i]["side"], kept[i - 1]["side"]) << i;
      EXPECT_GT(kept[i]["touchdown"].get<double>(), kept[i - 1]["touchdown"].get<double>()) << i;
    }
  }
  EXPECT_EQ(places.size(), kept.size());

  const json& log = data["log"];
  int inside = 0, defined = 0, estimated = 0;
  for (std::size_t i = 0; i < log["t"].size(); ++i) {
    if (!log["com_est_x"][i].is_null()) ++estimated;
    if (log["cop_x"][i].is_null() || log["support_x_min"][i].is_null()) continue;
    ++defined;
    constexpr double tol = 0.01;
    const double x = log["cop_x"][i], y = log["cop_y"][i];
    if (x > log["support_x_min"][i].get<double>() - tol && x < log["support_x_max"][i].get<double>() + tol &&
        y > log["support_y_min"][i].get<double>() - tol && y < log["support_y_max"][i].get<double>() + tol) {
      ++inside;
    }
  }
  EXPECT_GT(estimated, 300);
  EXPECT_GT(defined, 350);
  EXPECT_GE(inside, defined * 98 / 100);
}

}  // namespace
}  // namespace biped
