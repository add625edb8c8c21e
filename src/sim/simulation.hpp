#pragma once
// One simulated robot in its world: MuJoCo multibody dynamics with compliant unilateral foot
// contact, the robot's joint position controllers, emulated sensors, pushes and fall detection.
// The controller talks to it only through SensorData and JointCommand.
#include <mujoco/mujoco.h>

#include <array>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "interface/commands.hpp"
#include "interface/sensor_data.hpp"
#include "model/robot_model.hpp"
#include "sim/collision_gate.hpp"
#include "sim/disturbances.hpp"
#include "sim/fall_detection.hpp"
#include "sim/joint_drives.hpp"
#include "sim/sensor_emulation.hpp"
#include "sim/sole_contact.hpp"
#include "sim/world.hpp"

namespace biped {

// Software joint limits = hard limits minus this (robots.md); the one default of the simulated
// robot's and the controller's margin (make_run_config gives the simulation the controller's).
inline constexpr double kSoftwareLimitMarginRad = 5.0 * M_PI / 180.0;

struct SimulationParams {
  WorldSpec world;
  double control_period = 0.001;  // [s], a whole number of physics steps
  DriveParams drives;
  SoleContactParams sole_contact;
  int encoder_bits = 17;                       // default resolution
  std::map<std::string, int> encoder_bits_of;  // per joint name, overrides the default
  bool sensor_noise = false;
  SensorNoiseParams noise_levels;
  SensorErrorSpec sensor_errors;  // explicit errors and the IMU's attitude filter (default: ideal)
  int sensor_delay_cycles = 0;
  std::vector<SensorFault> faults;
  std::vector<Push> pushes;
  unsigned long long seed = 1;
  double software_limit_margin_rad = kSoftwareLimitMarginRad;
  // MuJoCo's collision detection only for steps in which a robot geom is near the ground (false:
  // every step; a run is the same either way, only slower).
  bool collision_gate = true;
};

// The physics blew up (MuJoCo found NaN, Inf or a huge value in the state and reset it): the run
// cannot go on. Usually a push, terrain, model error or simulation parameter far beyond anything
// physical (a sole stiffness of 10¹⁵ N/m diverges in the first steps).
class SimulationDiverged : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Simulation {
 public:
  // Builds the world; `controller_model` fixes the joint order of SensorData and JointCommand.
  // Throws ModelError when the world cannot be built or a controller joint is missing.
  Simulation(const SimulationParams& params, const RobotModel& controller_model);

  // The robot in its "stand" keyframe, soles resting on the ground, at time 0.
  void reset();
  // The sensor reading the controller receives now.
  void read_sensors(SensorData& out);
  // New joint set-points (controller order), held until the next command.
  void command(const JointCommand& setpoints);
  // Advances one control period: physics steps with the joint drives evaluated at every step.
  // Throws SimulationDiverged if the physics blew up.
  void advance();

  double time() const { return data_->time; }
  int physics_steps_per_control_period() const { return steps_per_period_; }
  int num_controller_joints() const { return static_cast<int>(plant_joint_of_.size()); }
  // The simulated robot's joint (plant().joints() index) that is the controller's joint `i`.
  int plant_joint_of(int i) const { return plant_joint_of_[i]; }
  const RobotModel& plant() const { return plant_; }
  const mjData* data() const { return data_.get(); }
  const JointDrives& drives() const { return drives_; }
  const SensorEmulation& sensors() const { return sensors_; }
  const Terrain& terrain() const { return terrain_; }
  const SoleContact& sole_contact() const { return sole_contact_; }
  // The soles' rectangles seen from above, where they are now (one per sole geom).
  struct SoleOutline {
    Side side;
    std::array<Eigen::Vector2d, 4> corners;  // in order around the sole
  };
  std::vector<SoleOutline> sole_outlines() const;
  const CollisionGate& collision_gate() const { return collision_gate_; }
  // Touchdowns and single supports of the ground truth, and when each push started.
  const GaitEvents& gait_events() const { return gait_; }
  const PushSchedule& pushes() const { return pushes_; }
  // Ground-truth normal contact force on a foot [N].
  double foot_contact_force(Side side) const;
  double standing_pelvis_height() const { return standing_pelvis_height_; }
  // nullptr while the robot has not fallen.
  const char* fall_reason() const { return fall_reason_; }
  double fall_time() const { return fall_time_; }

 private:
  struct MjDataDeleter {
    void operator()(mjData* d) const { mj_deleteData(d); }
  };
  SimulationParams params_;
  Terrain terrain_;
  RobotModel plant_;
  // The simulator's own world model, written during a run: the collision gate's flag.
  mjModel* model_;
  std::unique_ptr<mjData, MjDataDeleter> data_;
  std::vector<int> plant_joint_of_;
  JointDrives drives_;
  SensorEmulation sensors_;
  SoleContact sole_contact_;
  CollisionGate collision_gate_;
  GaitEvents gait_;
  PushSchedule pushes_;
  Eigen::VectorXd plant_setpoint_;
  int steps_per_period_ = 1;
  double standing_pelvis_height_ = 0.0;
  FallDetector fall_detector_;
  const char* fall_reason_ = nullptr;
  double fall_time_ = 0.0;
};

}  // namespace biped
