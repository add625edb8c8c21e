#include "studies/gain_tuning.hpp"

#include <pagmo/algorithms/cmaes.hpp>
#include <pagmo/population.hpp>
#include <pagmo/problem.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "io/campaign_database.hpp"
#include "io/campaign_spec.hpp"
#include "io/gain_file.hpp"
#include "io/output_files.hpp"
#include "io/scenario.hpp"
#include "io/yaml_reader.hpp"
#include "studies/campaign.hpp"

namespace fs = std::filesystem;

namespace biped {
namespace {

const StabilizerParams& stabilization(const RunConfig& c) { return c.controller.walking.stabilization; }
const TerrainAdaptationParams& terrain(const RunConfig& c) { return c.controller.walking.terrain; }
const StepAdaptationParams& steps(const RunConfig& c) { return c.controller.walking.step_adaptation; }
bool terrain_on(const RunConfig& c) { return terrain(c).enabled; }
bool steps_on(const RunConfig& c) { return steps(c).enabled; }
const UpperBodyLeanParams& lean(const RunConfig& c) { return c.controller.walking.upper_body_lean; }
bool lean_on(const RunConfig& c) { return lean(c).enabled; }

// The bounds are factors of the robot file's (hand-tuned) value; measured limits from
// docs/tuning.md (LOLA, a 0.3 m/s walk with pushes, and a 0.6 m/s walk) where there are some.
const std::vector<TunedParameter> kTunedParameters = {
    // eq. (10). ×0 falls after a push, ×0.5 walks with larger peaks, ×2 was better on one walk;
    // at ×4 a tilt of one degree already asks for about the torque that puts the CoP at a sole's
    // edge (LOLA: 2400 N·m/rad × 0.017 rad ≈ 42 N·m of ≈ 54), so more only saturates sooner.
    {"controller.stabilization.tilt_gain", [](const RunConfig& c) { return stabilization(c).tilt_gain; }, 0.25, 4.0,
     true},
    // ×3 oscillates from the start and falls (gyro noise through the drives' lag): the upper end.
    {"controller.stabilization.tilt_rate_gain", [](const RunConfig& c) { return stabilization(c).tilt_rate_gain; },
     0.25, 3.0, true},
    // ×0 walks, ×3 was better on one walk: a wide range on both sides.
    {"controller.stabilization.com_gain", [](const RunConfig& c) { return stabilization(c).com_gain; }, 0.25, 4.0,
     true},
    {"controller.stabilization.com_rate_gain", [](const RunConfig& c) { return stabilization(c).com_rate_gain; }, 0.25,
     4.0, true},
    // eq. (14). The force loop runs through 20 Hz position servos (≈ 125 /s): ×3 (60 /s) already
    // tracks worse than ×1 with ripple; ×0.25 (5 /s) lags the force ramps by 126 N.
    {"controller.stabilization.force_gain", [](const RunConfig& c) { return stabilization(c).force_gain; }, 0.25, 3.0,
     true},
    // 0: no feed-forward (walks, tracks worse); the pitch row tolerated up to 1.2 and failed beyond.
    {"controller.stabilization.feedforward_gain", [](const RunConfig& c) { return stabilization(c).feedforward_gain; },
     0.0, 1.5, false},
    // eq. (20): at ×0.4 (LOLA: 2 /s, 0.5 s) a foot's modification outlasts a swing phase; at ×4
    // (20 /s) it returns as fast as the force loop acts.
    {"controller.stabilization.position_gain", [](const RunConfig& c) { return stabilization(c).position_gain; }, 0.4,
     4.0, true},
    // sat of eq. (10): 0 walks; ×2 (4 cm of LOLA's 7 cm half width) left too little authority and fell.
    {"controller.stabilization.cop_margin", [](const RunConfig& c) { return stabilization(c).cop_margin; }, 0.0, 1.5,
     false},
    // Terrain adaptation. A foot searching slower than ×0.4 (0.1 m/s) finds a 2 cm step down only
    // after the double support; faster than ×2.5 (0.6 m/s) it lands hard.
    {"controller.terrain_adaptation.search_speed", [](const RunConfig& c) { return terrain(c).search_speed; }, 0.4, 2.5,
     true, terrain_on},
    // Below ×0.5 (2 cm) the stabilizer's own CoP shifts start the turn on flat ground; above ×2
    // (8 cm, more than LOLA's half sole width) it can never start.
    {"controller.terrain_adaptation.cop_band", [](const RunConfig& c) { return terrain(c).cop_band; }, 0.5, 2.0, false,
     terrain_on},
    // Step adaptation (only while it is on): how much of the DCM error a step takes up, and the
    // errors left to the stabilizer (the estimate's scatter: halving it moves steps on noise).
    {"controller.step_adaptation.gain", [](const RunConfig& c) { return steps(c).gain; }, 0.25, 1.5, false, steps_on},
    {"controller.step_adaptation.dead_band_forward", [](const RunConfig& c) { return steps(c).dead_band_forward; }, 0.5,
     2.0, true, steps_on},
    {"controller.step_adaptation.dead_band_sideways", [](const RunConfig& c) { return steps(c).dead_band_sideways; },
     0.5, 2.0, true, steps_on},
    // The hip strategy (only while it is on). Its gain: at ×0.25 (1 rad/m) a DCM error 0.1 m beyond
    // the dead band leans 0.1 rad, half the bound; ×3 reaches the bound 5 cm beyond it. Its bound:
    // 0.3 rad (×1.5) walked LOLA's training campaign (seed 11) 93.0 % against 93.3 %; larger leans
    // were not tried.
    {"controller.upper_body_lean.gain", [](const RunConfig& c) { return lean(c).gain; }, 0.25, 3.0, true, lean_on},
    {"controller.upper_body_lean.max_angle", [](const RunConfig& c) { return lean(c).max_angle; }, 0.5, 1.5, false,
     lean_on},
    // Its return: ×2 (3 rad/s) drove a sway that grew to a fall after an early sideways push;
    // ×0.67 (1 rad/s) walked the training campaign 92.7 % against 93.3 %.
    {"controller.upper_body_lean.return_frequency", [](const RunConfig& c) { return lean(c).return_frequency; }, 0.5,
     1.5, true, lean_on},
};

constexpr int kSignificantDigits = 3;  // of a candidate's values: what the gain file holds is what ran

std::string today() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[16];
  std::strftime(text, sizeof text, "%Y-%m-%d", &utc);
  return text;
}

std::string format(const char* pattern, double a, double b = 0.0, double c = 0.0) {
  char text[128];
  std::snprintf(text, sizeof text, pattern, a, b, c);
  return text;
}

// What one training run says about a gain set.
struct RunOutcome {
  bool fell = false;
  bool error = false;
  double fall_time_s = 0.0;
  double tilt_rms_deg = 0.0;
};

struct Evaluation {
  long runs = 0, falls = 0, errors = 0;
  double objective = 0.0;
  double tilt_rms_deg = 0.0;  // mean over the runs that stayed up
  double wall_time_s = 0.0;
};

// The run score of the header comment: below 0.5 for a run that stays up, 0.5..1 for a fall.
double run_score(const RunOutcome& r, double duration) {
  if (r.error) return 1.0;
  if (r.fell) return 0.5 + 0.5 * (1.0 - std::clamp(r.fall_time_s / duration, 0.0, 1.0));
  return 0.5 * r.tilt_rms_deg / (r.tilt_rms_deg + 1.0);
}

Evaluation evaluate(const CampaignSpec& training, const std::vector<std::string>& assignments, double duration,
                    int jobs) {
  CampaignSpec spec = training;
  spec.fixed.insert(spec.fixed.end(), assignments.begin(), assignments.end());
  const ScenarioCampaign work(spec);
  const auto start = std::chrono::steady_clock::now();
  const std::vector<RunOutcome> outcomes = parallel_map<RunOutcome>(spec.runs, jobs, [&](long i) {
    RunOutcome r;
    try {
      CampaignRow row;
      work.run(i, row);
      const nlohmann::json& s = row.result;
      r.fell = s.at("fell").get<bool>();
      if (r.fell) r.fall_time_s = s.at("fall_time_s").get<double>();
      const nlohmann::json& tilt = s.at("upper_body_tilt_deg");
      r.tilt_rms_deg = std::hypot(tilt.at("rms_x").get<double>(), tilt.at("rms_y").get<double>());
      r.error = !std::isfinite(r.tilt_rms_deg) || !std::isfinite(r.fall_time_s);
    } catch (const std::exception&) {
      r.error = true;  // counted as a fall at the start, the worst score
    }
    return r;
  });
  Evaluation e;
  e.runs = spec.runs;
  double scores = 0.0, tilt = 0.0;
  for (const RunOutcome& r : outcomes) {
    scores += run_score(r, duration);
    e.errors += r.error;
    e.falls += r.fell || r.error;
    if (!r.fell && !r.error) tilt += r.tilt_rms_deg;
  }
  e.objective = (static_cast<double>(e.falls) + scores / static_cast<double>(e.runs)) / static_cast<double>(e.runs);
  e.tilt_rms_deg = e.falls < e.runs ? tilt / static_cast<double>(e.runs - e.falls) : 0.0;
  e.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return e;
}

// The search: every candidate CMA-ES asks for, evaluated on the training runs and recorded.
class Tuner {
 public:
  Tuner(const TuningOptions& options, CampaignSpec training, std::vector<SearchRange> parameters,
        std::vector<std::string> start_assignments, double duration, long planned_candidates, int population,
        std::function<void(const nlohmann::json&)> on_candidate)
      : options_(options),
        training_(std::move(training)),
        parameters_(std::move(parameters)),
        start_assignments_(std::move(start_assignments)),
        duration_(duration),
        planned_candidates_(planned_candidates),
        population_(population),
        on_candidate_(std::move(on_candidate)),
        started_(std::chrono::steady_clock::now()) {}

  std::size_t dimension() const { return parameters_.size(); }
  const std::vector<SearchRange>& parameters() const { return parameters_; }
  const nlohmann::json& candidates() const { return candidates_; }
  long new_runs() const { return new_runs_; }

  // The evaluations of an earlier session of the same tuning (its tune.json's candidates): CMA-ES
  // asks for the same candidates again, and only those not in it are simulated.
  void resume_from(const nlohmann::json& earlier) {
    for (const nlohmann::json& c : earlier) {
      std::string key;
      for (const SearchRange& p : parameters_) key += exact_number(c.at("values").at(p.row.key).get<double>()) + "\n";
      Evaluation e;
      e.runs = c.at("runs").get<long>();
      e.falls = c.at("falls").get<long>();
      e.errors = c.at("errors").get<long>();
      e.objective = c.at("objective").get<double>();
      e.tilt_rms_deg = c.at("tilt_rms_deg").get<double>();
      e.wall_time_s = c.at("wall_time_s").get<double>();
      if (!c.at("repeated").get<bool>()) cache_[key] = e;
    }
  }

  // The starting gains exactly as given (robot file, --from), not rounded.
  double evaluate_start() {
    std::vector<std::string> texts;
    for (const SearchRange& p : parameters_) texts.push_back(exact_number(p.start));
    return record(start_assignments_, texts, true);
  }

  // A candidate from CMA-ES's unit box, its values rounded to kSignificantDigits.
  double objective(const std::vector<double>& u) {
    std::vector<std::string> assignments = start_assignments_, texts;
    for (std::size_t k = 0; k < parameters_.size(); ++k) {
      char text[32];
      std::snprintf(text, sizeof text, "%.*g", kSignificantDigits, parameters_[k].value(u[k]));
      texts.push_back(exact_number(std::strtod(text, nullptr)));  // 1140, not 1.14e+03
      assignments.push_back(std::string(parameters_[k].row.key) + "=" + texts.back());
    }
    return record(assignments, texts, false);
  }

  std::vector<double> start_point() const {
    std::vector<double> u;
    for (const SearchRange& p : parameters_) u.push_back(std::clamp(p.share(p.start), 0.0, 1.0));
    return u;
  }

  // The assignments of candidate `index` (tuned keys and the --from file's), and its values as run.
  const std::vector<std::string>& assignments_of(long index) const { return assignments_.at(static_cast<std::size_t>(index)); }
  const std::vector<std::string>& values_of(long index) const { return texts_.at(static_cast<std::size_t>(index)); }

 private:
  double record(const std::vector<std::string>& assignments, const std::vector<std::string>& texts, bool start) {
    // The same values give the same runs, whether written as the start or as a candidate.
    std::string key;
    for (const std::string& text : texts) key += text + "\n";
    const bool repeated = !seen_.insert(key).second;
    const auto cached = cache_.find(key);
    const bool earlier = !repeated && cached != cache_.end();
    const Evaluation e = cached != cache_.end() ? cached->second : evaluate(training_, assignments, duration_, options_.jobs);
    cache_[key] = e;
    if (!repeated) new_runs_ += e.runs;
    const long index = static_cast<long>(candidates_.size());
    const long generation = start ? 0 : 1 + (index - 1) / population_;
    nlohmann::json values = nlohmann::json::object();
    for (std::size_t k = 0; k < parameters_.size(); ++k) values[parameters_[k].row.key] = std::stod(texts[k]);
    candidates_.push_back({{"candidate", index}, {"generation", generation}, {"objective", e.objective},
                           {"falls", e.falls}, {"runs", e.runs}, {"errors", e.errors},
                           {"tilt_rms_deg", e.tilt_rms_deg}, {"repeated", repeated},
                           {"wall_time_s", repeated ? 0.0 : e.wall_time_s}, {"values", values}});
    assignments_.push_back(assignments);
    texts_.push_back(texts);
    if (start || e.objective < best_) best_ = e.objective;
    if (options_.progress) {
      const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
      const double eta = elapsed / static_cast<double>(index + 1) * static_cast<double>(planned_candidates_ - index - 1);
      *options_.progress << "tune " << options_.robot << ": candidate " << index + 1 << "/" << planned_candidates_
                         << " (generation " << generation << "): " << e.falls << "/" << e.runs << " falls, J "
                         << format("%.4f", e.objective) << " (best " << format("%.4f", best_) << ")"
                         << (repeated ? ", repeated" : earlier ? ", from the earlier session" : format(", %.1f s", e.wall_time_s))
                         << "; ETA "
                         << format("%.0f", std::max(0.0, eta)) << " s\n"
                         << std::flush;
    }
    on_candidate_(candidates_);
    return e.objective;
  }

  const TuningOptions& options_;
  CampaignSpec training_;
  std::vector<SearchRange> parameters_;
  std::vector<std::string> start_assignments_;
  double duration_;
  long planned_candidates_;
  long population_;
  std::function<void(const nlohmann::json&)> on_candidate_;
  std::chrono::steady_clock::time_point started_;
  std::map<std::string, Evaluation> cache_;
  std::set<std::string> seen_;  // the values of this tuning's candidates so far
  nlohmann::json candidates_ = nlohmann::json::array();
  std::vector<std::vector<std::string>> assignments_, texts_;
  long new_runs_ = 0;
  double best_ = 0.0;
};

// pagmo's user-defined problem: minimize J over the unit box.
class TrainingProblem {
 public:
  TrainingProblem() = default;
  explicit TrainingProblem(Tuner* tuner) : tuner_(tuner) {}
  pagmo::vector_double fitness(const pagmo::vector_double& u) const { return {tuner_->objective(u)}; }
  std::pair<pagmo::vector_double, pagmo::vector_double> get_bounds() const {
    const std::size_t n = tuner_ ? tuner_->dimension() : 1;
    return {pagmo::vector_double(n, 0.0), pagmo::vector_double(n, 1.0)};
  }
  std::string get_name() const { return "biped training campaign"; }

 private:
  Tuner* tuner_ = nullptr;
};

std::vector<std::string> with_prefix(const std::string& prefix, const std::vector<std::string>& assignments) {
  std::vector<std::string> out;
  for (const std::string& a : assignments) out.push_back(prefix + a);
  return out;
}

// The per-run scenario seeds (`seeds: per_run`) of a campaign.
std::set<std::string> scenario_seeds(const CampaignSpec& spec) {
  std::set<std::string> seeds;
  for (long i = 0; i < spec.runs; ++i) {
    for (const std::string& a : campaign_run(spec, i).assignments) {
      if (a.rfind("seed=", 0) == 0) seeds.insert(a);
    }
  }
  return seeds;
}

nlohmann::json heldout_summary(const nlohmann::json& summary, const std::string& dir) {
  return {{"dir", dir}, {"runs", summary.at("runs")}, {"completed", summary.at("completed")},
          {"errors", summary.at("errors")}, {"falls", summary.at("falls")},
          {"survival_rate", summary.at("survival_rate")}, {"survival_rate_95ci", summary.at("survival_rate_95ci")}};
}

// The same held-out runs with two gain sets: the runs only one of them fell in, and the exact
// two-sided McNemar test of "they fall equally often" (binomial on those discordant runs).
nlohmann::json paired_comparison(const std::string& start_db, const std::string& tuned_db) {
  std::map<long, bool> start_fell;
  for (const CampaignRow& row : CampaignDatabase(start_db).rows()) {
    if (row.status == "ok") start_fell[row.run] = row.result.at("fell").get<bool>();
  }
  long both_up = 0, both_fell = 0, only_start = 0, only_tuned = 0;
  for (const CampaignRow& row : CampaignDatabase(tuned_db).rows()) {
    const auto start = start_fell.find(row.run);
    if (row.status != "ok" || start == start_fell.end()) continue;
    const bool tuned = row.result.at("fell").get<bool>();
    (start->second ? (tuned ? both_fell : only_start) : (tuned ? only_tuned : both_up)) += 1;
  }
  const long n = only_start + only_tuned, k = std::min(only_start, only_tuned);
  double tail = 0.0;
  for (long i = 0; i <= k; ++i) {
    tail += std::exp(std::lgamma(n + 1.0) - std::lgamma(i + 1.0) - std::lgamma(n - i + 1.0) - n * std::log(2.0));
  }
  return {{"both_up", both_up}, {"both_fell", both_fell}, {"only_start_fell", only_start},
          {"only_tuned_fell", only_tuned}, {"mcnemar_p", std::min(1.0, 2.0 * tail)}};
}

// A path under the data directory relative to it (config/campaigns/lola-tune.yaml), else as given.
std::string display_path(const std::string& path) {
  const fs::path relative = fs::path(path).lexically_proximate(data_directory());
  return relative.empty() || *relative.begin() == ".." ? path : relative.string();
}

std::string survival_text(const nlohmann::json& h) {
  if (h.at("survival_rate").is_null()) return "no completed run";
  return format("%.1f %% (95 %% interval %.1f-%.1f %%)", 100.0 * h["survival_rate"].get<double>(),
                100.0 * h["survival_rate_95ci"][0].get<double>(), 100.0 * h["survival_rate_95ci"][1].get<double>()) +
         ", " + std::to_string(h["falls"].get<long>()) + " falls of " + std::to_string(h["completed"].get<long>());
}

}  // namespace

const std::vector<TunedParameter>& tuned_parameters() { return kTunedParameters; }

double SearchRange::value(double u) const {
  u = std::clamp(u, 0.0, 1.0);
  return row.logarithmic ? std::exp(std::log(lower) + u * (std::log(upper) - std::log(lower)))
                         : lower + u * (upper - lower);
}

double SearchRange::share(double v) const {
  if (upper <= lower) return 0.5;
  return row.logarithmic ? (std::log(v) - std::log(lower)) / (std::log(upper) - std::log(lower))
                         : (v - lower) / (upper - lower);
}

std::vector<SearchRange> search_ranges(const std::vector<TunedParameter>& rows, const RunConfig& reference,
                                       const RunConfig& start) {
  std::vector<SearchRange> ranges;
  for (const TunedParameter& row : rows) {
    if (row.applies && !row.applies(reference)) continue;
    SearchRange p{row, row.value(reference), row.value(start)};
    if (!(p.reference > 0.0)) continue;  // no relative bounds around 0
    p.lower = std::min(row.lower * p.reference, p.start);
    p.upper = std::max(row.upper * p.reference, p.start);
    if (row.logarithmic && !(p.lower > 0.0)) p.lower = row.lower * p.reference;  // a start of 0 on a log scale
    ranges.push_back(p);
  }
  return ranges;
}

int tuning_population(std::size_t parameters) {
  return std::max(5, 4 + static_cast<int>(std::floor(3.0 * std::log(static_cast<double>(std::max<std::size_t>(1, parameters))))));
}

nlohmann::json run_gain_tuning(const TuningOptions& options, const std::string& out_dir) {
  const auto started = std::chrono::steady_clock::now();
  const std::vector<std::string> robots = known_robots();
  if (std::find(robots.begin(), robots.end(), options.robot) == robots.end()) {
    std::string list;
    for (const std::string& name : robots) list += (list.empty() ? "" : ", ") + name;
    throw InputError("biped tune: --robot: unknown robot '" + options.robot + "' (known: " + list + ")");
  }
  if (options.budget < 1) {
    throw InputError("biped tune: --budget: must be at least 1 simulation run (got " + std::to_string(options.budget) + ")");
  }
  if (options.heldout_runs < 0) throw InputError("biped tune: --holdout: must not be negative");
  const std::string campaign_file =
      !options.campaign.empty()
          ? options.campaign
          : (fs::path(data_directory()) / "config" / "campaigns" / (options.robot + "-tune.yaml")).string();
  if (!fs::is_regular_file(campaign_file)) {
    throw InputError(options.campaign.empty() ? "biped tune: --campaign: robot '" + options.robot +
                                                    "' has no training campaign " + campaign_file + " (give --campaign FILE)"
                                              : "biped tune: --campaign: no such file '" + campaign_file + "'");
  }

  // The training campaign as the file gives it, with the training seed.
  std::vector<std::string> seed_override;
  if (options.seed) seed_override.push_back("seed=" + std::to_string(*options.seed));
  const CampaignSpec base = load_campaign_spec(campaign_file, seed_override);
  if (base.scenario.empty() || !base.cases.empty()) {
    throw InputError(campaign_file + ": key 'cases': a training campaign has one base scenario and no cases");
  }
  if (!base.seed_per_run) {
    throw InputError(campaign_file + ": key 'seeds': a training campaign needs per_run seeds (held-out runs need others)");
  }
  const Scenario reference_scenario = load_scenario(base.scenario, base.fixed);
  const RunConfig reference = make_run_config(reference_scenario);
  if (reference.robot != options.robot) {
    throw InputError(campaign_file + ": key 'scenario': its robot is '" + reference.robot + "', not '" +
                     options.robot + "'");
  }
  const std::uint64_t training_seed = base.seed;

  // The starting gains: the robot file's, or a gain file's over them.
  RunConfig start_config = reference;
  std::vector<std::string> start_assignments;
  if (!options.from.empty()) {
    if (!fs::is_regular_file(options.from)) throw InputError("biped tune: --from: no such file '" + options.from + "'");
    start_assignments = read_gain_file(options.from, reference);
    apply_include_file(options.from, start_config);
  }

  const std::vector<SearchRange> parameters = search_ranges(options.parameters, reference, start_config);
  for (const SearchRange& p : parameters) {
    for (const auto& [key, distribution] : base.vary) {
      if (p.row.key == key) {
        throw InputError(campaign_file + ": key 'vary." + key + "': the campaign varies a parameter that tune tunes");
      }
    }
  }
  if (parameters.empty()) throw InputError("biped tune: no parameter to tune for robot '" + options.robot + "'");

  const long runs_per_candidate = base.runs;
  const int population = tuning_population(parameters.size());
  const long generations = (options.budget - runs_per_candidate) / (population * runs_per_candidate);
  if (generations < 1) {
    throw InputError("biped tune: --budget: " + std::to_string(options.budget) +
                     " runs are less than the start and one generation: at least " +
                     std::to_string(runs_per_candidate * (1 + population)) + " (" + std::to_string(runs_per_candidate) +
                     " training runs per candidate, " + std::to_string(population) + " candidates per generation)");
  }

  std::vector<std::string> from_overrides = with_prefix("set.", start_assignments);
  const CampaignSpec training = [&] {
    std::vector<std::string> overrides = seed_override;
    overrides.insert(overrides.end(), from_overrides.begin(), from_overrides.end());
    return load_campaign_spec(campaign_file, overrides);
  }();
  const std::uint64_t heldout_seed = training_seed + 1;
  std::vector<std::string> heldout_overrides = {"seed=" + std::to_string(heldout_seed),
                                                "runs=" + std::to_string(std::max<long>(1, options.heldout_runs))};
  if (options.heldout_runs > 0) {
    const CampaignSpec heldout = load_campaign_spec(campaign_file, heldout_overrides);
    const std::set<std::string> a = scenario_seeds(training), b = scenario_seeds(heldout);
    for (const std::string& seed : b) {
      if (a.count(seed)) {
        throw InputError("biped tune: --seed: training and held-out runs share the scenario " + seed +
                         "; choose another seed");
      }
    }
  }

  prepare_output_directory(out_dir);
  const fs::path dir(out_dir);
  const long planned = 1 + generations * population;
  nlohmann::json result = {
      {"robot", options.robot},
      {"date", today()},
      {"command", options.command},
      {"campaign", campaign_file},
      {"from", options.from},
      {"budget", options.budget},
      {"runs_per_candidate", runs_per_candidate},
      {"population", population},
      {"generations", generations},
      {"planned_candidates", planned},
      {"training_seed", training_seed},
      {"heldout_seed", heldout_seed},
      {"heldout_runs", options.heldout_runs},
      {"sigma0", options.sigma0},
      {"significant_digits", kSignificantDigits},
      {"objective_definition",
       "(falls + mean run score) / runs; run score: fell 0.5 + 0.5 (1 - t_fall / T), up 0.5 theta / (theta + 1 deg), "
       "theta the upper body's tilt RMS"}};
  // What decides a candidate's evaluation: the training runs, the --from file's keys, the tuned keys.
  std::string identity = training.identity + "\nfrom:";
  for (const std::string& a : start_assignments) identity += " " + a;
  identity += "\ntuned:";
  for (const SearchRange& p : parameters) identity += " " + std::string(p.row.key);
  result["identity"] = identity;
  nlohmann::json earlier;
  if (fs::exists(dir / "tune.json")) {
    std::ifstream in(dir / "tune.json");
    const nlohmann::json saved = nlohmann::json::parse(in, nullptr, false);
    if (saved.is_discarded() || !saved.contains("identity") || saved["identity"] != identity) {
      throw InputError((dir / "tune.json").string() +
                       ": holds another tuning (robot, campaign, --from or parameters differ); choose another --out");
    }
    earlier = saved.at("candidates");
  }
  auto save = [&](const nlohmann::json& candidates) {
    nlohmann::json j = result;
    j["candidates"] = candidates;
    AtomicOutputFile file((dir / "tune.json").string());
    file.stream() << j.dump(1) << '\n';
    file.commit();
  };

  // tune.json is saved after every candidate (pagmo asks for one at a time).
  Tuner tuner(options, training, parameters, start_assignments, reference_scenario.duration, planned, population, save);
  if (!earlier.is_null()) tuner.resume_from(earlier);
  const double start_objective = tuner.evaluate_start();

  pagmo::problem problem{TrainingProblem(&tuner)};
  pagmo::population initial(problem, 0u, static_cast<unsigned>(training_seed));
  for (int i = 0; i < population; ++i) initial.push_back(tuner.start_point(), {start_objective});
  // ftol 0: a population that ties (as the start's copies do) does not end the search; xtol below
  // what the rounding to kSignificantDigits resolves.
  pagmo::cmaes cmaes(static_cast<unsigned>(generations), -1, -1, -1, -1, options.sigma0, 0.0, 1e-4, false, true,
                     static_cast<unsigned>(training_seed));
  cmaes.evolve(initial);

  const nlohmann::json& candidates = tuner.candidates();
  long best = 0;
  for (long i = 0; i < static_cast<long>(candidates.size()); ++i) {
    if (candidates[i]["objective"].get<double>() < candidates[best]["objective"].get<double>()) best = i;
  }
  const std::vector<std::string> tuned_assignments = tuner.assignments_of(best);
  nlohmann::json parameter_rows = nlohmann::json::array();
  for (const SearchRange& p : tuner.parameters()) {
    parameter_rows.push_back({{"key", p.row.key}, {"robot_file", p.reference}, {"start", p.start},
                              {"lower", p.lower}, {"upper", p.upper},
                              {"scale", p.row.logarithmic ? "log" : "linear"},
                              {"tuned", candidates[best]["values"][p.row.key]}});
  }
  result["parameters"] = parameter_rows;
  result["training_runs"] = tuner.new_runs();
  result["evaluated_candidates"] = candidates.size();
  result["best_candidate"] = best;
  result["objective"] = {{"start", start_objective}, {"tuned", candidates[best]["objective"]},
                         {"start_falls", candidates[0]["falls"]}, {"tuned_falls", candidates[best]["falls"]}};

  // Held-out: the starting and the tuned gains on the same runs of the next seed.
  if (options.heldout_runs > 0) {
    const MpiSession mpi;
    CampaignEngineOptions engine;
    engine.jobs = options.jobs;
    engine.progress = options.progress;
    auto run_heldout = [&](const std::vector<std::string>& assignments, const std::string& name) {
      std::vector<std::string> overrides = heldout_overrides;
      for (const std::string& a : with_prefix("set.", assignments)) overrides.push_back(a);
      const CampaignSpec spec = load_campaign_spec(campaign_file, overrides);
      engine.label = "tune " + options.robot + " held-out " + name;
      const std::string sub = (dir / ("heldout-" + name)).string();
      return heldout_summary(run_campaign(spec, sub, mpi, engine), sub);
    };
    nlohmann::json heldout;
    heldout["start"] = run_heldout(start_assignments, "start");
    heldout["tuned"] = best == 0 ? heldout["start"] : run_heldout(tuned_assignments, "tuned");
    heldout["paired"] = paired_comparison(heldout["start"]["dir"].get<std::string>() + "/campaign.sqlite",
                                          heldout["tuned"]["dir"].get<std::string>() + "/campaign.sqlite");
    result["heldout"] = heldout;
  }
  result["wall_time_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  save(candidates);
  result["candidates"] = candidates;

  // The gain file: the tuned keys only (a --from file's other keys stay in that file).
  std::vector<std::string> gains;
  for (std::size_t k = 0; k < tuner.parameters().size(); ++k) {
    gains.push_back(std::string(tuner.parameters()[k].row.key) + "=" + tuner.values_of(best)[k]);
  }
  std::vector<std::string> header = {
      "Gains of " + options.robot + " tuned by `biped tune` (CMA-ES), " + result["date"].get<std::string>(),
      "command: " + options.command,
      "training: " + display_path(campaign_file) + ", seed " + std::to_string(training_seed) + ", " +
          std::to_string(runs_per_candidate) + " runs per candidate; budget " + std::to_string(options.budget) +
          " runs, " + std::to_string(tuner.new_runs()) + " simulated (" + std::to_string(candidates.size()) +
          " candidates: the start, then " + std::to_string(generations) + " generations of " +
          std::to_string(population) + ")",
      "objective J = (falls + mean run score) / runs: start " + format("%.4f", start_objective) + " (" +
          std::to_string(candidates[0]["falls"].get<long>()) + " of the runs fell), tuned " +
          format("%.4f", candidates[best]["objective"].get<double>()) + " (" +
          std::to_string(candidates[best]["falls"].get<long>()) + ")" +
          (best == 0 ? ": no candidate beat the start" : "")};
  if (result.contains("heldout")) {
    header.push_back("held-out (seed " + std::to_string(heldout_seed) + ", " + std::to_string(options.heldout_runs) +
                     " runs): start survival " + survival_text(result["heldout"]["start"]));
    header.push_back("                                tuned survival " + survival_text(result["heldout"]["tuned"]));
    const nlohmann::json& paired = result["heldout"]["paired"];
    header.push_back("paired: " + std::to_string(paired["only_start_fell"].get<long>()) + " runs only the start fell in, " +
                     std::to_string(paired["only_tuned_fell"].get<long>()) + " only the tuned; exact McNemar p = " +
                     format("%.3g", paired["mcnemar_p"].get<double>()));
  }
  header.push_back("A robot file includes it with `include: PATH` (relative to the robot file); docs/tuning.md.");
  write_gain_file((dir / "gains.yaml").string(), header, gains);
  return result;
}

}  // namespace biped
