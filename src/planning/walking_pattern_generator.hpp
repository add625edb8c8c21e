#pragma once
// Walking pattern generator (Fig. 3; the paper's reference [8]): from the planned footsteps, the
// reference ZMP, the CoM trajectory of a simplified model (an upper-body mass plus one mass per leg,
// the legs following the planned foot trajectories) by spline collocation, the swing-foot
// trajectories, the upper-body heading, the arm swing, the ideal contact wrenches λ_id and the
// contact schedule. Replanned once per step; continuous in position, velocity and acceleration across
// the replanning instant. No allocation after construction.
#include <Eigen/Core>
#include <array>

#include "math/wrench.hpp"
#include "model/robot_model.hpp"
#include "planning/com_collocation.hpp"
#include "planning/footstep.hpp"

namespace biped {

struct PatternGeneratorParams {
  double body_mass = 35.0;       // [kg] everything but the legs' swinging shares
  double leg_mass = 10.0;        // [kg] each leg's share that follows the ankle (simplified_model_of)
  double leg_com_height = 0.35;  // [m] leg mass point above the ankle
  double ankle_height = 0.09;    // [m] ankle above the sole
  double gravity = 9.81;
  double zmp_offset_x = 0.0;     // [m] reference ZMP ahead of the ankle (sole centre)
  Eigen::Vector3d sensor_in_foot = Eigen::Vector3d::Zero();  // F/T sensor origin in the foot frame
  double mass_below_sensor = 0.0;  // [kg] per foot, carried by the ground directly
  double arm_swing_gain = 0.15;    // arm CoM forward offset per metre of foot separation
  double final_rest_time = 0.5;    // [s] the horizon ends this long after the last double support
  double settle_time = 1.0;        // [s] coming to rest without steps: the ZMP moves to mid-feet
  double com_height_variation = 0.01;  // [m] the body rises by this at mid single support
  int collocation_intervals = 48;
};

// Body-mass state along one horizontal axis.
struct AxisState {
  double position = 0.0, velocity = 0.0, acceleration = 0.0;
};

struct FootReference {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // ankle, world frame
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d acceleration = Eigen::Vector3d::Zero();
  double yaw = 0.0, yaw_rate = 0.0;
  bool in_contact = true;
  // In the swing: how far along the way to the foothold the foot is (the quintic blend s, 0 at
  // lift-off, 1 at touchdown) and its rate [1/s]; the time left to touchdown [s]. 0 on the ground.
  double swing_progress = 0.0, swing_progress_rate = 0.0;
  double time_to_touchdown = 0.0;
};

// Everything the controller takes from the pattern at one instant.
struct PatternSample {
  Eigen::Vector3d com = Eigen::Vector3d::Zero();  // robot CoM of the simplified model, world
  Eigen::Vector3d com_velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d com_acceleration = Eigen::Vector3d::Zero();
  AxisState body_x, body_y;                         // upper-body mass point (for replanning)
  std::array<FootReference, 2> feet;                // by Side
  double heading = 0.0, heading_rate = 0.0;         // upper-body yaw
  double arm_swing = 0.0;                           // right arm CoM forward (heading frame); left = −
  double arm_swing_rate = 0.0;
  Eigen::Vector2d zmp = Eigen::Vector2d::Zero();
  std::array<Wrench, 2> contact_wrench;             // λ_id in each foot's sensor frame
  std::array<double, 2> load_share = {0.5, 0.5};    // share of the normal force per foot
  Side stance = Side::Left;                         // foot carrying most load
  bool double_support = true;
};

class WalkingPatternGenerator {
 public:
  static constexpr int kMaxSteps = 3;

  explicit WalkingPatternGenerator(const PatternGeneratorParams& params);

  // New plan from t0 (a double support begins, both feet on the ground at `feet`, by Side) over the
  // next `num_steps` footsteps (0: come to rest between the feet), continuing the body state and the
  // ZMP of the previous plan. Each step's swing lasts the single-support time before its touchdown;
  // a first touchdown later than one step time gives a longer first double support (starting).
  void replan(double t0, const std::array<Footstep, 2>& feet, const std::array<Footstep, kMaxSteps>& steps,
              int num_steps, const StepParameters& parameters, const AxisState& body_x, const AxisState& body_y,
              const Eigen::Vector2d& zmp_now);

  void sample(double t, PatternSample& out) const;

  double horizon_start() const { return collocation_.t0(); }
  double horizon_end() const { return collocation_.t_end(); }
  // When the first planned step touches down (end of the first step), or the horizon end without steps.
  double next_touchdown() const { return num_steps_ > 0 ? steps_[0].touchdown : horizon_end(); }
  const PatternGeneratorParams& params() const { return params_; }
  // Height of the upper-body mass point at rest in the current plan [m].
  double body_height() const { return body_height_; }
  // The body's prescribed vertical motion: it rises by com_height_variation during each single
  // support (a C² bump, zero in double support).
  void body_vertical(double t, double& z, double& velocity, double& acceleration) const;

 private:
  void reference_zmp(double t, Eigen::Vector2d& zmp, double& share_of_new, int& phase_step) const;
  void foot_at(Side side, double t, FootReference& foot) const;
  // When step k's swing foot lifts off: a single-support time before its touchdown.
  double liftoff(int k) const;
  Eigen::Vector2d zmp_point(const Footstep& f) const;

  PatternGeneratorParams params_;
  StepParameters step_params_;
  ComCollocation collocation_;
  std::array<Footstep, 2> feet_;                 // footholds at t0, by Side
  std::array<Footstep, kMaxSteps> steps_;
  int num_steps_ = 0;
  double t0_ = 0.0;
  double double_support_time_ = 0.16;
  double body_height_ = 0.8;
  Eigen::Vector2d zmp_start_ = Eigen::Vector2d::Zero();
  // ZMP modification at the start of the plan (see ComCollocation): shapes and amplitudes per axis.
  void zmp_shapes(double t, double& b1, double& b2) const;
  double shape1_duration_ = 0.1, shape2_duration_ = 0.8;
  Eigen::Vector2d amplitude1_ = Eigen::Vector2d::Zero(), amplitude2_ = Eigen::Vector2d::Zero();
  Eigen::VectorXd rhs_x_, rhs_y_, coeff_x_, coeff_y_, shape1_, shape2_, knot_height_, knot_vertical_acc_;
};

}  // namespace biped

namespace biped {

// The simplified model's masses and the foot geometry, measured on the robot model in its
// "stand" keyframe. Each leg (subtree of the hip yaw joint's body) is split: the share of every
// segment's mass that follows the ankle when the leg swings about the hip (its depth below the hip
// over the ankle's) makes the leg mass point; the rest moves with the pelvis and joins the body.
PatternGeneratorParams simplified_model_of(const RobotModel& model);

}  // namespace biped
