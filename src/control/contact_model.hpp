#pragma once
// The controller's point-contact model of the foot-ground contact, eq. (11), in one place:
//   point_contact_stiffness: the per-foot 3×3 stiffness K the Stabilizer uses every cycle;
//   point_contact_wrench(es): the contact wrenches λ(q) of the model for a configuration;
//   general_force_position_map: the general S_λ∇_qλ(S̄_x∇_q x)^† of eq. (20), from ∇_qλ by finite
//     differences of λ(q). Analysis code for tests and documentation (it allocates and takes a few
//     hundred kinematics passes); the per-cycle controller uses −K per foot instead
//     (docs/stabilizer.md gives the measured difference).
// Controlled wrench components per foot (S_λ): λ_c = (F_z, T_x, T_y), the ground's force and
// torque on the sole about the F/T sensor point, in the sensor frame (the sensor's convention with
// the mass below the sensor neglected). Matching coordinates per foot (S̄_x): δ = (z, φ_x, φ_y),
// the foot's height and its tilt about the foot frame's x and y axes.
#include <Eigen/Core>
#include <array>

#include "model/robot_model.hpp"
#include "model/task_space.hpp"

namespace biped {

// K of (z, φ_x, φ_y) → (F_z, T_x, T_y) = −K δ for a flat foot on the ground, from the four sole
// corners each with stiffness C/4 [N/m].
Eigen::Matrix3d point_contact_stiffness(const FootInfo& foot, double contact_stiffness);

// λ_c of one foot with its sensor frame at (position, rotation) in the world and the ground plane
// at z = ground_height: each sole corner below the plane is pushed up by C/4 times its depth.
Eigen::Vector3d point_contact_wrench(const FootInfo& foot, double contact_stiffness,
                                     const Eigen::Vector3d& sensor_position, const Eigen::Matrix3d& sensor_rotation,
                                     double ground_height);

// λ_c of both feet (by index_of(Side)) at the configuration qpos (size nq), with the sensor frames
// from MuJoCo's kinematics on `data`.
std::array<Eigen::Vector3d, 2> point_contact_wrenches(const RobotModel& model, RobotData& data,
                                                      const Eigen::VectorXd& qpos, double contact_stiffness,
                                                      double ground_height);

// Rows of eq. (20) for both feet, left (z, φ_x, φ_y) then right, each with nv columns.
using FootRows = Eigen::Matrix<double, 6, Eigen::Dynamic>;

// S_λ∇_qλ by central differences of point_contact_wrenches along each generalized velocity
// (mj_integratePos, step h).
FootRows contact_jacobian(const RobotModel& model, const Eigen::VectorXd& qpos, double contact_stiffness,
                          double ground_height, double h = 1e-6);

// S̄_x∇_q x from data.x and data.J after evaluate(): per foot the height row foot_position[k] + 2
// (world z against the CoM) and the foot-frame tilt rates against the upper body,
// R_footᵀ(ω_foot − ω_UB) = exp(φ)ᵀ J_l(φ) ∇_qφ with φ the foot_orientation rows; their x and y rows.
FootRows selected_task_rows(const TaskSpace& space, const TaskSpaceData& data);

// S_λ∇_qλ(S̄_x∇_q x)^† (6×6, rows λ_c and columns δ of the left foot first).
Eigen::Matrix<double, 6, 6> general_force_position_map(const TaskSpace& space, const Eigen::VectorXd& qpos,
                                                       double contact_stiffness, double ground_height);

}  // namespace biped
