#pragma once
// The stabilizing control of the paper's Section IV:
//   contact force modification, eq. (10): λ_d = sat(λ_id + K_P Δx_IN + K_D Δẋ_IN), with
//     x_IN = (φ_UB, r_CoM): the upper body's inclination (IMU) and the horizontal CoM position
//     relative to the stance foot (encoders and IMU, control/state_estimation);
//   hybrid position/force control, eqs. (11)–(20): per foot, the normal force and the two contact-
//     plane torques are tracked by modifying the foot's height and tilt, through the explicit
//     point-contact model of eq. (11) (control/contact_model: the corners of each sole segment, for
//     LOLA heel and toe, placed with the measured toe angle; K from the elements in contact).
// With the point-contact model the map S_λ∇_qλ(S̄_x∇_q x)^† of eq. (20) is, per foot, minus the
// 3×3 contact stiffness K of (z, φ_x, φ_y) → (F_z, T_x, T_y); this implementation uses that small
// matrix (docs/stabilizer.md). Feet without contact blend to position control (α_λ → 0), which
// returns their modification to zero.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>

#include "control/contact_model.hpp"
#include "math/wrench.hpp"
#include "model/robot_model.hpp"

namespace biped {

struct StabilizerParams {
  double tilt_gain = 600.0;          // K_P [N·m/rad]: foot torque per radian of upper-body tilt error
  double tilt_rate_gain = 60.0;      // K_D [N·m·s/rad]
  double com_gain = 300.0;           // K_P [N·m/m]: foot torque per metre of CoM error
  double com_rate_gain = 30.0;       // K_D [N·m·s/m]
  double force_gain = 20.0;          // K_λ [1/s]
  double feedforward_gain = 1.0;     // K_λ,ff
  // Scale of eq. (14) on the pitch torque T_y: keeps the pitch loop's gain when the contact model's
  // pitch stiffness differs from the one the gains were tuned with (K_λ acts through −K⁻¹).
  double pitch_gain_scale = 1.0;
  double position_gain = 5.0;        // K_λx [1/s]: return of the modification without contact
  double contact_stiffness = 4.0e5;  // C of eq. (11) per foot [N/m]
  double heel_stiffness_share = 0.714; // share of C on the heel segment's elements (feet with a toe segment)
  double contact_tolerance = 5.0e-4; // [m] elements lifted less than this plus the sole's deflection touch
  bool toe_contact = false;          // recognize rolling on the toe (CoP ahead of the toe joint); docs/stabilizer.md
  double cop_margin = 0.02;          // [m] the desired CoP stays this far inside the sole
  double contact_filter_time = 0.02; // [s] first-order filter of the measured normal force
  double contact_force_low = 30.0;   // [N] filtered normal force: force control starts above ...
  double contact_force_high = 150.0; // ... and is complete above this
  double max_tilt = 0.15;            // [rad] bound of the foot tilt modification
  double max_height = 0.02;          // [m] bound of the foot height modification
  // Extension of eq. (14): integral action K_λ,INT ∫Δλ dt (0: off). The integral runs only with
  // contact (weighted by α_λ) and decays with K_λx without it, so it cannot wind up in swing.
  double force_integral_gain = 0.0;  // K_λ,INT [1/s²]
  // Extension: on-line adaptation of the contact stiffness C of eq. (11) from the measured normal
  // forces' response to the commanded foot heights in double support (least squares with forgetting).
  bool stiffness_adaptation = false;
  double adaptation_time = 0.5;        // [s] memory of the estimator (forgetting factor 1 − dt/T)
  double adaptation_min_scale = 0.25;  // the estimate stays within these multiples of C
  double adaptation_max_scale = 4.0;
};

// What the stabilizer reads each cycle: eq. (10)'s inputs and the measured wrenches of eq. (20).
struct StabilizerInput {
  std::array<Wrench, 2> ideal;             // λ_id of both feet (sensor frames), from the pattern
  std::array<bool, 2> planned_contact{};   // the pattern's contact schedule
  std::array<double, 2> load_share{};      // the pattern's split of the load
  std::array<Wrench, 2> measured;          // the F/T readings
  Eigen::Quaterniond imu_orientation = Eigen::Quaterniond::Identity();  // upper body in the world (IMU)
  Eigen::Vector3d imu_rate = Eigen::Vector3d::Zero();                   // its angular rate, IMU frame [rad/s]
  // Planned − estimated horizontal CoM relative to the stance foot (heading frame: x forward, y
  // left) [m], and its rate [m/s]: eq. (10)'s Δr_CoM.
  Eigen::Vector2d com_error = Eigen::Vector2d::Zero();
  Eigen::Vector2d com_rate_error = Eigen::Vector2d::Zero();
  // The upper body's planned inclination (sagittal, lateral: math::tilt_against_gravity's angles)
  // [rad] and its rate [rad/s]: zero in the paper; the hip strategy's lean (control/upper_body_lean).
  Eigen::Vector2d upper_body_lean = Eigen::Vector2d::Zero();
  Eigen::Vector2d upper_body_lean_rate = Eigen::Vector2d::Zero();
};

// Per-foot modification of the position-controlled foot coordinates (foot frame).
struct FootModification {
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  // Δx_λ: (z, φ_x, φ_y)
  Eigen::Vector3d rate = Eigen::Vector3d::Zero();    // Δẋ_λ
};

class Stabilizer {
 public:
  Stabilizer(const RobotModel& model, const StabilizerParams& params);
  void reset();

  // One cycle: eq. (10), then eq. (20) for each foot (and the stiffness estimate when enabled).
  void step(double dt, const StabilizerInput& in);

  // eq. (11) for this cycle, before step(): each foot's contact elements placed with the measured
  // toe angle (encoders, RobotModel::joints() order) and their contact state from the F/T readings
  // (control/contact_model); K and K⁻¹ of eq. (20) follow. Without it the feet are flat, every
  // element in contact.
  void update_contact_model(const Eigen::VectorXd& joint_position, const std::array<Wrench, 2>& measured);

  const std::array<Wrench, 2>& desired() const { return desired_; }
  const std::array<FootModification, 2>& modification() const { return modification_; }
  const std::array<double, 2>& force_control_share() const { return alpha_; }
  const std::array<ContactElements, 2>& contact_elements() const { return elements_; }
  const std::array<Eigen::Matrix3d, 2>& contact_stiffness_matrix() const { return stiffness_; }
  // The point-contact model of eq. (11) it uses.
  const ContactModelParams& contact_params() const { return contact_params_; }
  // The contact stiffness in use: C, or its on-line estimate [N/m].
  double contact_stiffness() const;
  // The sole's deflection (z, φ_x, φ_y) under a measured wrench by eq. (11)'s K⁻¹, with the
  // elements in contact and the stiffness in use: z is the sink at the sensor point [m].
  Eigen::Vector3d sole_deflection(Side side, const Wrench& measured) const;

 private:
  // eq. (10) with its saturation, from the tilt angles and their rates (sagittal, lateral).
  void contact_force_modification(const StabilizerInput& in, double tilt_sagittal, double tilt_lateral,
                                  double rate_sagittal, double rate_lateral);
  // eq. (20) for one foot.
  void hybrid_position_force_control(int foot, double dt, const Wrench& measured);
  // The contact-stiffness extension: updates the estimate from this cycle's readings.
  void adapt_contact_stiffness(double dt, const std::array<Wrench, 2>& measured);

  const RobotModel& model_;
  StabilizerParams params_;
  ContactModelParams contact_params_;
  std::array<ContactElements, 2> elements_;
  std::array<Eigen::Matrix3d, 2> stiffness_;  // K per foot, eq. (11)
  std::array<Eigen::Matrix3d, 2> compliance_; // K⁻¹
  std::array<Wrench, 2> desired_, previous_desired_;
  std::array<FootModification, 2> modification_;
  std::array<Eigen::Vector3d, 2> force_error_integral_;  // ∫(λ_d − λ) dt of the controlled rows
  // Least-squares sums of the stiffness estimate and the estimate as a multiple of C.
  double regression_xy_ = 0.0, regression_xx_ = 0.0;
  double stiffness_scale_ = 1.0;
  static constexpr int kAdaptationWindow = 20;            // cycles per regression sample
  int window_cycle_ = 0;
  std::array<double, 2> window_residual_ = {0.0, 0.0};    // F_z − F_z,d at the window's start
  std::array<Eigen::Vector3d, 2> window_offset_;          // Δx_λ at the window's start
  std::array<double, 2> filtered_force_ = {0.0, 0.0};
  std::array<double, 2> alpha_ = {0.0, 0.0};
  bool first_ = true;
};

}  // namespace biped
