// The `biped` command line: run scenarios (and, as the project grows, benchmarks and experiments).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>

#include "io/output_files.hpp"
#include "io/robot_config.hpp"
#include "io/step_tables.hpp"
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

int tables_command(const std::string& robot, const std::string& out_option) {
  biped::Scenario scenario;
  scenario.file = "biped tables --robot";
  scenario.robot = robot;
  scenario.duration = 1.0;
  const biped::RunConfig config = biped::make_run_config(scenario);
  const biped::RobotModel model = biped::load_controller_model(config);
  const std::string out = out_option.empty()
                              ? (std::filesystem::path(biped::data_directory()) / "config" / "tables" / (config.robot + ".csv")).string()
                              : out_option;
  biped::prepare_output_directory(std::filesystem::path(out).parent_path().string());
  biped::AtomicOutputFile file(out);
  const biped::StepTable table =
      biped::generate_step_table(model, config.controller.walking, biped::StepTableSearch{}, &config.sim, &std::cout);
  biped::write_step_table(table, file.stream());
  file.commit();
  std::printf("step table: %s\n", out.c_str());
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

  std::string robot, table_out;
  CLI::App* tables = app.add_subcommand("tables", "Generate the off-line step table of a robot (config/tables/NAME.csv)");
  tables->add_option("--robot", robot, "Robot name (a file config/robots/NAME.yaml)")->required();
  tables->add_option("--out", table_out, "Output CSV (default: config/tables/<robot>.csv)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kExitBadInput;
  }

  try {
    if (*run) return run_command(scenario_path, out_dir, overrides);
    if (*tables) return tables_command(robot, table_out);
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
