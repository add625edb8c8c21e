#include "io/step_tables.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/robot_config.hpp"
#include "io/yaml_reader.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

std::string temp_file(const std::string& name, const std::string& text) {
  const auto p = std::filesystem::temp_directory_path() / (name + "-" + std::to_string(::getpid()) + ".csv");
  std::ofstream(p) << text;
  return p.string();
}

TEST(StepTables, CsvRoundTrip) {
  StepTable table;
  table.rows = {{0.0, 0.8, 0.2, 0.04, 0.07}, {0.3, 1.0, 0.15, 0.04, 0.06}};
  std::stringstream csv;
  write_step_table(table, csv);
  const StepTable back = read_step_table(temp_file("table", csv.str()));
  ASSERT_EQ(back.rows.size(), 2u);
  EXPECT_DOUBLE_EQ(back.rows[1].step_time, 1.0);
  EXPECT_DOUBLE_EQ(back.rows[1].double_support_ratio, 0.15);
  EXPECT_DOUBLE_EQ(fastest_feasible_speed(back), 0.3);
}

TEST(StepTables, MalformedFilesNameTheLine) {
  const std::string header = "speed,step_time,double_support_ratio,clearance,zmp_margin_m\n";
  auto message = [](const std::string& path) {
    try {
      read_step_table(path);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message(temp_file("h", "speed,x\n")).find(":1: not a step table"), std::string::npos);
  EXPECT_NE(message(temp_file("r", header + "0,0.8,0.2,0.04,0.1\n0.5,abc\n")).find(":3: malformed"), std::string::npos);
  EXPECT_NE(message(temp_file("o", header + "0.5,0.8,0.2,0.04,0.1\n0.2,0.8,0.2,0.04,0.1\n")).find("increase"),
            std::string::npos);
  EXPECT_NE(message(temp_file("n", header + "0.5,nan,0.2,0.04,0.1\n")).find("malformed"), std::string::npos);
}

// The criterion separates a comfortable gait from an overreaching one.
TEST(StepTables, CriterionPrefersFeasibleGaitsWithZmpMargin) {
  const RobotModel model = test::load_model("johnnie");
  WalkingControllerParams base;
  const CandidateResult easy = evaluate_step_candidate(model, base, 0.3, 0.9, 0.2, 4, 2);
  EXPECT_TRUE(easy.feasible);
  EXPECT_GT(easy.zmp_margin, 0.02);
  const CandidateResult hard = evaluate_step_candidate(model, base, 1.0, 1.0, 0.1, 4, 2);  // 1 m steps
  EXPECT_FALSE(hard.feasible && hard.zmp_margin > 0.0);
}

// The shipped tables exist for both robots and bound the accepted commands.
TEST(StepTables, ShippedTablesBoundTheCommands) {
  for (const char* robot : {"lola", "johnnie"}) {
    Scenario s;
    s.file = "test";
    s.robot = robot;
    s.duration = 1.0;
    const RunConfig config = make_run_config(s);
    const StepTable& table = config.controller.walking.table;
    ASSERT_FALSE(table.empty()) << robot;
    EXPECT_DOUBLE_EQ(config.controller.walking.limits.vx_max, fastest_feasible_speed(table));
    EXPECT_GE(fastest_feasible_speed(table), 0.6) << robot;
  }
}

}  // namespace
}  // namespace biped
