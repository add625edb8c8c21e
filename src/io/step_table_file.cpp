#include "io/step_table_file.hpp"

#include <cmath>
#include <fstream>
#include <ostream>
#include <sstream>
#include <string>

#include "io/yaml_reader.hpp"

namespace biped {
namespace {

const std::string kHeader = "speed,step_time,double_support_ratio,clearance,swing_travel_share,zmp_margin_m";
// Tables written before the swing travel share column were made with the foot travelling the whole
// swing: their rows read 1.
const std::string kHeaderWithoutShare = "speed,step_time,double_support_ratio,clearance,zmp_margin_m";

}  // namespace

void write_step_table(const StepTable& table, std::ostream& out) {
  out << kHeader << '\n';
  for (const StepTableRow& r : table.rows) {
    out << r.speed << ',' << r.step_time << ',' << r.double_support_ratio << ',' << r.clearance << ','
        << r.swing_travel_share << ',' << r.zmp_margin << '\n';
  }
}

StepTable read_step_table(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open step table");
  std::string line;
  std::getline(in, line);
  if (line != kHeader && line != kHeaderWithoutShare) {
    throw InputError(path + ":1: not a step table (expected the header " + kHeader + ")");
  }
  const bool with_share = line == kHeader;
  StepTable table;
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    std::stringstream row(line);
    StepTableRow r;
    char c1, c2, c3, c4, c5 = ',';
    const bool parsed =
        (row >> r.speed >> c1 >> r.step_time >> c2 >> r.double_support_ratio >> c3 >> r.clearance >> c4) &&
        (!with_share || (row >> r.swing_travel_share >> c5)) && (row >> r.zmp_margin);
    if (!parsed || c1 != ',' || c2 != ',' || c3 != ',' || c4 != ',' || c5 != ',' || !std::isfinite(r.speed) ||
        !(r.step_time > 0.0) || !(r.double_support_ratio > 0.0 && r.double_support_ratio < 0.8) || r.clearance < 0.0 ||
        !(r.swing_travel_share > 0.0 && r.swing_travel_share <= 1.0)) {
      throw InputError(path + ":" + std::to_string(number) + ": malformed step table row '" + line + "'");
    }
    if (!table.rows.empty() && r.speed <= table.rows.back().speed) {
      throw InputError(path + ":" + std::to_string(number) + ": speeds must increase");
    }
    table.rows.push_back(r);
  }
  if (table.rows.empty()) throw InputError(path + ": the step table has no rows");
  return table;
}

}  // namespace biped
