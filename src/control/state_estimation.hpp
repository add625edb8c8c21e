#pragma once
// State estimation from sensors only: the robot CoM relative to the stance foot, from the joint
// encoders and the IMU's upper-body orientation (the kinematic chain anchored at the stance foot).
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "model/robot_model.hpp"

namespace biped {

class CoMEstimator {
 public:
  explicit CoMEstimator(const RobotModel& model);

  // r_CoM − r_foot in the gravity-aligned frame that has the upper body's heading, from the encoder
  // angles (RobotModel::joints() order) and the IMU orientation of the upper body. Allocation-free.
  Eigen::Vector3d com_from_foot(const Eigen::VectorXd& joint_positions, const Eigen::Quaterniond& upper_body,
                                Side foot);

 private:
  const RobotModel& model_;
  RobotData data_;
};

}  // namespace biped
