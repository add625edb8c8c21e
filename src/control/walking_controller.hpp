#pragma once
// One walking-controller cycle (Fig. 3): walking state machine, step sequence planner, walking
// pattern generator and resolved motion rate control with null-space optimization (eq. 21). The
// stabilizer (contact force modification, eq. 10, and hybrid position/force control, eqs. 11–20)
// plugs in between the pattern and eq. (21); without it this is the open-loop baseline.
// Sees only SensorData; allocation-free and NaN-free in step().
#include <array>
#include <memory>

#include "control/interface.hpp"
#include "control/resolved_motion_rate_control.hpp"
#include "control/sensor_check.hpp"
#include "control/stabilizer.hpp"
#include "control/state_estimation.hpp"
#include "control/terrain_adaptation.hpp"
#include "control/walking_state_machine.hpp"
#include "model/task_space.hpp"
#include "planning/step_sequence_planner.hpp"
#include "planning/step_table.hpp"
#include "planning/walking_pattern_generator.hpp"

namespace biped {

struct WalkingControllerParams {
  StepParameters step;            // step time, double support, clearance, width (com_height: measured)
  StepTable table;                // off-line table: step time, double support, clearance by speed (empty: `step`)
  CommandLimits limits;           // feasible commands; beyond them the command is saturated
  double start_shift = 0.6;       // [s] extra double support before the first step from standing
  double arm_swing_gain = 0.1;    // arm CoM forward offset per metre of foot separation
  ResolvedMotionRateControlParams rmrc;
  bool stabilizer = true;           // false: the open-loop baseline (pattern → eq. (21) only)
  StabilizerParams stabilization;
  TerrainAdaptationParams terrain;  // used with the stabilizer (it needs the F/T sensors)
  SensorLimits sensor_limits;
};

// Where a cycle's time goes (wall clock), for benchmarks and logs.
struct CycleTiming {
  double stabilizer_us = 0.0;  // state estimation, eq. (10), eq. (20)
  double rmrc_us = 0.0;        // eq. (21): kinematics, Jacobian, solve, integration
};

class WalkingController final : public Controller {
 public:
  WalkingController(const RobotModel& model, const WalkingControllerParams& params);

  void reset(const SensorData& first) override;
  void step(const SensorData& sensors, const WalkCommand& command, JointCommand& out) override;
  const ControllerStatus& status() const override { return status_; }

  WalkingState state() const { return fsm_.state(); }
  const PatternSample& pattern() const { return sample_; }
  const ResolvedMotionRateControl& rmrc() const { return rmrc_; }
  const Stabilizer& stabilizer() const { return stabilizer_; }
  const TerrainAdaptation& terrain() const { return terrain_; }
  const CycleTiming& timing() const { return timing_; }
  // The inputs eq. (21) got in the last cycle (to replay them, e.g. in the SVD baseline).
  const Eigen::VectorXd& task_reference() const { return x_id_; }
  const Eigen::VectorXd& task_reference_rate() const { return xdot_id_; }
  const Eigen::VectorXd& task_modification() const { return delta_x_; }
  const Eigen::VectorXd& task_modification_rate() const { return delta_xdot_; }
  Eigen::Matrix3d heading_frame() const;

 private:
  // Plans with the command's vx ramped from planned_vx_ (StartWalk, Continue).
  void replan(double t, StepDecision decision, const VelocityCommand& command);
  // The largest change of the gait's forward speed in one step (limits.vx_rate × step time).
  double max_speed_change() const;
  void task_reference(const PatternSample& s);
  // Δx_λ, Δẋ_λ of both feet in the task rows (foot height, foot tilt against the upper body).
  void stabilizer_modification(const PatternSample& s);
  // Δr_CoM and its rate for eq. (10): planned − estimated CoM relative to the stance foot.
  void com_error(const SensorData& sensors, const PatternSample& s, Eigen::Vector2d& error, Eigen::Vector2d& rate);

  const RobotModel& model_;
  WalkingControllerParams params_;
  TaskSpace space_;
  ResolvedMotionRateControl rmrc_;
  WalkingPatternGenerator pattern_;
  Stabilizer stabilizer_;
  TerrainAdaptation terrain_;
  CoMEstimator com_estimator_;
  FrozenSignalDetector frozen_;
  Eigen::Vector2d com_estimate_ = Eigen::Vector2d::Zero();       // CoM − stance foot, heading frame
  Eigen::Vector2d com_rate_estimate_ = Eigen::Vector2d::Zero();  // its filtered rate
  Side estimate_stance_ = Side::Left;
  bool has_estimate_ = false;
  WalkingStateMachine fsm_;
  ControllerStatus status_;
  CycleTiming timing_;

  double start_time_ = 0.0;
  std::array<Footstep, 2> feet_;              // current footholds (planner frame)
  std::array<Footstep, 3> planned_;           // steps of the current plan
  int num_planned_ = 0;
  double planned_vx_ = 0.0;                   // forward speed of the current plan (ramped, limits.vx_rate)
  PatternSample sample_;
  std::array<Eigen::Vector3d, 2> arm_offset_;  // arm CoM − upper body origin, heading frame
  std::array<Eigen::Vector3d, 2> arm_pivot_;   // shoulder pitch axis − upper body origin, heading frame
  Eigen::VectorXd x_id_, xdot_id_, delta_x_, delta_xdot_;
  Eigen::VectorXd last_setpoint_;
  int faulty_foot_sensor_ = -1;        // side index of a failed F/T sensor, −1: none
  SensorData substituted_sensors_;     // the readings with the failed sensor replaced (preallocated)
};

}  // namespace biped
