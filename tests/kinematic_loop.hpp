#pragma once
// The walking controller in a kinematic loop, for tests: its joint set-points become the next
// cycle's encoder readings (no dynamics, no simulator), with constant F/T and IMU readings.
#include <string>

#include "control/walking_controller.hpp"
#include "test_support.hpp"

namespace biped::test {

struct KinematicLoop {
  RobotModel model;
  WalkingController controller;
  SensorData sensors;
  JointCommand out;

  static WalkingControllerParams open_loop() {
    WalkingControllerParams p;
    p.stabilizer = false;  // the kinematic loop has no real contact forces to stabilize with
    p.sensor_limits.frozen_cycles = 0;  // and its F/T and IMU readings are constant
    return p;
  }
  explicit KinematicLoop(const std::string& robot)
      : model(load_model(robot)), controller(model, open_loop()), sensors(model.num_joints()), out(model.num_joints()) {
    sensors.joint_position = model.stand_pose();
    sensors.imu_acceleration = Eigen::Vector3d(0, 0, 9.81);
    for (Wrench& w : sensors.foot_wrench) w.force.z() = 0.5 * model.weight_above_sensors();
    controller.reset(sensors);
  }
  void cycle(double t, const WalkCommand& command) {
    sensors.time = t;
    controller.step(sensors, command, out);
    sensors.joint_position = out.position;
  }
};

}  // namespace biped::test
