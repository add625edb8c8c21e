#pragma once
// Where a controller starts from: the first encoder reading when it is plausible, else the stand
// pose; clamped to the software limits.
#include <Eigen/Core>

#include "control/sensor_check.hpp"

namespace biped {

// The joint angles (RobotModel::joints() order).
Eigen::VectorXd initial_joint_pose(const RobotModel& model, const SensorLimits& limits, const SensorData& first);
// The same written into a full configuration (the stand keyframe's floating base).
Eigen::VectorXd initial_configuration(const RobotModel& model, const SensorLimits& limits, const SensorData& first);

}  // namespace biped
