#include "io/step_table_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "io/yaml_reader.hpp"

namespace biped {
namespace {

std::string temp_file(const std::string& name, const std::string& text) {
  const auto p = std::filesystem::temp_directory_path() / (name + "-" + std::to_string(::getpid()) + ".csv");
  std::ofstream(p) << text;
  return p.string();
}

TEST(StepTableFile, CsvRoundTrip) {
  StepTable table;
  table.rows = {{0.0, 0.8, 0.2, 0.04, 0.07, 0.8}, {0.3, 1.0, 0.15, 0.04, 0.06, 1.0}};
  std::stringstream csv;
  write_step_table(table, csv);
  const StepTable back = read_step_table(temp_file("table", csv.str()));
  ASSERT_EQ(back.rows.size(), 2u);
  EXPECT_DOUBLE_EQ(back.rows[1].step_time, 1.0);
  EXPECT_DOUBLE_EQ(back.rows[1].double_support_ratio, 0.15);
  EXPECT_DOUBLE_EQ(back.rows[0].swing_travel_share, 0.8);
  EXPECT_DOUBLE_EQ(back.rows[1].swing_travel_share, 1.0);
  EXPECT_DOUBLE_EQ(fastest_feasible_speed(back), 0.3);
}

// A table written before the swing travel share column was made with the foot travelling the
// whole swing, and reads so.
TEST(StepTableFile, TableWithoutTheSwingTravelShareReadsTheWholeSwing) {
  const StepTable old = read_step_table(
      temp_file("old", "speed,step_time,double_support_ratio,clearance,zmp_margin_m\n0,0.8,0.2,0.04,0.07\n0.3,1,0.15,0.04,0.06\n"));
  ASSERT_EQ(old.rows.size(), 2u);
  EXPECT_DOUBLE_EQ(old.rows[1].zmp_margin, 0.06);
  StepParameters base;
  base.swing_travel_share = 0.8;
  EXPECT_DOUBLE_EQ(old.lookup(0.2, base).swing_travel_share, 1.0);
}

TEST(StepTableFile, MalformedFilesNameTheLine) {
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
  const std::string with_share = "speed,step_time,double_support_ratio,clearance,swing_travel_share,zmp_margin_m\n";
  EXPECT_NE(message(temp_file("s", with_share + "0,0.8,0.2,0.04,0.8,0.1\n0.5,0.8,0.2,0.04,1.5,0.1\n")).find(":3: malformed"),
            std::string::npos);
  EXPECT_NE(message(temp_file("m", with_share + "0,0.8,0.2,0.04,0.1\n")).find(":2: malformed"), std::string::npos);
}

}  // namespace
}  // namespace biped
