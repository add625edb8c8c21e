// The whole walking-controller cycle (FSM, pattern, state estimation, eqs. (10), (20), (21)) on a
// recorded closed-loop walk: LOLA and JOHNNIE at 0.6 m/s (JOHNNIE 0.4 m/s), the sensor readings of
// a simulated run replayed in order, so every cycle computes what it computed in the loop.
// Run: biped_benchmarks --benchmark_filter=WalkingController
#include <benchmark/benchmark.h>

#include <vector>

#include "control/walking_controller.hpp"
#include "io/robot_config.hpp"
#include "sim/simulation.hpp"
#include "studies/scenario_runner.hpp"

namespace biped {
namespace {

struct Recording {
  std::vector<SensorData> sensors;
  std::vector<WalkCommand> commands;
};

// The sensor readings of a closed-loop walk, one per control cycle.
Recording record_walk(const RunConfig& config, const RobotModel& model, double speed, double duration) {
  Simulation sim(config.sim, model);
  WalkingController controller(model, config.controller.walking);
  Recording r;
  SensorData sensors(model.num_joints());
  JointCommand out(model.num_joints());
  sim.reset();
  sim.read_sensors(sensors);
  controller.reset(sensors);
  const long cycles = static_cast<long>(duration / config.sim.control_period);
  for (long i = 0; i < cycles; ++i) {
    WalkCommand command;
    command.vx = sim.time() >= 0.5 ? speed : 0.0;
    r.sensors.push_back(sensors);
    r.commands.push_back(command);
    controller.step(sensors, command, out);
    sim.command(out);
    sim.advance();
    sim.read_sensors(sensors);
  }
  return r;
}

void BM_WalkingControllerCycle(benchmark::State& state, const char* robot, double speed) {
  Scenario scenario;
  scenario.file = "benchmark";
  scenario.robot = robot;
  scenario.duration = 1.0;
  const RunConfig config = make_run_config(scenario);
  const RobotModel model = load_controller_model(config);
  const Recording walk = record_walk(config, model, speed, 6.0);
  WalkingController controller(model, config.controller.walking);
  JointCommand out(model.num_joints());
  std::size_t i = walk.sensors.size();
  for (auto _ : state) {
    if (i == walk.sensors.size()) {  // start the walk over (not timed)
      state.PauseTiming();
      controller.reset(walk.sensors.front());
      i = 0;
      state.ResumeTiming();
    }
    controller.step(walk.sensors[i], walk.commands[i], out);
    benchmark::DoNotOptimize(out.position.data());
    ++i;
  }
}

BENCHMARK_CAPTURE(BM_WalkingControllerCycle, lola, "lola", 0.6)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_WalkingControllerCycle, johnnie, "johnnie", 0.4)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace biped
