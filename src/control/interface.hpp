#pragma once
// What crosses the boundary between the controller and the robot (or the simulator).
// The controller sees SensorData only, never the simulator's state.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>

#include "math/wrench.hpp"
#include "model/robot_model.hpp"

namespace biped {

struct SensorData {
  double time = 0.0;                // [s] since the start of the run
  Eigen::VectorXd joint_position;   // link-side encoders [rad], in RobotModel::joints() order
  Eigen::Quaterniond imu_orientation = Eigen::Quaterniond::Identity();  // IMU frame in the world
  Eigen::Vector3d imu_angular_rate = Eigen::Vector3d::Zero();           // [rad/s], IMU frame
  Eigen::Vector3d imu_acceleration = Eigen::Vector3d::Zero();           // specific force [m/s²], IMU frame
  std::array<Wrench, 2> foot_wrench;                                    // indexed by Side

  explicit SensorData(int num_joints = 0) : joint_position(Eigen::VectorXd::Zero(num_joints)) {}
};

// Joint position set-points, in RobotModel::joints() order.
struct JointCommand {
  Eigen::VectorXd position;
  explicit JointCommand(int num_joints = 0) : position(Eigen::VectorXd::Zero(num_joints)) {}
};

// The "joystick": desired walking velocity in the robot's heading frame.
struct WalkCommand {
  double vx = 0.0;     // forward [m/s]
  double vy = 0.0;     // to the left [m/s]
  double omega = 0.0;  // turning rate [rad/s]
  bool stop = false;   // come to a standstill with both feet side by side
};

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
  const char* fault_reason = "";
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
