#pragma once
// Adaptation to ground heights the controller is not told about (steps, slopes). The pattern plans
// every foothold at the height of the ground it was planned for; the F/T sensors tell where the
// ground really is:
//  - early contact: a swing foot that meets the ground while descending stops there (its height is
//    latched while the plan would move it further down);
//  - late contact: a foot that finds no ground at the planned touchdown, or loses it again (it met
//    the ground on one edge and bounced off) before it has found its support while the plan shifts
//    load onto it, descends at a search speed until it does;
//  - partial support: a foot that has just touched down and cannot put its centre of pressure where
//    the stabilizer asks (the measured one stays more than a band from it, e.g. on a step edge with
//    the front of the sole over the lower level) turns about its present centre of pressure
//    towards the desired one at a search speed until the sole finds the ground there; the tilt
//    holds for that stance and returns to zero in the swing. Across an oblique edge the sole's
//    unsupported part lies behind and to one side: at a step found (the footholds' heights
//    differ) the turn lowers it in that direction, pitch and roll, elsewhere about the foot's
//    lateral axis only;
//  - the foot's height at touchdown is the ground height of that foothold; the next swing foot aims
//    at the ground height of the stance foot, and the CoM height follows the mean ground height of
//    the footholds, so the legs keep their planned length;
//  - the level: in the double support after a touchdown the encoders and the IMU measure the new
//    foothold's height against the other's; the footholds' heights chain these measured steps, and
//    every height above moves together to them (an extension: see step());
//  - downhill slopes: the orientation a standing foot is commanded to (the slope it took, its tilt,
//    force control's turn of eq. 20) while its centre of pressure is inside the sole, so that the
//    sole lies flat, is the ground's slope there. Where that slope descends from the stance foot
//    and the footholds' heights agree with it, the swing foot turns to it and aims at the height
//    it gives. (Aiming at the stance foot's height, LOLA's feet landed late on a 4° downhill
//    slope, heel first, behind the CoM: each touchdown added some 5 cm to the DCM error, the
//    stabilizer asked for the centre of pressure at the toe, the heel lifted, and it fell within a
//    few steps.) Elsewhere (level ground ahead, or uphill) the swing foot still rolls to that
//    slope's sideways part, where the footholds' heights agree with it: landing level on a side
//    slope, its uphill edge touched first and the centre of pressure held there pushed the CoM
//    downhill at every touchdown. Without the downhill prediction, a foot landing lower than the
//    stance foot also aims at the drop that sideways part gives (the downhill side's foot landed
//    late at every step).
// The outputs are height offsets added to the feet's and the CoM's planned heights, and tilts added
// to the feet's planned orientations in eq. (21); force control (eq. 20) acts on top of them.
#include <array>
#include <cmath>

#include <Eigen/Core>

#include "math/wrench.hpp"
#include "model/robot_model.hpp"
#include "planning/walking_pattern_generator.hpp"

namespace biped {

struct TerrainAdaptationParams {
  bool enabled = true;
  double contact_force = 60.0;    // [N] filtered normal force that means ground contact
  double filter_time = 0.005;     // [s] first-order filter of the normal force
  double search_speed = 0.25;     // [m/s] descent of a foot that found no ground at touchdown ...
  // ... this long after it [s]. A foot landing on time on the expected ground meets it with almost
  // no force and reaches contact_force only as the plan shifts load onto it (about 25 ms for LOLA);
  // searching at once would lower every foothold by a few millimetres and walk the estimate down.
  double search_delay = 0.04;
  // Each new foothold's height measured against the other foot's in the double support after its
  // touchdown, by the encoders' leg kinematics turned by the IMU's orientation (step():
  // `measured_ground`); all heights the adaptation commands then shift together to the measured
  // level (below). Not while the upper body leans more than `step_height_max_lean` [rad] from its
  // command: in larger motions the attitude estimate lags.
  bool measure_step_height = true;
  double step_height_max_lean = 0.035;
  double max_step = 0.05;         // [m] bound of a foothold's height against the other foot's
  // Standing (after a stop or at the end of a safe stop), the feet's heights against each other
  // follow the measured step between them
  // (level_standing_feet()), whatever the upper body's lean: the difference beyond
  // `standing_level_dead_band` [m] with time constant `standing_level_time` [s], at most
  // `standing_level_speed` [m/s]. (Taken up at the bound's speed whatever its size, the
  // difference rocked LOLA from foot to foot: 170-380 N of load swinging between the feet.)
  bool level_standing_feet = true;
  double standing_level_dead_band = 0.003;
  double standing_level_time = 0.5;
  double standing_level_speed = 0.02;
  double com_follow_time = 0.3;   // [s] time constant of the CoM height following the footholds
  double cop_band = 0.04;         // [m] desired centre of pressure this far from the measured one at touchdown: the sole lacks support there
  double cop_filter_time = 0.03;  // [s] first-order filter of that distance
  double tilt_search_speed = 0.5; // [rad/s] turn of a foot in edge contact about that edge
  double max_tilt = 0.15;         // [rad] bound of a foot's tilt (the norm of its roll and pitch)
  // The partial support's turn also about the foot's forward axis: the centre of pressure's error
  // sideways counts as well as along the foot (an edge crossed at an angle), where the foothold's
  // ground differs from the other foot's by more than a centimetre (a step found). Off: about the
  // lateral axis only, the error along the foot alone (edges across the walking direction).
  bool tilt_search_roll = true;
  bool predict_slope = true;      // downhill, the swing foot takes the stance foot's ground slope (above)
  // Elsewhere (level or uphill) the swing foot still takes that slope's roll about its own forward
  // axis (a side slope), not its pitch or height.
  bool take_side_slope = true;
  // ... and where the downhill prediction does not act (`predict_slope` off) while the swing foot
  // lands lower than the stance foot, it aims at the drop the side slope alone gives over the feet's
  // distance sideways (not the pitch's), where that side slope is steeper than 1.5 × min_slope or
  // the foot's last foothold lay lower than the stance foot's already: the foot on the downhill side
  // otherwise lands late every step, and the robot rolls downhill while it searches (JVRC-1,
  // docs/stabilizer.md "Side slopes").
  bool side_slope_height = true;
  double min_slope = 0.02;        // [rad] shallower slopes are taken for level ground
  double max_slope = 0.1;         // [rad] bound of that slope
  // [m] the slope is taken if the height it gives between the last two footholds is within this
  // (plus half the height itself) of their estimated heights' difference
  double slope_tolerance = 0.005;
};

class TerrainAdaptation {
 public:
  // The soles' heel and toe edges come from the model's foot geometry.
  TerrainAdaptation(const RobotModel& model, const TerrainAdaptationParams& params);
  void reset();
  // One cycle with the pattern's sample, the measured and the desired contact wrenches (λ_d of
  // eq. 10, last cycle), and where each standing foot's ground lies above its planned height plus
  // offset: force control's height modification (Δz of eq. 20) and the sole's deflection under
  // its load. A foot whose F/T reading is not `trusted` (a failed sensor) finds no ground of its
  // own: its phase follows the plan, standing it keeps its offset, in the air it goes to the other
  // foot's ground height; so its state is consistent when the sensor is trusted again. Only late
  // ground is still found while the other foot's reading is trusted: its load is the weight the
  // other foot no longer carries. Without any trusted reading the CoM height holds too.
  // `turn_above_command`: force control's turn of each foot (φ_x, φ_y of eq. 20's Δx_λ) [rad].
  // `measured_ground`: the height of the ground under each sole against a common point of the
  // robot, vertical in the world (the sole's height from the encoders' leg kinematics turned by the
  // IMU's orientation, plus its deflection under its load) [m]; not finite where not known. The
  // searches and latches find each foothold relative to the command, and whatever lifts a landing
  // foot above its command (the robot's lean at touchdown: the commands assume the planned
  // orientation) makes every foothold found some millimetres low or high: their heights walk away
  // step by step (LOLA's 0.5 s steps: 1.7 dm in 20 s). Measured, the footholds' heights chain
  // the measured steps instead; every height the adaptation commands (the feet's offsets, the
  // footholds, the CoM's) shifts together towards that level, which changes no joint angle: the walk
  // stays as the searches and latches make it, the heights stay at the ground's.
  void step(double dt, const PatternSample& s, const std::array<Wrench, 2>& measured,
            const std::array<Wrench, 2>& desired = {}, const std::array<double, 2>& ground_above_command = {0.0, 0.0},
            const std::array<bool, 2>& trusted = {true, true},
            const std::array<Eigen::Vector2d, 2>& turn_above_command = {Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()},
            const std::array<double, 2>& measured_ground = {NAN, NAN});

  // Standing (after step(), the walk at rest): the footholds' heights against each other move
  // towards the measured step between them while both soles lie flat, each foot half of it, their
  // mean unchanged (an extension). A foot that landed while the robot rolled towards it met the
  // ground early and is latched centimetres high (or searched low); walking, its next step finds
  // the ground again, but standing on it the robot leans by that difference and force control's
  // bounded Δz cannot take it up: LOLA, pushed 12 N·s sideways in its stop step, stood 6-10°
  // rolled on a foot latched 2.4 cm high and fell over 3.6 s later. `measured_ground` as for step(),
  // but taken at any lean: the robot stands still and the attitude estimate does not lag.
  void level_standing_feet(double dt, const std::array<double, 2>& measured_ground);

  // Offsets of the planned heights [m] and their rates [m/s]: per foot (by Side) and of the CoM.
  // A tilted foot's ankle moves with the tilt so that the point it turned about stays in place.
  double foot_offset(int k) const { return feet_[k].offset + lift_of_ankle(feet_[k], feet_[k].tilt); }
  double foot_offset_rate(int k) const { return feet_[k].rate + lift_of_ankle(feet_[k], feet_[k].tilt_rate); }
  // Tilt of each foot about its lateral axis (positive: toes down) [rad] and its rate [rad/s]:
  // the slope it takes and its turn about an edge.
  double foot_tilt(int k) const { return feet_[k].tilt.y() + feet_[k].slope.y(); }
  double foot_tilt_rate(int k) const { return feet_[k].tilt_rate.y() + feet_[k].slope_rate.y(); }
  // Roll of each foot about its forward axis (positive: its left edge up) [rad] and its rate [rad/s].
  double foot_roll(int k) const { return feet_[k].tilt.x() + feet_[k].slope.x(); }
  double foot_roll_rate(int k) const { return feet_[k].tilt_rate.x() + feet_[k].slope_rate.x(); }
  // The ground's gradient (∂z/∂x, ∂z/∂y, world frame) under each foot's current or last foothold,
  // where its sole last lay flat.
  const Eigen::Vector2d& ground_gradient(int k) const { return feet_[k].ground_gradient; }
  double com_offset() const { return com_offset_; }
  double com_offset_rate() const { return com_rate_; }
  // Estimated ground height under each foothold, relative to the ground the plan assumes.
  double ground_height(int k) const { return feet_[k].ground; }

 private:
  enum class Phase { Stance, Swing, Latched, Searching };
  struct Foot {
    Phase phase = Phase::Stance;
    double ground = 0.0;        // ground height of the current or last foothold
    double offset = 0.0, rate = 0.0;
    double latched_height = 0.0;  // planned height + offset when the ground was met
    double search_time = 0.0;     // time since the planned touchdown without contact
    // The step measured in the double support after touchdown (measure_step):
    bool measuring = false;        // from touchdown until the other foot lifts off
    bool measured = false;         // measured_height holds a measurement
    double reference = 0.0;        // the other foothold's (measured) ground height at touchdown [m]
    // Sums and counts of the measured step's samples before and after the plan's half of the load transfer:
    std::array<double, 2> step_sum = {0.0, 0.0};  // [m]
    std::array<int, 2> step_samples = {0, 0};
    double measured_height = 0.0;  // reference + the mean measured step [m]
    double filtered_force = 0.0;
    double planned_ground = 0.0;  // the plan's height of this foot standing (its swing clearance is above it)
    double filtered_torque = 0.0;  // T_y, filtered like the force
    bool settling = false;         // from touchdown until the sole has found its support
    // The foot met the ground before its planned touchdown (latched), so it was loaded from the
    // plan's first cycle of contact; and the time of this stance's settling with the sole loaded [s].
    bool met_early = false;
    double settle_time = 0.0;
    // The partial support's turn (roll, pitch) [rad] and its rate [rad/s], about `pivot`, the
    // (x, y) of the centre of pressure where it began (sensor frame) [m].
    Eigen::Vector2d tilt = Eigen::Vector2d::Zero(), tilt_rate = Eigen::Vector2d::Zero();
    Eigen::Vector2d pivot = Eigen::Vector2d::Zero();
    // The direction (x, y, sensor frame) in which this stance's turn lowers the sole (zero: not started).
    Eigen::Vector2d search_direction = Eigen::Vector2d::Zero();
    Eigen::Vector2d cop_error = Eigen::Vector2d::Zero();  // desired − measured centre of pressure (x, y), filtered [m]
    double load_share = 0.0;       // the plan's share of the load, last cycle
    double filtered_roll_torque = 0.0;  // T_x, filtered like the force
    Eigen::Vector2d slope = Eigen::Vector2d::Zero(), slope_rate = Eigen::Vector2d::Zero();  // (roll, pitch) taken
    Eigen::Vector2d ground_gradient = Eigen::Vector2d::Zero();  // ∂z/∂x, ∂z/∂y of the ground under it, world frame
    Eigen::Vector2d position = Eigen::Vector2d::Zero();  // planned x, y of the current or last foothold [m]
  };
  void set_offset(Foot& foot, double offset, double dt);
  // A standing foot's measured step against the other foot, while both soles lie flat.
  void measure_step(Foot& foot, int k, const PatternSample& s, const std::array<double, 2>& measured_ground);
  bool sole_lies_flat(const Foot& foot, int k) const;
  // Every height the adaptation commands moves together towards the newest measured foothold.
  void shift_to_measured_level(double dt);
  // Edge contact at touchdown: the tilt search, and the tilt's return to zero in the swing.
  void settle(Foot& foot, int k, double dt, const Wrench& desired, bool loading);
  void return_tilt(Foot& foot, double dt);
  // How far the ankle rises as the foot turns by `turn` (roll, pitch) about its pivot [m].
  static double lift_of_ankle(const Foot& foot, const Eigen::Vector2d& turn) {
    return foot.pivot.x() * turn.y() - foot.pivot.y() * turn.x();
  }
  // Standing: the ground's slope from the foot's orientation, while its sole lies flat.
  void measure_slope(Foot& foot, int k, double yaw, const Eigen::Vector2d& turn_above_command);
  // In the air: the slope the foot turns to, and the ground height it aims at (`target`, the stance
  // foot's ground on entry), from the stance foot's slope.
  void take_slope(Foot& foot, const Foot& stance, const FootReference& plan, double dt, double& target);
  // The swing foot's (roll, pitch) moves to `goal`.
  static void turn_to_slope(Foot& foot, const Eigen::Vector2d& goal, double dt);
  // A centre of pressure this far inside the sole's edges means the sole lies flat [m].
  static constexpr double kFlatSoleMargin = 0.02;
  static constexpr double kSlopeAgreement = 0.5;  // share of the slope's height the footholds' heights may lag
  // A side slope this many times min_slope is one, not force control's turn on level ground (about
  // a degree): its drop is aimed at before the footholds show it.
  static constexpr double kSteepSideSlope = 1.5;
  // A foot without a trusted F/T reading: see step(). `other_trusted`: the other foot's is.
  void follow_plan(Foot& foot, const Foot& other, const FootReference& plan, double ground_above_command, double dt,
                   bool other_trusted);
  // Share of the weight above the F/T sensors the other foot no longer carries that means a foot
  // without a trusted reading has met the ground: above the estimate's errors (the upper body's
  // mass known to some 5 %, the CoM's vertical acceleration in the double support).
  static constexpr double kUntrustedContactShare = 0.2;
  static constexpr double kLevelSpeed = 0.02;  // [m/s] that shift's speed at most
  static constexpr double kSwingSpeed = 0.5;  // [m/s] a swinging foot's offset moves to its target at most this fast

  static constexpr double kBandToStop = 0.5;  // share of cop_band inside which a started turn stops
  // After an early contact, a support is taken as found only after this many cop_filter_time of
  // loaded settling: the filtered CoP error starts from zero at each touchdown.
  static constexpr double kFilterFill = 2.0;
  // [m] the footholds' heights differ by more than this: a sole may straddle an edge, and the
  // partial support's turn may roll it (tilt_search_roll)
  static constexpr double kStepForRoll = 0.01;
  static constexpr double kTiltReturnTime = 0.05;  // [s] time constant of the tilt's return in the swing

  TerrainAdaptationParams params_;
  double weight_ = 0.0;  // [N] above the F/T sensors
  std::array<double, 2> heel_x_{}, toe_x_{};  // sole edges per foot (sensor frame) [m]
  std::array<double, 2> right_y_{}, left_y_{};  // the soles' right and left edges (sensor frame) [m]
  std::array<Foot, 2> feet_;
  double com_offset_ = 0.0, com_rate_ = 0.0;
  int newest_measured_ = -1;  // the foot whose measurement is the newest (-1: none)
};

}  // namespace biped
