#pragma once
// One walking-controller cycle (Fig. 3): walking state machine, step sequence planner, walking
// pattern generator and resolved motion rate control with null-space optimization (eq. 21). The
// stabilizer (contact force modification, eq. 10, and hybrid position/force control, eqs. 11–20)
// plugs in between the pattern and eq. (21); without it this is the open-loop baseline.
// Sees only SensorData; allocation-free and NaN-free in step().
#include <array>

#include "control/com_estimator.hpp"
#include "control/resolved_motion_rate_control.hpp"
#include "control/attitude_estimator.hpp"
#include "control/sensor_calibration.hpp"
#include "control/sensor_monitor.hpp"
#include "control/stabilizer.hpp"
#include "control/step_adaptation.hpp"
#include "control/upper_body_lean.hpp"
#include "control/task_reference.hpp"
#include "control/terrain_adaptation.hpp"
#include "control/walking_plan.hpp"
#include "model/kinematics.hpp"
#include "interface/controller.hpp"
#include "model/task_space.hpp"

namespace biped {

struct WalkingControllerParams {
  WalkingPlanParams plan;           // FSM, step sequence planner and its table, pattern generator
  ResolvedMotionRateControlParams rmrc;
  bool stabilizer = true;           // false: the open-loop baseline (pattern → eq. (21) only)
  StabilizerParams stabilization;
  TerrainAdaptationParams terrain;  // used with the stabilizer (it needs the F/T sensors)
  StepAdaptationParams step_adaptation;  // used with the stabilizer (it needs the state estimate)
  UpperBodyLeanParams upper_body_lean;   // the hip strategy; used with the stabilizer, as the step adaptation
  SensorLimits sensor_limits;
  SensorCalibrationParams calibration;  // IMU and F/T errors estimated and removed (an extension)
  AttitudeEstimatorParams attitude;     // roll and pitch aided by the leg kinematics (an extension)
  // [rad] the upper body tilted this far from vertical (IMU) is beyond recovery: the fallen state.
  double fall_tilt = 25.0 * M_PI / 180.0;
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
  // The stages of Fig. 3, in this order: detect_faults → calibrate → advance the plan → adapt to the terrain →
  // the task reference → stabilize → resolve rates (eq. 21) → publish the status.
  void step(const SensorData& sensors, const WalkCommand& command, JointCommand& out) override;
  const ControllerStatus& status() const override { return status_; }

  WalkingState state() const { return plan_.state(); }
  const PatternSample& pattern() const { return plan_.sample(); }
  const WalkingPlan& plan() const { return plan_; }
  const ResolvedMotionRateControl& rmrc() const { return rmrc_; }
  const Stabilizer& stabilizer() const { return stabilizer_; }
  const TerrainAdaptation& terrain() const { return terrain_; }
  const SensorCalibration& calibration() const { return calibration_; }
  const StepAdaptation& step_adaptation() const { return step_adaptation_; }
  const UpperBodyLean& upper_body_lean() const { return lean_; }
  const CycleTiming& timing() const { return timing_; }
  // The inputs eq. (21) got in the last cycle (to replay them, e.g. in the SVD baseline).
  const Eigen::VectorXd& task_reference() const { return reference_.x(); }
  const Eigen::VectorXd& task_reference_rate() const { return reference_.rate(); }
  const Eigen::VectorXd& task_modification() const { return reference_.modification(); }
  const Eigen::VectorXd& task_modification_rate() const { return reference_.modification_rate(); }
  Eigen::Matrix3d heading_frame() const;

 private:
  // Every signal checked every cycle (control/sensor_monitor); a fault starts the safe stop.
  // Returns the readings the cycle works with, each failed signal replaced by what the controller
  // knows in its place: a failed F/T sensor reads the wrench the controller asked for (no force
  // error, feed-forward only), a failed encoder its set-point, a failed IMU the upper body's
  // orientation on a flat stance foot (no tilt feedback), a failed clock the last time plus Δt.
  const SensorData& detect_faults(const SensorData& raw);
  // The upper body tilted beyond recovery: the fallen state.
  bool detect_fall(const SensorData& sensors);
  // Where the foot in the air lands, from the last cycle's state estimate (control/step_adaptation).
  void adapt_steps(const SensorData& sensors);
  // Standing (also at the end of a safe stop): whether the measured DCM has come within standing_step_margin of the
  // edge of the feet's support, or beyond it, and which foot then steps first (`swing`).
  bool needs_standing_step(const PatternSample& s, Side& swing) const;
  // The footholds' and the CoM's heights from the F/T sensors (both needed).
  void adapt_to_terrain(const SensorData& sensors);
  // The height of the ground under a foot's sole against the pelvis, vertical in the world: the
  // encoders' leg kinematics turned by the estimated upper-body orientation, plus the sole's
  // deflection there under its measured wrench (eq. (11)'s contact model) [m]. NaN while the IMU
  // or an encoder has failed.
  double measured_ground(Side side, const SensorData& sensors) const;
  // eqs. (10)–(20) with the state estimate: the feet's modification Δx_λ of eq. (21)'s reference;
  // and the upper body's lean (the hip strategy, control/upper_body_lean).
  void stabilize(const SensorData& sensors);
  // eq. (21): the joint set-points, held when the rates come out non-finite.
  void resolve_rates(JointCommand& out);
  void publish_status();
  // The stabilizer works while one F/T sensor at least is healthy; finding the ground needs both.
  bool uses_sensors() const { return health().force_torque[0] || health().force_torque[1]; }
  const SensorHealth& health() const { return monitor_.health(); }

  const RobotModel& model_;
  WalkingControllerParams params_;
  TaskSpace space_;
  ResolvedMotionRateControl rmrc_;
  WalkingPlan plan_;
  TaskReference reference_;
  Stabilizer stabilizer_;
  TerrainAdaptation terrain_;
  StepAdaptation step_adaptation_;
  UpperBodyLean lean_;
  CoMEstimator com_estimator_;
  EncoderKinematics encoders_;  // this cycle's frames of the (fault-checked) encoder angles
  SensorMonitor monitor_;
  SensorCalibration calibration_;
  AttitudeEstimator attitude_;
  FaultList new_faults_;
  ControllerStatus status_;
  CycleTiming timing_;

  double start_time_ = 0.0;
  double last_time_ = 0.0;             // of the last trusted reading
  Eigen::VectorXd last_setpoint_;
  SensorData substituted_sensors_;     // the readings with the failed signals replaced (preallocated)
};

}  // namespace biped
