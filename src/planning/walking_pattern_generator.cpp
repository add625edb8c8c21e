#include "planning/walking_pattern_generator.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Geometry>

#include "math/rotations.hpp"
#include "model/kinematics.hpp"

namespace biped {
namespace {

// Quintic blend 0 → 1 with zero velocity and acceleration at both ends; derivatives w.r.t. τ.
void quintic(double tau, double& s, double& ds, double& dds) {
  s = tau * tau * tau * (10.0 + tau * (-15.0 + 6.0 * tau));
  ds = 30.0 * tau * tau * (1.0 - tau) * (1.0 - tau);
  dds = 60.0 * tau * (1.0 - tau) * (1.0 - 2.0 * tau);
}

// Swing height profile 64 τ³(1−τ)³ (1 at mid-swing), zero velocity and acceleration at both ends.
void lift(double tau, double& l, double& dl, double& ddl) {
  const double a = tau * (1.0 - tau);
  l = 64.0 * a * a * a;
  dl = 64.0 * 3.0 * a * a * (1.0 - 2.0 * tau);
  ddl = 64.0 * 6.0 * a * (1.0 - 5.0 * tau + 5.0 * tau * tau);
}

}  // namespace

WalkingPatternGenerator::WalkingPatternGenerator(const PatternGeneratorParams& params)
    : params_(params),
      collocation_(params.collocation_intervals),
      rhs_x_(Eigen::VectorXd::Zero(params.collocation_intervals + 1)),
      rhs_y_(Eigen::VectorXd::Zero(params.collocation_intervals + 1)),
      coeff_x_(Eigen::VectorXd::Zero(params.collocation_intervals + 3)),
      coeff_y_(Eigen::VectorXd::Zero(params.collocation_intervals + 3)),
      shape1_(Eigen::VectorXd::Zero(params.collocation_intervals + 1)),
      shape2_(Eigen::VectorXd::Zero(params.collocation_intervals + 1)),
      knot_height_(Eigen::VectorXd::Zero(params.collocation_intervals + 1)),
      knot_vertical_acc_(Eigen::VectorXd::Zero(params.collocation_intervals + 1)) {}

void WalkingPatternGenerator::body_vertical(double t, double& z, double& velocity, double& acceleration) const {
  z = body_height_;
  velocity = acceleration = 0.0;
  for (int k = 0; k < num_steps_; ++k) {
    const double start = liftoff(k), end = steps_[k].touchdown;
    if (t <= start || t >= end) continue;
    const double duration = end - start;
    double l, dl, ddl;
    lift((t - start) / duration, l, dl, ddl);
    const double a = params_.com_height_variation;
    z += a * l;
    velocity = a * dl / duration;
    acceleration = a * ddl / (duration * duration);
    return;
  }
}

// b₁ fades from 1 to 0 over the first double support (takes up the ZMP at the replanning instant);
// b₂ is a bump over the same double support (steers the divergent mode of the CoM while both feet
// are on the ground, so the modified ZMP stays inside the larger support polygon).
void WalkingPatternGenerator::zmp_shapes(double t, double& b1, double& b2) const {
  const double tau1 = std::clamp((t - t0_) / shape1_duration_, 0.0, 1.0);
  const double tau2 = std::clamp((t - t0_) / shape2_duration_, 0.0, 1.0);
  double s, ds, dds, l, dl, ddl;
  quintic(tau1, s, ds, dds);
  lift(tau2, l, dl, ddl);
  b1 = 1.0 - s;
  b2 = l;
}

Eigen::Vector2d WalkingPatternGenerator::zmp_point(const Footstep& f) const {
  return f.position + params_.zmp_offset_x * Eigen::Vector2d(std::cos(f.yaw), std::sin(f.yaw));
}

void WalkingPatternGenerator::replan(double t0, const std::array<Footstep, 2>& feet,
                                     const std::array<Footstep, kMaxSteps>& steps, int num_steps,
                                     const StepParameters& parameters, const AxisState& body_x,
                                     const AxisState& body_y, const Eigen::Vector2d& zmp_now) {
  t0_ = t0;
  feet_ = feet;
  steps_ = steps;
  num_steps_ = std::clamp(num_steps, 0, kMaxSteps);
  step_params_ = parameters;
  double_support_time_ = parameters.step_time * parameters.double_support_ratio;
  zmp_start_ = zmp_now;
  // The body mass height that puts the model's CoM at the commanded CoM height with both feet down.
  const double m_total = params_.body_mass + 2.0 * params_.leg_mass;
  body_height_ = (m_total * parameters.com_height -
                  2.0 * params_.leg_mass * (params_.ankle_height + params_.leg_com_height)) / params_.body_mass;

  const double last_touchdown = num_steps_ > 0 ? steps_[num_steps_ - 1].touchdown : t0;
  // Coming to rest (no steps), the ZMP moves to the middle of the feet in the settle time.
  const double final_shift = num_steps_ > 0 ? double_support_time_ : std::max(double_support_time_, params_.settle_time);
  const double t_end = last_touchdown + final_shift + params_.final_rest_time;
  collocation_.set_horizon(t0, t_end);
  shape1_duration_ = std::max(num_steps_ > 0 ? liftoff(0) - t0 : final_shift, 0.05);
  shape2_duration_ = num_steps_ > 0 ? shape1_duration_ : 0.5 * (t_end - t0);

  // Dividing the model equation by m_b: z_b ẍ_b − g x_b + W p̃ = −(1/m_b) Σ_i m_i [z_i ẍ_i − x_i (z̈_i + g)]
  // with W = z̈_b + g + (1/m_b) Σ_i m_i (z̈_i + g), p̃ = p + δ₁ b₁ + δ₂ b₂, and the body's prescribed
  // height z_b(t) on the left: z_b ẍ_b − (z̈_b + g) x_b.
  const double g = params_.gravity;
  for (int k = 0; k < collocation_.knots(); ++k) {
    const double t = collocation_.knot_time(k);
    Eigen::Vector2d p;
    double share;
    int phase;
    reference_zmp(t, p, share, phase);
    double z_b, zd_b, zdd_b;
    body_vertical(t, z_b, zd_b, zdd_b);
    knot_height_[k] = z_b;
    knot_vertical_acc_[k] = zdd_b;
    double weight = zdd_b + g;
    Eigen::Vector2d legs = Eigen::Vector2d::Zero();
    for (Side side : kSides) {
      FootReference foot;
      foot_at(side, t, foot);
      const Eigen::Vector3d& acc = foot.acceleration;
      const double z = foot.position.z() + params_.leg_com_height;
      weight += params_.leg_mass * (acc.z() + g) / params_.body_mass;
      for (int a = 0; a < 2; ++a) legs[a] += params_.leg_mass * (z * acc[a] - foot.position[a] * (acc.z() + g));
    }
    rhs_x_[k] = -weight * p.x() - legs.x() / params_.body_mass;
    rhs_y_[k] = -weight * p.y() - legs.y() / params_.body_mass;
    double b1, b2;
    zmp_shapes(t, b1, b2);
    shape1_[k] = b1 * weight / g;
    shape2_[k] = b2 * weight / g;
  }
  collocation_.prepare(knot_height_, knot_vertical_acc_, g, shape1_, shape2_);
  // At rest at the end, the body mass sits where the model's ZMP is the final reference ZMP:
  // x_b = p + (1/m_b) Σ_i m_i (p − x_i) with the legs standing still.
  Eigen::Vector2d p_end;
  double share;
  int phase;
  reference_zmp(t_end, p_end, share, phase);
  Eigen::Vector2d body_end = p_end;
  for (Side side : kSides) {
    FootReference foot;
    foot_at(side, t_end, foot);
    body_end += params_.leg_mass / params_.body_mass * (p_end - foot.position.head<2>());
  }
  collocation_.solve(rhs_x_, body_x.position, body_x.velocity, body_x.acceleration, body_end.x(), coeff_x_,
                     amplitude1_.x(), amplitude2_.x());
  collocation_.solve(rhs_y_, body_y.position, body_y.velocity, body_y.acceleration, body_end.y(), coeff_y_,
                     amplitude1_.y(), amplitude2_.y());
}

// Piecewise-linear reference ZMP: at the stance foot in single support, moving from the old to the
// new stance foot in double support, and to the midpoint of the feet at the end of the horizon.
// `share_of_new`: how far it has moved (the new stance foot's load share); `phase_step`: the step
// whose double support this is (−1: the first double support from t0).
void WalkingPatternGenerator::reference_zmp(double t, Eigen::Vector2d& zmp, double& share_of_new,
                                            int& phase_step) const {
  const double ds = double_support_time_;
  auto blend = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b, double start) {
    share_of_new = std::clamp((t - start) / ds, 0.0, 1.0);
    zmp = a + share_of_new * (b - a);
  };
  if (num_steps_ == 0) {
    phase_step = -1;
    share_of_new = std::clamp((t - t0_) / shape1_duration_, 0.0, 1.0);
    zmp = zmp_start_ + share_of_new * (0.5 * (zmp_point(feet_[0]) + zmp_point(feet_[1])) - zmp_start_);
    return;
  }
  // Before the first step lifts off: from the current ZMP to the first stance foot (a start from
  // standing gets a longer first double support to shift the weight).
  const Footstep& first_stance = feet_[index_of(other(steps_[0].side))];
  const double first_liftoff = liftoff(0);
  if (t < first_liftoff) {
    phase_step = -1;
    share_of_new = std::clamp((t - t0_) / (first_liftoff - t0_), 0.0, 1.0);
    zmp = zmp_start_ + share_of_new * (zmp_point(first_stance) - zmp_start_);
    return;
  }
  Eigen::Vector2d stance = zmp_point(first_stance);
  for (int k = 0; k < num_steps_; ++k) {
    if (t < steps_[k].touchdown) {  // single support on the stance foot
      phase_step = k;
      zmp = stance;
      share_of_new = 0.0;
      return;
    }
    const bool last = k == num_steps_ - 1;
    const Eigen::Vector2d next = last ? 0.5 * (stance + zmp_point(steps_[k])) : zmp_point(steps_[k]);
    if (last || t < steps_[k].touchdown + ds) {
      phase_step = k;
      blend(stance, next, steps_[k].touchdown);
      if (last) share_of_new *= 0.5;  // the ZMP stops halfway: both feet carry half
      return;
    }
    stance = next;
  }
}

double WalkingPatternGenerator::liftoff(int k) const {
  return steps_[k].touchdown - step_params_.step_time * (1.0 - step_params_.double_support_ratio);
}

void WalkingPatternGenerator::foot_at(Side side, double t, FootReference& foot) const {
  Footstep from = feet_[index_of(side)];
  foot.velocity.setZero();
  foot.acceleration.setZero();
  foot.yaw_rate = 0.0;
  foot.in_contact = true;
  foot.swing_progress = foot.swing_progress_rate = foot.time_to_touchdown = 0.0;
  for (int k = 0; k < num_steps_; ++k) {
    if (steps_[k].side != side) continue;
    const double lift_time = liftoff(k);
    const double touchdown = steps_[k].touchdown;
    if (t < lift_time) break;
    if (t >= touchdown) {
      from = steps_[k];
      continue;
    }
    // Swinging from `from` to steps_[k].
    const double duration = touchdown - lift_time;
    const double tau = (t - lift_time) / duration;
    double s, ds_dtau, dds_dtau, l, dl, ddl;
    const double travel = step_params_.swing_travel_share;
    quintic(std::min(tau / travel, 1.0), s, ds_dtau, dds_dtau);
    ds_dtau /= travel;
    dds_dtau /= travel * travel;
    lift(tau, l, dl, ddl);
    const Eigen::Vector2d delta = steps_[k].position - from.position;
    const double dyaw = math::wrap_angle(steps_[k].yaw - from.yaw);
    const double c = step_params_.clearance;
    foot.position << from.position + s * delta, params_.ankle_height + c * l;
    foot.velocity << ds_dtau / duration * delta, c * dl / duration;
    foot.acceleration << dds_dtau / (duration * duration) * delta, c * ddl / (duration * duration);
    foot.yaw = math::wrap_angle(from.yaw + s * dyaw);
    foot.yaw_rate = ds_dtau / duration * dyaw;
    foot.in_contact = false;
    foot.swing_progress = s;
    foot.swing_progress_rate = ds_dtau / duration;
    foot.time_to_touchdown = touchdown - t;
    return;
  }
  foot.position << from.position, params_.ankle_height;
  foot.yaw = from.yaw;
}

void WalkingPatternGenerator::sample(double t, PatternSample& out) const {
  const double g = params_.gravity;
  collocation_.evaluate(coeff_x_, t, out.body_x.position, out.body_x.velocity, out.body_x.acceleration);
  collocation_.evaluate(coeff_y_, t, out.body_y.position, out.body_y.velocity, out.body_y.acceleration);
  if (t >= collocation_.t_end()) {  // the plan ends at rest and stays there
    out.body_x.velocity = out.body_x.acceleration = 0.0;
    out.body_y.velocity = out.body_y.acceleration = 0.0;
  }

  for (Side side : kSides) foot_at(side, t, out.feet[index_of(side)]);

  // Robot CoM of the simplified model.
  const double m_b = params_.body_mass, m_l = params_.leg_mass, m_total = m_b + 2.0 * m_l;
  double z_b, zd_b, zdd_b;
  body_vertical(t, z_b, zd_b, zdd_b);
  const Eigen::Vector3d body(out.body_x.position, out.body_y.position, z_b);
  const Eigen::Vector3d body_vel(out.body_x.velocity, out.body_y.velocity, zd_b);
  const Eigen::Vector3d body_acc(out.body_x.acceleration, out.body_y.acceleration, zdd_b);
  const Eigen::Vector3d leg_offset(0.0, 0.0, params_.leg_com_height);
  out.com = m_b * body;
  out.com_velocity = m_b * body_vel;
  out.com_acceleration = m_b * body_acc;
  for (int k = 0; k < 2; ++k) {
    out.com += m_l * (out.feet[k].position + leg_offset);
    out.com_velocity += m_l * out.feet[k].velocity;
    out.com_acceleration += m_l * out.feet[k].acceleration;
  }
  out.com /= m_total;
  out.com_velocity /= m_total;
  out.com_acceleration /= m_total;

  // Upper-body heading halfway between the feet; arms swing against the legs.
  const FootReference& left = out.feet[0];
  const FootReference& right = out.feet[1];
  out.heading = math::wrap_angle(left.yaw + 0.5 * math::wrap_angle(right.yaw - left.yaw));
  out.heading_rate = 0.5 * (left.yaw_rate + right.yaw_rate);
  const Eigen::Vector2d forward(std::cos(out.heading), std::sin(out.heading));
  out.arm_swing = params_.arm_swing_gain * forward.dot((left.position - right.position).head<2>());
  out.arm_swing_rate = params_.arm_swing_gain * forward.dot((left.velocity - right.velocity).head<2>());

  // Reference ZMP and load shares.
  double share_of_new;
  int phase;
  reference_zmp(t, out.zmp, share_of_new, phase);
  double b1, b2;
  zmp_shapes(t, b1, b2);
  out.zmp += b1 * amplitude1_ + b2 * amplitude2_;
  out.double_support = left.in_contact && right.in_contact;
  if (!left.in_contact) {
    out.load_share = {0.0, 1.0};
  } else if (!right.in_contact) {
    out.load_share = {1.0, 0.0};
  } else {
    // Split by where the ZMP lies between the two feet's ZMP points.
    const Eigen::Vector2d a = zmp_point({Side::Left, left.position.head<2>(), left.yaw, 0.0});
    const Eigen::Vector2d b = zmp_point({Side::Right, right.position.head<2>(), right.yaw, 0.0});
    const Eigen::Vector2d ab = b - a;
    const double right_share = ab.squaredNorm() > 1e-12 ? std::clamp((out.zmp - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.5;
    out.load_share = {1.0 - right_share, right_share};
  }
  out.stance = out.load_share[0] >= out.load_share[1] ? Side::Left : Side::Right;

  // Ideal contact wrenches λ_id: the model's total ground reaction, split by load share, acting at
  // each foot's ZMP point (the reference ZMP itself in single support), seen by the F/T sensor.
  const Eigen::Vector3d total = m_total * out.com_acceleration + m_total * g * Eigen::Vector3d::UnitZ();
  for (Side side : kSides) {
    const int k = index_of(side);
    const FootReference& foot = out.feet[k];
    const double c = std::cos(foot.yaw), s = std::sin(foot.yaw);
    Eigen::Matrix3d yaw;
    yaw << c, -s, 0, s, c, 0, 0, 0, 1;
    const Eigen::Vector3d sensor = foot.position + yaw * params_.sensor_in_foot;
    const Eigen::Vector2d point = out.double_support ? zmp_point({side, foot.position.head<2>(), foot.yaw, 0.0}) : out.zmp;
    const Eigen::Vector3d cop(point.x(), point.y(), foot.position.z() - params_.ankle_height);
    const Eigen::Vector3d force = out.load_share[k] * total;
    const Eigen::Vector3d torque = (cop - sensor).cross(force);
    // The sensor does not see the part of the foot below it.
    const Eigen::Vector3d below = params_.mass_below_sensor * (foot.acceleration + g * Eigen::Vector3d::UnitZ());
    out.contact_wrench[k].force = yaw.transpose() * (force - below);
    out.contact_wrench[k].torque = yaw.transpose() * torque;
  }
}

}  // namespace biped

namespace biped {

PatternGeneratorParams simplified_model_of(const RobotModel& model) {
  // Each leg point carries the mass that moves with its foot (model/kinematics.hpp), the rest joins
  // the body. (The whole leg at the ankle overstated the swing leg's effect on the ZMP about
  // twofold: the multibody ZMP missed the reference by 47 mm RMS at 0.6 m/s, 131 mm at 1.0 m/s.)
  const LegMassSplit legs = leg_mass_split(model);
  PatternGeneratorParams p;
  for (Side side : kSides) {
    const FootInfo& foot = model.foot(side);
    p.mass_below_sensor = foot.mass_below_sensor;
    p.sensor_in_foot = foot.sensor_position;
    p.zmp_offset_x = p.sensor_in_foot.x() + 0.5 * (foot.sole_x_min + foot.sole_x_max);
  }
  p.leg_mass = 0.5 * legs.moving_mass;
  p.body_mass = model.total_mass() - legs.moving_mass;
  p.leg_com_height = legs.moving_height;
  p.ankle_height = legs.ankle_height;
  p.gravity = model.gravity();
  return p;
}

}  // namespace biped
