#pragma once
// The reference of eq. (21) in the task coordinates of Table I: x_id and ẋ_id from the walking
// pattern (feet and CoM, the heading, the arms swinging against the legs) with the terrain
// adaptation's height and tilt offsets, and Δx, Δẋ: the stabilizer's foot modifications S̄ᵀΔx_λ of
// eq. (20) placed in the foot rows.
#include <Eigen/Core>
#include <array>

#include "control/stabilizer.hpp"
#include "control/terrain_adaptation.hpp"
#include "control/upper_body_lean.hpp"
#include "model/task_space.hpp"
#include "planning/walking_pattern_generator.hpp"

namespace biped {

class TaskReference {
 public:
  explicit TaskReference(const TaskSpace& space);

  // Takes the arms' geometry from the start configuration (`start` evaluated there): their CoM
  // offsets and shoulder pitch axes relative to the upper body, in the heading frame `heading`.
  // Clears the modification.
  void reset(const TaskSpaceData& start, double heading);

  // x_id, ẋ_id for the pattern sample. `kinematic_state` is eq. (21)'s own state of the last cycle:
  // the arms are placed relative to its upper body and CoM. The upper body leans by `lean` (zero
  // in the paper); the feet's orientations, relative to it, turn back so the feet keep theirs, and
  // the arms turn with it.
  void update(const PatternSample& s, const TerrainAdaptation& terrain, const UpperBodyLean& lean,
              const TaskSpaceData& kinematic_state);

  // Δx, Δẋ: each foot's height and tilt modification (foot frame) in its task rows, the tilt
  // turned into the upper body's heading frame.
  void set_modification(const PatternSample& s, const std::array<FootModification, 2>& modification);
  // Without force feedback the modification returns to the plan: Δx ← factor·Δx, Δẋ = 0.
  void decay_modification(double factor);

  const Eigen::VectorXd& x() const { return x_id_; }
  const Eigen::VectorXd& rate() const { return xdot_id_; }
  const Eigen::VectorXd& modification() const { return delta_x_; }
  const Eigen::VectorXd& modification_rate() const { return delta_xdot_; }

 private:
  const TaskSpace& space_;
  std::array<Eigen::Vector3d, 2> arm_offset_;  // arm CoM − upper body origin, heading frame
  std::array<Eigen::Vector3d, 2> arm_pivot_;   // shoulder pitch axis − upper body origin, heading frame
  Eigen::VectorXd x_id_, xdot_id_, delta_x_, delta_xdot_;
};

}  // namespace biped
