#include "control/terrain_adaptation.hpp"

#include <algorithm>

namespace biped {

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
      foot.rate = 0.0;
      continue;
    }
    const double target = feet_[1 - k].ground;
    set_offset(foot, foot.offset + std::clamp(target - foot.offset, -kSwingSpeed * dt, kSwingSpeed * dt), dt);
  }
  com_rate_ = 0.0;
}

void TerrainAdaptation::set_offset(Foot& foot, double offset, double dt) {
  foot.rate = (offset - foot.offset) / dt;
  foot.offset = offset;
}

void TerrainAdaptation::step(double dt, const PatternSample& s, const std::array<Wrench, 2>& measured) {
  if (!params_.enabled) return;
  const double filter = dt / (params_.filter_time + dt);
  for (int k = 0; k < 2; ++k) {
    Foot& foot = feet_[k];
    const Foot& other = feet_[1 - k];
    const FootReference& plan = s.feet[k];
    foot.filtered_force += filter * (measured[k].force.z() - foot.filtered_force);
    const bool contact = foot.filtered_force > params_.contact_force;
    const double lowest = other.ground - params_.max_step, highest = other.ground + params_.max_step;
    if (!plan.in_contact) {
      if (foot.phase == Phase::Stance) foot.phase = Phase::Swing;
      if (foot.phase == Phase::Swing) {
        // Aim at the ground the stance foot stands on; lift-off lets the force fade first.
        const double target = other.ground;
        set_offset(foot, foot.offset + std::clamp(target - foot.offset, -kSwingSpeed * dt, kSwingSpeed * dt), dt);
        if (contact && plan.velocity.z() < 0.0) {
          foot.phase = Phase::Latched;
          foot.latched_height = plan.position.z() + foot.offset;
        }
      }
      if (foot.phase == Phase::Latched) {
        set_offset(foot, std::min(foot.latched_height - plan.position.z(), highest), dt);
      }
    } else {
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
        foot.ground = foot.offset;
        foot.rate = 0.0;
      }
    }
  }
  const double mean_ground = 0.5 * (feet_[0].ground + feet_[1].ground);
  com_rate_ = (mean_ground - com_offset_) / params_.com_follow_time;
  com_offset_ += com_rate_ * dt;
}

}  // namespace biped
