#include "control/terrain_adaptation.hpp"

#include <algorithm>

namespace biped {

TerrainAdaptation::TerrainAdaptation(const RobotModel& model, const TerrainAdaptationParams& params) : params_(params) {
  for (Side side : kSides) {
    heel_x_[index_of(side)] = model.foot(side).sole_x_min;
    toe_x_[index_of(side)] = model.foot(side).sole_x_max;
  }
}

void TerrainAdaptation::reset() {
  feet_ = {};
  com_offset_ = com_rate_ = 0.0;
}

void TerrainAdaptation::hold(double dt) {
  // A foot that was not standing when the readings stopped being trusted goes to the height of the
  // ground the other foot stands on, so that it lands there.
  for (int k = 0; k < 2; ++k) {
    Foot& foot = feet_[k];
    if (foot.phase == Phase::Stance) {
      foot.rate = foot.tilt_rate = 0.0;
      continue;
    }
    return_tilt(foot, dt);
    const double target = feet_[1 - k].ground;
    set_offset(foot, foot.offset + std::clamp(target - foot.offset, -kSwingSpeed * dt, kSwingSpeed * dt), dt);
  }
  com_rate_ = 0.0;
}

void TerrainAdaptation::settle(Foot& foot, int k, double dt) {
  foot.tilt_rate = 0.0;
  if (!foot.settling || foot.filtered_force <= params_.contact_force) return;
  // T_y = −x_CoP F_z in the sensor frame.
  const double cop = -foot.filtered_torque / foot.filtered_force;
  double direction = 0.0;
  if (cop < heel_x_[k] + params_.edge_band) {
    direction = 1.0;  // on the heel edge only: toes down
    foot.pivot = heel_x_[k];
  } else if (cop > toe_x_[k] - params_.edge_band) {
    direction = -1.0;  // on the toe edge only: heel down
    foot.pivot = toe_x_[k];
  }
  const double tilt = std::clamp(foot.tilt + direction * params_.tilt_search_speed * dt, -params_.max_tilt, params_.max_tilt);
  // The sole has found its support (or the bound is reached): the tilt holds for this stance.
  if (direction == 0.0 || tilt == foot.tilt) {
    foot.settling = false;
    return;
  }
  foot.tilt_rate = (tilt - foot.tilt) / dt;
  foot.tilt = tilt;
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
                             const std::array<double, 2>& height_modification) {
  if (!params_.enabled) return;
  const double filter = dt / (params_.filter_time + dt);
  for (int k = 0; k < 2; ++k) {
    Foot& foot = feet_[k];
    const Foot& other = feet_[1 - k];
    const FootReference& plan = s.feet[k];
    foot.filtered_force += filter * (measured[k].force.z() - foot.filtered_force);
    foot.filtered_torque += filter * (measured[k].torque.y() - foot.filtered_torque);
    const bool contact = foot.filtered_force > params_.contact_force;
    const double lowest = other.ground - params_.max_step, highest = other.ground + params_.max_step;
    if (!plan.in_contact) {
      if (foot.phase == Phase::Stance) foot.phase = Phase::Swing;
      foot.settling = true;
      return_tilt(foot, dt);
      if (foot.phase == Phase::Swing) {
        // Aim at the ground the stance foot stands on. A higher target is reached while the foot
        // rises; a lower one only while it descends, in proportion to the planned descent, so the
        // foot neither pushes into the ground it lifts off from nor jerks.
        const double target = other.ground;
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
        set_offset(foot, std::min(foot.latched_height - plan.position.z(), highest), dt);
      }
    } else {
      foot.planned_ground = plan.position.z();
      if (foot.phase == Phase::Swing) foot.phase = contact ? Phase::Stance : Phase::Searching;
      if (foot.phase == Phase::Latched) foot.phase = Phase::Stance;
      if (foot.phase == Phase::Searching) {
        if (contact || foot.offset <= lowest) {
          foot.phase = Phase::Stance;
        } else {
          set_offset(foot, std::max(foot.offset - params_.search_speed * dt, lowest), dt);
        }
      }
      if (foot.phase == Phase::Stance) {
        // Force control lowers or raises the foot onto the ground on top of the offset.
        foot.ground = foot.offset + height_modification[k];
        foot.rate = 0.0;
        settle(foot, k, dt);
      }
    }
  }
  const double mean_ground = 0.5 * (feet_[0].ground + feet_[1].ground);
  com_rate_ = (mean_ground - com_offset_) / params_.com_follow_time;
  com_offset_ += com_rate_ * dt;
}

}  // namespace biped
