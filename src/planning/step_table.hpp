#pragma once
// Off-line step tables (Fig. 3): for a grid of commanded forward speeds, the step parameters chosen
// off-line (`biped tables`). The planner interpolates them at run time.
#include <vector>

#include "planning/footstep.hpp"

namespace biped {

struct StepTableRow {
  double speed = 0.0;  // commanded forward speed [m/s]
  double step_time = 0.8;
  double double_support_ratio = 0.2;
  double clearance = 0.04;
  double zmp_margin = 0.0;  // [m] the criterion's value for this choice (for the record)
  double swing_travel_share = 1.0;  // StepParameters::swing_travel_share (1 in a table written before it)
};

struct StepTable {
  std::vector<StepTableRow> rows;  // by increasing speed

  bool empty() const { return rows.empty(); }
  // Step time, double-support share, clearance and swing travel share for |speed|, linearly
  // interpolated between rows and held beyond the ends; the rest of `base` (width, CoM height) is kept.
  StepParameters lookup(double speed, const StepParameters& base) const;
};

// The fastest speed of the table whose choice has a ZMP margin above `min_margin` [m] (0 if none).
double fastest_feasible_speed(const StepTable& table, double min_margin = 0.0);

}  // namespace biped
