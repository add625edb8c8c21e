#pragma once
// Campaign files (docs/campaigns.md): a base scenario, a number of runs, a seed, and what varies.
// Every run is a list of `--set KEY=VALUE` assignments on the base scenario, fully determined by
// (campaign file, run index): each varied key and each generator draws from its own random stream,
// seeded by the campaign's seed, the key and the run index, so adding a key changes no other draw.
//
//   vary:         any scenario key by dotted path: {uniform: [lo, hi]} (also vectors: [[..], [..]]),
//                 {normal: {mean, std, min, max}}, {integer: [lo, hi]}, {choice: [a, b, ...]},
//                 {grid: [a, b, ...]} or {grid: {from, to, step}} (grids: the runs cycle through
//                 their product, the first key slowest)
//   cases:        a list of named runs, each with its own scenario, `set` and expected outcome
//   generators:   joystick (random command timelines), and list generators that write a whole list
//                 key from templates whose fields may be distributions: pushes (disturbances),
//                 terrain (terrain), sensor_faults (sensors.faults)
#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace biped {

// One random stream: SplitMix64, with its own uniform and normal transforms so that a run draws
// the same numbers with any standard library.
class CampaignRandom {
 public:
  explicit CampaignRandom(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next();
  double uniform();                       // [0, 1)
  double uniform(double lo, double hi);   // [lo, hi]
  long integer(long lo, long hi);         // lo..hi inclusive
  double normal(double mean, double std);  // Box-Muller

 private:
  std::uint64_t state_;
};

// One named run of a list (`cases:`): its own scenario and assignments, and the outcome expected
// (walks, falls, or empty). A regression battery is a list of cases.
struct CampaignCase {
  std::string name;
  std::string scenario;
  std::vector<std::string> set;
  std::string expect;
};

struct CampaignSpec {
  std::string file;           // the campaign file
  std::string name;
  std::string scenario;       // path of the base scenario (as it resolves from the working directory)
  std::vector<CampaignCase> cases;  // when given, run i is case i mod cases (grids advance per round)
  bool seed_per_run = true;   // `seeds: per_run` (default) or `scenario` (each scenario keeps its seed)
  long runs = 0;
  std::uint64_t seed = 1;
  std::vector<std::string> fixed;  // `set:` assignments applied to every run
  std::vector<std::pair<std::string, YAML::Node>> vary;        // key, distribution
  std::vector<std::pair<std::string, YAML::Node>> generators;  // name, its mapping
  long grid_size = 1;
  std::string identity;       // the resolved campaign (after --set) and the base scenario's text
};

// What a run varies: the assignments to apply, and per varied key or generator feature a value
// for the results (numbers where the draw is a number, else its YAML text).
struct CampaignRun {
  long index = 0;
  std::string scenario;       // the base scenario of this run
  std::string case_name;      // with `cases:`
  std::string expect;         // walks | falls | empty
  std::vector<std::string> assignments;  // KEY=VALUE: the case's, the fixed ones, the seed, varied keys, generators
  std::vector<std::string> sources;      // the campaign key each assignment comes from
  std::vector<std::pair<std::string, YAML::Node>> parameters;
};

// Reads and checks a campaign file after applying `--set` overrides to it; every varied key and
// generator is tried on the base scenario. Throws InputError with one line naming the file and key.
CampaignSpec load_campaign_spec(const std::string& path, const std::vector<std::string>& overrides = {});

// The assignments of run `index` (0 <= index < runs).
CampaignRun campaign_run(const CampaignSpec& spec, long index);

// `biped run SCENARIO --set ... ` reproducing a run, quoted for a POSIX shell.
std::string reproduce_command(const std::string& scenario, const std::vector<std::string>& assignments);

// The shortest text that reads back as the same double.
std::string exact_number(double value);

}  // namespace biped
