// Campaign files (io/campaign_spec.cpp): runs determined by (file, index), grids enumerated, each
// varied key and generator giving valid scenario assignments, bad files refused naming file and key.
#include "io/campaign_spec.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "io/scenario.hpp"
#include "io/yaml_reader.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

std::string write_spec(const std::string& name, const std::string& text) {
  const auto dir = test::fresh_dir(("spec-" + name).c_str());
  const std::string path = (dir / (name + ".yaml")).string();
  std::ofstream(path) << "scenario: " << test::source_path("config/scenarios/lola-walk.yaml") << "\n" << text;
  return path;
}

std::string error_of(const std::string& path, const std::vector<std::string>& overrides = {}) {
  try {
    load_campaign_spec(path, overrides);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(CampaignRandom, DrawsStayInRangeAndRepeatForTheSameSeed) {
  CampaignRandom a(42), b(42);
  for (int i = 0; i < 1000; ++i) {
    const double u = a.uniform(-2.0, 3.0);
    EXPECT_GE(u, -2.0);
    EXPECT_LE(u, 3.0);
    EXPECT_EQ(u, b.uniform(-2.0, 3.0));
    const long k = a.integer(1, 3);
    EXPECT_GE(k, 1);
    EXPECT_LE(k, 3);
    b.integer(1, 3);
  }
  double sum = 0.0, squares = 0.0;
  for (int i = 0; i < 20000; ++i) {
    const double x = a.normal(1.0, 2.0);
    sum += x;
    squares += x * x;
  }
  EXPECT_NEAR(sum / 20000, 1.0, 0.05);
  EXPECT_NEAR(std::sqrt(squares / 20000 - 1.0), 2.0, 0.05);
}

TEST(ExactNumber, ReadsBackAsTheSameDouble) {
  for (double v : {0.1, 1.0 / 3.0, -123.456e-7, 0.30000000000000004}) EXPECT_EQ(std::stod(exact_number(v)), v);
  EXPECT_EQ(exact_number(0.25), "0.25");
}

TEST(CampaignSpec, EachRunIsDeterminedByTheFileAndItsIndex) {
  const std::string path = write_spec("determined", R"(runs: 20
seed: 5
set: {duration: 3.0}
vary:
  sensors.noise: {choice: [true, false]}
  commands.1.vx: {uniform: [0.1, 0.5]}
  model_error.upper_body_mass_scale: {normal: {mean: 1.0, std: 0.05, min: 0.9, max: 1.1}}
generators:
  joystick: {start: 1.0, end: 2.5, interval: [0.5, 1.0], vx: [0.0, 0.4], omega: [-0.2, 0.2], stop_probability: 0.3}
  pushes:
    count: [0, 2]
    items: [{type: push, t: {uniform: [1, 2]}, direction_deg: {uniform: [-180, 180]}, impulse_Ns: {uniform: [0, 9]}}]
)");
  const CampaignSpec a = load_campaign_spec(path), b = load_campaign_spec(path);
  std::set<std::vector<std::string>> distinct;
  for (long i = 0; i < a.runs; ++i) {
    const CampaignRun run = campaign_run(a, i);
    EXPECT_EQ(run.assignments, campaign_run(b, i).assignments);
    distinct.insert(run.assignments);
    // Every run is a valid scenario: its assignments read back through the scenario reader.
    const Scenario s = load_scenario(a.scenario, run.assignments);
    EXPECT_EQ(s.duration, 3.0);
    EXPECT_LE(s.pushes.size(), 2u);
    for (std::size_t k = 1; k < s.commands.size(); ++k) EXPECT_GE(s.commands[k].t, s.commands[k - 1].t);
    EXPECT_TRUE(s.commands.back().command.stop);
  }
  EXPECT_EQ(distinct.size(), 20u);
  // Another seed draws other runs.
  EXPECT_NE(campaign_run(load_campaign_spec(path, {"seed=6"}), 0).assignments, campaign_run(a, 0).assignments);
}

TEST(CampaignSpec, AddingAKeyChangesNoOtherDraw) {
  const std::string one = write_spec("one", "runs: 3\nvary:\n  commands.1.vx: {uniform: [0.1, 0.5]}\n");
  const std::string two = write_spec("two", "runs: 3\nvary:\n  sensors.delay_cycles: {integer: [0, 2]}\n"
                                            "  commands.1.vx: {uniform: [0.1, 0.5]}\n");
  for (long i = 0; i < 3; ++i) {
    const auto a = campaign_run(load_campaign_spec(one), i).assignments;
    const auto b = campaign_run(load_campaign_spec(two), i).assignments;
    EXPECT_EQ(a.back(), b.back());
  }
}

TEST(CampaignSpec, GridsCycleThroughTheirProductFirstKeySlowest) {
  const std::string path = write_spec("grid", "vary:\n  sensors.delay_cycles: {grid: [0, 1]}\n"
                                              "  commands.1.vx: {grid: {from: 0.1, to: 0.3, step: 0.1}}\n");
  const CampaignSpec spec = load_campaign_spec(path);
  EXPECT_EQ(spec.runs, 6);  // no `runs`: the grid's size
  std::vector<std::string> seen;
  for (long i = 0; i < 6; ++i) {
    const CampaignRun r = campaign_run(spec, i);
    seen.push_back(r.assignments[1] + " " + r.assignments[2]);
  }
  EXPECT_EQ(seen[0], "sensors.delay_cycles=0 commands.1.vx=0.1");
  EXPECT_EQ(seen[2], "sensors.delay_cycles=0 commands.1.vx=0.3");
  EXPECT_EQ(seen[3], "sensors.delay_cycles=1 commands.1.vx=0.1");
  EXPECT_EQ(campaign_run(spec, 7).assignments[2], "commands.1.vx=0.2");  // with more runs, the grid repeats
}

TEST(CampaignSpec, OverridesApplyToCampaignKeys) {
  const std::string path = write_spec("override", "runs: 100\nvary:\n  commands.1.vx: {uniform: [0.1, 0.5]}\n");
  EXPECT_EQ(load_campaign_spec(path, {"runs=8"}).runs, 8);
  // A varied key's distribution, addressed through its dotted name.
  const CampaignSpec narrowed = load_campaign_spec(path, {"vary.commands.1.vx.uniform=[0.3, 0.3]"});
  EXPECT_EQ(campaign_run(narrowed, 5).assignments.back(), "commands.1.vx=0.3");
  EXPECT_NE(error_of(path, {"vary.commands.1.vx.uniform=[0.5, 0.1]"}).find("empty range"), std::string::npos);
}

TEST(CampaignSpec, BadFilesAreRefusedNamingFileAndKey) {
  struct Case {
    const char* text;
    const char* key;
  };
  const std::vector<Case> cases = {
      {"runs: 2\nrepeats: 3\n", "'repeats'"},
      {"runs: 2\nvary:\n  commands.1.vx: {uniform: [0.5, 0.1]}\n", "vary.commands.1.vx.uniform': empty range"},
      {"runs: 2\nvary:\n  commands.1.vx: {integer: [3, 1]}\n", "empty range"},
      {"runs: 2\nvary:\n  commands.1.vx: {choice: []}\n", "vary.commands.1.vx.choice"},
      {"runs: 2\nvary:\n  commands.1.vx: {normal: {mean: 0, std: -1}}\n", "vary.commands.1.vx.normal.std"},
      {"runs: 2\nvary:\n  commands.1.vx: {normal: {mean: 0, std: 0.01, min: 5, max: 6}}\n", "impossible distribution"},
      {"runs: 2\nvary:\n  commands.1.vx: {poisson: 3}\n", "vary.commands.1.vx': expected a distribution"},
      {"runs: 2\nvary:\n  controller.no_such_gain: {uniform: [1, 2]}\n", "vary.controller.no_such_gain"},
      {"runs: 2\ngenerators:\n  weather: {count: [0, 1]}\n", "generators.weather': unknown generator"},
      {"runs: 2\ngenerators:\n  pushes: {count: [2, 1], items: [{type: push, t: 1}]}\n", "generators.pushes.count"},
      {"runs: 2\ngenerators:\n  terrain: {count: [1, 1], items: [{type: cliff, x: 1}]}\n", "generators.terrain"},
      {"runs: 2\ngenerators:\n  joystick: {end: 5}\n", "generators.joystick.interval"},
      {"runs: 0\n", "'runs'"},
      {"vary:\n  commands.1.vx: {uniform: [0.1, 0.2]}\n", "'runs'"},
  };
  for (const Case& c : cases) {
    const std::string path = write_spec("bad", c.text);
    const std::string message = error_of(path);
    EXPECT_NE(message.find(path), std::string::npos) << c.text << " -> " << message;
    EXPECT_NE(message.find(c.key), std::string::npos) << c.text << " -> " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(CampaignSpec, CasesRunTheirOwnScenarioAndKeepItsSeed) {
  const auto dir = test::fresh_dir("spec-cases");
  const std::string path = (dir / "cases.yaml").string();
  std::ofstream(path) << "seeds: scenario\nset: {sensors: {noise: true}}\ncases:\n"
                      << "  - {name: a, scenario: " << test::source_path("config/scenarios/lola-stand.yaml")
                      << ", set: {duration: 2}, expect: walks}\n"
                      << "  - {name: b, scenario: " << test::source_path("config/scenarios/johnnie-walk.yaml")
                      << ", expect: falls}\n";
  const CampaignSpec spec = load_campaign_spec(path);
  EXPECT_EQ(spec.runs, 2);
  const CampaignRun a = campaign_run(spec, 0), b = campaign_run(spec, 1);
  EXPECT_EQ(a.case_name, "a");
  EXPECT_EQ(b.expect, "falls");
  EXPECT_NE(b.scenario.find("johnnie-walk.yaml"), std::string::npos);
  // The case's own keys, then the campaign's `set` (flattened: one key, not the whole section); no seed.
  EXPECT_EQ(a.assignments, (std::vector<std::string>{"duration=2", "sensors.noise=true"}));
  EXPECT_EQ(load_scenario(b.scenario, b.assignments).seed, load_scenario(b.scenario).seed);
  EXPECT_NE(error_of(path, {"cases.1.expect=stumbles"}).find("cases.1.expect"), std::string::npos);
}

TEST(ReproduceCommand, QuotesForTheShell) {
  EXPECT_EQ(reproduce_command("a.yaml", {"seed=3", "commands=[{t: 0, vx: 0.1}]"}),
            "build/biped run a.yaml --set seed=3 --set 'commands=[{t: 0, vx: 0.1}]'");
}

TEST(CampaignSpec, ShippedCampaignFilesLoad) {
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(test::source_path("config/campaigns"))) {
    const CampaignSpec spec = load_campaign_spec(entry.path().string());
    EXPECT_GT(spec.runs, 0) << entry.path();
    ++files;
  }
  EXPECT_GE(files, 5);
}

}  // namespace
}  // namespace biped
