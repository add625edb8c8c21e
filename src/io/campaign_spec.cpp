#include "io/campaign_spec.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "io/robot_config.hpp"
#include "io/scenario.hpp"
#include "io/yaml_reader.hpp"
#include "model/robot_model.hpp"

namespace biped {
namespace {

const std::vector<std::string> kDistributions = {"uniform", "normal", "integer", "choice", "grid"};

// List generators: the scenario list key each writes. A new list-valued scenario key needs one row.
const std::vector<std::pair<std::string, std::string>> kListGenerators = {
    {"pushes", "disturbances"}, {"terrain", "terrain"}, {"sensor_faults", "sensors.faults"}};

std::uint64_t mix(std::uint64_t z) {  // SplitMix64's finalizer
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

std::uint64_t fnv1a(const std::string& text) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char c : text) h = (h ^ c) * 0x100000001b3ULL;
  return h;
}

CampaignRandom stream(const CampaignSpec& spec, const std::string& key, long index) {
  return CampaignRandom(mix(mix(spec.seed ^ fnv1a(key)) + static_cast<std::uint64_t>(index)));
}

bool is_distribution(const YAML::Node& node) {
  return node.IsMap() && node.size() == 1 &&
         std::find(kDistributions.begin(), kDistributions.end(), node.begin()->first.Scalar()) != kDistributions.end();
}

std::string kind_of(const YAML::Node& distribution) { return distribution.begin()->first.Scalar(); }

YAML::Node scalar(const std::string& text) { return YAML::Node(text); }

std::string emit_flow(const YAML::Node& node) {
  YAML::Emitter out;
  out.SetMapFormat(YAML::Flow);
  out.SetSeqFormat(YAML::Flow);
  out << node;
  return out.c_str();
}

// Checks one distribution (`where` names it); a grid only where `grid_allowed`.
class DistributionChecker {
 public:
  explicit DistributionChecker(const YamlReader& r) : r_(r) {}

  double number(const YAML::Node& node, const std::string& key) const {
    double v = 0.0;
    if (!node.IsScalar() || !YAML::convert<double>::decode(node, v) || !std::isfinite(v)) {
      r_.fail(node, key, "expected a finite number");
    }
    return v;
  }

  void check(const YAML::Node& d, const std::string& where, bool grid_allowed) const {
    const std::string kind = kind_of(d);
    const YAML::Node a = d[kind];
    const std::string key = where + "." + kind;
    if (kind == "uniform" || kind == "integer") {
      if (!a.IsSequence() || a.size() != 2) r_.fail(a, key, "expected [low, high]");
      if (kind == "uniform" && a[0].IsSequence()) {
        if (!a[1].IsSequence() || a[0].size() != a[1].size() || a[0].size() == 0) {
          r_.fail(a, key, "expected two lists of the same length, [[low...], [high...]]");
        }
        for (std::size_t i = 0; i < a[0].size(); ++i) {
          if (number(a[0][i], key) > number(a[1][i], key)) r_.fail(a, key, "empty range (low > high)");
        }
        return;
      }
      if (kind == "integer") {
        long lo = 0, hi = 0;
        if (!YAML::convert<long>::decode(a[0], lo) || !YAML::convert<long>::decode(a[1], hi)) {
          r_.fail(a, key, "expected two integers");
        }
        if (lo > hi) r_.fail(a, key, "empty range (low > high)");
        return;
      }
      if (number(a[0], key) > number(a[1], key)) r_.fail(a, key, "empty range (low > high)");
    } else if (kind == "normal") {
      if (!a.IsMap()) r_.fail(a, key, "expected {mean, std} (and optionally min, max)");
      r_.expect_keys(a, key, {"mean", "std", "min", "max"});
      const double mean = r_.number(a, key, "mean"), std = r_.number(a, key, "std");
      if (std < 0.0) r_.fail(a["std"], key + ".std", "must not be negative");
      const double lo = r_.number_or(a, key, "min", -INFINITY), hi = r_.number_or(a, key, "max", INFINITY);
      if (lo >= hi) r_.fail(a, key, "empty range (min >= max)");
      // Rejection sampling: the truncation must keep a reasonable share of the distribution.
      const double share = std > 0.0 ? 0.5 * (std::erfc((lo - mean) / (std * M_SQRT2)) -
                                              std::erfc((hi - mean) / (std * M_SQRT2)))
                                     : (mean >= lo && mean <= hi ? 1.0 : 0.0);
      if (share < 1e-3) r_.fail(a, key, "impossible distribution: [min, max] holds almost none of it");
    } else if (kind == "choice" || kind == "grid") {
      if (kind == "grid" && !grid_allowed) r_.fail(a, key, "a grid only as a value of `vary`");
      if (kind == "grid" && a.IsMap()) {
        r_.expect_keys(a, key, {"from", "to", "step"});
        const double from = r_.number(a, key, "from"), to = r_.number(a, key, "to"), step = r_.number(a, key, "step");
        if (!(step > 0.0)) r_.fail(a["step"], key + ".step", "must be positive");
        if (to < from) r_.fail(a, key, "empty range (from > to)");
        if ((to - from) / step > 1e6) r_.fail(a, key, "more than a million points");
        return;
      }
      if (!a.IsSequence() || a.size() == 0) r_.fail(a, key, "expected a non-empty list of values");
    }
  }

  // Templates of list generators: any field may be a distribution.
  void check_template(const YAML::Node& node, const std::string& where) const {
    if (is_distribution(node)) {
      check(node, where, false);
    } else if (node.IsMap()) {
      for (const auto& e : node) check_template(e.second, where + "." + e.first.Scalar());
    } else if (node.IsSequence()) {
      for (std::size_t i = 0; i < node.size(); ++i) check_template(node[i], where + "." + std::to_string(i));
    }
  }

 private:
  const YamlReader& r_;
};

std::vector<YAML::Node> grid_values(const YAML::Node& d) {
  const YAML::Node a = d["grid"];
  std::vector<YAML::Node> values;
  if (a.IsSequence()) {
    for (const auto& v : a) values.push_back(v);
    return values;
  }
  const double from = a["from"].as<double>(), to = a["to"].as<double>(), step = a["step"].as<double>();
  const long n = static_cast<long>(std::floor((to - from) / step + 1e-9)) + 1;
  for (long i = 0; i < n; ++i) {
    // To 12 significant digits: from + i·step carries the sum's rounding error (0.30000000000000004).
    char text[32];
    std::snprintf(text, sizeof text, "%.12g", from + i * step);
    values.push_back(scalar(exact_number(std::stod(text))));
  }
  return values;
}

// A draw from a checked distribution (not a grid).
YAML::Node sample(const YAML::Node& d, CampaignRandom& rng) {
  const std::string kind = kind_of(d);
  const YAML::Node a = d[kind];
  if (kind == "uniform") {
    if (a[0].IsSequence()) {
      YAML::Node out(YAML::NodeType::Sequence);
      for (std::size_t i = 0; i < a[0].size(); ++i) {
        out.push_back(scalar(exact_number(rng.uniform(a[0][i].as<double>(), a[1][i].as<double>()))));
      }
      return out;
    }
    return scalar(exact_number(rng.uniform(a[0].as<double>(), a[1].as<double>())));
  }
  if (kind == "integer") return scalar(std::to_string(rng.integer(a[0].as<long>(), a[1].as<long>())));
  if (kind == "normal") {
    const double mean = a["mean"].as<double>(), std = a["std"].as<double>();
    const double lo = a["min"] ? a["min"].as<double>() : -INFINITY, hi = a["max"] ? a["max"].as<double>() : INFINITY;
    for (;;) {
      const double v = rng.normal(mean, std);
      if (v >= lo && v <= hi) return scalar(exact_number(v));
    }
  }
  // choice
  return YAML::Clone(a[static_cast<std::size_t>(rng.integer(0, static_cast<long>(a.size()) - 1))]);
}

YAML::Node instantiate(const YAML::Node& node, CampaignRandom& rng) {
  if (is_distribution(node)) return sample(node, rng);
  if (node.IsMap()) {
    YAML::Node out(YAML::NodeType::Map);
    for (const auto& e : node) out[e.first.Scalar()] = instantiate(e.second, rng);
    return out;
  }
  if (node.IsSequence()) {
    YAML::Node out(YAML::NodeType::Sequence);
    for (const auto& item : node) out.push_back(instantiate(item, rng));
    return out;
  }
  return YAML::Clone(node);
}

// The numbers of a generated list for the results: its length and, per numeric field (by dotted
// path), the largest absolute value over its items.
void list_features(const YAML::Node& node, const std::string& path, std::map<std::string, double>& largest) {
  if (node.IsMap()) {
    for (const auto& e : node) list_features(e.second, path.empty() ? e.first.Scalar() : path + "." + e.first.Scalar(), largest);
  } else if (node.IsScalar()) {
    double v = 0.0;
    if (YAML::convert<double>::decode(node, v)) largest[path] = std::max(largest.count(path) ? largest[path] : 0.0, std::abs(v));
  }
}

// The numeric fields of a template (numbers or numeric distributions), by dotted path: every run
// reports them, 0 when its list has none.
void template_numeric_paths(const YAML::Node& node, const std::string& path, std::map<std::string, double>& paths) {
  double v = 0.0;
  if (is_distribution(node)) {
    if (kind_of(node) != "choice") paths[path] = 0.0;
  } else if (node.IsMap()) {
    for (const auto& e : node) template_numeric_paths(e.second, path.empty() ? e.first.Scalar() : path + "." + e.first.Scalar(), paths);
  } else if (node.IsScalar() && YAML::convert<double>::decode(node, v)) {
    paths[path] = 0.0;
  }
}

double range_draw(const YAML::Node& g, const char* key, CampaignRandom& rng) {
  const YAML::Node r = g[key];
  if (!r) return 0.0;
  return rng.uniform(r[0].as<double>(), r[1].as<double>());
}

// Random joystick timeline: standing until `start`, then a new (vx, vy, ω) or a stop every
// `interval` seconds, and a stop at `end`.
YAML::Node joystick_timeline(const YAML::Node& g, CampaignRandom& rng, std::vector<std::pair<std::string, YAML::Node>>& features) {
  const double start = g["start"] ? g["start"].as<double>() : 1.0;
  const double end = g["end"].as<double>();
  const double stop_probability = g["stop_probability"] ? g["stop_probability"].as<double>() : 0.0;
  YAML::Node list(YAML::NodeType::Sequence);
  auto command = [&](double t, double vx, double vy, double omega, bool stop) {
    YAML::Node c(YAML::NodeType::Map);
    c["t"] = scalar(exact_number(t));
    if (stop) {
      c["stop"] = scalar("true");
    } else {
      c["vx"] = scalar(exact_number(vx));
      c["vy"] = scalar(exact_number(vy));
      c["omega"] = scalar(exact_number(omega));
    }
    list.push_back(c);
  };
  command(0.0, 0.0, 0.0, 0.0, false);
  double largest_vx = 0.0, largest_vy = 0.0, largest_omega = 0.0;
  long changes = 0, stops = 0;
  for (double t = start; t < end; t += range_draw(g, "interval", rng)) {
    const bool stop = changes > 0 && rng.uniform() < stop_probability;
    const double vx = range_draw(g, "vx", rng), vy = range_draw(g, "vy", rng), omega = range_draw(g, "omega", rng);
    command(t, vx, vy, omega, stop);
    ++changes;
    if (stop) {
      ++stops;
    } else {
      largest_vx = std::max(largest_vx, std::abs(vx));
      largest_vy = std::max(largest_vy, std::abs(vy));
      largest_omega = std::max(largest_omega, std::abs(omega));
    }
  }
  command(end, 0.0, 0.0, 0.0, true);
  features.push_back({"joystick.changes", scalar(std::to_string(changes))});
  features.push_back({"joystick.stops", scalar(std::to_string(stops))});
  features.push_back({"joystick.max_abs_vx", scalar(exact_number(largest_vx))});
  features.push_back({"joystick.max_abs_vy", scalar(exact_number(largest_vy))});
  features.push_back({"joystick.max_abs_omega", scalar(exact_number(largest_omega))});
  return list;
}

void check_range(const YamlReader& r, const DistributionChecker& checker, const YAML::Node& g, const std::string& where,
                 const char* key, bool required, bool positive) {
  const YAML::Node node = g[key];
  if (!node) {
    if (required) r.fail(g, where + "." + key, "missing (required)");
    return;
  }
  if (!node.IsSequence() || node.size() != 2) r.fail(node, where + "." + key, "expected [low, high]");
  const double lo = checker.number(node[0], where + "." + key), hi = checker.number(node[1], where + "." + key);
  if (lo > hi) r.fail(node, where + "." + key, "empty range (low > high)");
  if (positive && !(lo > 0.0)) r.fail(node, where + "." + key, "must be positive");
}

void check_generator(const YamlReader& r, const DistributionChecker& checker, const std::string& name, const YAML::Node& g) {
  const std::string where = "generators." + name;
  if (!g.IsMap()) r.fail(g, where, "expected a mapping of keys to values");
  if (name == "joystick") {
    r.expect_keys(g, where, {"start", "end", "interval", "vx", "vy", "omega", "stop_probability"});
    const double start = r.non_negative_or(g, where, "start", 1.0);
    const double end = r.number(g, where, "end");
    if (end < start) r.fail(g["end"], where + ".end", "must not be before start");
    check_range(r, checker, g, where, "interval", true, true);
    for (const char* key : {"vx", "vy", "omega"}) check_range(r, checker, g, where, key, false, false);
    const double p = r.number_or(g, where, "stop_probability", 0.0);
    if (p < 0.0 || p > 1.0) r.fail(g["stop_probability"], where + ".stop_probability", "must be between 0 and 1");
    return;
  }
  const bool known = std::any_of(kListGenerators.begin(), kListGenerators.end(), [&](const auto& e) { return e.first == name; });
  if (!known) {
    std::string list = "joystick";
    for (const auto& e : kListGenerators) list += ", " + e.first;
    r.fail(g, where, "unknown generator (known: " + list + ")");
  }
  r.expect_keys(g, where, {"count", "items"});
  const YAML::Node count = g["count"];
  if (!count || !count.IsSequence() || count.size() != 2) r.fail(count ? count : g, where + ".count", "expected [fewest, most]");
  long lo = 0, hi = 0;
  if (!YAML::convert<long>::decode(count[0], lo) || !YAML::convert<long>::decode(count[1], hi) || lo < 0) {
    r.fail(count, where + ".count", "expected two non-negative integers");
  }
  if (lo > hi) r.fail(count, where + ".count", "empty range (fewest > most)");
  const YAML::Node items = g["items"];
  if (!items || !items.IsSequence() || items.size() == 0) r.fail(items ? items : g, where + ".items", "expected a non-empty list of templates");
  for (std::size_t i = 0; i < items.size(); ++i) checker.check_template(items[i], where + ".items." + std::to_string(i));
}

// `set:` mappings as dotted assignments: {controller: {stabilizer: false}} sets one key, not the
// whole `controller` section (as `--set set.controller.stabilizer=false` writes it).
void flatten_assignments(const YAML::Node& node, const std::string& prefix, std::vector<std::string>& out) {
  if (!node) return;
  for (const auto& e : node) {
    const std::string key = prefix.empty() ? e.first.Scalar() : prefix + "." + e.first.Scalar();
    if (e.second.IsMap() && e.second.size() > 0) {
      flatten_assignments(e.second, key, out);
    } else {
      out.push_back(key + "=" + emit_flow(e.second));
    }
  }
}

std::string read_text_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string shell_quote(const std::string& word) {
  if (!word.empty() && word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-./=:,+") == std::string::npos) {
    return word;
  }
  std::string quoted = "'";
  for (char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

}  // namespace

std::uint64_t CampaignRandom::next() {
  state_ += 0x9e3779b97f4a7c15ULL;
  return mix(state_);
}

double CampaignRandom::uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

double CampaignRandom::uniform(double lo, double hi) { return lo == hi ? lo : lo + (hi - lo) * uniform(); }

long CampaignRandom::integer(long lo, long hi) {
  const auto span = static_cast<std::uint64_t>(hi - lo) + 1;
  return lo + static_cast<long>(next() % span);
}

double CampaignRandom::normal(double mean, double std) {
  const double u1 = 1.0 - uniform(), u2 = uniform();  // u1 in (0, 1]
  return mean + std * std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
}

std::string exact_number(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

CampaignSpec load_campaign_spec(const std::string& path, const std::vector<std::string>& overrides) {
  YAML::Node root = load_yaml_file(path);
  if (!root.IsMap()) throw InputError(path + ": expected a mapping of keys to values at the top level");
  for (const std::string& assignment : overrides) {
    // Varied keys are dotted scenario keys: `vary.commands.1.vx.uniform=[0, 1]` addresses the
    // entry `commands.1.vx` of `vary`, not nested mappings.
    bool done = false;
    if (assignment.rfind("vary.", 0) == 0 && root["vary"].IsMap()) {
      for (const auto& e : root["vary"]) {
        const std::string key = e.first.Scalar();
        const std::string rest = assignment.substr(5);
        if (rest.rfind(key + ".", 0) == 0 && rest.find('=') > key.size()) {
          YAML::Node entry = root["vary"][key];
          apply_override(entry, rest.substr(key.size() + 1));
          done = true;
          break;
        }
      }
    }
    if (!done) apply_override(root, assignment);
  }
  const YamlReader r(path);
  r.expect_keys(root, "", {"name", "scenario", "runs", "seed", "seeds", "set", "vary", "generators", "cases"});
  const DistributionChecker checker(r);

  CampaignSpec spec;
  spec.file = path;
  spec.name = r.text_or(root, "", "name", std::filesystem::path(path).stem().string());
  auto scenario_path = [&](const YAML::Node& map, const std::string& where) {
    const std::filesystem::path scenario(r.text(map, where, "scenario"));
    const std::string resolved =
        scenario.is_absolute() ? scenario.string()
                               : (std::filesystem::path(path).parent_path() / scenario).lexically_normal().string();
    if (!std::filesystem::is_regular_file(resolved)) {
      r.fail(map["scenario"], YamlReader::join(where, "scenario"),
             "no such file '" + resolved + "' (paths are relative to the campaign file)");
    }
    return resolved;
  };
  const YAML::Node cases = r.sequence(root, "", "cases");
  if (root["scenario"] || cases.size() == 0) spec.scenario = scenario_path(root, "");
  const long seed = r.integer_or(root, "", "seed", 1);
  if (seed < 0) r.fail(root["seed"], "seed", "must not be negative");
  spec.seed = static_cast<std::uint64_t>(seed);
  const std::string seeds = r.text_or(root, "", "seeds", "per_run");
  if (seeds != "per_run" && seeds != "scenario") r.fail(root["seeds"], "seeds", "expected per_run or scenario");
  spec.seed_per_run = seeds == "per_run";

  const YAML::Node fixed = r.mapping(root, "", "set");
  flatten_assignments(fixed, "", spec.fixed);
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const std::string where = "cases." + std::to_string(i);
    const YAML::Node c = cases[i];
    r.expect_keys(c, where, {"name", "scenario", "set", "expect"});
    CampaignCase campaign_case;
    campaign_case.name = r.text(c, where, "name");
    campaign_case.scenario = c["scenario"] ? scenario_path(c, where) : spec.scenario;
    if (campaign_case.scenario.empty()) r.fail(c, where + ".scenario", "missing (no campaign-wide scenario)");
    flatten_assignments(r.mapping(c, where, "set"), "", campaign_case.set);
    const std::string expect = r.text_or(c, where, "expect", "");
    if (!expect.empty() && expect != "walks" && expect != "falls") r.fail(c["expect"], where + ".expect", "expected walks or falls");
    campaign_case.expect = expect;
    spec.cases.push_back(campaign_case);
  }
  const YAML::Node vary = r.mapping(root, "", "vary");
  if (vary) {
    for (const auto& e : vary) {
      const std::string key = e.first.Scalar();
      if (key == "seed") r.fail(e.first, "vary.seed", "each run has its own seed, drawn from the campaign's");
      if (!is_distribution(e.second)) {
        r.fail(e.second, "vary." + key, "expected a distribution: {uniform: [lo, hi]}, {normal: {mean, std}}, "
                                        "{integer: [lo, hi]}, {choice: [...]} or {grid: [...]}");
      }
      checker.check(e.second, "vary." + key, true);
      spec.vary.push_back({key, e.second});
      if (kind_of(e.second) == "grid") spec.grid_size *= static_cast<long>(grid_values(e.second).size());
    }
  }
  const YAML::Node generators = r.mapping(root, "", "generators");
  if (generators) {
    for (const auto& e : generators) {
      check_generator(r, checker, e.first.Scalar(), e.second);
      spec.generators.push_back({e.first.Scalar(), e.second});
    }
  }
  const long cycle = spec.grid_size * std::max<long>(1, static_cast<long>(spec.cases.size()));
  if (root["runs"]) {
    spec.runs = r.integer_or(root, "", "runs", 0);
    if (spec.runs < 1) r.fail(root["runs"], "runs", "must be at least 1");
  } else {
    if (cycle == 1) r.fail(root, "runs", "missing (required unless a grid or cases give the count)");
    spec.runs = cycle;
  }

  // Each assignment of the first run of every case on its scenario alone, then all together: a key
  // the scenario does not know is named here rather than as an error in every run.
  auto try_on_scenario = [&](const std::string& scenario, const std::vector<std::string>& assignments,
                             const std::string& key) {
    const std::vector<std::string> parts = split_dotted_key(key);
    // The node the key names (for its line); reset() rebinds, where `=` would assign into root.
    YAML::Node node;
    node.reset(root);
    for (const std::string& part : parts) {
      if (!node.IsMap() && !node.IsSequence()) break;
      const YAML::Node next = node.IsSequence() ? YAML::Node(node)[std::stoul(part)] : YAML::Node(node)[part];
      if (!next.IsDefined()) break;
      node.reset(next);
    }
    try {
      (void)make_run_config(load_scenario(scenario, assignments));
    } catch (const InputError& e) {
      r.fail(node, key, std::string("not a valid scenario: ") + e.what());
    } catch (const ModelError& e) {
      r.fail(node, key, std::string("not a valid scenario: ") + e.what());
    }
  };
  const long firsts = std::max<long>(1, static_cast<long>(spec.cases.size()));
  for (long i = 0; i < std::min(firsts, spec.runs); ++i) {
    const CampaignRun run = campaign_run(spec, i);
    for (std::size_t k = 0; k < run.assignments.size(); ++k) {
      try_on_scenario(run.scenario, {run.assignments[k]}, run.sources[k]);
    }
    try_on_scenario(run.scenario, run.assignments, spec.cases.empty() ? "(run 0)" : "cases." + std::to_string(i));
  }

  spec.identity = emit_flow(root);
  std::set<std::string> scenarios = {spec.scenario};
  for (const CampaignCase& c : spec.cases) scenarios.insert(c.scenario);
  for (const std::string& scenario : scenarios) {
    if (!scenario.empty()) spec.identity += "\n" + read_text_file(scenario);
  }
  return spec;
}

CampaignRun campaign_run(const CampaignSpec& spec, long index) {
  CampaignRun run;
  run.index = index;
  run.scenario = spec.scenario;
  auto assign = [&](const std::string& assignment, const std::string& source) {
    run.assignments.push_back(assignment);
    run.sources.push_back(source);
  };
  long rest = index;
  if (!spec.cases.empty()) {
    const long k = index % static_cast<long>(spec.cases.size());
    rest = index / static_cast<long>(spec.cases.size());
    const CampaignCase& c = spec.cases[static_cast<std::size_t>(k)];
    run.scenario = c.scenario;
    run.case_name = c.name;
    run.expect = c.expect;
    for (const std::string& a : c.set) assign(a, "cases." + std::to_string(k) + ".set");
    run.parameters.push_back({"case", scalar(c.name)});
  }
  for (const std::string& a : spec.fixed) assign(a, "set");
  if (spec.seed_per_run) {
    CampaignRandom seeds = stream(spec, "seed", index);
    assign("seed=" + std::to_string(seeds.next() >> 33), "seed");
  }
  long grid_rest = rest % spec.grid_size, grid_span = spec.grid_size;
  for (const auto& [key, distribution] : spec.vary) {
    YAML::Node value;
    if (kind_of(distribution) == "grid") {
      const std::vector<YAML::Node> values = grid_values(distribution);
      grid_span /= static_cast<long>(values.size());
      value = YAML::Clone(values[static_cast<std::size_t>(grid_rest / grid_span)]);
      grid_rest %= grid_span;
    } else {
      CampaignRandom rng = stream(spec, "vary." + key, index);
      value = sample(distribution, rng);
    }
    assign(key + "=" + emit_flow(value), "vary." + key);
    run.parameters.push_back({key, value});
  }
  for (const auto& [name, g] : spec.generators) {
    CampaignRandom rng = stream(spec, "generators." + name, index);
    if (name == "joystick") {
      assign("commands=" + emit_flow(joystick_timeline(g, rng, run.parameters)), "generators.joystick");
      continue;
    }
    const auto target = std::find_if(kListGenerators.begin(), kListGenerators.end(), [&](const auto& e) { return e.first == name; });
    const long count = rng.integer(g["count"][0].as<long>(), g["count"][1].as<long>());
    YAML::Node list(YAML::NodeType::Sequence);
    std::map<std::string, double> largest;
    for (const auto& item : g["items"]) template_numeric_paths(item, "", largest);
    for (long i = 0; i < count; ++i) {
      const YAML::Node items = g["items"];
      const YAML::Node item = instantiate(items[static_cast<std::size_t>(rng.integer(0, static_cast<long>(items.size()) - 1))], rng);
      list_features(item, "", largest);
      list.push_back(item);
    }
    assign(target->second + "=" + emit_flow(list), "generators." + name);
    run.parameters.push_back({name + ".count", scalar(std::to_string(count))});
    for (const auto& [field, value] : largest) run.parameters.push_back({name + ".max_abs." + field, scalar(exact_number(value))});
  }
  return run;
}

std::string reproduce_command(const std::string& scenario, const std::vector<std::string>& assignments) {
  std::string command = "build/biped run " + shell_quote(scenario);
  for (const std::string& a : assignments) command += " --set " + shell_quote(a);
  return command;
}

}  // namespace biped
