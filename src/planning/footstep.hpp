#pragma once
// What the step sequence planner hands to the walking pattern generator.
#include <Eigen/Core>

#include "model/robot_model.hpp"

namespace biped {

// Per-sequence walking parameters (after LOLA's interface: step time, double-support share,
// CoM height, swing clearance, nominal step width); chosen from the off-line tables.
struct StepParameters {
  double step_time = 0.8;             // [s] one step: single plus double support
  double double_support_ratio = 0.2;  // share of the step time with both feet on the ground
  double com_height = 0.88;           // [m] height of the upper-body mass point above the ground
  double clearance = 0.04;            // [m] swing-foot lift
  // Share of the swing time in which the swing foot travels horizontally (the quintic blend of
  // position and yaw); the lift spans the whole swing. Below 1 the foot has arrived above its
  // foothold while still up and comes down vertically, so a foot that meets a kerb or step edge
  // early does not slide on over it (1: the paper's blend over the whole swing).
  double swing_travel_share = 1.0;
  double step_width = 0.18;           // [m] lateral distance of the feet when walking straight
};

// A foot placed on the ground: where, with which heading, and when it carries load.
struct Footstep {
  Side side = Side::Left;
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  // ankle (foot frame origin) on the ground, world x-y
  double yaw = 0.0;
  double touchdown = 0.0;  // [s] when the foot lands (start of the double support that follows)
};

// A planar pose of the walking "heading frame" (the robot's path).
struct PlanarPose {
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  double yaw = 0.0;
};

}  // namespace biped
