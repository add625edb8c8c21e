#pragma once
// The step-table file (config/tables/NAME.csv): the off-line tables of Fig. 3 as CSV, header
// `speed,step_time,double_support_ratio,clearance,zmp_margin_m`, one row per speed.
#include <iosfwd>
#include <string>

#include "planning/step_table.hpp"

namespace biped {

void write_step_table(const StepTable& table, std::ostream& out);
// Throws InputError naming the file and line for a malformed file.
StepTable read_step_table(const std::string& path);

}  // namespace biped
