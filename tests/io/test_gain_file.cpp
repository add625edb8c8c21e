#include "io/gain_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "io/yaml_reader.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

RunConfig lola() { return make_run_config(test::robot_scenario("lola")); }

// What write_gain_file writes reads back as an include and as the same assignments.
TEST(GainFile, WrittenFileReadsBackAsIncludeAndAssignments) {
  const auto path = (test::fresh_dir("gain-file") / "gains.yaml").string();
  const std::vector<std::string> assignments = {"controller.stabilization.tilt_gain=812",
                                                "controller.stabilization.cop_margin=0.0231",
                                                "controller.terrain_adaptation.search_speed=0.3"};
  write_gain_file(path, {"tuned for a test", "second line"}, assignments);
  std::ifstream in(path);
  std::string first;
  std::getline(in, first);
  EXPECT_EQ(first, "# tuned for a test");

  RunConfig c = lola();
  apply_include_file(path, c);
  EXPECT_EQ(c.controller.walking.stabilization.tilt_gain, 812.0);
  EXPECT_EQ(c.controller.walking.stabilization.cop_margin, 0.0231);
  EXPECT_EQ(c.controller.walking.terrain.search_speed, 0.3);
  EXPECT_EQ(read_gain_file(path, lola()), assignments);
}

TEST(GainFile, OnlyControllerNumbersAndBooleansAreStartingGains) {
  const auto dir = test::fresh_dir("gain-file-bad");
  const auto path = (dir / "gains.yaml").string();
  auto error_of = [&](const std::string& body) {
    std::ofstream(path) << body;
    try {
      read_gain_file(path, lola());
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(error_of("controller: {stabilizer: false}\n"), "");
  EXPECT_EQ(error_of("drives: {bandwidth_hz: 18}\n"),
            path + ":1: key 'drives': a starting gain set holds controller keys only");
  EXPECT_EQ(error_of("controller:\n  step_table: other.csv\n")
                .find(path + ":2: key 'controller.step_table': no such file: " + (dir / "other.csv").string()),
            0u);
  EXPECT_NE(error_of("controller:\n  type: standing\n").find(path + ":2: key 'controller.type': a gain file holds numbers"),
            std::string::npos);
  EXPECT_NE(error_of("controller:\n  stabilization: {tilt_gian: 3}\n").find(path + ":2: key 'controller.stabilization.tilt_gian'"),
            std::string::npos);
}

}  // namespace
}  // namespace biped
