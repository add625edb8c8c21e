#include "control/terrain_adaptation.hpp"

#include <algorithm>
#include <cmath>

namespace biped {

TerrainAdaptation::TerrainAdaptation(const RobotModel& model, const TerrainAdaptationParams& params)
    : params_(params), weight_(model.weight_above_sensors()) {
  for (Side side : kSides) {
    heel_x_[index_of(side)] = model.foot(side).sole_x_min;
    toe_x_[index_of(side)] = model.foot(side).sole_x_max;
    right_y_[index_of(side)] = model.foot(side).sole_y_min;
    left_y_[index_of(side)] = model.foot(side).sole_y_max;
  }
}

void TerrainAdaptation::reset() {
  feet_ = {};
  com_offset_ = com_rate_ = 0.0;
  newest_measured_ = -1;
}

void TerrainAdaptation::follow_plan(Foot& foot, const Foot& other, const FootReference& plan,
                                    double ground_above_command, double dt, bool other_trusted) {
  foot.settling = false;
  foot.search_direction.setZero();
  foot.cop_error.setZero();
  foot.measuring = foot.measured = false;
  if (plan.in_contact) {
    foot.tilt_rate.setZero();
    foot.slope_rate.setZero();
    if (foot.phase == Phase::Swing || foot.phase == Phase::Latched) {
      foot.phase = Phase::Searching;
      foot.search_time = 0.0;
      foot.planned_ground = plan.position.z();
    }
    if (foot.phase == Phase::Searching) {
      // Late ground, found by the load the other foot gives up: without it the plan shifts the
      // weight onto a foot still in the air.
      const bool loaded = weight_ - other.filtered_force > kUntrustedContactShare * weight_;
      const double lowest = other.ground - params_.max_step;
      foot.search_time += dt;
      if (!other_trusted || loaded || foot.offset <= lowest) {
        foot.phase = Phase::Stance;
        foot.ground = foot.offset + ground_above_command;
      } else if (foot.search_time > params_.search_delay) {
        set_offset(foot, std::max(foot.offset - params_.search_speed * dt, lowest), dt);
        return;
      }
    }
    foot.rate = 0.0;
    return;
  }
  foot.phase = Phase::Swing;
  return_tilt(foot, dt);
  turn_to_slope(foot, Eigen::Vector2d::Zero(), dt);
  set_offset(foot, foot.offset + std::clamp(other.ground - foot.offset, -kSwingSpeed * dt, kSwingSpeed * dt), dt);
}

void TerrainAdaptation::settle(Foot& foot, int k, double dt, const Wrench& desired, bool loading) {
  foot.tilt_rate.setZero();
  if (!foot.settling) return;
  if (foot.filtered_force <= params_.contact_force || desired.force.z() <= params_.contact_force) return;
  foot.settle_time += dt;
  // Sensor frame: T_x = y_CoP F_z, T_y = −x_CoP F_z. The error is filtered: landing on flat ground
  // moves the centre of pressure for a few tens of milliseconds, a missing support keeps it away.
  const Eigen::Vector2d cop(-foot.filtered_torque / foot.filtered_force, foot.filtered_roll_torque / foot.filtered_force);
  Eigen::Vector2d error(-desired.torque.y() / desired.force.z() - cop.x(), desired.torque.x() / desired.force.z() - cop.y());
  // Sideways only where this foothold's ground differs from the other's (a step found): on level
  // ground a centre of pressure held at the sole's side is a push, and rolling the foot about that
  // edge tipped LOLA over it.
  const bool at_a_step = std::abs(foot.ground - feet_[1 - k].ground) > kStepForRoll;
  if (!params_.tilt_search_roll || !at_a_step) error.y() = 0.0;
  foot.cop_error += dt / (params_.cop_filter_time + dt) * (error - foot.cop_error);
  // A turn once started goes on until the error along it is well inside the band: stopping at the
  // band's edge leaves the sole as unsupported as it was when the turn began.
  const bool started = !foot.search_direction.isZero();
  const double band = started ? kBandToStop * params_.cop_band : params_.cop_band;
  const double error_along = started ? foot.cop_error.dot(foot.search_direction) : foot.cop_error.norm();
  if (error_along < -band) {
    foot.settling = false;  // a reversal: no further search in this stance
    return;
  }
  if (error_along <= band) {
    // Found, once the load has come over to this foot (the other one has left the ground, or the
    // plan no longer shifts load to it, as when standing after the last step): the tilt holds for
    // this stance. A foot landing on time takes load only as the plan shifts it, so the filtered
    // error has built by then; one that met a step's top early is loaded from the plan's first
    // cycle of contact, when the plan's share has not risen yet, and ended its settling there with
    // its sole on the edge (JOHNNIE, steps up crossed at an angle: no turn at all). It waits for
    // the filter.
    const bool filled = !foot.met_early || foot.settle_time >= kFilterFill * params_.cop_filter_time;
    if (!loading && filled) foot.settling = false;
    return;
  }
  if (!started) {
    // Turning starts about the present centre of pressure: the edge of the support the sole has.
    foot.search_direction = foot.cop_error.normalized();
    foot.pivot = Eigen::Vector2d(std::clamp(cop.x(), heel_x_[k], toe_x_[k]), std::clamp(cop.y(), right_y_[k], left_y_[k]));
  }
  // Lowering the sole along d (x, y): pitch toes down by d_x, roll (left edge up) by −d_y.
  const Eigen::Vector2d turn(-foot.search_direction.y(), foot.search_direction.x());
  Eigen::Vector2d tilt = foot.tilt + params_.tilt_search_speed * dt * turn;
  if (tilt.norm() > params_.max_tilt) tilt *= params_.max_tilt / tilt.norm();
  if (tilt == foot.tilt) {
    foot.settling = false;  // the bound: no further search in this stance
    return;
  }
  foot.tilt_rate = (tilt - foot.tilt) / dt;
  foot.tilt = tilt;
}

void TerrainAdaptation::measure_slope(Foot& foot, int k, double yaw, const Eigen::Vector2d& turn_above_command) {
  if (foot.settling || foot.filtered_force <= params_.contact_force) return;
  // Sensor frame: T_x = y_CoP F_z, T_y = −x_CoP F_z.
  const double x = -foot.filtered_torque / foot.filtered_force;
  const double y = foot.filtered_roll_torque / foot.filtered_force;
  if (x < heel_x_[k] + kFlatSoleMargin || x > toe_x_[k] - kFlatSoleMargin || y < right_y_[k] + kFlatSoleMargin ||
      y > left_y_[k] - kFlatSoleMargin) {
    return;  // on an edge the sole may be rolling off: its orientation is not the ground's
  }
  // The sole's (roll, pitch) as commanded: the slope it took, its tilt, force control's turn.
  const Eigen::Vector2d orientation = foot.slope + foot.tilt + turn_above_command;
  const Eigen::Vector2d along_foot(-std::tan(orientation.y()), std::tan(orientation.x()));
  const double c = std::cos(yaw), s = std::sin(yaw);
  Eigen::Vector2d gradient(c * along_foot.x() - s * along_foot.y(), s * along_foot.x() + c * along_foot.y());
  const double bound = std::tan(params_.max_slope);
  if (gradient.norm() > bound) gradient *= bound / gradient.norm();
  if (gradient.allFinite()) foot.ground_gradient = gradient;
}

void TerrainAdaptation::take_slope(Foot& foot, const Foot& stance, const FootReference& plan, double dt,
                                   double& target) {
  Eigen::Vector2d goal = Eigen::Vector2d::Zero();
  // Only where the ground descends from the stance foot: a foot that meets its ground early is
  // held there (the latch) and its tilt search turns it onto an upward slope; one that meets it late
  // lets the robot fall into the step. Not on level ground: there force control's turn, which
  // follows the upper body's sway, reads as slopes of up to about a degree, and aiming lower by
  // them walked the footholds' estimate down (1.9 cm in 20 s at 0.6 m/s).
  // And only a slope the footholds' heights agree with: a sole turned about a step's edge lies like
  // one on a slope (a foot landing with only its heel on the upper level of a 2 cm step down turns
  // 4–5° toes down until its toe finds the lower level), but the ankle has not come down with it.
  // The footholds' heights lag a real slope (a late foot stops where it finds support), hence the
  // share.
  const Eigen::Vector2d& gradient = stance.ground_gradient;
  const double predicted = gradient.dot(stance.position - foot.position);
  const bool agrees = std::abs(predicted - (stance.ground - foot.ground)) <=
                      kSlopeAgreement * std::abs(predicted) + params_.slope_tolerance;
  const double descent = gradient.dot(plan.position.head<2>() - stance.position);
  const bool slope_known = gradient.norm() > std::tan(params_.min_slope) && agrees;
  const Eigen::Vector2d forward(std::cos(plan.yaw), std::sin(plan.yaw)), left(-forward.y(), forward.x());
  if (params_.predict_slope && descent < 0.0 && slope_known) {
    goal = Eigen::Vector2d(std::atan(gradient.dot(left)), -std::atan(gradient.dot(forward)));
    target += descent;
  } else if (params_.take_side_slope && slope_known) {
    // Not descending, the foot still rolls to the ground's side slope: landing level on it, its
    // uphill edge would touch first, the centre of pressure held there pushing the CoM downhill at
    // every touchdown, and no search turns a sole about its long axis.
    const double side_gradient = gradient.dot(left);
    goal.x() = std::atan(side_gradient);
    // Only on a side slope clearly steeper than the least one taken, or where this foot's last
    // foothold lay lower than the stance foot's by more than the tolerance already: on level ground
    // force control's turn reads as slopes of about a degree, and aiming lower by them walked
    // JVRC-1's footholds 3 cm down in 20 s.
    const double side_descent = side_gradient * (plan.position.head<2>() - stance.position).dot(left);
    const bool lower_before = stance.ground - foot.ground > params_.slope_tolerance;
    const bool steep = std::abs(side_gradient) > std::tan(kSteepSideSlope * params_.min_slope);
    if (params_.side_slope_height && descent < 0.0 && side_descent < 0.0 && (lower_before || steep)) {
      target += std::max(descent, side_descent);
    }
  }
  turn_to_slope(foot, goal, dt);
}

void TerrainAdaptation::turn_to_slope(Foot& foot, const Eigen::Vector2d& goal, double dt) {
  // Critically damped, as the tilt's return.
  const double w = 1.0 / kTiltReturnTime;
  foot.slope_rate += dt * (w * w * (goal - foot.slope) - 2.0 * w * foot.slope_rate);
  foot.slope += dt * foot.slope_rate;
}

void TerrainAdaptation::return_tilt(Foot& foot, double dt) {
  // Critically damped, so the return starts without a jerk.
  const double w = 1.0 / kTiltReturnTime;
  foot.tilt_rate += dt * (-w * w * foot.tilt - 2.0 * w * foot.tilt_rate);
  foot.tilt += dt * foot.tilt_rate;
}

void TerrainAdaptation::set_offset(Foot& foot, double offset, double dt) {
  foot.rate = (offset - foot.offset) / dt;
  foot.offset = offset;
}

void TerrainAdaptation::step(double dt, const PatternSample& s, const std::array<Wrench, 2>& measured,
                             const std::array<Wrench, 2>& desired, const std::array<double, 2>& ground_above_command,
                             const std::array<bool, 2>& trusted, const std::array<Eigen::Vector2d, 2>& turn_above_command,
                             const std::array<double, 2>& measured_ground) {
  if (!params_.enabled) return;
  const double filter = dt / (params_.filter_time + dt);
  for (int k = 0; k < 2; ++k) {
    Foot& foot = feet_[k];
    const Foot& other = feet_[1 - k];
    const FootReference& plan = s.feet[k];
    // The plan is shifting load onto this foot (the double support after its touchdown).
    const bool loading = s.feet[1 - k].in_contact && s.load_share[k] > foot.load_share;
    foot.load_share = s.load_share[k];
    foot.filtered_force += filter * (measured[k].force.z() - foot.filtered_force);
    foot.filtered_torque += filter * (measured[k].torque.y() - foot.filtered_torque);
    foot.filtered_roll_torque += filter * (measured[k].torque.x() - foot.filtered_roll_torque);
    if (plan.in_contact) foot.position = plan.position.head<2>();
    if (!trusted[k]) {
      follow_plan(foot, other, plan, ground_above_command[k], dt, trusted[1 - k]);
      continue;
    }
    const bool contact = foot.filtered_force > params_.contact_force;
    const double lowest = other.ground - params_.max_step, highest = other.ground + params_.max_step;
    if (!plan.in_contact) {
      if (foot.phase == Phase::Stance) foot.phase = Phase::Swing;
      foot.settling = true;
      foot.settle_time = 0.0;
      foot.search_direction.setZero();
      foot.cop_error.setZero();
      return_tilt(foot, dt);
      if (foot.phase == Phase::Swing) {
        // Aim at the ground the stance foot stands on. A higher target is reached while the foot
        // rises; a lower one only while it descends, in proportion to the planned descent, so the
        // foot neither pushes into the ground it lifts off from nor jerks.
        double target = other.ground;
        take_slope(foot, other, plan, dt, target);
        const double clearance = plan.position.z() - foot.planned_ground;
        if (plan.velocity.z() < 0.0 && clearance > 0.0) {
          const double share = std::min(1.0, -plan.velocity.z() * dt / clearance);
          set_offset(foot, foot.offset + share * (target - foot.offset), dt);
        } else if (target > foot.offset) {
          set_offset(foot, std::min(target, foot.offset + kSwingSpeed * dt), dt);
        } else {
          foot.rate = 0.0;
        }
        if (contact && plan.velocity.z() < 0.0) {
          foot.phase = Phase::Latched;
          foot.latched_height = plan.position.z() + foot.offset;
        }
      }
      if (foot.phase == Phase::Latched) {
        foot.slope_rate.setZero();
        set_offset(foot, std::min(foot.latched_height - plan.position.z(), highest), dt);
      }
    } else {
      foot.planned_ground = plan.position.z();
      foot.slope_rate.setZero();
      // A foot that met the ground early but lost it again by the planned touchdown (it brushed
      // the ground) searches like one that met none.
      if (foot.phase == Phase::Swing || foot.phase == Phase::Latched) {
        foot.met_early = foot.phase == Phase::Latched && contact;
        foot.phase = contact ? Phase::Stance : Phase::Searching;
        foot.search_time = 0.0;
        foot.measuring = true;
        foot.measured = false;
        foot.reference = other.measured ? other.measured_height : other.ground;
        foot.step_sum = {0.0, 0.0};
        foot.step_samples = {0, 0};
      }
      // A foot that loses its contact again before it found its support (it met the ground on one
      // edge and bounced off) while the plan shifts load onto it searches again: position control
      // alone would leave it hanging where it first touched.
      if (foot.phase == Phase::Stance && foot.settling && !contact && desired[k].force.z() > params_.contact_force) {
        foot.phase = Phase::Searching;
        foot.search_time = 0.0;
      }
      if (foot.phase == Phase::Searching) {
        foot.search_time += dt;
        if (contact || foot.offset <= lowest) {
          foot.phase = Phase::Stance;
        } else if (foot.search_time > params_.search_delay) {
          set_offset(foot, std::max(foot.offset - params_.search_speed * dt, lowest), dt);
        } else {
          foot.rate = 0.0;
        }
      }
      if (foot.phase == Phase::Stance) {
        // Force control lowers or raises the foot onto the ground on top of the offset.
        foot.ground = foot.offset + ground_above_command[k];
        foot.rate = 0.0;
        measure_step(foot, k, s, measured_ground);
        settle(foot, k, dt, desired[k], loading);
        measure_slope(foot, k, plan.yaw, turn_above_command[k]);
      }
    }
  }
  if (!trusted[0] && !trusted[1]) {
    com_rate_ = 0.0;
    return;
  }
  const double mean_ground = 0.5 * (feet_[0].ground + feet_[1].ground);
  com_rate_ = (mean_ground - com_offset_) / params_.com_follow_time;
  com_offset_ += com_rate_ * dt;
  shift_to_measured_level(dt);
}

bool TerrainAdaptation::sole_lies_flat(const Foot& foot, int k) const {
  if (foot.filtered_force <= params_.contact_force) return false;
  const double x = -foot.filtered_torque / foot.filtered_force;  // T_y = −x_CoP F_z, sensor frame
  return x > heel_x_[k] + kFlatSoleMargin && x < toe_x_[k] - kFlatSoleMargin;
}

void TerrainAdaptation::measure_step(Foot& foot, int k, const PatternSample& s,
                                     const std::array<double, 2>& measured_ground) {
  const Foot& other = feet_[1 - k];
  if (!s.feet[1 - k].in_contact) foot.measuring = false;  // the step ends with the other foot's lift-off
  // Both soles flat on the ground: a sole rolling over its edge lies above the ground under its
  // sensor, one landing on its heel not yet on it.
  if (!params_.measure_step_height || !foot.measuring || other.phase != Phase::Stance || !sole_lies_flat(foot, k) ||
      !sole_lies_flat(other, 1 - k) || !std::isfinite(measured_ground[k]) || !std::isfinite(measured_ground[1 - k])) {
    return;
  }
  // The samples from the plan's half of the load transfer on where there are any: early on, with
  // one sole loaded on its heel and the other on its toe, the soles' sinks depart most from the
  // contact model (LOLA, exact sensors: 0.4 mm per step against 0.1 later).
  const int half = s.load_share[k] < 0.5 ? 0 : 1;
  foot.step_sum[half] += measured_ground[k] - measured_ground[1 - k] - (foot.planned_ground - other.planned_ground);
  ++foot.step_samples[half];
  const int used = foot.step_samples[1] > 0 ? 1 : 0;
  foot.measured_height = foot.reference + foot.step_sum[used] / foot.step_samples[used];
  foot.measured = true;
  newest_measured_ = k;
}

void TerrainAdaptation::level_standing_feet(double dt, const std::array<double, 2>& measured_ground) {
  if (!params_.enabled || !params_.level_standing_feet) return;
  Foot& left = feet_[0];
  Foot& right = feet_[1];
  if (left.phase != Phase::Stance || right.phase != Phase::Stance || !sole_lies_flat(left, 0) ||
      !sole_lies_flat(right, 1) || !std::isfinite(measured_ground[0]) || !std::isfinite(measured_ground[1])) {
    return;
  }
  const double measured_step = measured_ground[0] - measured_ground[1] - (left.planned_ground - right.planned_ground);
  const double error = measured_step - (left.ground - right.ground);
  const double beyond = std::copysign(std::max(0.0, std::abs(error) - params_.standing_level_dead_band), error);
  const double limit = params_.standing_level_speed * dt;
  const double change = std::clamp(beyond * dt / params_.standing_level_time, -limit, limit);
  for (int k = 0; k < 2; ++k) {
    Foot& foot = feet_[k];
    const double share = k == 0 ? 0.5 * change : -0.5 * change;
    foot.offset += share;
    foot.rate += share / dt;
    foot.ground += share;
    foot.latched_height += share;
  }
}

void TerrainAdaptation::shift_to_measured_level(double dt) {
  if (newest_measured_ < 0 || !feet_[newest_measured_].measured) return;
  const Foot& newest = feet_[newest_measured_];
  const double shift = std::clamp(newest.measured_height - newest.ground, -kLevelSpeed * dt, kLevelSpeed * dt);
  for (Foot& foot : feet_) {
    foot.offset += shift;
    foot.rate += shift / dt;
    foot.ground += shift;
    foot.latched_height += shift;
  }
  com_offset_ += shift;
  com_rate_ += shift / dt;
}

}  // namespace biped
