#pragma once
// The closed loop: sensors -> controller -> joint set-points -> physics, in lockstep, with the
// set-points held over each control period (zero-order hold).
#include <vector>

#include "interface/controller.hpp"
#include "sim/simulation.hpp"

namespace biped {

// The joystick timeline: from time t on, this command holds.
struct TimedCommand {
  double t = 0.0;
  WalkCommand command;
};

// Receives the loop's state at the logging rate (record) and, for observers that sample at a
// rate of their own such as a video, at the start of every control cycle (cycle_start).
class RunObserver {
 public:
  virtual ~RunObserver() = default;
  virtual void record(const Simulation& sim, const SensorData& sensors, const JointCommand& setpoints,
                      const ControllerStatus& status, double cycle_us) = 0;
  virtual void cycle_start(const Simulation& /*sim*/) {}
};

struct RunResult {
  double sim_time = 0.0;   // [s] simulated
  double wall_time = 0.0;  // [s] spent in the loop
  bool fell = false;
  double fall_time = 0.0;
  const char* fall_reason = "";
  std::vector<double> cycle_us;  // controller step() duration of every cycle
};

struct RunOptions {
  double duration = 10.0;           // [s]
  double log_period = 0.01;         // [s]
  double run_on_after_fall = 1.0;   // [s] simulated after a fall before the run ends
};

RunResult run_closed_loop(Simulation& sim, Controller& controller, const std::vector<TimedCommand>& commands,
                          const RunOptions& options, RunObserver* observer);

}  // namespace biped
