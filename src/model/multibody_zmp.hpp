#pragma once
// ZMP of the full multibody model for a given motion, by inverse dynamics: the wrench the ground
// must supply at the floating base (MuJoCo's mj_inverse), moved to the ground plane z = 0.
#include <Eigen/Core>

#include "model/robot_model.hpp"

namespace biped {

// q0, q1, q2: full configurations at t − dt, t, t + dt (central differences give q̇ and q̈ at t).
// `normal_force` (if given) receives the vertical force the ground must supply [N].
// Uses `data` as workspace; allocation-free.
Eigen::Vector2d multibody_zmp(const RobotModel& model, RobotData& data, const Eigen::VectorXd& q0,
                              const Eigen::VectorXd& q1, const Eigen::VectorXd& q2, double dt,
                              double* normal_force = nullptr);

}  // namespace biped
