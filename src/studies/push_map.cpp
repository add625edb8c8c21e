#include "studies/push_map.hpp"

#include <mujoco/mujoco.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/campaign_report.hpp"
#include "io/campaign_spec.hpp"
#include "io/output_files.hpp"
#include "io/yaml_reader.hpp"
#include "studies/scenario_runner.hpp"

namespace biped {
namespace {

constexpr double kGravity = 9.81;

double cell_direction(int k, int directions) {
  const double deg = 360.0 * k / directions;
  return deg > 180.0 ? deg - 360.0 : deg;
}

// Distance from `c` (inside) to the convex polygon's edge along unit direction `u`.
double distance_to_edge(const std::vector<Eigen::Vector2d>& hull, const Eigen::Vector2d& c, const Eigen::Vector2d& u) {
  double best = INFINITY;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Eigen::Vector2d a = hull[i], e = hull[(i + 1) % hull.size()] - a;
    const double denom = u.x() * e.y() - u.y() * e.x();
    if (std::abs(denom) < 1e-12) continue;
    const Eigen::Vector2d w = a - c;
    const double t = (w.x() * e.y() - w.y() * e.x()) / denom;   // along u
    const double s = (w.x() * u.y() - w.y() * u.x()) / denom;   // along the edge
    if (t >= 0.0 && s >= -1e-9 && s <= 1.0 + 1e-9) best = std::min(best, t);
  }
  return best;
}

// Andrew's monotone chain.
std::vector<Eigen::Vector2d> convex_hull(std::vector<Eigen::Vector2d> p) {
  std::sort(p.begin(), p.end(), [](const auto& a, const auto& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
  };
  std::vector<Eigen::Vector2d> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(h[k - 2], h[k - 1], p[i - 1]) <= 0) --k;
    h[k++] = p[i - 1];
  }
  h.resize(k - 1);
  return h;
}

class PushMapWork final : public CampaignWork {
 public:
  PushMapWork(std::string path, std::vector<std::string> overrides, PushMapOptions options, bool standing,
              std::string identity)
      : path_(std::move(path)), overrides_(std::move(overrides)), options_(options), standing_(standing),
        phases_(standing ? 1 : options.phases), identity_(std::move(identity)) {}

  long size() const override { return static_cast<long>(options_.directions) * phases_; }
  std::string identity() const override { return identity_; }

  CampaignRow describe(long index) const override {
    CampaignRow row;
    row.run = index;
    row.parameters["direction_deg"] = direction(index);
    row.parameters["phase"] = standing_ ? nlohmann::json(nullptr) : nlohmann::json(phase(index));
    std::string command = "build/biped push-test " + path_ + " --direction-deg " + exact_number(direction(index));
    command += standing_ ? " --at-time " + exact_number(options_.test.earliest) : " --phase " + exact_number(phase(index));
    for (const std::string& o : overrides_) command += " --set '" + o + "'";
    row.command = command;
    return row;
  }

  void run(long index, CampaignRow& row) const override {
    const Scenario scenario = load_scenario(path_, overrides_);
    const RunConfig config = make_run_config(scenario);
    PushTestOptions test = options_.test;
    test.direction_deg = direction(index);
    test.phase = phase(index);
    if (standing_) test.at_time = test.earliest;
    test.progress = nullptr;
    row.result = run_push_test(scenario, config, test);
  }

 private:
  double direction(long index) const { return cell_direction(static_cast<int>(index / phases_), options_.directions); }
  double phase(long index) const { return standing_ ? 0.0 : (static_cast<double>(index % phases_) + 0.5) / phases_; }

  std::string path_;
  std::vector<std::string> overrides_;
  PushMapOptions options_;
  bool standing_;
  int phases_;
  std::string identity_;
};

}  // namespace

bool scenario_walks(const Scenario& scenario) {
  for (const TimedCommand& c : scenario.commands) {
    if (!c.command.stop && (c.command.vx != 0.0 || c.command.vy != 0.0 || c.command.omega != 0.0)) return true;
  }
  return false;
}

nlohmann::json capture_point_bound(const RunConfig& config, bool standing, int directions) {
  const RobotModel model = load_controller_model(config);
  const Simulation sim(config.sim, model);
  const RobotModel& plant = sim.plant();
  const mjModel* m = plant.mj();
  std::unique_ptr<mjData, void (*)(mjData*)> d(mj_makeData(m), mj_deleteData);
  mj_copyData(d.get(), m, sim.data());
  mj_forward(m, d.get());
  double mass = 0.0;
  for (int b = 1; b < m->nbody; ++b) mass += m->body_mass[b];
  const Eigen::Vector3d com(d->subtree_com[3], d->subtree_com[4], d->subtree_com[5]);  // body 1: the robot's root
  std::vector<Eigen::Vector2d> corners;
  double ground = INFINITY;
  for (Side side : {Side::Left, Side::Right}) {
    const FootInfo& f = plant.foot(side);
    const Eigen::Vector3d origin(d->site_xpos + 3 * f.sensor_site);
    const Eigen::Matrix<double, 3, 3, Eigen::RowMajor> rotation(d->site_xmat + 9 * f.sensor_site);
    std::vector<Eigen::Vector2d> sole;
    for (double x : {f.sole_x_min, f.sole_x_max}) {
      for (double y : {f.sole_y_min, f.sole_y_max}) {
        const Eigen::Vector3d p = origin + rotation * Eigen::Vector3d(x, y, f.sole_z);
        ground = std::min(ground, p.z());
        sole.push_back(p.head<2>());
      }
    }
    if (!standing) {  // one sole, centred under the CoM
      Eigen::Vector2d centre = Eigen::Vector2d::Zero();
      for (const auto& p : sole) centre += p / 4.0;
      for (auto& p : sole) corners.push_back(p - centre + com.head<2>());
      break;
    }
    corners.insert(corners.end(), sole.begin(), sole.end());
  }
  const std::vector<Eigen::Vector2d> hull = convex_hull(corners);
  const double height = com.z() - ground, omega = std::sqrt(kGravity / height);
  nlohmann::json bound = nlohmann::json::array();
  for (int k = 0; k < directions; ++k) {
    const double deg = cell_direction(k, directions), a = deg * M_PI / 180.0;
    const double distance = distance_to_edge(hull, com.head<2>(), Eigen::Vector2d(std::cos(a), std::sin(a)));
    bound.push_back({{"direction_deg", deg}, {"distance_m", distance}, {"max_impulse_Ns", mass * omega * distance}});
  }
  return {{"mass_kg", mass}, {"com_height_m", height}, {"omega_per_s", omega},
          {"support", standing ? "both soles" : "one sole"}, {"per_direction", bound}};
}

nlohmann::json run_push_map(const std::string& scenario_path, const std::vector<std::string>& overrides,
                            const std::string& out_dir, const PushMapOptions& options, const MpiSession& mpi,
                            const CampaignEngineOptions& engine) {
  if (options.directions < 1 || options.directions > 360) throw InputError("--directions: must be between 1 and 360");
  if (options.phases < 1 || options.phases > 100) throw InputError("--phases: must be between 1 and 100");
  const Scenario scenario = load_scenario(scenario_path, overrides);
  const RunConfig config = make_run_config(scenario);
  const bool standing = !scenario_walks(scenario);
  std::ostringstream identity;
  identity << "push-map " << options.directions << " " << options.phases << " " << options.test.earliest << " "
           << options.test.max_impulse << " " << options.test.resolution << "\n";
  for (const std::string& o : overrides) identity << o << "\n";
  identity << std::ifstream(scenario_path).rdbuf();
  const PushMapWork work(scenario_path, overrides, options, standing, identity.str());

  if (mpi.rank() == 0) prepare_output_directory(out_dir);
  const std::filesystem::path dir(out_dir);
  const CampaignEngineOutcome outcome = run_campaign_engine(work, (dir / "campaign.sqlite").string(), mpi, engine);
  if (!outcome.coordinator) return nullptr;

  const CampaignDatabase db((dir / "campaign.sqlite").string());
  const std::vector<CampaignRow> rows = db.rows();
  const nlohmann::json bound = capture_point_bound(config, standing, options.directions);
  nlohmann::json header = {{"scenario", scenario.name},
                           {"robot", config.robot},
                           {"stabilizer", config.controller.stabilizer},
                           {"standing", standing},
                           {"directions", options.directions},
                           {"phases", standing ? 1 : options.phases},
                           {"push_duration_s", options.test.push_duration},
                           {"resolution_Ns", options.test.resolution},
                           {"largest_impulse_tried_Ns", options.test.max_impulse},
                           {"overrides", overrides},
                           {"capture_point", bound},
                           {"capture_point_bound_Ns", bound["per_direction"]}};
  const nlohmann::json map = push_map_json(rows, header);
  AtomicOutputFile json((dir / "push_map.json").string()), report((dir / "report.html").string());
  json.stream() << map.dump(2) << '\n';
  write_push_map_report(map, report.stream());
  CampaignSession session{"push-map " + scenario.name, outcome.wall_time_s, outcome.ranks, outcome.workers,
                          outcome.finished_before,
                          outcome.storing_s, outcome.ran};
  AtomicOutputFile summary((dir / "summary.json").string());
  summary.stream() << campaign_summary(rows, outcome.total, session).dump(2) << '\n';
  json.commit();
  report.commit();
  summary.commit();
  return map;
}

}  // namespace biped
