#pragma once
// Off-line step tables: the search that generates them (`biped tables --robot NAME`).
//
// For each commanded forward speed of a grid, every candidate (step time, double-support share) is
// walked by the walking controller on its own kinematic loop (no simulation: the planned motion
// itself) and judged by
//   1. kinematic feasibility through eq. (21): no joint held at a software limit, no joint-rate
//      limiting, the CoM tracked within 1 cm;
//   2. the ZMP margin of the full multibody model: the ZMP of the planned motion by inverse dynamics
//      (mj_inverse), its smallest distance to the edge of the support polygon over the gait at the
//      speed, after `settle_steps` (the start from standing to full speed in one step is a different
//      manoeuvre: criterion 3 walks it in closed loop); optionally, for the speeds above the fastest
//      row that passed, again with the ZMP averaged over `relaxed_zmp_window`;
//   3. (when simulation parameters are given) the same gait walked in the full simulation with the
//      stabilizer, turning at `turn_rate`, without a fall: the kinematic criteria alone admitted long
//      steps with short double support that fell in closed loop while turning.
// The feasible candidate with the largest margin is chosen (if none is feasible, the one with the
// largest margin, and the row says so with a negative or zero margin). Speed 0 is standing: its row
// keeps the nominal parameters (used by the stop step). The fastest row with a positive margin
// bounds the commands the planner accepts (faster ones are saturated). Each row is searched with the
// robot file's swing travel share and, where that is below 1, with the foot travelling the whole
// swing; the row keeps the set-down share unless the whole-swing travel has more than
// `margin_tolerance` more margin (or is the only one that passes).
#include <iosfwd>
#include <string>

#include "control/walking_controller.hpp"
#include "planning/step_table.hpp"
#include "sim/simulation.hpp"

namespace biped {

struct StepTableSearch {
  std::vector<double> speeds = {0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0};
  // Fast gaits need short steps: at 1.0 m/s steps of 0.5 s and more stretch LOLA's knee.
  std::vector<double> step_times = {0.4, 0.45, 0.5, 0.55, 0.6, 0.7, 0.8, 0.9, 1.0};
  std::vector<double> double_support_ratios = {0.1, 0.15, 0.2, 0.3};
  int steps = 8;           // steps walked per candidate
  int settle_steps = 2;    // steps after the start that criterion 2 does not judge
  // [s] between adjacent rows (the next faster row with a feasible choice): the gait changes its
  // speed by a row per step or so, and LOLA fell going from 0.9 s steps at 0.4 m/s to 0.55 s at 0.6.
  double max_step_time_change = 0.1;
  // [m] a longer step time within this of the largest margin is preferred (fewer touchdowns, lower
  // joint rates), or a shorter one with `prefer_short_steps` (a foothold sooner after a disturbance).
  double margin_tolerance = 0.005;
  bool prefer_short_steps = false;
  double turn_rate = 0.15;  // [rad/s] of the closed-loop check
  // [s] criterion 2 judges the ZMP averaged over this window (weighted by the normal force); 0: each
  // instant (one cycle).
  double zmp_window = 0.0;
  // [s] speeds above the fastest row that passed, where no candidate passes, are searched again
  // (slowest first, each near the next slower row's step time) with the ZMP averaged over this window;
  // 0: never. The drives realize the set-points only up to their position-loop bandwidth: one period
  // of it is the natural window (20 Hz: 0.05 s). A swing leg stopping short before touchdown throws
  // JVRC-1's instantaneous ZMP at 0.7 m/s 13 cm past the toe for about 10 ms, in a gait that walks
  // in closed loop (docs/walking.md "Off-line step tables").
  double relaxed_zmp_window = 0.0;
  // Threads for the candidates of a speed (0: every core; studies/campaign_engine.hpp's parallel
  // map). The choice is the serial search's whatever the number.
  int jobs = 0;
};

struct CandidateResult {
  bool feasible = false;
  double zmp_margin = 0.0;
};

// Judges one candidate at one speed (criteria above).
CandidateResult evaluate_step_candidate(const RobotModel& model, const WalkingControllerParams& base, double speed,
                                        double step_time, double double_support_ratio, int steps, int settle_steps,
                                        double zmp_window);
// Criterion 3: true when the gait walks `steps` steps in the simulation without a fall.
bool survives_in_simulation(const RobotModel& model, const WalkingControllerParams& base,
                            const SimulationParams& sim, double speed, double turn_rate, double step_time,
                            double double_support_ratio, int steps);

// Builds the table; `sim` (may be null) enables criterion 3; `progress` (may be null) gets one line
// per speed.
StepTable generate_step_table(const RobotModel& model, const WalkingControllerParams& base,
                              const StepTableSearch& search, const SimulationParams* sim, std::ostream* progress);

}  // namespace biped
