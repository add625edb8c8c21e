#pragma once
// The standing controller: moves from the measured joint angles to the model's reference standing
// pose (keyframe "stand") and holds it. It takes the same slot as the walking controller and checks
// the sensors the same way: on a fault it enters the safe stop state and holds its last set-point.
#include "control/sensor_check.hpp"
#include "interface/controller.hpp"

namespace biped {

struct StandingControllerParams {
  double ramp_time = 1.0;  // [s] from the initial pose to the reference pose
  SensorLimits sensor_limits;
};

class StandingController final : public Controller {
 public:
  StandingController(const RobotModel& model, const StandingControllerParams& params);

  void reset(const SensorData& first) override;
  void step(const SensorData& sensors, const WalkCommand& command, JointCommand& out) override;
  const ControllerStatus& status() const override { return status_; }

 private:
  const RobotModel& model_;
  StandingControllerParams params_;
  ControllerStatus status_;
  double start_time_ = 0.0;
  Eigen::VectorXd start_pose_;
  Eigen::VectorXd last_setpoint_;
};

}  // namespace biped
