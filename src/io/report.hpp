#pragma once
// report.html: one self-contained page with the plots and the 3D replay of a run. The data is
// gathered at the logging rate from the loop (controller status, sensor readings) and from the
// simulator's ground truth (poses, contact, CoM: this is visualization), and embedded as JSON next
// to the viewer script bundled at build time from web/report/ (three.js, uPlot).
#include <Eigen/Core>
#include <map>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "sim/closed_loop.hpp"

namespace biped {

// The viewer script (web/report/src bundled with its libraries), compiled into the program.
std::string_view report_bundle();

class ReportWriter final : public RunObserver {
 public:
  // Takes the static data (geoms, soles, joint limits) from the simulated model. Body poses for
  // the replay are kept at most at `replay_rate_hz`.
  explicit ReportWriter(const Simulation& sim, double replay_rate_hz = 30.0);

  void record(const Simulation& sim, const SensorData& sensors, const JointCommand& setpoints,
              const ControllerStatus& status, double cycle_us) override;

  // Everything the page shows; `summary` is the run's summary.json, `cycle_us` the duration of
  // every controller cycle (RunResult::cycle_us; the longest of each log interval is plotted).
  nlohmann::json data(const nlohmann::json& summary, const std::vector<double>& cycle_us) const;
  // The page: the data and the viewer script inline, nothing loaded from elsewhere.
  void write_html(std::ostream& out, const nlohmann::json& summary, const std::vector<double>& cycle_us) const;

 private:
  // A logged signal, rounded to `decimals` in the page (NaN: no value, shown as a gap).
  struct Column {
    int decimals = 4;
    std::vector<double> values;
  };
  struct Footprint {
    Side side;
    Eigen::Vector2d planned;  // controller frame
    double planned_yaw;
    Eigen::Vector2d world;    // drawn here: the planned place, registered to the world
    double world_yaw;
    double touchdown;
    double first_planned, last_planned;  // [s] when it was in the controller's plan
    bool stepped = false;     // the controller completed this step
    bool superseded = false;  // dropped from the plan without being stepped on (replanned, a stop)
  };
  void add(const std::string& name, int decimals, double value);
  void register_controller_frame(const Simulation& sim);
  Eigen::Vector2d to_world(const Eigen::Vector2d& p) const;
  void note_planned_steps(const ControllerStatus& status, double t);

  nlohmann::json model_;                 // geoms, bodies, soles
  nlohmann::json joints_ = nlohmann::json::array();  // names and limits [deg]
  std::vector<int> replay_bodies_;       // MuJoCo body ids whose poses are replayed
  double control_period_;          // [s]
  std::vector<long> cycle_index_;  // controller cycle of each record
  double replay_period_;
  double next_replay_t_ = 0.0;
  std::vector<double> replay_t_;
  std::vector<std::vector<double>> replay_frames_;  // per frame: x y z qw qx qy qz of each body
  std::map<std::string, Column> log_;
  std::vector<std::string> states_;
  std::vector<Footprint> footprints_;
  std::vector<std::size_t> plan_;  // footprints_ of the last recorded plan, the next step first
  int steps_completed_ = 0;
  // The controller's frame drifts from the world as the robot walks (it knows its feet only from
  // its plan). This planar transform puts the planned foothold of the stance foot where that foot
  // really is, so that plans and measurements can be drawn together.
  double frame_yaw_ = 0.0;
  Eigen::Vector2d frame_offset_ = Eigen::Vector2d::Zero();
};

}  // namespace biped
