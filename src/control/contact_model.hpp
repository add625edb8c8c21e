#pragma once
// The controller's point-contact model of the foot-ground contact, eq. (11), in one place:
//   contact_elements: each foot's point contacts with stiffness C_i, the four corners of every
//     sole segment (JOHNNIE: one rigid sole; LOLA: heel segment and toe segment, the toe's corners
//     placed through the measured toe angle), and which of them touch the ground;
//   point_contact_stiffness: the per-foot 3×3 stiffness K the Stabilizer uses every cycle, from the
//     elements in contact;
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

#include "math/wrench.hpp"
#include "model/robot_model.hpp"
#include "model/task_space.hpp"

namespace biped {

struct ContactModelParams {
  double stiffness = 4.0e5;   // C: sum of the C_i of one foot [N/m]
  double heel_share = 0.714;  // share of C on the segment rigid with the sensor when the foot has a toe segment
  double tolerance = 5.0e-4;  // [m] an element lifted less than this plus the sole's deflection still touches
  bool toe_contact = false;   // recognize rolling on the toe segment (else a bent-up toe is always lifted)
};

// Four corners per sole segment.
inline constexpr int kMaxContactElements = 4 * FootInfo::kMaxSegments;

// The point contacts of one foot (fixed size: filled every cycle without allocation).
struct ContactElements {
  int count = 0;
  std::array<Eigen::Vector3d, kMaxContactElements> position;  // in the sensor frame [m]
  std::array<double, kMaxContactElements> stiffness{};         // C_i [N/m]
  std::array<int, kMaxContactElements> segment{};              // index in FootInfo::segments
  std::array<bool, kMaxContactElements> in_contact{};
  // The ground normal in the sensor frame: the normal of the sole plane the foot rests on.
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
};

// The elements of a foot with its toe joint at `toe_angle` [rad] (ignored without a toe segment),
// all in contact, the ground normal the sensor's z axis. A non-finite angle counts as zero.
void place_contact_elements(const FootInfo& foot, const ContactModelParams& params, double toe_angle,
                            ContactElements& elements);

// The contact state from the sensors: elements placed with the measured toe angle, in contact
// where they lie within the sole's deflection (measured normal force / C) plus the tolerance of the
// plane the foot rests on; that plane is the heel segment's, the toe segment's when the toe is bent
// up, the measured centre of pressure is ahead of the toe joint and params.toe_contact is set, and
// the plane through the heel's rear edge and the toe's tip when the toe is bent down
// (docs/stabilizer.md).
void contact_elements(const FootInfo& foot, const ContactModelParams& params, double toe_angle, const Wrench& measured,
                      ContactElements& elements);

// K of (z, φ_x, φ_y) → (F_z, T_x, T_y) = −K δ from the elements in contact (eq. 11 linearized with
// the ground normal `elements.normal`).
Eigen::Matrix3d point_contact_stiffness(const ContactElements& elements);
// K of a flat foot, toe at zero, every element in contact.
Eigen::Matrix3d point_contact_stiffness(const FootInfo& foot, const ContactModelParams& params);

// λ_c of one foot with its toe at toe_angle and its sensor frame at (position, rotation) in the
// world, the ground plane at z = ground_height: each element below the plane is pushed up by C_i
// times its depth.
Eigen::Vector3d point_contact_wrench(const FootInfo& foot, const ContactModelParams& params, double toe_angle,
                                     const Eigen::Vector3d& sensor_position, const Eigen::Matrix3d& sensor_rotation,
                                     double ground_height);

// The toe angle of a foot in qpos (size nq); 0 without a toe segment.
double toe_angle(const RobotModel& model, const FootInfo& foot, const Eigen::VectorXd& qpos);

// λ_c of both feet (by index_of(Side)) at the configuration qpos (size nq), with the sensor frames
// from MuJoCo's kinematics on `data` and the toe angles from qpos.
std::array<Eigen::Vector3d, 2> point_contact_wrenches(const RobotModel& model, RobotData& data,
                                                      const Eigen::VectorXd& qpos, const ContactModelParams& params,
                                                      double ground_height);

// Rows of eq. (20) for both feet, left (z, φ_x, φ_y) then right, each with nv columns.
using FootRows = Eigen::Matrix<double, 6, Eigen::Dynamic>;

// S_λ∇_qλ by central differences of point_contact_wrenches along each generalized velocity
// (integrate_configuration, step h).
FootRows contact_jacobian(const RobotModel& model, const Eigen::VectorXd& qpos, const ContactModelParams& params,
                          double ground_height, double h = 1e-6);

// S̄_x∇_q x from data.x and data.J after evaluate(): per foot the height row foot_position[k] + 2
// (world z against the CoM) and the foot-frame tilt rates against the upper body,
// R_footᵀ(ω_foot − ω_UB) = exp(φ)ᵀ J_l(φ) ∇_qφ with φ the foot_orientation rows; their x and y rows.
FootRows selected_task_rows(const TaskSpace& space, const TaskSpaceData& data);

// S_λ∇_qλ(S̄_x∇_q x)^† (6×6, rows λ_c and columns δ of the left foot first).
Eigen::Matrix<double, 6, 6> general_force_position_map(const TaskSpace& space, const Eigen::VectorXd& qpos,
                                                       const ContactModelParams& params, double ground_height);

}  // namespace biped
