#include "studies/gain_tuning.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/yaml_reader.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;

namespace biped {
namespace {

RunConfig lola(const std::string& controller_yaml = "") {
  Scenario s = test::robot_scenario("lola");
  if (!controller_yaml.empty()) s.controller = YAML::Load(controller_yaml);
  return make_run_config(s);
}

std::vector<TunedParameter> rows(const std::vector<std::string>& keys) {
  std::vector<TunedParameter> out;
  for (const TunedParameter& p : tuned_parameters()) {
    if (std::find(keys.begin(), keys.end(), p.key) != keys.end()) out.push_back(p);
  }
  return out;
}

// LOLA walking at 0.3 m/s for 5 s onto an unexpected 3 cm step up or down or a 5° slope up or
// down, the step adaptation and the hip strategy off: with the robot file's gains it walks on (no
// fall in 16 runs on seeds 1 and 2 alike), with eq. (10)'s tilt gains and eq. (14)'s force gain at a
// fifth it falls in half (8 and 8 of 16; at a tenth 10 and 12, from where three generations did not
// halve them). Measured 2026-12-07: the tuner from a fifth, training 8 -> 2 falls, held-out 8 -> 0.
// (A sideways push at a touchdown, this campaign until the gait events stopped counting a foot's
// bounce as a touchdown, does not tell the gains apart once it lands where it is timed: 13-16 N·s
// with the extensions off fell 10 of 16 runs with the robot file's gains.)
fs::path short_terrain_campaign(const fs::path& dir, int runs = 4) {
  const fs::path file = dir / "terrain.yaml";
  std::ofstream(file) << "scenario: " << test::source_path("config/scenarios/lola-walk.yaml") << "\n"
                      << "runs: " << runs << "\nseed: 1\n"
                      << "set: {duration: 5.0, commands: [{t: 0.0, vx: 0.3}]}\n"
                      << "generators:\n"
                      << "  terrain: {count: [1, 1], items: [\n"
                      << "    {type: step, x: {uniform: [0.3, 0.6]}, height: {choice: [-0.03, 0.03]}},\n"
                      << "    {type: slope, x: {uniform: [0.2, 0.4]}, angle_deg: {choice: [-5, 5]}, length: 3.0}]}\n";
  return file;
}

fs::path detuned_gains(const fs::path& dir) {
  const fs::path file = dir / "detuned.yaml";
  // Without the step adaptation and the hip strategy, whose steps and lean would catch some of the
  // falls the gains are to cure: the three gains are what is tuned.
  std::ofstream(file) << "controller:\n  stabilization: {tilt_gain: 120, tilt_rate_gain: 12, force_gain: 4}\n"
                         "  step_adaptation: {enabled: false}\n  upper_body_lean: {enabled: false}\n";
  return file;
}

TEST(GainTuning, PopulationIsCmaesDefaultAndAtLeastFive) {
  EXPECT_EQ(tuning_population(1), 5);
  EXPECT_EQ(tuning_population(3), 7);
  EXPECT_EQ(tuning_population(10), 10);
}

// Parameters that do not apply to the robot are left out; the bounds hold a start below them; the
// unit interval maps onto the bounds and back.
TEST(GainTuning, SearchRangesApplyToTheRobotAndHoldTheStart) {
  const RunConfig reference = lola();
  const std::vector<SearchRange> all = search_ranges(tuned_parameters(), reference, reference);
  for (const SearchRange& p : all) {
    EXPECT_LT(p.lower, p.reference);
    EXPECT_GT(p.upper, p.reference);
    EXPECT_DOUBLE_EQ(p.value(0.0), p.lower);
    EXPECT_NEAR(p.value(1.0), p.upper, 1e-12 * p.upper);
    EXPECT_NEAR(p.value(p.share(p.reference)), p.reference, 1e-9 * p.reference) << p.row.key;
    EXPECT_DOUBLE_EQ(p.value(2.0), p.value(1.0));
  }
  EXPECT_GE(all.size(), 6u);
  EXPECT_LE(all.size(), 16u);
  // Switched off, the step adaptation's and the hip strategy's parameters are not tuned.
  for (const char* extension : {"step_adaptation", "upper_body_lean"}) {
    const std::vector<SearchRange> without =
        search_ranges(tuned_parameters(), lola("{" + std::string(extension) + ": {enabled: false}}"), reference);
    EXPECT_LT(without.size(), all.size()) << extension;
    for (const SearchRange& p : without) EXPECT_EQ(std::string(p.row.key).find(extension), std::string::npos);
  }

  const RunConfig detuned = lola("{stabilization: {tilt_gain: 12}}");
  const std::vector<SearchRange> widened = search_ranges(rows({"controller.stabilization.tilt_gain"}), reference, detuned);
  ASSERT_EQ(widened.size(), 1u);
  EXPECT_DOUBLE_EQ(widened[0].lower, 12.0);
  EXPECT_DOUBLE_EQ(widened[0].start, 12.0);
  EXPECT_DOUBLE_EQ(widened[0].reference, reference.controller.walking.stabilization.tilt_gain);
}

// The optimizer on a small budget: from a detuned gain set that falls, the tuned set scores better
// on the training runs and walks on held-out runs where the detuned set falls. The gain file holds
// what was tuned and reads as an include.
TEST(GainTuning, ImprovesADetunedGainSetOnTrainingAndHeldOutRuns) {
  const fs::path dir = test::fresh_dir("tune-detuned");
  TuningOptions options;
  options.robot = "lola";
  options.campaign = short_terrain_campaign(dir, 16).string();
  options.from = detuned_gains(dir).string();
  options.parameters = rows({"controller.stabilization.tilt_gain", "controller.stabilization.tilt_rate_gain",
                             "controller.stabilization.force_gain"});
  options.budget = 16 * (1 + 3 * tuning_population(3));  // the start and three generations
  options.heldout_runs = 16;
  const nlohmann::json r = run_gain_tuning(options, (dir / "out").string());

  EXPECT_EQ(r["generations"], 3);
  EXPECT_EQ(r["evaluated_candidates"], 1 + 3 * tuning_population(3));
  EXPECT_LE(r["training_runs"].get<long>(), options.budget);
  EXPECT_LT(r["objective"]["tuned"].get<double>(), r["objective"]["start"].get<double>());
  EXPECT_LT(r["objective"]["tuned_falls"].get<long>(), r["objective"]["start_falls"].get<long>());
  const nlohmann::json& start = r["heldout"]["start"];
  const nlohmann::json& tuned = r["heldout"]["tuned"];
  EXPECT_EQ(start["completed"], 16);
  EXPECT_EQ(tuned["completed"], 16);
  EXPECT_GE(start["falls"].get<long>(), 8) << "the detuned set should fall in half the held-out runs or more";
  EXPECT_LE(2 * tuned["falls"].get<long>(), start["falls"].get<long>()) << r["heldout"].dump();

  // Every candidate stays inside its bounds; the gain file holds the best one and nothing else.
  RunConfig included = lola();
  apply_include_file((dir / "out" / "gains.yaml").string(), included);
  const StabilizerParams& gains = included.controller.walking.stabilization;
  const nlohmann::json& best = r["candidates"][r["best_candidate"].get<std::size_t>()]["values"];
  EXPECT_DOUBLE_EQ(gains.tilt_gain, best["controller.stabilization.tilt_gain"].get<double>());
  EXPECT_DOUBLE_EQ(gains.tilt_rate_gain, best["controller.stabilization.tilt_rate_gain"].get<double>());
  EXPECT_DOUBLE_EQ(gains.force_gain, best["controller.stabilization.force_gain"].get<double>());
  EXPECT_DOUBLE_EQ(gains.com_gain, lola().controller.walking.stabilization.com_gain);
  for (const auto& p : r["parameters"]) {
    for (const auto& c : r["candidates"]) {
      const double v = c["values"][p["key"].get<std::string>()].get<double>();
      EXPECT_GE(v, p["lower"].get<double>() * (1 - 5e-3));
      EXPECT_LE(v, p["upper"].get<double>() * (1 + 5e-3));
    }
  }
  std::ifstream saved(dir / "out" / "tune.json");
  EXPECT_EQ(nlohmann::json::parse(saved)["candidates"].size(), r["candidates"].size());
}

// A tuning run again into the same folder simulates only the candidates it had not: a killed tune
// continues, a larger budget adds generations. Another tuning's folder is refused.
TEST(GainTuning, RunAgainContinuesFromTheEarlierCandidates) {
  const fs::path dir = test::fresh_dir("tune-resume");
  const fs::path campaign = short_terrain_campaign(dir, 2);
  TuningOptions options;
  options.robot = "lola";
  options.campaign = campaign.string();
  options.parameters = rows({"controller.stabilization.force_gain"});
  options.heldout_runs = 0;
  const int population = tuning_population(1);
  std::ostringstream first_progress, second_progress;
  options.progress = &first_progress;
  options.budget = 2 * (1 + population);
  const nlohmann::json first = run_gain_tuning(options, (dir / "out").string());
  options.progress = &second_progress;
  options.budget = 2 * (1 + 2 * population);
  const nlohmann::json second = run_gain_tuning(options, (dir / "out").string());

  ASSERT_EQ(second["candidates"].size(), 1u + 2u * population);
  for (std::size_t i = 0; i < first["candidates"].size(); ++i) {
    EXPECT_EQ(second["candidates"][i]["values"], first["candidates"][i]["values"]);
    EXPECT_EQ(second["candidates"][i]["objective"], first["candidates"][i]["objective"]);
  }
  const std::string text = second_progress.str();
  long earlier = 0;
  for (std::size_t at = text.find("from the earlier session"); at != std::string::npos;
       at = text.find("from the earlier session", at + 1)) {
    ++earlier;
  }
  long repeated = 0;
  for (const auto& c : first["candidates"]) repeated += c["repeated"].get<bool>();
  EXPECT_EQ(earlier, static_cast<long>(first["candidates"].size()) - repeated) << text;
  EXPECT_EQ(first_progress.str().find("from the earlier session"), std::string::npos);

  options.from = detuned_gains(dir).string();
  try {
    run_gain_tuning(options, (dir / "out").string());
    FAIL() << "another tuning's folder was used";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("tune.json: holds another tuning"), std::string::npos) << e.what();
  }
}

std::string error_of(const TuningOptions& options, const fs::path& out) {
  try {
    run_gain_tuning(options, out.string());
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// Bad input is named before anything runs or is written.
TEST(GainTuning, BadInputIsOneLineNamingTheOptionOrKey) {
  const fs::path dir = test::fresh_dir("tune-bad");
  const fs::path out = dir / "out";
  TuningOptions options;
  options.robot = "asimo";
  options.budget = 100;
  EXPECT_NE(error_of(options, out).find("--robot: unknown robot 'asimo' (known: "), std::string::npos);
  options.robot = "lola";
  options.budget = 0;
  EXPECT_NE(error_of(options, out).find("--budget: must be at least 1"), std::string::npos);
  options.campaign = short_terrain_campaign(dir).string();
  const int tuned = static_cast<int>(search_ranges(tuned_parameters(), lola(), lola()).size());
  options.budget = 4 * tuning_population(tuned);
  EXPECT_NE(error_of(options, out).find("--budget: " + std::to_string(options.budget) +
                                        " runs are less than the start and one generation: at least " +
                                        std::to_string(4 * (1 + tuning_population(tuned)))),
            std::string::npos);
  options.budget = 1000;
  options.robot = "johnnie";
  EXPECT_NE(error_of(options, out).find(options.campaign + ": key 'scenario': its robot is 'lola', not 'johnnie'"),
            std::string::npos);
  options.robot = "lola";
  const fs::path bad_gains = dir / "bad.yaml";
  std::ofstream(bad_gains) << "controller:\n  stabilization: {tilt_gian: 3}\n";
  options.from = bad_gains.string();
  EXPECT_NE(error_of(options, out).find(bad_gains.string() + ":2: key 'controller.stabilization.tilt_gian'"),
            std::string::npos);
  std::ofstream(bad_gains) << "drives: {bandwidth_hz: 18}\n";
  EXPECT_NE(error_of(options, out).find(bad_gains.string() + ":1: key 'drives'"), std::string::npos);
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace biped
