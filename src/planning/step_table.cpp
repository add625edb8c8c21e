#include "planning/step_table.hpp"

#include <algorithm>
#include <cmath>

namespace biped {

StepParameters StepTable::lookup(double speed, const StepParameters& base) const {
  StepParameters p = base;
  if (rows.empty()) return p;
  const double v = std::abs(speed);
  const StepTableRow* lo = &rows.front();
  const StepTableRow* hi = &rows.back();
  for (std::size_t i = 0; i + 1 < rows.size(); ++i) {
    if (v >= rows[i].speed && v <= rows[i + 1].speed) {
      lo = &rows[i];
      hi = &rows[i + 1];
      break;
    }
  }
  const double span = hi->speed - lo->speed;
  const double a = span > 0.0 ? std::clamp((v - lo->speed) / span, 0.0, 1.0) : (v > lo->speed ? 1.0 : 0.0);
  p.step_time = lo->step_time + a * (hi->step_time - lo->step_time);
  p.double_support_ratio = lo->double_support_ratio + a * (hi->double_support_ratio - lo->double_support_ratio);
  p.clearance = lo->clearance + a * (hi->clearance - lo->clearance);
  p.swing_travel_share = lo->swing_travel_share + a * (hi->swing_travel_share - lo->swing_travel_share);
  return p;
}

double fastest_feasible_speed(const StepTable& table, double min_margin) {
  double fastest = 0.0;
  for (const StepTableRow& r : table.rows) {
    if (r.zmp_margin > min_margin) fastest = std::max(fastest, r.speed);
  }
  return fastest;
}

}  // namespace biped
