// The `biped` command line: run scenarios (and, as the project grows, benchmarks and experiments).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>

#include "io/robot_config.hpp"
#include "io/scenario.hpp"
#include "io/scenario_runner.hpp"
#include "io/yaml_reader.hpp"

namespace {

constexpr int kExitBadInput = 2;
constexpr int kExitInternal = 1;

int run_command(const std::string& scenario_path, const std::string& out_option,
                const std::vector<std::string>& overrides) {
  const biped::Scenario scenario = biped::load_scenario(scenario_path, overrides);
  const biped::RunConfig config = biped::make_run_config(scenario);
  const std::string out_dir =
      out_option.empty() ? (std::filesystem::path("out") / scenario.name).string() : out_option;
  const biped::ScenarioResult result = biped::run_scenario(scenario, config, out_dir);
  const auto& s = result.summary;
  std::printf("%s (%s): %.1f s simulated in %.2f s (%.1fx real time), %s\n", scenario.name.c_str(),
              config.robot.c_str(), s["sim_time_s"].get<double>(), s["wall_time_s"].get<double>(),
              s["realtime_factor"].get<double>(),
              s["fell"].get<bool>() ? ("FELL at " + std::to_string(s["fall_time_s"].get<double>()) + " s: " +
                                       s["fall_reason"].get<std::string>())
                                          .c_str()
                                    : "no fall");
  std::printf("results: %s/summary.json, %s/log.csv\n", out_dir.c_str(), out_dir.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"biped: real-time walking control with hybrid position/force control (LOLA, JOHNNIE)"};
  app.require_subcommand(1);

  std::string scenario_path, out_dir;
  std::vector<std::string> overrides;
  CLI::App* run = app.add_subcommand("run", "Run one closed-loop simulation of a scenario file");
  run->add_option("scenario", scenario_path, "Scenario file (YAML)")->required();
  run->add_option("--out", out_dir, "Output folder (default: out/<scenario name>)");
  run->add_option("--set", overrides, "Override a scenario key, e.g. --set controller.stabilizer=false")
      ->type_name("KEY=VALUE");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kExitBadInput;
  }

  try {
    if (*run) return run_command(scenario_path, out_dir, overrides);
  } catch (const biped::InputError& e) {
    std::cerr << "error: " << e.what() << '\n';
    return kExitBadInput;
  } catch (const biped::ModelError& e) {
    std::cerr << "error: " << e.what() << '\n';
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "internal error: " << e.what() << '\n';
    return kExitInternal;
  }
  return kExitInternal;
}
