#include "io/campaign_report.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "io/output_files.hpp"

namespace biped {
namespace {

std::string html_escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '&': out += "&amp;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string json_text(const nlohmann::json& v) {
  if (v.is_null()) return "";
  if (v.is_string()) return v.get<std::string>();
  if (v.is_boolean()) return v.get<bool>() ? "1" : "0";
  return v.dump();
}

std::string fixed(double v, int digits) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(digits);
  s << v;
  return s.str();
}

bool fell(const CampaignRow& r) { return r.status == "ok" && r.result.value("fell", false); }

std::vector<std::string> parameter_keys(const std::vector<CampaignRow>& rows) {
  std::vector<std::string> keys;
  for (const CampaignRow& r : rows) {
    for (const auto& [key, value] : r.parameters.items()) {
      if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
    }
  }
  return keys;
}

// Survival rate per bin (numbers) or per value (anything else) of one parameter, as an SVG bar chart.
std::string survival_chart(const std::vector<CampaignRow>& rows, const std::string& key) {
  std::vector<std::string> labels;
  std::vector<long> runs, survived;
  bool numeric = true;
  std::set<double> distinct;
  double lo = INFINITY, hi = -INFINITY;
  for (const CampaignRow& r : rows) {
    if (r.status != "ok" || !r.parameters.contains(key)) continue;
    const nlohmann::json& v = r.parameters[key];
    if (!v.is_number()) numeric = false;
    else {
      distinct.insert(v.get<double>());
      lo = std::min(lo, v.get<double>());
      hi = std::max(hi, v.get<double>());
    }
  }
  const bool binned = numeric && distinct.size() > 12;
  const int bins = 10;
  std::map<std::string, std::size_t> slot;
  if (binned) {
    for (int b = 0; b < bins; ++b) {
      labels.push_back(fixed(lo + (hi - lo) * b / bins, 3) + "…");
      runs.push_back(0);
      survived.push_back(0);
    }
  } else if (numeric) {
    for (double d : distinct) {
      slot[nlohmann::json(d).dump()] = labels.size();
      labels.push_back(nlohmann::json(d).dump());
      runs.push_back(0);
      survived.push_back(0);
    }
  }
  for (const CampaignRow& r : rows) {
    if (r.status != "ok" || !r.parameters.contains(key)) continue;
    const nlohmann::json& v = r.parameters[key];
    std::size_t i = 0;
    if (binned) {
      i = static_cast<std::size_t>(std::min(bins - 1, static_cast<int>((v.get<double>() - lo) / (hi - lo) * bins)));
    } else {
      const std::string label = numeric ? nlohmann::json(v.get<double>()).dump() : json_text(v);
      if (!slot.count(label)) {
        if (labels.size() >= 20) continue;
        slot[label] = labels.size();
        labels.push_back(label);
        runs.push_back(0);
        survived.push_back(0);
      }
      i = slot[label];
    }
    ++runs[i];
    if (!fell(r)) ++survived[i];
  }
  const int width = 560, height = 190, left = 40, bottom = 40, top = 10;
  const double bar = static_cast<double>(width - left - 10) / std::max<std::size_t>(1, labels.size());
  std::ostringstream svg;
  svg << "<svg width='" << width << "' height='" << height << "' font-size='10' font-family='sans-serif'>";
  const int plot = height - bottom - top;
  for (int pct : {0, 50, 100}) {
    const double y = top + plot * (1.0 - pct / 100.0);
    svg << "<line x1='" << left << "' x2='" << width - 10 << "' y1='" << y << "' y2='" << y << "' stroke='#ddd'/>"
        << "<text x='" << left - 4 << "' y='" << y + 3 << "' text-anchor='end'>" << pct << "%</text>";
  }
  for (std::size_t i = 0; i < labels.size(); ++i) {
    const double x = left + i * bar;
    if (runs[i] > 0) {
      const double rate = static_cast<double>(survived[i]) / runs[i];
      svg << "<rect x='" << x + 1 << "' y='" << top + plot * (1.0 - rate) << "' width='" << bar - 2 << "' height='"
          << plot * rate << "' fill='" << (rate > 0.95 ? "#4a8" : rate > 0.5 ? "#db4" : "#d54") << "'><title>"
          << html_escape(labels[i]) << ": " << survived[i] << "/" << runs[i] << " survived</title></rect>"
          << "<text x='" << x + bar / 2 << "' y='" << top + plot - 2 << "' text-anchor='middle' fill='#333'>" << runs[i]
          << "</text>";
    }
    std::string label = labels[i].size() > 14 ? labels[i].substr(0, 13) + "…" : labels[i];
    svg << "<text x='" << x + bar / 2 << "' y='" << height - bottom + 12 << "' text-anchor='end' transform='rotate(-30 "
        << x + bar / 2 << " " << height - bottom + 12 << ")'>" << html_escape(label) << "</text>";
  }
  svg << "</svg>";
  return svg.str();
}

const char* kStyle =
    "<style>body{font-family:sans-serif;margin:1.5em;max-width:1100px}table{border-collapse:collapse;font-size:13px}"
    "td,th{border:1px solid #ccc;padding:2px 6px;text-align:left}code{font-size:11px;word-break:break-all}"
    ".chart{display:inline-block;margin:0 1em 1em 0}</style>";

}  // namespace

std::pair<double, double> wilson_interval(long successes, long trials) {
  if (trials <= 0) return {0.0, 1.0};
  const double z = 1.959963984540054, n = static_cast<double>(trials), p = successes / n;
  const double centre = (p + z * z / (2 * n)) / (1 + z * z / n);
  const double half = z / (1 + z * z / n) * std::sqrt(p * (1 - p) / n + z * z / (4 * n * n));
  return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

nlohmann::json campaign_summary(const std::vector<CampaignRow>& rows, long total, const CampaignSession& session) {
  long completed = 0, errors = 0, falls = 0, judged = 0, unexpected = 0;
  double run_time = 0.0;
  std::set<std::string> hosts;
  for (const CampaignRow& r : rows) {
    (r.status == "ok" ? completed : errors) += 1;
    if (fell(r)) ++falls;
    if (r.result.contains("as_expected")) {
      ++judged;
      if (!r.result["as_expected"].get<bool>()) ++unexpected;
    }
    run_time += r.wall_time_s;
    hosts.insert(r.host);
  }
  const auto [lo, hi] = wilson_interval(completed - falls, completed);
  nlohmann::json summary = {{"campaign", session.name},
          {"runs", total},
          {"finished", static_cast<long>(rows.size())},
          {"completed", completed},
          {"errors", errors},
          {"falls", falls},
          {"survival_rate", completed > 0 ? nlohmann::json(static_cast<double>(completed - falls) / completed) : nlohmann::json(nullptr)},
          {"survival_rate_95ci", {lo, hi}},
          {"wall_time_s", session.wall_time_s},
          {"run_time_s", run_time},
          {"finished_before_this_session", session.finished_before},
          {"storing_s_per_run", session.ran > 0 ? session.storing_s / session.ran : 0.0},
          {"ranks", session.ranks},
          {"workers", session.workers},
          {"hosts", hosts}};
  if (judged > 0) summary["unexpected"] = unexpected;  // runs with an expected outcome (cases) that ended otherwise
  return summary;
}

void write_results_csv(const std::vector<CampaignRow>& rows, std::ostream& out) {
  const std::vector<std::string> keys = parameter_keys(rows);
  out << "run,status,error";
  for (const ResultColumn& c : campaign_result_columns()) out << ',' << c.name;
  out << ",wall_time_s,host,rank";
  for (const std::string& k : keys) out << ',' << csv_field(k);
  out << ",command\n";
  for (const CampaignRow& r : rows) {
    out << r.run << ',' << r.status << ',' << csv_field(r.error);
    for (const ResultColumn& c : campaign_result_columns()) {
      const nlohmann::json::json_pointer p(c.pointer);
      out << ',' << csv_field(r.result.contains(p) ? json_text(r.result[p]) : "");
    }
    out << ',' << r.wall_time_s << ',' << csv_field(r.host) << ',' << r.rank;
    for (const std::string& k : keys) out << ',' << csv_field(r.parameters.contains(k) ? json_text(r.parameters[k]) : "");
    out << ',' << csv_field(r.command) << '\n';
  }
}

void write_campaign_report(const std::vector<CampaignRow>& rows, const nlohmann::json& s, std::ostream& out) {
  out << "<!DOCTYPE html><html><head><meta charset='utf-8'><title>campaign " << html_escape(s["campaign"])
      << "</title>" << kStyle << "</head><body>";
  out << "<h1>Campaign " << html_escape(s["campaign"]) << "</h1><p>" << s["finished"] << " of " << s["runs"]
      << " runs finished: " << s["completed"] << " completed, " << s["errors"] << " errors, " << s["falls"] << " falls. ";
  if (s.contains("unexpected")) out << "<b>" << s["unexpected"] << " ended otherwise than expected.</b> ";
  if (!s["survival_rate"].is_null()) {
    out << "Survival " << fixed(100.0 * s["survival_rate"].get<double>(), 1) << " % (95 % interval "
        << fixed(100.0 * s["survival_rate_95ci"][0].get<double>(), 1) << "–"
        << fixed(100.0 * s["survival_rate_95ci"][1].get<double>(), 1) << " %). ";
  }
  out << "Wall time of the last session " << fixed(s["wall_time_s"].get<double>(), 1) << " s on " << s["ranks"]
      << " rank(s), " << s["workers"] << " worker(s); run time in all " << fixed(s["run_time_s"].get<double>(), 1)
      << " s.</p>";
  out << "<h2>Survival per varied parameter</h2><p>Bars: share of completed runs without a fall; the number is the "
         "runs in the bar.</p>";
  for (const std::string& key : parameter_keys(rows)) {
    out << "<div class='chart'><b>" << html_escape(key) << "</b><br>" << survival_chart(rows, key) << "</div>";
  }
  out << "<h2>Failures</h2><table><tr><th>run</th><th>outcome</th><th>reproduce</th></tr>";
  long shown = 0;
  for (const CampaignRow& r : rows) {
    const bool unexpected = r.result.contains("as_expected") && !r.result["as_expected"].get<bool>();
    if (!(fell(r) || r.status != "ok" || unexpected) || ++shown > 500) continue;
    std::string outcome = r.status != "ok" ? "error: " + r.error
                          : fell(r) ? "fell at " + fixed(r.result.value("fall_time_s", 0.0), 2) + " s: " +
                                          r.result.value("fall_reason", std::string())
                                    : "walked";
    if (r.result.contains("expected")) outcome += unexpected ? " (UNEXPECTED: expected " + r.result["expected"].get<std::string>() + ")" : " (as expected)";
    out << "<tr><td>" << r.run << "</td><td>" << html_escape(outcome) << "</td><td><code>" << html_escape(r.command)
        << "</code></td></tr>";
  }
  out << "</table>";
  if (shown > 500) out << "<p>" << shown - 500 << " more in results.csv.</p>";
  std::vector<const CampaignRow*> slowest;
  for (const CampaignRow& r : rows) slowest.push_back(&r);
  std::sort(slowest.begin(), slowest.end(), [](auto a, auto b) { return a->wall_time_s > b->wall_time_s; });
  if (slowest.size() > 10) slowest.resize(10);
  out << "<h2>Slowest runs</h2><table><tr><th>run</th><th>wall time [s]</th><th>host/rank</th><th>reproduce</th></tr>";
  for (const CampaignRow* r : slowest) {
    out << "<tr><td>" << r->run << "</td><td>" << fixed(r->wall_time_s, 2) << "</td><td>" << html_escape(r->host)
        << "/" << r->rank << "</td><td><code>" << html_escape(r->command) << "</code></td></tr>";
  }
  out << "</table></body></html>\n";
}

nlohmann::json push_map_json(const std::vector<CampaignRow>& rows, const nlohmann::json& header) {
  nlohmann::json map = header;
  map["cells"] = nlohmann::json::array();
  for (const CampaignRow& r : rows) {
    nlohmann::json cell = {{"direction_deg", r.parameters["direction_deg"]}, {"phase", r.parameters["phase"]}};
    if (r.status == "ok") {
      cell["max_impulse_Ns"] = r.result["max_impulse_Ns"];
      cell["falls_without_push"] = r.result["falls_without_push"];
      cell["survived_every_impulse_tried"] = r.result["survived_every_impulse_tried"];
      cell["push_time_s"] = r.result["push_time_s"];
    } else {
      cell["max_impulse_Ns"] = nullptr;
      cell["error"] = r.error;
    }
    cell["command"] = r.command;
    map["cells"].push_back(cell);
  }
  return map;
}

void write_push_map_report(const nlohmann::json& map, std::ostream& out) {
  // Polar figure: one closed curve per phase, radius = largest survived impulse, angle = push
  // direction in the heading frame (0° forward, up; 90° left).
  std::map<double, std::vector<std::pair<double, double>>> curves;  // phase -> (direction, impulse)
  double largest = 1.0;
  for (const auto& c : map["cells"]) {
    if (c["max_impulse_Ns"].is_null()) continue;
    curves[c["phase"].is_null() ? -1.0 : c["phase"].get<double>()].push_back({c["direction_deg"].get<double>(), c["max_impulse_Ns"].get<double>()});
    largest = std::max(largest, c["max_impulse_Ns"].get<double>());
  }
  if (map.contains("capture_point_bound_Ns")) {
    for (const auto& b : map["capture_point_bound_Ns"]) largest = std::max(largest, b["max_impulse_Ns"].get<double>());
  }
  const double ring = std::ceil(largest / 10.0) * 10.0, size = 480, centre = size / 2, radius = size / 2 - 40;
  auto point = [&](double deg, double value) {
    const double a = deg * M_PI / 180.0, r = radius * value / ring;
    return std::make_pair(centre - r * std::sin(a), centre - r * std::cos(a));
  };
  std::ostringstream svg;
  svg << "<svg width='" << size + 160 << "' height='" << size << "' font-size='11' font-family='sans-serif'>";
  for (int k = 1; k <= 4; ++k) {
    svg << "<circle cx='" << centre << "' cy='" << centre << "' r='" << radius * k / 4 << "' fill='none' stroke='#ddd'/>"
        << "<text x='" << centre + 3 << "' y='" << centre - radius * k / 4 - 2 << "' fill='#888'>" << fixed(ring * k / 4, 0)
        << " N·s</text>";
  }
  for (int deg = 0; deg < 360; deg += 45) {
    const auto [x, y] = point(deg, ring * 1.08);
    svg << "<text x='" << x << "' y='" << y + 4 << "' text-anchor='middle'>" << (deg > 180 ? deg - 360 : deg) << "°</text>";
  }
  auto polygon = [&](const std::vector<std::pair<double, double>>& pts, const std::string& colour, const std::string& dash) {
    std::vector<std::pair<double, double>> sorted = pts;
    std::sort(sorted.begin(), sorted.end());
    svg << "<polygon fill='none' stroke='" << colour << "' stroke-width='2' stroke-dasharray='" << dash << "' points='";
    for (const auto& [deg, value] : sorted) {
      const auto [x, y] = point(deg, value);
      svg << x << ',' << y << ' ';
    }
    svg << "'/>";
  };
  int i = 0;
  const std::size_t n = curves.size();
  for (const auto& [phase, pts] : curves) {
    const int hue = n > 1 ? static_cast<int>(260.0 * i / (n - 1)) : 210;
    const std::string colour = "hsl(" + std::to_string(hue) + ",70%,45%)";
    polygon(pts, colour, "");
    svg << "<text x='" << size + 10 << "' y='" << 20 + 16 * i << "' fill='" << colour << "'>" << (phase < 0.0 ? std::string("standing") : "phase " + fixed(phase, 3))
        << "</text>";
    ++i;
  }
  if (map.contains("capture_point_bound_Ns")) {
    std::vector<std::pair<double, double>> bound;
    for (const auto& b : map["capture_point_bound_Ns"]) bound.push_back({b["direction_deg"], b["max_impulse_Ns"]});
    polygon(bound, "#000", "5,4");
    svg << "<text x='" << size + 10 << "' y='" << 20 + 16 * i << "'>- - bound without a step</text>";
  }
  svg << "</svg>";

  out << "<!DOCTYPE html><html><head><meta charset='utf-8'><title>push map " << html_escape(map.value("scenario", ""))
      << "</title>" << kStyle << "</head><body><h1>Push-recovery map: " << html_escape(map.value("scenario", "")) << " ("
      << html_escape(map.value("robot", "")) << ", stabilizer " << (map.value("stabilizer", true) ? "on" : "off")
      << ")</h1><p>The largest impulse of a " << fixed(map.value("push_duration_s", 0.1), 2)
      << " s push on the upper body that the robot survives, by push direction in its heading frame (0° forward, 90° "
         "left) and by the phase of the single support at which the push starts; bisection to "
      << fixed(map.value("resolution_Ns", 1.0), 1) << " N·s.</p>" << svg.str();
  out << "<h2>Cells</h2><table><tr><th>direction [°]</th><th>phase</th><th>largest survived [N·s]</th><th>reproduce</th></tr>";
  for (const auto& c : map["cells"]) {
    out << "<tr><td>" << c["direction_deg"] << "</td><td>" << c["phase"] << "</td><td>"
        << (c["max_impulse_Ns"].is_null() ? "error: " + html_escape(c.value("error", "")) : c["max_impulse_Ns"].dump())
        << (c.value("falls_without_push", false) ? " (falls without a push)" : "")
        << (c.value("survived_every_impulse_tried", false) ? " (every impulse tried)" : "") << "</td><td><code>"
        << html_escape(c["command"]) << "</code></td></tr>";
  }
  out << "</table></body></html>\n";
}

nlohmann::json write_campaign_outputs(const std::string& dir, const std::vector<CampaignRow>& rows, long total,
                                      const CampaignSession& session) {
  const std::filesystem::path d(dir);
  AtomicOutputFile csv((d / "results.csv").string()), summary_file((d / "summary.json").string()),
      report((d / "report.html").string());
  const nlohmann::json summary = campaign_summary(rows, total, session);
  write_results_csv(rows, csv.stream());
  summary_file.stream() << summary.dump(2) << '\n';
  write_campaign_report(rows, summary, report.stream());
  csv.commit();
  summary_file.commit();
  report.commit();
  return summary;
}

}  // namespace biped
