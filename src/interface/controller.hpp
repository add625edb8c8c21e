#pragma once
// The boundary between a controller and the robot it drives (simulated or real): the Controller
// base, and the status a controller reports about itself each cycle. sim/ and control/ both speak
// this layer and never include each other.
#include <Eigen/Core>
#include <array>

#include "interface/commands.hpp"
#include "interface/fault.hpp"
#include "interface/sensor_data.hpp"
#include "math/side.hpp"
#include "math/wrench.hpp"

namespace biped {

// A footstep the current walking pattern is planned through (controller frame).
struct PlannedStep {
  Side side = Side::Left;
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  // ankle (foot frame origin) on the ground
  double yaw = 0.0;
  double touchdown = 0.0;  // [s] since the controller's reset
};
inline constexpr int kMaxPlannedSteps = 3;

// What the controller reports about itself each cycle (for logs and for the caller's safety logic).
struct ControllerStatus {
  const char* state = "init";   // FSM state name, e.g. "standing", "walking", "safe_stop"
  bool fault = false;           // a sensor fault was detected; set-points are held safe
  Fault first_fault;            // the first fault detected (what the safe stop answers)
  FaultList faults;             // every signal found failed so far, in the order found
  FaultList recovered;          // failed signals trusted again (healthy for a while), in that order
  std::array<Wrench, 2> desired_wrench;  // contact wrench the controller aims for, per foot
  Eigen::Vector3d com_desired = Eigen::Vector3d::Zero();  // planned CoM (controller frame)
  Eigen::Vector2d zmp_desired = Eigen::Vector2d::Zero();  // planned ZMP (controller frame)
  bool command_saturated = false;                         // the walk command was clamped
  double contact_stiffness = 0.0;  // [N/m] C used by eq. (20): configured, or its on-line estimate (0: none)
  int steps_completed = 0;
  std::array<PlannedStep, kMaxPlannedSteps> planned_steps;  // upcoming footsteps, the next first
  int num_planned_steps = 0;
  // The CoM as the controller estimates it (eq. 10's r_CoM), placed at the planned stance foot
  // (controller frame); valid while the stabilizer uses the sensors.
  Eigen::Vector2d com_estimated = Eigen::Vector2d::Zero();
  bool com_estimate_valid = false;
  std::array<double, 2> foot_height_offset{};  // [m] terrain adaptation's offset of each foot's planned height
  std::array<double, 2> foot_tilt{};           // [rad] terrain adaptation's tilt of each foot (toes down)
  std::array<double, 2> foot_roll{};           // [rad] terrain adaptation's roll of each foot (left edge up)
  // [rad] the upper body's tilt against gravity (sagittal, lateral) as the controller uses it: the
  // IMU's after the sensor calibration.
  std::array<double, 2> upper_body_tilt{};
  // The sensor calibration's estimates (zero while off): the IMU's roll/pitch misalignment [rad]
  // (rotation vector, upper-body axes), the gyro bias [rad/s] and the F/T offsets, by Side.
  Eigen::Vector3d imu_misalignment = Eigen::Vector3d::Zero();
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();
  std::array<Wrench, 2> ft_offset;
  // Step adaptation: the DCM error (measured − planned) and the shift of the landing point of the
  // step in the air [m], heading frame (x forward, y left).
  Eigen::Vector2d dcm_error = Eigen::Vector2d::Zero();
  Eigen::Vector2d landing_shift = Eigen::Vector2d::Zero();
  // The hip strategy's planned lean of the upper body (sagittal, lateral, as upper_body_tilt) [rad].
  Eigen::Vector2d upper_body_lean = Eigen::Vector2d::Zero();
};

class Controller {
 public:
  virtual ~Controller() = default;
  // Called once with the first sensor reading, before the first step().
  virtual void reset(const SensorData& first) = 0;
  // One control cycle: never allocates, never throws, never writes NaN into `out`.
  virtual void step(const SensorData& sensors, const WalkCommand& command, JointCommand& out) = 0;
  virtual const ControllerStatus& status() const = 0;
};

}  // namespace biped
