#pragma once
// Pushes on the simulated robot: a force on any body, at any point, in any direction, timed by the
// clock or by gait events. Gait events come from the ground truth of the sole contacts (a touchdown
// is the normal force rising above 50 N, a lift-off falling below 10 N, each counted once it has
// held for 10 ms), so a push lands at the same moment of the gait whatever the controller plans,
// and needs no dry run.
#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "math/side.hpp"
#include "model/robot_model.hpp"

namespace biped {

// A moment of the gait: `phase` (0..1) through a single support, measured against the duration of
// the single support before it. The single support is the one after the `touchdown`-th touchdown
// (counted from the start of the run), or, with `after_time` ≥ 0, the first one that starts after
// that time. A moment that has passed when its single support is confirmed (a phase within the
// first 10 ms) starts the push at once.
struct GaitMoment {
  int touchdown = -1;
  double after_time = -1.0;  // [s]
  double phase = 0.5;
};

struct Push {
  double t = 0.0;               // [s] start (unless timed by a gait moment)
  double duration = 0.1;        // [s]
  std::string body = "upper_body";
  // [N] world frame; with `heading_frame`, in the robot's heading frame at the push's start
  // (x forward, y left, z up; the pelvis' ground-truth yaw).
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  bool heading_frame = false;
  bool at_gait_moment = false;  // timed by `moment` instead of `t`
  GaitMoment moment{};
  bool at_point = false;        // false: at the body's CoM
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // [m] application point in the body frame
};

// Touchdowns and single supports of the ground truth, from the feet's normal contact forces.
// A change of a foot's contact counts once it has held for kConfirmS (the force has not crossed
// back over the other threshold) and is dated to its start: a foot that bounces off the ground for
// a few milliseconds at touchdown or lift-off makes no touchdown and no single support of its own.
class GaitEvents {
 public:
  static constexpr double kTouchdownN = 50.0;
  static constexpr double kLiftoffN = 10.0;
  static constexpr double kConfirmS = 0.01;
  void reset();
  // One physics step at time t with each foot's normal force [N].
  void update(double t, const std::array<double, 2>& normal_force);

  int touchdowns() const { return touchdowns_; }
  bool single_support() const { return single_support_; }
  double single_support_start() const { return support_start_; }  // [s] of the current or last one
  double last_single_support_duration() const { return last_duration_; }  // [s]; 0: none completed
  int single_supports_started() const { return supports_started_; }
  int touchdowns_before_current_support() const { return touchdowns_at_support_start_; }

 private:
  std::array<bool, 2> in_contact_{true, true};
  std::array<double, 2> change_since_{-1.0, -1.0};  // [s] when a pending change began; < 0: none
  int touchdowns_ = 0;
  bool single_support_ = false;
  double support_start_ = 0.0, last_duration_ = 0.0;
  int supports_started_ = 0;
  int touchdowns_at_support_start_ = 0;
};

// When each push acts, and its force on the plant.
class PushSchedule {
 public:
  // Throws ModelError for a push on an unknown body.
  PushSchedule(const RobotModel& plant, std::vector<Push> pushes);
  void reset();
  // One physics step: decides the gait-timed pushes' start times, then adds the active pushes'
  // forces (and their torques about the bodies' CoMs) to d->xfrc_applied. Needs the kinematics of d.
  void apply(mjData* d, const GaitEvents& gait);

  // [s] when each push started (NaN: not yet, or never: a gait moment that did not come).
  const std::vector<double>& start_times() const { return start_; }

 private:
  const RobotModel& plant_;
  std::vector<Push> pushes_;
  std::vector<int> body_;
  std::vector<double> start_;
  std::vector<Eigen::Vector3d> world_force_;  // fixed at the start (heading frame resolved)
};

}  // namespace biped
