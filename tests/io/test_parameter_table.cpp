#include "io/parameter_table.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <sstream>

#include "io/robot_config.hpp"
#include "io/yaml_reader.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

struct Gains {
  double gain = 2.5;
  double offset = -1.0;
  double share = 0.5;
  double angle_rad = 0.1;
  int cycles = 3;
  bool enabled = true;
};

const ParameterTable<Gains> kGains = {
    {"gain", &Gains::gain, "1/s", kPositive, "the gain"},
    {"offset", &Gains::offset, "m", kFinite, "the offset"},
    {"share", &Gains::share, "", positive_below(1.0, "the rest needs some"), "the share"},
    {"angle_deg", Degrees<Gains>{&Gains::angle_rad}, "deg", kNonNegative, "the angle"},
    {"cycles", &Gains::cycles, "", kNonNegative, "the cycles (0: off)"},
    {"enabled", &Gains::enabled, "", {}, "on or off"},
};

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string read_error(const std::string& yaml) {
  Gains g;
  const YamlReader r("gains.yaml");
  const YAML::Node root = YAML::Load(yaml);
  return message_of([&] { read_section(r, root["gains"], {"gains", {{kGains, g}}, {"model"}}); });
}

TEST(ParameterTable, ReadingSetsTheGivenKeysAndKeepsTheOthers) {
  Gains g;
  const YamlReader r("gains.yaml");
  const YAML::Node root = YAML::Load("gains: {gain: 4, angle_deg: 90, cycles: 0, enabled: false, model: x}\n");
  read_section(r, root["gains"], {"gains", {{kGains, g}}, {"model"}});
  EXPECT_EQ(g.gain, 4.0);
  EXPECT_EQ(g.angle_rad, 90.0 * (M_PI / 180.0));
  EXPECT_EQ(g.cycles, 0);
  EXPECT_FALSE(g.enabled);
  EXPECT_EQ(g.offset, Gains{}.offset);
  EXPECT_EQ(g.share, Gains{}.share);
}

TEST(ParameterTable, AnAbsentSectionChangesNothing) {
  Gains g;
  g.gain = 7.0;
  read_section(YamlReader("gains.yaml"), YAML::Node(), {"gains", {{kGains, g}}, {}});
  EXPECT_EQ(g.gain, 7.0);
}

TEST(ParameterTable, UnknownKeysNameFileKeyAndTheAllowedOnes) {
  EXPECT_EQ(read_error("gains:\n  gian: 1\n"),
            "gains.yaml:2: key 'gains.gian': unknown key (allowed here: gain, offset, share, angle_deg, cycles, "
            "enabled, model)");
}

TEST(ParameterTable, BadValuesFailWithOneLineNamingFileAndKey) {
  const std::string lines = "gains:\n  model: x\n";
  EXPECT_EQ(read_error(lines + "  gain: -1\n"), "gains.yaml:3: key 'gains.gain': must be positive (got -1)");
  EXPECT_EQ(read_error(lines + "  gain: 0\n"), "gains.yaml:3: key 'gains.gain': must be positive (got 0)");
  EXPECT_EQ(read_error(lines + "  gain: fast\n"), "gains.yaml:3: key 'gains.gain': expected a number");
  EXPECT_EQ(read_error(lines + "  gain: .nan\n"), "gains.yaml:3: key 'gains.gain': must be a finite number (got '.nan')");
  EXPECT_EQ(read_error(lines + "  offset: [1]\n"), "gains.yaml:3: key 'gains.offset': expected a number");
  EXPECT_EQ(read_error(lines + "  share: 1\n"),
            "gains.yaml:3: key 'gains.share': must be below 1 (the rest needs some)");
  EXPECT_EQ(read_error(lines + "  angle_deg: -2\n"), "gains.yaml:3: key 'gains.angle_deg': must not be negative (got -2)");
  EXPECT_EQ(read_error(lines + "  cycles: 1.5\n"), "gains.yaml:3: key 'gains.cycles': expected an integer");
  EXPECT_EQ(read_error(lines + "  cycles: -1\n"), "gains.yaml:3: key 'gains.cycles': must not be negative (got -1)");
  EXPECT_EQ(read_error(lines + "  cycles: 99999999999\n"), "gains.yaml:3: key 'gains.cycles': out of range (got 99999999999)");
  EXPECT_EQ(read_error(lines + "  enabled: 3\n"), "gains.yaml:3: key 'gains.enabled': expected true or false");
  for (const char* bad : {"  gain: -1\n", "  gain: x\n", "  gain: .nan\n", "  cycles: -1\n"}) {
    EXPECT_EQ(read_error(lines + bad).find('\n'), std::string::npos) << bad;
  }
}

TEST(ParameterTable, UpperBoundsMayIncludeTheBound) {
  const YamlReader r("f.yaml");
  const YAML::Node map = YAML::Load("{k: 1, m: 1.5}");
  EXPECT_EQ(*read_number(r, map, "s", "k", positive_at_most(1.0)), 1.0);
  EXPECT_EQ(message_of([&] { read_number(r, map, "s", "m", positive_at_most(1.0, "why")); }),
            "f.yaml:1: key 's.m': must be at most 1 (why)");
  EXPECT_FALSE(read_number(r, map, "s", "absent", kPositive));
}

TEST(ParameterTable, ReferenceShowsTheStructsDefaultsAndChecks) {
  std::vector<ParameterDoc> rows;
  document_parameters("gains", kGains, Gains{}, rows);
  ASSERT_EQ(rows.size(), kGains.size());
  EXPECT_EQ(rows[0].key, "gains.gain");
  EXPECT_EQ(rows[0].default_value, "2.5");
  EXPECT_EQ(rows[0].check, "> 0");
  EXPECT_EQ(rows[1].default_value, "-1");
  EXPECT_EQ(rows[1].check, "finite");
  EXPECT_EQ(rows[2].check, "> 0, < 1");
  EXPECT_EQ(rows[3].default_value, number_text(Gains{}.angle_rad * 180.0 / M_PI));
  EXPECT_EQ(rows[4].default_value, "3");
  EXPECT_EQ(rows[4].check, "integer ≥ 0");
  EXPECT_EQ(rows[5].default_value, "true");
  EXPECT_EQ(markdown_table({rows[0]}),
            "| key | unit | default | check | description |\n|---|---|---|---|---|\n"
            "| `gains.gain` | 1/s | 2.5 | > 0 | the gain |\n");
}

const ParameterDoc& row_of(const std::vector<ParameterDoc>& rows, const std::string& key) {
  for (const ParameterDoc& row : rows) {
    if (row.key == key) return row;
  }
  throw std::runtime_error("no row " + key);
}

TEST(ParameterTable, RobotParameterDefaultsAreTheStructs) {
  const auto rows = parameter_reference();
  EXPECT_EQ(row_of(rows, "controller.stabilization.tilt_gain").default_value, number_text(StabilizerParams{}.tilt_gain));
  EXPECT_EQ(row_of(rows, "controller.step_time").default_value, number_text(StepParameters{}.step_time));
  EXPECT_EQ(row_of(rows, "simulation.timestep").default_value, number_text(WorldSpec{}.timestep));
  EXPECT_EQ(row_of(rows, "controller.sensor_limits.frozen_cycles").default_value,
            std::to_string(SensorLimits{}.frozen_cycles));
  EXPECT_EQ(row_of(rows, "controller.software_limit_margin_deg").default_value, "5");
  EXPECT_EQ(row_of(rows, "sensor_noise.imu_misalignment_deg").default_value,
            number_text(SensorNoiseParams{}.imu_misalignment_rad * 180.0 / M_PI));
}

// docs/scenarios.md holds the output of `biped params --markdown` between the markers.
TEST(ParameterTable, ScenarioDocumentationHoldsTheGeneratedReference) {
  std::ifstream in(test::source_path("docs/scenarios.md"));
  ASSERT_TRUE(in);
  std::stringstream text;
  text << in.rdbuf();
  const std::string doc = text.str();
  const std::string begin = "<!-- BEGIN parameters (biped params --markdown) -->\n";
  const std::string end = "<!-- END parameters -->";
  const auto from = doc.find(begin);
  ASSERT_NE(from, std::string::npos) << "no '" << begin << "' in docs/scenarios.md";
  const auto to = doc.find(end, from);
  ASSERT_NE(to, std::string::npos) << "no '" << end << "' in docs/scenarios.md";
  EXPECT_EQ(doc.substr(from + begin.size(), to - from - begin.size()), markdown_table(parameter_reference()))
      << "docs/scenarios.md is stale: replace the block with the output of `biped params --markdown`";
}

}  // namespace
}  // namespace biped
