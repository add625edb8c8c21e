#pragma once
#include <Eigen/Core>

namespace biped {

// A 6-axis wrench (force and torque about a stated point, in a stated frame).
// For the foot F/T sensors: the wrench the sole exerts on the ankle side, expressed in the sensor
// frame (standing still, force.z() > 0 is the load carried).
struct Wrench {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();
};

}  // namespace biped
