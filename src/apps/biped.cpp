// The `biped` command line: run scenarios (and, as the project grows, benchmarks and experiments).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <memory>

#include "apps/allocation_counter.hpp"
#include "io/output_files.hpp"
#include "io/robot_config.hpp"
#include "io/scenario.hpp"
#include "io/step_table_file.hpp"
#include "io/urdf_import.hpp"
#include "io/video_recorder.hpp"
#include "io/yaml_reader.hpp"
#include "io/campaign_spec.hpp"
#include "studies/campaign.hpp"
#include "studies/controller_bench.hpp"
#include "studies/gain_tuning.hpp"
#include "studies/push_map.hpp"
#include "studies/push_test.hpp"
#include "studies/robot_check.hpp"
#include "studies/scenario_runner.hpp"
#include "sim/simulation.hpp"
#include "studies/speed_sweep.hpp"
#include "studies/step_table_search.hpp"

namespace {

constexpr int kExitBadInput = 2;
constexpr int kExitInternal = 1;

// CLI11 reads "nan" and "inf" as numbers, and a NaN passes its ranges: every real-valued option
// is checked with this first.
const CLI::Validator kFiniteNumber(
    [](std::string& input) {
      char* end = nullptr;
      const double value = std::strtod(input.c_str(), &end);
      if (end == input.c_str() || *end != '\0' || !std::isfinite(value)) {
        return "must be a finite number (got " + input + ")";
      }
      return std::string();
    },
    "NUMBER");

int run_command(const std::string& scenario_path, const std::string& out_option,
                const std::vector<std::string>& overrides, biped::VideoOptions video, const std::string& video_size) {
  if (!video.path.empty()) {
    if (!video_size.empty()) biped::parse_video_size(video_size, video);
    biped::check_video_options(video);
  }
  const biped::Scenario scenario = biped::load_scenario(scenario_path, overrides);
  const biped::RunConfig config = biped::make_run_config(scenario);
  // By default the latest run's files are out/<scenario>/*, earlier runs' out/<scenario>/previous/<n>/;
  // --out DIR is written as given.
  const bool default_out = out_option.empty();
  const std::string out_dir = default_out ? (std::filesystem::path("out") / scenario.name).string() : out_option;
  const biped::ScenarioResult result = biped::run_scenario(scenario, config, out_dir, nullptr,
                                                           video.path.empty() ? nullptr : &video, default_out);
  const auto& s = result.summary;
  char fall[256] = "no fall";
  if (s["fell"].get<bool>()) {
    std::snprintf(fall, sizeof(fall), "FELL at %.3f s: %s", s["fall_time_s"].get<double>(),
                  s["fall_reason"].get<std::string>().c_str());
  }
  std::printf("%s (%s): %.1f s simulated in %.2f s (%.1fx real time), %s\n", scenario.name.c_str(),
              config.robot.c_str(), s["sim_time_s"].get<double>(), s["wall_time_s"].get<double>(),
              s["realtime_factor"].get<double>(), fall);
  if (s["command_saturated"].get<bool>() && s.contains("command_beyond_limits")) {
    const nlohmann::json& beyond = s["command_beyond_limits"];
    for (auto axis = beyond.begin(); axis != beyond.end(); ++axis) {
      const double limit = (*axis)["limit"].get<double>();
      std::fprintf(stderr, "warning: %s: walk command %s = %g is beyond the limit %g (step table, controller.limits): "
                   "the controller saturated it to %g\n", scenario_path.c_str(), axis.key().c_str(),
                   (*axis)["commanded"].get<double>(), limit, limit);
    }
  }
  std::printf("results: %s/summary.json, %s/log.csv, %s/report.html\n", out_dir.c_str(), out_dir.c_str(),
              out_dir.c_str());
  if (!result.previous_run_dir.empty()) {
    std::printf("the previous run's files: %s/ (the last %d runs are kept)\n", result.previous_run_dir.c_str(),
                biped::kPreviousRunsKept);
  }
  if (s.contains("video")) {
    const auto& v = s["video"];
    std::printf("video: %s (%d frames, %.1f s rendering, %.0f ms a frame)\n", video.path.c_str(),
                v["frames"].get<int>(), v["render_s"].get<double>(),
                1e3 * v["render_s"].get<double>() / std::max(1, v["frames"].get<int>()));
  }
  return 0;
}

int tables_command(const std::string& robot, const std::string& out_option) {
  biped::Scenario scenario;
  scenario.file = "biped tables --robot";
  scenario.robot = robot;
  scenario.duration = 1.0;
  const biped::RunConfig config = biped::make_run_config(scenario, biped::MissingStepTable::UseDefault);
  const biped::RobotModel model = biped::load_controller_model(config);
  const std::string out = out_option.empty()
                              ? (std::filesystem::path(biped::data_directory()) / "config" / "tables" / (config.robot + ".csv")).string()
                              : out_option;
  const std::filesystem::path out_dir = std::filesystem::path(out).parent_path();
  biped::prepare_output_directory(out_dir.empty() ? "." : out_dir.string());
  biped::AtomicOutputFile file(out);
  biped::StepTableSearch search;
  search.relaxed_zmp_window = config.controller.step_table_relaxed_zmp_window;
  search.prefer_short_steps = config.controller.step_table_prefer_short_steps;
  const biped::StepTable table = biped::generate_step_table(model, config.controller.walking, search, &config.sim, &std::cout);
  biped::write_step_table(table, file.stream());
  file.commit();
  std::printf("step table: %s\n", out.c_str());
  return 0;
}

int bench_command(const std::string& robot, const std::string& json_path, double duration) {
  biped::ControllerBenchOptions options;
  options.robot = robot;
  options.duration = duration;
  std::unique_ptr<biped::AtomicOutputFile> file;
  if (!json_path.empty()) {
    const auto dir = std::filesystem::path(json_path).parent_path();
    if (!dir.empty()) biped::prepare_output_directory(dir.string());
    file = std::make_unique<biped::AtomicOutputFile>(json_path);
  }
  nlohmann::json r = biped::run_controller_bench(options, heap_allocations);
  // The counter sees the program's own start-up allocations; if it did not, "0 per cycle" would mean nothing.
  r["allocation_counter_active"] = heap_allocations() > 0;
  auto line = [&](const char* what, const char* key) {
    std::printf("  %-44s median %8.2f us   p99 %8.2f us\n", what, r[key]["median"].get<double>(),
                r[key]["p99"].get<double>());
  };
  std::printf("%s: %ld controller cycles walking at %.1f m/s (stabilizer on)%s\n", r["robot"].get<std::string>().c_str(),
              r["cycles"].get<long>(), options.speed, r["fell"].get<bool>() ? " -- THE ROBOT FELL" : "");
  std::printf("  measured on %s (%d hardware threads), %s\n", r["cpu_model"].get<std::string>().c_str(),
              r["hardware_threads"].get<int>(), r["date"].get<std::string>().c_str());
  line("whole cycle", "cycle_us");
  line("stabilizer (estimation, eqs. 10, 20)", "stabilizer_us");
  line("resolved motion rate control (eq. 21)", "rmrc_us");
  line("eq. (21) with explicit SVD pseudo-inverse", "svd_baseline_us");
  line("one physics step of the same robot", "physics_step_us");
  std::printf("  the whole cycle takes %.2f physics steps (a ratio that holds across machines)\n",
              r["cycle_per_physics_step"].get<double>());
  std::printf("  eq. (21) speed-up over explicit SVD: %.1fx; heap allocations per cycle: %g; real-time factor %.1f\n",
              r["speedup_vs_svd"].get<double>(), r["allocations_per_cycle"].get<double>(),
              r["realtime_factor"].get<double>());
  std::printf("  paper: 393 us (JOHNNIE) and 720 us (LOLA) on a 2.33 GHz T7600, 211 us (LOLA) on a 3.0 GHz E8400\n");
  if (file) {
    file->stream() << r.dump(2) << '\n';
    file->commit();
  }
  return 0;
}

int push_test_command(const std::string& scenario_path, biped::PushTestOptions options,
                      const std::vector<std::string>& overrides) {
  const biped::Scenario scenario = biped::load_scenario(scenario_path, overrides);
  const biped::RunConfig config = biped::make_run_config(scenario);
  options.progress = &std::cerr;
  std::printf("%s\n", biped::run_push_test(scenario, config, options).dump().c_str());
  return 0;
}

int speed_sweep_command(const std::string& scenario_path, const biped::SpeedSweepOptions& options,
                        const std::vector<std::string>& overrides, const std::string& json_path) {
  const biped::Scenario scenario = biped::load_scenario(scenario_path, overrides);
  const biped::RunConfig config = biped::make_run_config(scenario);
  std::unique_ptr<biped::AtomicOutputFile> file;
  if (!json_path.empty()) {
    const auto dir = std::filesystem::path(json_path).parent_path();
    if (!dir.empty()) biped::prepare_output_directory(dir.string());
    file = std::make_unique<biped::AtomicOutputFile>(json_path);
  }
  // Progress on stderr as each speed finishes; on stdout the result, its JSON on the last line.
  const nlohmann::json r = biped::run_speed_sweep(scenario, config, options, &std::cerr);
  std::printf("fastest without a fall: %.2f m/s\n", r["fastest_without_fall_mps"].get<double>());
  std::printf("%s\n", r.dump().c_str());
  if (file) {
    file->stream() << r.dump(2) << '\n';
    file->commit();
  }
  return 0;
}

// Campaigns and push maps run under MPI when an MPI launcher started the program. A failure on one
// rank ends them all (the others would wait for it).
template <class Study>
int distributed_command(Study&& study) {
  const biped::MpiSession mpi;
  try {
    study(mpi);
    return 0;
  } catch (const biped::InputError& e) {
    std::cerr << "error: " << e.what() << '\n';
    if (mpi.size() > 1) mpi.abort(kExitBadInput);
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "internal error: " << e.what() << '\n';
    if (mpi.size() > 1) mpi.abort(kExitInternal);
    return kExitInternal;
  }
}

int campaign_command(const std::string& spec_path, const std::string& out_dir, int jobs,
                     const std::vector<std::string>& overrides) {
  // The file is read and checked before MPI starts: a bad file stops every rank the same way.
  const biped::CampaignSpec spec = biped::load_campaign_spec(spec_path, overrides);
  return distributed_command([&](const biped::MpiSession& mpi) {
    biped::CampaignEngineOptions options;
    options.jobs = jobs;
    options.progress = &std::cerr;
    options.label = spec.name;
    const nlohmann::json s = biped::run_campaign(spec, out_dir, mpi, options);
    if (s.is_null()) return;
    std::printf("%s: %ld runs, %ld completed, %ld errors, %ld falls", spec.name.c_str(), s["runs"].get<long>(),
                s["completed"].get<long>(), s["errors"].get<long>(), s["falls"].get<long>());
    if (!s["survival_rate"].is_null()) {
      std::printf(", survival %.1f %% (95 %% interval %.1f-%.1f %%)", 100.0 * s["survival_rate"].get<double>(),
                  100.0 * s["survival_rate_95ci"][0].get<double>(), 100.0 * s["survival_rate_95ci"][1].get<double>());
    }
    std::printf("; %.1f s on %d rank(s), %d worker(s)\n", s["wall_time_s"].get<double>(), s["ranks"].get<int>(),
                s["workers"].get<int>());
    std::printf("results: %s/campaign.sqlite, %s/results.csv, %s/summary.json, %s/report.html\n", out_dir.c_str(),
                out_dir.c_str(), out_dir.c_str(), out_dir.c_str());
  });
}

int push_map_command(const std::string& scenario_path, const std::string& out_dir, const biped::PushMapOptions& options,
                     int jobs, const std::vector<std::string>& overrides) {
  (void)biped::load_scenario(scenario_path, overrides);  // bad input stops every rank before MPI starts
  return distributed_command([&](const biped::MpiSession& mpi) {
    biped::CampaignEngineOptions engine;
    engine.jobs = jobs;
    engine.progress = &std::cerr;
    engine.label = "push-map";
    const nlohmann::json map = biped::run_push_map(scenario_path, overrides, out_dir, options, mpi, engine);
    if (map.is_null()) return;
    std::printf("push map: %s/push_map.json, %s/report.html (%zu cells)\n", out_dir.c_str(), out_dir.c_str(),
                map["cells"].size());
  });
}

int tune_command(biped::TuningOptions options, const std::string& out_option) {
  if (biped::MpiSession::launched_under_mpi()) {
    throw biped::InputError("biped tune: runs on one machine (--jobs), not under an MPI launcher");
  }
  options.progress = &std::cerr;
  const std::string out_dir = out_option.empty() ? (std::filesystem::path("out") / "tune" / options.robot).string() : out_option;
  const nlohmann::json r = biped::run_gain_tuning(options, out_dir);
  std::printf("%s: %ld candidates (the start, then %ld generations of %d), %ld training runs of %ld per candidate\n",
              options.robot.c_str(), static_cast<long>(r["evaluated_candidates"].get<long>()), r["generations"].get<long>(),
              r["population"].get<int>(), r["training_runs"].get<long>(), r["runs_per_candidate"].get<long>());
  std::printf("  %-46s %10s %10s %10s   %s\n", "parameter", "robot file", "start", "tuned", "bounds");
  for (const auto& p : r["parameters"]) {
    std::printf("  %-46s %10.4g %10.4g %10.4g   %.4g..%.4g (%s)\n", p["key"].get<std::string>().c_str(),
                p["robot_file"].get<double>(), p["start"].get<double>(), p["tuned"].get<double>(), p["lower"].get<double>(),
                p["upper"].get<double>(), p["scale"].get<std::string>().c_str());
  }
  const nlohmann::json& j = r["objective"];
  std::printf("  training objective J: start %.4f (%ld falls), tuned %.4f (%ld falls)\n", j["start"].get<double>(),
              j["start_falls"].get<long>(), j["tuned"].get<double>(), j["tuned_falls"].get<long>());
  if (r.contains("heldout")) {
    for (const char* set : {"start", "tuned"}) {
      const nlohmann::json& h = r["heldout"][set];
      if (h["survival_rate"].is_null()) continue;
      std::printf("  held-out (seed %ld, %ld runs), %s gains: survival %.1f %% (95 %% interval %.1f-%.1f %%), %ld falls\n",
                  r["heldout_seed"].get<long>(), h["runs"].get<long>(), set, 100.0 * h["survival_rate"].get<double>(),
                  100.0 * h["survival_rate_95ci"][0].get<double>(), 100.0 * h["survival_rate_95ci"][1].get<double>(),
                  h["falls"].get<long>());
    }
    const nlohmann::json& p = r["heldout"]["paired"];
    std::printf("  paired: %ld held-out runs only the start fell in, %ld only the tuned; exact McNemar p = %.3g\n",
                p["only_start_fell"].get<long>(), p["only_tuned_fell"].get<long>(), p["mcnemar_p"].get<double>());
  }
  std::printf("results: %s/gains.yaml, %s/tune.json, %s/heldout-start/, %s/heldout-tuned/ (%.0f s)\n", out_dir.c_str(),
              out_dir.c_str(), out_dir.c_str(), out_dir.c_str(), r["wall_time_s"].get<double>());
  return 0;
}

int params_command(bool markdown) {
  const std::vector<biped::ParameterDoc> rows = biped::parameter_reference();
  std::cout << (markdown ? biped::markdown_table(rows) : biped::text_table(rows));
  return 0;
}

std::string join(const std::vector<std::string>& names) {
  std::string list;
  for (const std::string& name : names) list += (list.empty() ? "" : ", ") + name;
  return list;
}

int robot_check_command(const std::string& robot_file, double stand_duration) {
  biped::RobotCheckOptions options;
  options.stand_duration = stand_duration;
  const biped::RobotCheckReport r = biped::check_robot(biped::resolve_robot_file(robot_file), options);
  std::printf("robot file: %s\n", r.robot_file.c_str());
  if (!r.mjcf.empty()) std::printf("model:      %s\n", r.mjcf.c_str());
  if (r.description) {
    const biped::RobotDescription& d = *r.description;
    std::printf("robot:      '%s', %.1f kg; nq %d, nv %d; %d driven joints (%d locked), %d passive\n", d.name.c_str(),
                d.mass, d.nq, d.nv, d.actuated, d.locked, d.passive);
    for (biped::Side side : biped::kSides) {
      const int k = biped::index_of(side);
      std::printf("%-5s leg:  %zu DoF: %s%s%s\n", biped::name_of(side), d.leg_joints[k].size(), join(d.leg_joints[k]).c_str(),
                  d.toe_joints[k].empty() ? "" : "; toe joint ", d.toe_joints[k].c_str());
      std::printf("            foot body %s, F/T site %s; sole %.3f m x %.3f m; hip to ankle %.3f m standing, "
                  "%.3f m stretched\n", d.foot_bodies[k].c_str(), d.ft_sites[k].c_str(), d.sole_length[k],
                  d.sole_width[k], d.leg_length_stand[k], d.leg_length_stretched[k]);
    }
    std::printf("arms:       left %d DoF, right %d DoF\n", d.arm_dof[0], d.arm_dof[1]);
    std::printf("IMU:        site %s in body %s\n", d.imu_site.c_str(), d.upper_body.c_str());
    std::printf("standing:   CoM %.3f m above the soles\n", d.com_height_stand);
  }
  if (r.stand.ran) {
    std::printf("stood %.1f s (standing controller): %s, max tilt %.2f deg, CoM drift %.1f mm, CoM height %.3f m\n",
                r.stand.duration, r.stand.fell ? "FELL" : "no fall", r.stand.max_tilt_deg, 1e3 * r.stand.com_drift,
                r.stand.com_height);
  }
  for (const std::string& line : r.warnings) std::printf("warning: %s\n", line.c_str());
  for (const std::string& line : r.problems) std::cerr << line << '\n';
  if (!r.problems.empty()) {
    std::fprintf(stderr, "robot check: %zu problem(s)\n", r.problems.size());
    return kExitBadInput;
  }
  std::printf("robot check: no problems%s\n", r.warnings.empty() ? "" : ", but see the warnings");
  return 0;
}

int robot_import_command(const std::string& urdf, const std::string& out, const biped::UrdfImportOptions& options) {
  const biped::UrdfImport r = biped::import_urdf(urdf, out, options);
  for (const std::string& note : r.notes) std::fprintf(stderr, "%s\n", note.c_str());
  std::fprintf(stderr, "MJCF: %s\n", out.c_str());
  if (options.robot_file.empty()) {
    std::printf("%s", r.robot_file.c_str());
    return 0;
  }
  biped::AtomicOutputFile file(options.robot_file);
  file.stream() << r.robot_file;
  file.commit();
  std::fprintf(stderr, "robot file: %s (check it: biped robot check %s)\n", options.robot_file.c_str(),
               options.robot_file.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"biped: real-time walking control with hybrid position/force control (LOLA, JOHNNIE, JVRC-1 or a robot file of your own)"};
  app.require_subcommand(1);

  std::string scenario_path, out_dir;
  std::vector<std::string> overrides;
  CLI::App* run = app.add_subcommand("run", "Run one closed-loop simulation of a scenario file");
  run->add_option("scenario", scenario_path, "Scenario file (YAML)")->required();
  run->add_option("--out", out_dir, "Output folder (default: out/<scenario name>)");
  run->add_option("--set", overrides, "Override a scenario key, e.g. --set controller.stabilizer=false")
      ->type_name("KEY=VALUE");
  biped::VideoOptions video;
  std::string video_size;
  run->add_option("--video", video.path, "Also render the run offscreen to this .mp4 (needs ffmpeg)")->type_name("FILE.mp4");
  run->add_option("--video-fps", video.fps, "Video frames per second of simulated time")
      ->capture_default_str()
      ->check(kFiniteNumber);
  run->add_option("--video-size", video_size, "Video size in pixels (default 640x480)")->type_name("WxH");

  std::string robot, table_out;
  CLI::App* tables = app.add_subcommand("tables", "Generate the off-line step table of a robot (config/tables/NAME.csv)");
  tables->add_option("--robot", robot, "Robot name (a file config/robots/NAME.yaml)")->required();
  tables->add_option("--out", table_out, "Output CSV (default: config/tables/<robot>.csv)");

  std::string bench_robot = "lola", bench_json;
  double bench_duration = 10.0;
  CLI::App* bench = app.add_subcommand("bench", "Time the controller cycle on a walking trajectory (and eq. 21 with explicit SVD)");
  bench->add_option("--robot", bench_robot, "Robot name")->capture_default_str();
  bench->add_option("--json", bench_json, "Write the figures as JSON");
  bench->add_option("--duration", bench_duration, "Simulated seconds")->capture_default_str()->check(kFiniteNumber)->check(CLI::Range(1.0, 600.0));

  std::string push_scenario;
  std::vector<std::string> push_overrides;
  biped::PushTestOptions push_options;
  double push_direction_deg = 0.0;
  CLI::App* push = app.add_subcommand("push-test", "Largest 0.1 s push impulse survived, by bisection to 1 N·s");
  push->add_option("scenario", push_scenario, "Scenario file (YAML)")->required();
  CLI::Option* named = push->add_option("--direction", push_options.direction, "forward | backward | left | right");
  CLI::Option* angle =
      push->add_option("--direction-deg", push_direction_deg, "Direction in the robot's heading frame (0 forward, 90 left)")->check(kFiniteNumber);
  named->excludes(angle);
  push->add_option("--phase", push_options.phase, "Share of the single support at the push (0..1)")
      ->capture_default_str()
      ->check(kFiniteNumber)
      ->check(CLI::Range(0.0, 1.0));
  push->add_option("--earliest", push_options.earliest, "Push in the first single support after this time [s]")
      ->capture_default_str()
      ->check(kFiniteNumber)
      ->check(CLI::NonNegativeNumber);
  push->add_option("--set", push_overrides, "Override a scenario key")->type_name("KEY=VALUE");
  double push_at_time = 0.0;
  push->add_option("--at-time", push_at_time, "Push at this time [s] instead of a gait phase (a robot that stands)")
      ->excludes("--phase")
      ->check(kFiniteNumber);

  std::string sweep_scenario, sweep_json;
  std::vector<std::string> sweep_overrides;
  biped::SpeedSweepOptions sweep_options;
  CLI::App* sweep = app.add_subcommand("speed-sweep", "Straight walks at rising speeds: the highest speed without a fall");
  sweep->add_option("scenario", sweep_scenario, "Scenario file (YAML): robot and parameters; its commands are replaced")->required();
  sweep->add_option("--from", sweep_options.from, "First commanded speed [m/s]")->capture_default_str()->check(kFiniteNumber);
  sweep->add_option("--to", sweep_options.to, "Last commanded speed [m/s]")->capture_default_str()->check(kFiniteNumber);
  sweep->add_option("--step", sweep_options.step, "Speed increment [m/s]")->capture_default_str()->check(kFiniteNumber);
  sweep->add_option("--hold", sweep_options.hold, "Seconds walked at each speed")->capture_default_str()->check(kFiniteNumber)->check(CLI::Range(1.0, 600.0));
  sweep->add_option("--json", sweep_json, "Write the results as JSON");
  sweep->add_option("--set", sweep_overrides, "Override a scenario key")->type_name("KEY=VALUE");

  std::string campaign_spec, campaign_out;
  std::vector<std::string> campaign_overrides;
  int campaign_jobs = 0;
  CLI::App* campaign = app.add_subcommand("campaign", "Many variants of a scenario on all cores or MPI ranks, into SQLite (resumable)");
  campaign->add_option("spec", campaign_spec, "Campaign file (YAML, config/campaigns/)")->required();
  campaign->add_option("--out", campaign_out, "Output folder (campaign.sqlite, results.csv, summary.json, report.html)")->required();
  campaign->add_option("--jobs", campaign_jobs, "Worker threads (default: every core; 1 per rank under MPI)")->check(CLI::Range(1, 4096));
  campaign->add_option("--set", campaign_overrides, "Override a campaign key, e.g. --set runs=8")->type_name("KEY=VALUE");

  std::string map_scenario, map_out;
  std::vector<std::string> map_overrides;
  biped::PushMapOptions map_options;
  int map_jobs = 0;
  CLI::App* push_map = app.add_subcommand("push-map", "Largest survivable push per direction and gait phase (a campaign)");
  push_map->add_option("scenario", map_scenario, "Scenario file (YAML)")->required();
  push_map->add_option("--out", map_out, "Output folder (push_map.json, report.html, campaign.sqlite)")->required();
  push_map->add_option("--directions", map_options.directions, "Push directions, evenly spaced")->capture_default_str();
  push_map->add_option("--phases", map_options.phases, "Single-support phases")->capture_default_str();
  push_map->add_option("--earliest", map_options.test.earliest, "Push in the first single support after this time [s] (standing: at it)")
      ->capture_default_str()
      ->check(kFiniteNumber);
  push_map->add_option("--max-impulse", map_options.test.max_impulse, "Largest impulse tried [N·s]")->capture_default_str()->check(kFiniteNumber);
  push_map->add_option("--jobs", map_jobs, "Worker threads (default: every core)")->check(CLI::Range(1, 4096));
  push_map->add_option("--set", map_overrides, "Override a scenario key")->type_name("KEY=VALUE");

  biped::TuningOptions tune_options;
  tune_options.budget = 2448;  // the start and 5 generations of 10 with 48 runs per candidate
  std::string tune_out;
  long tune_seed = 0;
  CLI::App* tune = app.add_subcommand("tune", "Tune the stabilizer's gains by CMA-ES on a training campaign; held-out check; gain file");
  tune->add_option("--robot", tune_options.robot, "Robot name (a file config/robots/NAME.yaml)")->required();
  tune->add_option("--budget", tune_options.budget, "Training simulation runs (candidates x runs per candidate)")->capture_default_str();
  tune->add_option("--out", tune_out, "Output folder (default: out/tune/<robot>)");
  tune->add_option("--seed", tune_seed, "Training seed, also CMA-ES's (default: the campaign file's); held-out: seed + 1")
      ->check(CLI::NonNegativeNumber);
  tune->add_option("--jobs", tune_options.jobs, "Worker threads (default: every core)")->check(CLI::Range(1, 4096));
  tune->add_option("--campaign", tune_options.campaign, "Training campaign (default: config/campaigns/<robot>-tune.yaml)");
  tune->add_option("--from", tune_options.from, "Start from this gain file's controller keys (default: the robot file's)");
  tune->add_option("--holdout", tune_options.heldout_runs, "Held-out runs per gain set (0: none)")->capture_default_str();

  bool params_markdown = false;
  CLI::App* params = app.add_subcommand("params", "List the robot files' parameters: key, default, unit, check, description");
  params->add_flag("--markdown", params_markdown, "As the Markdown table of docs/scenarios.md");

  std::string check_robot_file;
  double check_stand_duration = 3.0;
  CLI::App* robot_app = app.add_subcommand("robot", "Bring a robot in: import a URDF, check a robot file against its MJCF");
  robot_app->require_subcommand(1);
  CLI::App* robot_check = robot_app->add_subcommand(
      "check", "Check a robot file against its MJCF (every problem, one line each), describe the robot, stand it");
  robot_check->add_option("robot", check_robot_file, "Robot file (config/robots/NAME.yaml) or robot name")->required();
  robot_check->add_option("--stand-time", check_stand_duration, "Seconds standing in simulation")
      ->capture_default_str()
      ->check(kFiniteNumber)
      ->check(CLI::Range(0.5, 60.0));

  std::string import_urdf, import_out;
  biped::UrdfImportOptions import_options;
  CLI::App* robot_import = robot_app->add_subcommand(
      "import", "Turn a URDF into MJCF (free joint, motors, IMU and F/T sites added) and guess the robot file");
  robot_import->add_option("urdf", import_urdf, "URDF file")->required();
  robot_import->add_option("--out", import_out, "MJCF file to write")->required();
  robot_import->add_option("--meshdir", import_options.meshdir, "Folder of the mesh files (default: as the URDF says)");
  robot_import->add_option("--robot-file", import_options.robot_file,
                           "Write the guessed robot file there (default: print it)");

  // A mistyped command: CLI11 alone would only say that a subcommand is required.
  std::string known;
  bool is_known = false;
  for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
    known += (known.empty() ? "" : ", ") + sub->get_name();
    is_known = is_known || (argc > 1 && sub->check_name(argv[1]));
  }
  if (argc > 1 && argv[1][0] != '-' && !is_known) {
    std::cerr << "error: unknown command '" << argv[1] << "' (commands: " << known << "; see biped --help)\n";
    return kExitBadInput;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help
    std::cerr << "error: " << e.what() << " (biped --help)\n";
    return kExitBadInput;
  }

  try {
    if (*run) return run_command(scenario_path, out_dir, overrides, video, video_size);
    if (*tables) return tables_command(robot, table_out);
    if (*bench) return bench_command(bench_robot, bench_json, bench_duration);
    if (*push) {
      if (push->count("--direction-deg") > 0) push_options.direction_deg = push_direction_deg;
      else if (push->count("--direction") == 0) throw biped::InputError("push-test: give --direction or --direction-deg");
      if (push->count("--at-time") > 0) push_options.at_time = push_at_time;
      return push_test_command(push_scenario, push_options, push_overrides);
    }
    if (*sweep) return speed_sweep_command(sweep_scenario, sweep_options, sweep_overrides, sweep_json);
    if (*params) return params_command(params_markdown);
    if (*robot_check) return robot_check_command(check_robot_file, check_stand_duration);
    if (*robot_import) return robot_import_command(import_urdf, import_out, import_options);
    if (*campaign) return campaign_command(campaign_spec, campaign_out, campaign_jobs, campaign_overrides);
    if (*tune) {
      if (tune->count("--seed") > 0) tune_options.seed = static_cast<std::uint64_t>(tune_seed);
      // As the campaigns' reproduce commands write it: from the repository's root.
      tune_options.command = "build/biped";
      for (int i = 1; i < argc; ++i) tune_options.command += " " + std::string(argv[i]);
      return tune_command(tune_options, tune_out);
    }
    if (*push_map) return push_map_command(map_scenario, map_out, map_options, map_jobs, map_overrides);
  } catch (const biped::InputError& e) {
    std::cerr << "error: " << e.what() << '\n';
    return kExitBadInput;
  } catch (const biped::ModelError& e) {
    std::cerr << "error: " << e.what() << '\n';
    return kExitBadInput;
  } catch (const biped::VideoError& e) {
    std::cerr << "error: " << e.what() << '\n';
    return kExitInternal;
  } catch (const biped::SimulationDiverged& e) {
    std::cerr << "error: " << e.what() << '\n';
    return kExitInternal;
  } catch (const std::exception& e) {
    std::cerr << "internal error: " << e.what() << '\n';
    return kExitInternal;
  }
  return kExitInternal;
}
