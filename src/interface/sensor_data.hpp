#pragma once
// What a robot (real or simulated) hands its controller every cycle: encoders, IMU, two foot F/T
// sensors and the time. The controller sees these and nothing else.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>

#include "math/side.hpp"
#include "math/wrench.hpp"

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

}  // namespace biped
