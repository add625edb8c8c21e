#include "studies/controller_bench.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <fstream>
#include <thread>

#include "control/resolved_motion_rate_control_svd.hpp"
#include "control/walking_controller.hpp"
#include "io/robot_config.hpp"
#include "sim/simulation.hpp"
#include "studies/scenario_runner.hpp"

namespace biped {
namespace {

nlohmann::json stats(std::vector<double> v) {
  if (v.empty()) return {{"median", 0.0}, {"p99", 0.0}};
  auto at = [&](double p) {
    const std::size_t k = std::min(v.size() - 1, static_cast<std::size_t>(p * (v.size() - 1) + 0.5));
    std::nth_element(v.begin(), v.begin() + static_cast<long>(k), v.end());
    return v[k];
  };
  const double median = at(0.5);
  return {{"median", median}, {"p99", at(0.99)}};
}

}  // namespace

nlohmann::json run_controller_bench(const ControllerBenchOptions& options, const std::function<long()>& allocations) {
  using Clock = std::chrono::steady_clock;
  Scenario scenario;
  scenario.file = "biped bench --robot";
  scenario.robot = options.robot;
  scenario.duration = options.duration;
  const RunConfig config = make_run_config(scenario);
  const RobotModel model = load_controller_model(config);
  WalkingControllerParams params = config.controller.walking;
  params.stabilizer = true;
  WalkingController controller(model, params);
  const TaskSpace space(model);
  ResolvedMotionRateControlSvd svd(model, space, params.rmrc);
  Simulation sim(config.sim, model);

  SensorData sensors(model.num_joints());
  JointCommand out(model.num_joints());
  sim.read_sensors(sensors);
  controller.reset(sensors);
  WalkCommand command;
  const double period = config.sim.control_period;
  const long cycles = std::lround(options.duration / period);  // as the closed loop counts them
  std::vector<double> whole, stabilizer, rmrc, baseline, physics;
  physics.reserve(cycles);
  whole.reserve(cycles);
  stabilizer.reserve(cycles);
  rmrc.reserve(cycles);
  baseline.reserve(cycles);
  long cycle_allocations = 0;
  Eigen::VectorXd q_before(model.mj()->nq);
  double loop_wall = 0.0;
  for (long i = 0; i < cycles; ++i) {
    command.vx = sim.time() >= 1.0 ? options.speed : 0.0;
    q_before = controller.rmrc().qpos_d();
    const long allocations_before = allocations();
    const auto start = Clock::now();
    controller.step(sensors, command, out);
    const auto end = Clock::now();
    cycle_allocations += allocations() - allocations_before;
    whole.push_back(std::chrono::duration<double, std::micro>(end - start).count());
    stabilizer.push_back(controller.timing().stabilizer_us);
    rmrc.push_back(controller.timing().rmrc_us);
    // The same eq. (21) inputs through the explicit-SVD implementation, from the same state.
    svd.reset(q_before);
    const auto svd_start = Clock::now();
    svd.step(controller.task_reference(), controller.task_reference_rate(), controller.heading_frame(),
             controller.task_modification(), controller.task_modification_rate());
    baseline.push_back(std::chrono::duration<double, std::micro>(Clock::now() - svd_start).count());
    const auto sim_start = Clock::now();
    sim.command(out);
    const auto advance_start = Clock::now();
    sim.advance();
    physics.push_back(std::chrono::duration<double, std::micro>(Clock::now() - advance_start).count() /
                      sim.physics_steps_per_control_period());
    sim.read_sensors(sensors);
    loop_wall += std::chrono::duration<double>(Clock::now() - sim_start).count() +
                 std::chrono::duration<double>(end - start).count();
  }
  nlohmann::json j;
  j["robot"] = config.robot;
  j["fell"] = sim.fall_reason() != nullptr;
  j["cycles"] = cycles;
  j["cycle_us"] = stats(whole);
  j["stabilizer_us"] = stats(stabilizer);
  j["rmrc_us"] = stats(rmrc);
  j["svd_baseline_us"] = stats(baseline);
  j["speedup_vs_svd"] = j["svd_baseline_us"]["median"].get<double>() / j["rmrc_us"]["median"].get<double>();
  j["allocations_per_cycle"] = static_cast<double>(cycle_allocations) / static_cast<double>(std::max(1L, cycles));
  j["realtime_factor"] = loop_wall > 0.0 ? sim.time() / loop_wall : 0.0;
  // Machine-independent figures: the cycle against one physics step of the same robot on the same
  // machine, as eq. (21)'s speed-up against explicit SVD is.
  j["physics_step_us"] = stats(physics);
  j["cycle_per_physics_step"] = j["cycle_us"]["median"].get<double>() / j["physics_step_us"]["median"].get<double>();
  j["cpu_model"] = cpu_model();
  j["hardware_threads"] = std::thread::hardware_concurrency();
  j["date"] = utc_date();
  return j;
}

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) == 0) {
      const std::size_t colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(" \t", colon + 1));
    }
  }
  return "unknown";
}

std::string utc_date() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

}  // namespace biped
