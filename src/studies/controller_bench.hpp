#pragma once
// `biped bench`: times the walking controller's cycle in the closed loop on a walking trajectory
// (straight at 0.6 m/s, stabilizer on): the whole cycle, its stabilizer part, its eq. (21) part, and
// the same eq. (21) inputs solved by the explicit-SVD implementation (pseudo-inverse and null-space
// projector formed), in one run.
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

namespace biped {

struct ControllerBenchOptions {
  std::string robot = "lola";
  double duration = 10.0;  // [s] simulated
  double speed = 0.6;      // [m/s]
};

// `allocations` returns the process's heap allocation count so far (the CLI installs a counter);
// the bench reports the allocations during the controller's cycles. Throws InputError for an
// unknown robot.
// Besides DESIGN.md's keys: physics_step_us (one physics step of the same robot: mj_step1, joint
// drives, sole contact, mj_step2), cycle_per_physics_step (the whole cycle's median in those steps: a
// figure that holds across machines, as speedup_vs_svd does), cpu_model, hardware_threads, date.
nlohmann::json run_controller_bench(const ControllerBenchOptions& options, const std::function<long()>& allocations);

// The machine a timing was taken on: the CPU's model name (/proc/cpuinfo; "unknown" elsewhere) and
// the date and time now (UTC, ISO 8601).
std::string cpu_model();
std::string utc_date();

}  // namespace biped
