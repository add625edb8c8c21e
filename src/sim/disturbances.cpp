#include "sim/disturbances.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "math/rotations.hpp"

namespace biped {

void GaitEvents::reset() { *this = GaitEvents{}; }

void GaitEvents::update(double t, const std::array<double, 2>& normal_force) {
  double event_time = t;
  for (int k = 0; k < 2; ++k) {
    // A pending change starts at its threshold and is called off only by the opposite one.
    const bool starts = in_contact_[k] ? normal_force[k] < kLiftoffN : normal_force[k] > kTouchdownN;
    const bool called_off = in_contact_[k] ? normal_force[k] > kTouchdownN : normal_force[k] < kLiftoffN;
    if (called_off) change_since_[k] = -1.0;
    if (starts && change_since_[k] < 0.0) change_since_[k] = t;
    if (change_since_[k] < 0.0 || t - change_since_[k] < kConfirmS - 1e-9) continue;
    in_contact_[k] = !in_contact_[k];
    if (in_contact_[k]) ++touchdowns_;
    event_time = change_since_[k];
    change_since_[k] = -1.0;
  }
  const bool single = in_contact_[0] != in_contact_[1];
  if (single && !single_support_) {
    support_start_ = event_time;
    ++supports_started_;
    touchdowns_at_support_start_ = touchdowns_;
  } else if (!single && single_support_) {
    last_duration_ = event_time - support_start_;
  }
  single_support_ = single;
}

PushSchedule::PushSchedule(const RobotModel& plant, std::vector<Push> pushes)
    : plant_(plant), pushes_(std::move(pushes)) {
  for (const Push& push : pushes_) {
    const int body = plant_.body_named(push.body);
    if (body < 0) throw ModelError(plant_.path() + ": push on unknown body '" + push.body + "'");
    body_.push_back(body);
  }
  reset();
}

void PushSchedule::reset() {
  start_.assign(pushes_.size(), std::numeric_limits<double>::quiet_NaN());
  world_force_.assign(pushes_.size(), Eigen::Vector3d::Zero());
}

void PushSchedule::apply(mjData* d, const GaitEvents& gait) {
  const double t = d->time;
  for (std::size_t k = 0; k < pushes_.size(); ++k) {
    const Push& push = pushes_[k];
    if (std::isnan(start_[k])) {
      double start = push.t;
      if (push.at_gait_moment) {
        // Planned once its single support has begun and the one before it is known.
        const GaitMoment& g = push.moment;
        const bool this_support = gait.single_support() && gait.last_single_support_duration() > 0.0 &&
                                  (g.touchdown >= 0 ? gait.touchdowns_before_current_support() >= g.touchdown
                                                    : gait.single_support_start() >= g.after_time);
        if (!this_support) continue;
        start = std::max(t, gait.single_support_start() + g.phase * gait.last_single_support_duration());
      }
      if (t < start - 1e-9) continue;
      start_[k] = start;
      Eigen::Vector3d force = push.force;
      if (push.heading_frame) {
        const double yaw = math::heading_of(math::mat_from_mujoco(d->xmat + 9 * plant_.pelvis_body()));
        force = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * force;
      }
      world_force_[k] = force;
    }
    if (t >= start_[k] + push.duration - 1e-9) continue;
    const int b = body_[k];
    const Eigen::Vector3d& f = world_force_[k];
    for (int a = 0; a < 3; ++a) d->xfrc_applied[6 * b + a] += f[a];
    if (push.at_point) {
      // xfrc_applied acts at the body's CoM: a force elsewhere adds its moment about the CoM.
      const Eigen::Vector3d point =
          Eigen::Vector3d(d->xpos + 3 * b) + math::mat_from_mujoco(d->xmat + 9 * b) * push.point;
      const Eigen::Vector3d torque = (point - Eigen::Vector3d(d->xipos + 3 * b)).cross(f);
      for (int a = 0; a < 3; ++a) d->xfrc_applied[6 * b + 3 + a] += torque[a];
    }
  }
}

}  // namespace biped
