#pragma once
// `biped tune`: the stabilizer's gains (eqs. 10 and 14), and the terrain and step adaptation's
// parameters, tuned by CMA-ES (pagmo) over a training campaign, and checked on held-out runs.
//
// A candidate gain set is scored on the same training runs every time (the campaign file's runs
// with the training seed: common random numbers, so the objective of a gain set is a number, not a
// draw): J = (falls + mean run score) / runs, where a fallen run scores 0.5 + 0.5 (1 − t_fall/T)
// (falling later is progress) and a run that stays up 0.5 θ/(θ + 1°), θ the RMS of its upper-body
// tilt. A run score is below 1, so one fall fewer always lowers J more than any change of the
// scores. The held-out runs are the same campaign with the next seed (disjoint scenario seeds,
// checked), run for the starting gains and for the tuned ones through the campaign engine.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "io/robot_config.hpp"
#include "studies/campaign_engine.hpp"

namespace biped {

// One tuned parameter: a key of the robot file, searched between factors of the robot file's own
// (hand-tuned) value. A parameter that does not apply to the robot (e.g. step adaptation while it
// is off) or whose robot-file value is 0 (no relative bounds) is left out.
struct TunedParameter {
  const char* key;                           // dotted key of the robot file / scenario
  double (*value)(const RunConfig&);         // where the key's value lives
  double lower, upper;                       // bounds as factors of the robot file's value
  bool logarithmic;                          // searched on a log scale (gains spanning a decade)
  bool (*applies)(const RunConfig&) = nullptr;  // nullptr: always
};

// The parameters `biped tune` tunes (studies/gain_tuning.cpp says why each bound).
const std::vector<TunedParameter>& tuned_parameters();

// A parameter as searched: its bounds in the robot's units, and CMA-ES's unit interval onto them.
struct SearchRange {
  TunedParameter row;
  double reference = 0.0;  // the robot file's value
  double start = 0.0;      // the starting value (robot file or --from)
  double lower = 0.0, upper = 0.0;
  double value(double share) const;  // share 0 → lower, 1 → upper (clamped), log or linear
  double share(double value) const;  // its inverse
};

// The rows of `rows` that apply to the robot, with their bounds: the factors of the reference
// (the robot file's) values, widened to hold the starting values.
std::vector<SearchRange> search_ranges(const std::vector<TunedParameter>& rows, const RunConfig& reference,
                                       const RunConfig& start);

struct TuningOptions {
  std::string robot;
  std::string campaign;          // training campaign file ("": config/campaigns/<robot>-tune.yaml)
  long budget = 0;               // training simulation runs (candidates × the campaign's runs)
  std::optional<std::uint64_t> seed;  // training seed (default: the campaign file's); also CMA-ES's
  long heldout_runs = 200;       // runs of the held-out campaign, per gain set (0: none)
  std::string from;              // gain file to start from ("": the robot file's gains)
  int jobs = 0;                  // worker threads (0: every core)
  std::vector<TunedParameter> parameters = tuned_parameters();
  double sigma0 = 0.3;           // CMA-ES's initial step, as a share of each parameter's range
  std::string command;           // the command line, for the gain file's header
  std::ostream* progress = nullptr;
};

// CMA-ES's population for n parameters: its default 4 + ⌊3 ln n⌋, at least pagmo's 5.
int tuning_population(std::size_t parameters);

// Tunes, writes DIR/gains.yaml (the tuned `controller:` keys under a header), DIR/tune.json (every
// evaluated candidate, the parameters and bounds, the held-out results) and the held-out campaigns
// (DIR/heldout-start/, DIR/heldout-tuned/: campaign.sqlite, summary.json, report.html), and returns
// tune.json's content. Throws InputError for bad input (unknown robot, budget below one
// generation, bad campaign or gain file).
nlohmann::json run_gain_tuning(const TuningOptions& options, const std::string& out_dir);

}  // namespace biped
