#include "sim/closed_loop.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace biped {

RunResult run_closed_loop(Simulation& sim, Controller& controller, const std::vector<TimedCommand>& commands,
                          const RunOptions& options, RunObserver* observer) {
  using Clock = std::chrono::steady_clock;
  SensorData sensors(sim.num_controller_joints());
  JointCommand setpoints(sim.num_controller_joints());
  RunResult result;
  const double period = sim.plant().mj()->opt.timestep * sim.physics_steps_per_control_period();
  const long cycles = std::lround(options.duration / period);
  const long log_every = std::max(1L, std::lround(options.log_period / period));
  result.cycle_us.reserve(static_cast<std::size_t>(cycles));

  sim.reset();
  sim.read_sensors(sensors);
  controller.reset(sensors);
  std::size_t next_command = 0;
  WalkCommand command;

  const auto wall_start = Clock::now();
  for (long cycle = 0; cycle < cycles; ++cycle) {
    const double t = sim.time();
    if (observer) observer->cycle_start(sim);
    while (next_command < commands.size() && commands[next_command].t <= t + 1e-9) {
      command = commands[next_command++].command;
    }
    const auto step_start = Clock::now();
    controller.step(sensors, command, setpoints);
    const double cycle_us = std::chrono::duration<double, std::micro>(Clock::now() - step_start).count();
    result.cycle_us.push_back(cycle_us);
    if (observer && cycle % log_every == 0) observer->record(sim, sensors, setpoints, controller.status(), cycle_us);
    sim.command(setpoints);
    sim.advance();
    if (sim.fall_reason() && sim.time() >= sim.fall_time() + options.run_on_after_fall) break;
    sim.read_sensors(sensors);
  }
  result.wall_time = std::chrono::duration<double>(Clock::now() - wall_start).count();
  result.sim_time = sim.time();
  result.fell = sim.fall_reason() != nullptr;
  result.fall_time = sim.fall_time();
  result.fall_reason = result.fell ? sim.fall_reason() : "";
  return result;
}

}  // namespace biped
