#pragma once
// Records a closed-loop run: writes log.csv rows (DESIGN.md "log.csv") and gathers the figures of
// summary.json from the simulator's ground truth.
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "sim/closed_loop.hpp"

namespace biped {

class RunRecorder final : public RunObserver {
 public:
  // `csv` may be null: then only the summary figures are gathered.
  RunRecorder(const Simulation& sim, std::ostream* csv);

  void record(const Simulation& sim, const SensorData& sensors, const JointCommand& setpoints,
              const ControllerStatus& status, double cycle_us) override;

  // summary.json as in DESIGN.md, plus a few extra keys. `steps` counts touchdowns up to the fall;
  // `fault` is the controller's first sensor fault if it came before the fall (or with no fall),
  // `fault_after_fall` if it came after (a fall's impact trips the checks); `fault_time_s` when it
  // was first logged; `command_saturated` whether the walk command was clamped to the limits.
  nlohmann::json summary(const std::string& robot, const std::string& scenario, const RunResult& result,
                         const ControllerStatus& final_status) const;

  // Ground-truth series at the logging rate, for tests and reports.
  struct Sample {
    double t;
    double pelvis_z;
    double tilt_sagittal, tilt_lateral;  // [rad]
  };
  const std::vector<Sample>& samples() const { return samples_; }

 private:
  std::ostream* csv_;
  std::vector<std::string> joint_names_;  // by the controller's joint index (Fault::index)
  std::vector<Sample> samples_;
  double start_x_ = 0.0, start_y_ = 0.0, start_yaw_ = 0.0;
  double final_pos_[3] = {0.0, 0.0, 0.0};
  double path_length_ = 0.0;  // [m] of the pelvis over the ground, sway included
  double final_yaw_ = 0.0;
  double max_tilt_ = 0.0;
  bool started_ = false;
  int touchdowns_ = 0;
  bool fault_seen_ = false, fault_after_fall_ = false;
  double fault_time_ = 0.0;
  bool command_saturated_ = false;
  std::string row_;  // the log.csv row being written
};

}  // namespace biped
