#include "control/task_reference.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "math/rotations.hpp"

namespace biped {
namespace {

Eigen::Matrix3d yaw_rotation(double yaw) {
  return Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

}  // namespace

TaskReference::TaskReference(const TaskSpace& space)
    : space_(space),
      x_id_(Eigen::VectorXd::Zero(space.dim())),
      xdot_id_(Eigen::VectorXd::Zero(space.dim())),
      delta_x_(Eigen::VectorXd::Zero(space.dim())),
      delta_xdot_(Eigen::VectorXd::Zero(space.dim())) {
  for (auto& v : arm_offset_) v.setZero();
  for (auto& v : arm_pivot_) v.setZero();
}

void TaskReference::reset(const TaskSpaceData& start, double heading) {
  delta_x_.setZero();
  delta_xdot_.setZero();
  // The arms hang from the upper body and swing: their CoM offsets are kept relative to the upper
  // body's origin, in the heading frame (x_id then gives arm CoM − robot CoM as in Table I).
  const Eigen::Vector3d& body = start.upper_body_position;
  const TaskLayout& L = space_.layout();
  const RobotModel& model = space_.model();
  for (Side side : kSides) {
    const int k = index_of(side);
    Eigen::Vector3d arm = start.com;
    arm.head(L.arm_com_rows) += start.x.segment(L.arm_com[k], L.arm_com_rows);
    arm_offset_[k] = yaw_rotation(-heading) * (arm - body);
    // The arm swings as a rigid body about its shoulder's pitch axis (the upper body's y axis
    // through the shoulder): the pivot relative to the upper body, in the heading frame.
    arm_pivot_[k] = yaw_rotation(-heading) * (start.frames().joint_anchor[model.arm_root_joint(side)] - body);
  }
}

// Table I coordinates of the pattern sample (see model/task_space.hpp for the rows).
void TaskReference::update(const PatternSample& s, const TerrainAdaptation& terrain, const UpperBodyLean& lean,
                           const TaskSpaceData& kinematic_state) {
  const TaskLayout& L = space_.layout();
  const Eigen::Matrix3d heading = yaw_rotation(s.heading);
  const Eigen::Vector3d lean_vector = lean.rotation_vector();
  const Eigen::Vector3d lean_rate = lean.angular_rate();
  const Eigen::Matrix3d lean_rotation = math::so3::exp(lean_vector);
  for (Side side : kSides) {
    const int k = index_of(side);
    const FootReference& foot = s.feet[k];
    x_id_.segment<3>(L.foot_position[k]) = foot.position - s.com;
    xdot_id_.segment<3>(L.foot_position[k]) = foot.velocity - s.com_velocity;
    x_id_[L.foot_position[k] + 2] += terrain.foot_offset(k) - terrain.com_offset();
    xdot_id_[L.foot_position[k] + 2] += terrain.foot_offset_rate(k) - terrain.com_offset_rate();
    // The terrain adaptation's tilt is about the foot's lateral axis, its roll about the forward
    // axis, turned into the heading frame.
    const Eigen::Matrix3d to_heading = yaw_rotation(math::wrap_angle(foot.yaw - s.heading));
    Eigen::Vector3d foot_in_heading = to_heading * Eigen::Vector3d(terrain.foot_roll(k), terrain.foot_tilt(k), 0.0);
    foot_in_heading.z() = math::wrap_angle(foot.yaw - s.heading);
    Eigen::Vector3d foot_rate = to_heading * Eigen::Vector3d(terrain.foot_roll_rate(k), terrain.foot_tilt_rate(k), 0.0);
    foot_rate.z() = foot.yaw_rate - s.heading_rate;
    // Relative to the leaning upper body: log(exp(−φ_lean) exp(φ_foot)), its rate to first order.
    if (lean.angle().isZero()) {
      x_id_.segment<3>(L.foot_orientation[k]) = foot_in_heading;
    } else {
      const Eigen::Matrix3d relative = lean_rotation.transpose() * math::so3::exp(foot_in_heading);
      x_id_.segment<3>(L.foot_orientation[k]) = math::so3::log(Eigen::Quaterniond(relative));
    }
    xdot_id_.segment<3>(L.foot_orientation[k]) = foot_rate - lean_rate;
    // Arms swing against the legs: the right arm forward with the left leg.
    const double swing = side == Side::Right ? s.arm_swing : -s.arm_swing;
    const double swing_rate = side == Side::Right ? s.arm_swing_rate : -s.arm_swing_rate;
    // The upper body where eq. (21)'s own kinematic state has it (last cycle), moving like the CoM.
    const Eigen::Vector3d& body = kinematic_state.upper_body_position;
    // Rotation about the shoulder's pitch axis by the angle that moves the CoM forward by `swing`.
    const Eigen::Vector3d lever = arm_offset_[k] - arm_pivot_[k];
    const double radius = std::max(0.05, std::hypot(lever.x(), lever.z()));
    const double angle = swing / radius, angle_rate = swing_rate / radius;
    const Eigen::Vector3d swung = Eigen::AngleAxisd(-angle, Eigen::Vector3d::UnitY()) * lever;
    const Eigen::Vector3d offset = heading * lean_rotation * (arm_pivot_[k] + swung);
    const Eigen::Vector3d arm = body + offset - kinematic_state.com;
    const Eigen::Vector3d arm_rate = s.heading_rate * Eigen::Vector3d::UnitZ().cross(offset) +
                                     heading * (lean_rate.cross(lean_rotation * (arm_pivot_[k] + swung)) +
                                                lean_rotation * (-angle_rate * Eigen::Vector3d::UnitY().cross(swung)));
    x_id_.segment(L.arm_com[k], L.arm_com_rows) = arm.head(L.arm_com_rows);
    xdot_id_.segment(L.arm_com[k], L.arm_com_rows) = arm_rate.head(L.arm_com_rows);
  }
  x_id_.segment<3>(L.upper_body_orientation) = lean_vector;
  xdot_id_.segment<3>(L.upper_body_orientation) = lean_rate + Eigen::Vector3d(0.0, 0.0, s.heading_rate);
  x_id_.segment<3>(L.com) = s.com;
  xdot_id_.segment<3>(L.com) = s.com_velocity;
  x_id_[L.com + 2] += terrain.com_offset();
  xdot_id_[L.com + 2] += terrain.com_offset_rate();
}

// S̄ᵀΔx_λ of eq. (21): the feet's height and tilt modifications enter the foot rows; the tilt is
// turned from the foot frame into the upper body's heading frame.
void TaskReference::set_modification(const PatternSample& s, const std::array<FootModification, 2>& modification) {
  const TaskLayout& L = space_.layout();
  for (Side side : kSides) {
    const int k = index_of(side);
    const FootModification& m = modification[k];
    const Eigen::Matrix3d to_heading = yaw_rotation(math::wrap_angle(s.feet[k].yaw - s.heading));
    delta_x_[L.foot_position[k] + 2] = m.offset[0];
    delta_xdot_[L.foot_position[k] + 2] = m.rate[0];
    delta_x_.segment<3>(L.foot_orientation[k]) = to_heading * Eigen::Vector3d(m.offset[1], m.offset[2], 0.0);
    delta_xdot_.segment<3>(L.foot_orientation[k]) = to_heading * Eigen::Vector3d(m.rate[1], m.rate[2], 0.0);
  }
}

void TaskReference::decay_modification(double factor) {
  delta_x_ *= factor;
  delta_xdot_.setZero();
}

}  // namespace biped
