#include "planning/walking_pattern_generator.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <Eigen/Geometry>

#include "planning/step_sequence_planner.hpp"

namespace biped {
namespace {

// LOLA-like simplified model and sole: x from −0.09 to +0.19 about the ankle, width 0.14.
PatternGeneratorParams lola_like() {
  PatternGeneratorParams p;
  p.body_mass = 34.3;
  p.leg_mass = 10.3;
  p.zmp_offset_x = 0.05;
  p.sensor_in_foot = Eigen::Vector3d(0, 0, -0.05);
  p.mass_below_sensor = 1.3;
  return p;
}
constexpr double kSoleBack = 0.09, kSoleFront = 0.19, kSoleHalfWidth = 0.07;

// Replans at every touchdown, as the walking controller does, and samples every 5 ms.
struct Walk {
  WalkingPatternGenerator generator{lola_like()};
  StepParameters params;
  std::array<Footstep, 2> feet{Footstep{Side::Left, {0.0, 0.09}, 0.0, 0.0}, Footstep{Side::Right, {0.0, -0.09}, 0.0, 0.0}};
  Side next_swing = Side::Right;
  std::vector<PatternSample> samples;
  std::vector<double> times;

  void start() {
    std::array<Footstep, 3> none;
    AxisState x, y;
    x.position = 0.05;  // body above the ZMP points
    generator.replan(0.0, feet, none, 0, params, x, y, Eigen::Vector2d(0.05, 0.0));
  }

  // Walks `steps` steps with the command, replanning at each touchdown; a start from standing
  // shifts the weight for `start_shift` seconds first.
  void walk(const VelocityCommand& v, int steps, double t_start, double start_shift = 0.0) {
    double t = t_start;
    for (int s = 0; s < steps; ++s) {
      PatternSample now;
      generator.sample(t, now);
      std::array<Footstep, 3> plan;
      const Footstep& stance = feet[index_of(next_swing == Side::Left ? Side::Right : Side::Left)];
      plan_steps(stance, v, params, t + params.step_time + (s == 0 ? start_shift : 0.0), 3, plan);
      generator.replan(t, feet, plan, 3, params, now.body_x, now.body_y, now.zmp);
      const double next = generator.next_touchdown();
      for (; t < next - 1e-9; t += 0.005) {
        PatternSample sample;
        generator.sample(t, sample);
        samples.push_back(sample);
        times.push_back(t);
      }
      t = next;
      feet[index_of(plan[0].side)] = plan[0];
      next_swing = next_swing == Side::Left ? Side::Right : Side::Left;
    }
  }
};

bool inside_sole(const Eigen::Vector2d& point, const FootReference& foot, double margin) {
  const Eigen::Vector2d d = point - foot.position.head<2>();
  const double c = std::cos(foot.yaw), s = std::sin(foot.yaw);
  const double x = c * d.x() + s * d.y(), y = -s * d.x() + c * d.y();
  return x > -kSoleBack + margin && x < kSoleFront - margin && std::abs(y) < kSoleHalfWidth - margin;
}

// Inside the convex hull of both soles (double support), by sampling the segment between them.
bool inside_support(const Eigen::Vector2d& point, const PatternSample& s, double margin) {
  for (double a = 0.0; a <= 1.0; a += 0.01) {
    FootReference blend = s.feet[0];
    blend.position = (1 - a) * s.feet[0].position + a * s.feet[1].position;
    blend.yaw = s.feet[0].yaw + a * std::remainder(s.feet[1].yaw - s.feet[0].yaw, 2 * M_PI);
    if (inside_sole(point, blend, margin)) return true;
  }
  return false;
}

// The ZMP that the planned motion of the simplified model produces (recomputed from the sampled
// body and leg accelerations, not the reference) stays inside the support polygon with a margin.
TEST(WalkingPatternGenerator, ModelZmpStaysInsideTheSupportPolygon) {
  for (const VelocityCommand v : {VelocityCommand{0.6, 0, 0}, VelocityCommand{0.3, 0.05, 0.2}, VelocityCommand{1.0, 0, 0}}) {
    Walk walk;
    walk.start();
    walk.walk(v, 10, 0.5, 0.6);
    const PatternGeneratorParams p = lola_like();
    const double m_total = p.body_mass + 2 * p.leg_mass;
    for (std::size_t i = 1; i + 1 < walk.samples.size(); ++i) {
      const PatternSample& s = walk.samples[i];
      // p = Σ m (x (z̈+g) − z ẍ) / Σ m (z̈+g) over the body mass and the two leg masses.
      double zb, zdb, zddb;
      walk.generator.body_vertical(walk.times[i], zb, zdb, zddb);
      double fz = p.body_mass * (zddb + p.gravity);
      Eigen::Vector2d moment(p.body_mass * (s.body_x.position * (zddb + p.gravity) - zb * s.body_x.acceleration),
                             p.body_mass * (s.body_y.position * (zddb + p.gravity) - zb * s.body_y.acceleration));
      for (const FootReference& f : s.feet) {
        const double z = f.position.z() + p.leg_com_height, zdd = f.acceleration.z() + p.gravity;
        fz += p.leg_mass * zdd;
        for (int a = 0; a < 2; ++a) moment[a] += p.leg_mass * (f.position[a] * zdd - z * f.acceleration[a]);
      }
      const Eigen::Vector2d zmp = moment / fz;
      (void)m_total;
      const double margin = 0.01;
      const bool ok = s.double_support ? inside_support(zmp, s, margin)
                                       : inside_sole(zmp, s.feet[index_of(s.stance)], margin);
      ASSERT_TRUE(ok) << "v=" << v.vx << " t=" << walk.times[i] << " zmp=" << zmp.transpose()
                      << " ref=" << s.zmp.transpose();
    }
  }
}

TEST(WalkingPatternGenerator, ContinuousAcrossReplanning) {
  Walk walk;
  walk.start();
  walk.walk({0.5, 0.0, 0.0}, 3, 0.5);
  // At the next touchdown, sample the old plan, then replan with a different command.
  const double t = walk.generator.next_touchdown();
  PatternSample before, after;
  walk.generator.sample(t, before);
  walk.walk({0.8, 0.05, 0.3}, 1, t);
  walk.generator.sample(t, after);
  EXPECT_LT((before.com - after.com).norm(), 1e-9);
  EXPECT_LT((before.com_velocity - after.com_velocity).norm(), 1e-9);
  EXPECT_LT((before.com_acceleration - after.com_acceleration).norm(), 1e-7);
  for (int k = 0; k < 2; ++k) EXPECT_LT((before.feet[k].position - after.feet[k].position).norm(), 1e-12);
}

// λ_id: the two feet's forces (plus the mass below the sensors) carry the model's total
// ground reaction, and their centre of pressure is the reference ZMP.
TEST(WalkingPatternGenerator, IdealContactWrenchesMatchTheModel) {
  Walk walk;
  walk.start();
  walk.walk({0.6, 0.0, 0.15}, 4, 0.5);
  const PatternGeneratorParams p = lola_like();
  const double m_total = p.body_mass + 2 * p.leg_mass;
  for (std::size_t i = 0; i < walk.samples.size(); i += 7) {
    const PatternSample& s = walk.samples[i];
    Eigen::Vector3d force = Eigen::Vector3d::Zero();
    Eigen::Vector3d moment_about_zmp = Eigen::Vector3d::Zero();
    for (int k = 0; k < 2; ++k) {
      const FootReference& f = s.feet[k];
      Eigen::Matrix3d yaw = Eigen::AngleAxisd(f.yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      const Eigen::Vector3d fw = yaw * s.contact_wrench[k].force;
      const Eigen::Vector3d below = p.mass_below_sensor * p.gravity * Eigen::Vector3d::UnitZ();
      const Eigen::Vector3d ground = fw + (f.in_contact ? below : Eigen::Vector3d::Zero());
      force += f.in_contact ? ground : Eigen::Vector3d::Zero();
      const Eigen::Vector3d sensor = f.position + yaw * p.sensor_in_foot;
      const Eigen::Vector3d zmp(s.zmp.x(), s.zmp.y(), 0.0);
      if (f.in_contact && !s.double_support) moment_about_zmp += yaw * s.contact_wrench[k].torque + (sensor - zmp).cross(ground);
    }
    EXPECT_NEAR(force.z(), m_total * (s.com_acceleration.z() + p.gravity), 0.05 * m_total) << walk.times[i];
    EXPECT_NEAR(force.x(), m_total * s.com_acceleration.x(), 0.05 * m_total);
    EXPECT_NEAR(moment_about_zmp.x(), 0.0, 1e-6);
    EXPECT_NEAR(moment_about_zmp.y(), 0.0, 1e-6);
  }
}

// The body rises and falls smoothly within each single support and is back at its height in double support.
TEST(WalkingPatternGenerator, PrescribedVerticalBodyMotion) {
  Walk walk;
  walk.start();
  walk.walk({0.5, 0.0, 0.0}, 4, 0.5);
  const double base = walk.generator.body_height();
  double highest = 0.0;
  for (std::size_t i = 0; i < walk.samples.size(); ++i) {
    double z, zd, zdd;
    walk.generator.body_vertical(walk.times[i], z, zd, zdd);
    if (walk.samples[i].double_support) {
      EXPECT_NEAR(z, base, 1e-12);
    }
    highest = std::max(highest, z - base);
  }
  EXPECT_NEAR(highest, lola_like().com_height_variation, 1e-4);
}

// The swing foot has arrived above its foothold after `swing_travel_share` of the swing and comes
// down vertically from there; its velocity is the derivative of its position throughout.
TEST(WalkingPatternGenerator, SwingFootArrivesAboveItsFootholdThenComesDownVertically) {
  for (const double share : {0.8, 1.0}) {
    const PatternGeneratorParams p = lola_like();
    Walk walk;
    walk.params.swing_travel_share = share;
    walk.start();
    walk.walk({0.6, 0.0, 0.2}, 4, 0.5);
    const double dt = 0.005, single_support = walk.params.step_time * (1.0 - walk.params.double_support_ratio);
    int late_samples = 0;
    double late_horizontal_speed = 0.0;
    for (std::size_t i = 1; i + 1 < walk.samples.size(); ++i) {
      for (int k = 0; k < 2; ++k) {
        const FootReference& f = walk.samples[i].feet[k];
        if (f.in_contact || walk.samples[i - 1].feet[k].in_contact || walk.samples[i + 1].feet[k].in_contact) continue;
        const Eigen::Vector3d difference =
            (walk.samples[i + 1].feet[k].position - walk.samples[i - 1].feet[k].position) / (2 * dt);
        EXPECT_LT((difference - f.velocity).norm(), 0.02) << "share " << share << " t " << walk.times[i];
        const double tau = 1.0 - f.time_to_touchdown / single_support;
        if (tau < 0.85) continue;
        ++late_samples;
        late_horizontal_speed = std::max(late_horizontal_speed, f.velocity.head<2>().norm());
        EXPECT_GT(f.position.z(), p.ankle_height) << "share " << share << " t " << walk.times[i];
        if (share < 1.0) {
          EXPECT_NEAR(f.swing_progress, 1.0, 1e-12);
        }
      }
    }
    ASSERT_GT(late_samples, 10);
    if (share < 1.0) {
      EXPECT_LT(late_horizontal_speed, 1e-12);
    } else {
      EXPECT_GT(late_horizontal_speed, 0.1);  // the blend over the whole swing still moves the foot
    }
  }
}

TEST(WalkingPatternGenerator, StopBringsTheCoMToRestBetweenTheFeet) {
  Walk walk;
  walk.start();
  walk.walk({0.5, 0.0, 0.0}, 6, 0.5);
  walk.walk({0.0, 0.0, 0.0}, 1, walk.generator.next_touchdown());
  // Now no further steps: rest between the feet.
  const double t = walk.generator.next_touchdown();
  PatternSample now;
  walk.generator.sample(t, now);
  std::array<Footstep, 3> none;
  walk.generator.replan(t, walk.feet, none, 0, walk.params, now.body_x, now.body_y, now.zmp);
  PatternSample end;
  walk.generator.sample(walk.generator.horizon_end(), end);
  const Eigen::Vector2d mid = 0.5 * (walk.feet[0].position + walk.feet[1].position);
  EXPECT_NEAR((walk.feet[0].position - walk.feet[1].position).norm(), walk.params.step_width, 1e-9);
  EXPECT_LT(end.com_velocity.norm(), 0.02);
  EXPECT_LT((end.com.head<2>() - mid - Eigen::Vector2d(0.05, 0)).norm(), 0.02);
}

}  // namespace
}  // namespace biped
