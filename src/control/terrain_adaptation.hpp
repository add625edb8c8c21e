#pragma once
// Adaptation to ground heights the controller is not told about (steps, slopes). The pattern plans
// every foothold at the height of the ground it was planned for; the F/T sensors tell where the
// ground really is:
//  - early contact: a swing foot that meets the ground while descending stops there (its height is
//    latched while the plan would move it further down);
//  - late contact: a foot that finds no ground at the planned touchdown keeps descending at a search
//    speed until it does;
//  - the foot's height at touchdown is the ground height of that foothold; the next swing foot aims
//    at the ground height of the stance foot, and the CoM height follows the mean ground height of
//    the footholds, so the legs keep their planned length.
// The outputs are height offsets added to the feet's and the CoM's planned heights in eq. (21);
// force control (eq. 20) acts on top of them.
#include <array>

#include "math/wrench.hpp"
#include "planning/walking_pattern_generator.hpp"

namespace biped {

struct TerrainAdaptationParams {
  bool enabled = true;
  double contact_force = 60.0;    // [N] filtered normal force that means ground contact
  double filter_time = 0.005;     // [s] first-order filter of the normal force
  double search_speed = 0.25;     // [m/s] descent of a foot that found no ground at touchdown
  double max_step = 0.05;         // [m] bound of a foothold's height against the other foot's
  double com_follow_time = 0.3;   // [s] time constant of the CoM height following the footholds
};

class TerrainAdaptation {
 public:
  explicit TerrainAdaptation(const TerrainAdaptationParams& params) : params_(params) {}
  void reset();
  // One cycle with the pattern's sample and the measured contact wrenches.
  void step(double dt, const PatternSample& s, const std::array<Wrench, 2>& measured);
  // Without trusted force readings: standing feet keep their offsets, a foot in the air goes to the
  // other foot's ground height.
  void hold(double dt);

  // Offsets of the planned heights [m] and their rates [m/s]: per foot (by Side) and of the CoM.
  double foot_offset(int k) const { return feet_[k].offset; }
  double foot_offset_rate(int k) const { return feet_[k].rate; }
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
    double filtered_force = 0.0;
  };
  void set_offset(Foot& foot, double offset, double dt);
  static constexpr double kSwingSpeed = 0.5;  // [m/s] a swinging foot's offset moves to its target at most this fast

  TerrainAdaptationParams params_;
  std::array<Foot, 2> feet_;
  double com_offset_ = 0.0, com_rate_ = 0.0;
};

}  // namespace biped
