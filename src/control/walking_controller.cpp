#include "control/walking_controller.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include <Eigen/Geometry>

#include "math/rotations.hpp"

namespace biped {
namespace {

double wrap(double a) { return std::atan2(std::sin(a), std::cos(a)); }

Eigen::Matrix3d yaw_rotation(double yaw) {
  return Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

PatternGeneratorParams pattern_params(const RobotModel& model, const WalkingControllerParams& params) {
  PatternGeneratorParams p = simplified_model_of(model);
  p.arm_swing_gain = params.arm_swing_gain;
  return p;
}

}  // namespace

WalkingController::WalkingController(const RobotModel& model, const WalkingControllerParams& params)
    : model_(model),
      params_(params),
      space_(model),
      rmrc_(model, space_, params.rmrc),
      pattern_(pattern_params(model, params)),
      stabilizer_(model, params.stabilization),
      terrain_(model, params.terrain),
      com_estimator_(model),
      x_id_(Eigen::VectorXd::Zero(space_.dim())),
      xdot_id_(Eigen::VectorXd::Zero(space_.dim())),
      delta_x_(Eigen::VectorXd::Zero(space_.dim())),
      delta_xdot_(Eigen::VectorXd::Zero(space_.dim())),
      last_setpoint_(model.stand_pose()),
      substituted_sensors_(model.num_joints()) {}

void WalkingController::reset(const SensorData& first) {
  start_time_ = first.time;
  status_ = ControllerStatus{};
  fsm_ = WalkingStateMachine{};
  num_planned_ = 0;
  planned_vx_ = 0.0;
  stabilizer_.reset();
  terrain_.reset();
  faulty_foot_sensor_ = -1;
  frozen_.reset(first);
  has_estimate_ = false;
  delta_x_.setZero();
  delta_xdot_.setZero();

  // The controller's own frame: the stand keyframe's base with the measured joint angles, shifted
  // so the soles are at z = 0.
  Eigen::VectorXd q = initial_configuration(model_, params_.sensor_limits, first);
  TaskSpaceData data(space_);
  evaluate(space_, q, Eigen::Matrix3d::Identity(), data);
  const double ankle_height = pattern_.params().ankle_height;
  const double ground = 0.5 * (data.foot_position[0].z() + data.foot_position[1].z()) - ankle_height;
  q[2] -= ground;
  evaluate(space_, q, Eigen::Matrix3d::Identity(), data);
  rmrc_.reset(q);

  const mjData* d = data.robot_data().mj();
  for (Side side : kSides) {
    const int k = index_of(side);
    feet_[k].side = side;
    feet_[k].position = data.foot_position[k].head<2>();
    feet_[k].yaw = math::heading_of(math::mat_from_mujoco(d->xmat + 9 * space_.foot_body(side)));
    feet_[k].touchdown = 0.0;
  }
  params_.step.com_height = data.com.z();
  params_.step.step_width = (feet_[0].position - feet_[1].position).norm();

  // Body mass point of the simplified model so that its CoM is the robot's.
  const PatternGeneratorParams& p = pattern_.params();
  const double m_total = p.body_mass + 2.0 * p.leg_mass;
  AxisState bx, by;
  bx.position = (m_total * data.com.x() - p.leg_mass * (feet_[0].position.x() + feet_[1].position.x())) / p.body_mass;
  by.position = (m_total * data.com.y() - p.leg_mass * (feet_[0].position.y() + feet_[1].position.y())) / p.body_mass;
  pattern_.replan(0.0, feet_, planned_, 0, params_.step, bx, by, data.com.head<2>());
  pattern_.sample(0.0, sample_);
  // The arms hang from the upper body and swing: their CoM offsets are kept relative to the upper
  // body's origin, in the heading frame (x_id then gives arm CoM − robot CoM as in Table I).
  const double heading = wrap(feet_[0].yaw + 0.5 * wrap(feet_[1].yaw - feet_[0].yaw));
  const Eigen::Vector3d& body = data.upper_body_position;
  const TaskLayout& L = space_.layout();
  for (Side side : kSides) {
    Eigen::Vector3d arm = data.com;
    arm.head(L.arm_com_rows) += data.x.segment(L.arm_com[index_of(side)], L.arm_com_rows);
    arm_offset_[index_of(side)] = yaw_rotation(-heading) * (arm - body);
    // The arm swings as a rigid body about its shoulder's pitch axis (the upper body's y axis
    // through the shoulder): the pivot relative to the upper body, in the heading frame.
    const int shoulder = mj_name2id(model_.mj(), mjOBJ_JOINT, (std::string(name_of(side)) + "_shoulder_pitch").c_str());
    arm_pivot_[index_of(side)] = yaw_rotation(-heading) * (Eigen::Vector3d(d->xanchor + 3 * shoulder) - body);
  }
  for (int i = 0; i < model_.num_joints(); ++i) last_setpoint_[i] = q[model_.joints()[i].qpos_adr];
  status_.state = name_of(fsm_.state());
}

double WalkingController::max_speed_change() const {
  return params_.limits.vx_rate * params_.table.lookup(planned_vx_, params_.step).step_time;
}

void WalkingController::replan(double t, StepDecision decision, const VelocityCommand& command) {
  if (decision == StepDecision::None) return;
  VelocityCommand v = command;
  planned_vx_ = decision == StepDecision::StartWalk || decision == StepDecision::Continue
                    ? ramp_towards(planned_vx_, command.vx, max_speed_change())
                    : 0.0;
  v.vx = planned_vx_;
  PatternSample now;
  pattern_.sample(t, now);
  const StepParameters step = params_.table.lookup(decision == StepDecision::StopStep ? 0.0 : v.vx, params_.step);
  switch (decision) {
    case StepDecision::StartWalk: {
      // Step first with the foot on the side the robot moves or turns to.
      const Side first_swing = (v.vy > 1e-3 || (std::abs(v.vy) <= 1e-3 && v.omega > 1e-3)) ? Side::Left : Side::Right;
      const Footstep& stance = feet_[index_of(first_swing == Side::Left ? Side::Right : Side::Left)];
      plan_steps(stance, v, step, t + step.step_time + params_.start_shift, 3, planned_);
      num_planned_ = 3;
      break;
    }
    case StepDecision::Continue:
      plan_steps(feet_[index_of(planned_[0].side)], v, step, t + step.step_time, 3, planned_);
      num_planned_ = 3;
      break;
    case StepDecision::StopStep:
      plan_steps(feet_[index_of(planned_[0].side)], VelocityCommand{}, step, t + step.step_time, 1,
                 planned_);
      num_planned_ = 1;
      break;
    case StepDecision::Stand:
      num_planned_ = 0;
      break;
    case StepDecision::None:
      return;
  }
  pattern_.replan(t, feet_, planned_, num_planned_, step, now.body_x, now.body_y, now.zmp);
}

// Table I coordinates of the pattern sample (see model/task_space.hpp for the rows).
void WalkingController::task_reference(const PatternSample& s) {
  const TaskLayout& L = space_.layout();
  const Eigen::Matrix3d heading = yaw_rotation(s.heading);
  for (Side side : kSides) {
    const int k = index_of(side);
    const FootReference& foot = s.feet[k];
    x_id_.segment<3>(L.foot_position[k]) = foot.position - s.com;
    xdot_id_.segment<3>(L.foot_position[k]) = foot.velocity - s.com_velocity;
    x_id_[L.foot_position[k] + 2] += terrain_.foot_offset(k) - terrain_.com_offset();
    xdot_id_[L.foot_position[k] + 2] += terrain_.foot_offset_rate(k) - terrain_.com_offset_rate();
    // The terrain adaptation's tilt is about the foot's lateral axis, turned into the heading frame.
    const Eigen::Vector3d tilt_axis = yaw_rotation(wrap(foot.yaw - s.heading)) * Eigen::Vector3d::UnitY();
    x_id_.segment<3>(L.foot_orientation[k]) = terrain_.foot_tilt(k) * tilt_axis;
    x_id_[L.foot_orientation[k] + 2] = wrap(foot.yaw - s.heading);
    xdot_id_.segment<3>(L.foot_orientation[k]) = terrain_.foot_tilt_rate(k) * tilt_axis;
    xdot_id_[L.foot_orientation[k] + 2] = foot.yaw_rate - s.heading_rate;
    // Arms swing against the legs: the right arm forward with the left leg.
    const double swing = side == Side::Right ? s.arm_swing : -s.arm_swing;
    const double swing_rate = side == Side::Right ? s.arm_swing_rate : -s.arm_swing_rate;
    // The upper body where eq. (21)'s own kinematic state has it (last cycle), moving like the CoM.
    const Eigen::Vector3d& body = rmrc_.task().upper_body_position;
    // Rotation about the shoulder's pitch axis by the angle that moves the CoM forward by `swing`.
    const Eigen::Vector3d lever = arm_offset_[k] - arm_pivot_[k];
    const double radius = std::max(0.05, std::hypot(lever.x(), lever.z()));
    const double angle = swing / radius, angle_rate = swing_rate / radius;
    const Eigen::Vector3d swung = Eigen::AngleAxisd(-angle, Eigen::Vector3d::UnitY()) * lever;
    const Eigen::Vector3d offset = heading * (arm_pivot_[k] + swung);
    const Eigen::Vector3d arm = body + offset - rmrc_.task().com;
    const Eigen::Vector3d arm_rate = s.heading_rate * Eigen::Vector3d::UnitZ().cross(offset) +
                                     heading * (-angle_rate * Eigen::Vector3d::UnitY().cross(swung));
    x_id_.segment(L.arm_com[k], L.arm_com_rows) = arm.head(L.arm_com_rows);
    xdot_id_.segment(L.arm_com[k], L.arm_com_rows) = arm_rate.head(L.arm_com_rows);
  }
  x_id_.segment<3>(L.upper_body_orientation).setZero();
  xdot_id_.segment<3>(L.upper_body_orientation) << 0.0, 0.0, s.heading_rate;
  x_id_.segment<3>(L.com) = s.com;
  xdot_id_.segment<3>(L.com) = s.com_velocity;
  x_id_[L.com + 2] += terrain_.com_offset();
  xdot_id_[L.com + 2] += terrain_.com_offset_rate();
}

// S̄ᵀΔx_λ of eq. (21): the feet's height and tilt modifications enter the foot rows; the tilt is
// turned from the foot frame into the upper body's heading frame.
void WalkingController::stabilizer_modification(const PatternSample& s) {
  const TaskLayout& L = space_.layout();
  for (Side side : kSides) {
    const int k = index_of(side);
    const FootModification& m = stabilizer_.modification()[k];
    const Eigen::Matrix3d to_heading = yaw_rotation(wrap(s.feet[k].yaw - s.heading));
    delta_x_[L.foot_position[k] + 2] = m.offset[0];
    delta_xdot_[L.foot_position[k] + 2] = m.rate[0];
    delta_x_.segment<3>(L.foot_orientation[k]) = to_heading * Eigen::Vector3d(m.offset[1], m.offset[2], 0.0);
    delta_xdot_.segment<3>(L.foot_orientation[k]) = to_heading * Eigen::Vector3d(m.rate[1], m.rate[2], 0.0);
  }
}

void WalkingController::com_error(const SensorData& sensors, const PatternSample& s, Eigen::Vector2d& error,
                                  Eigen::Vector2d& rate) {
  const Side stance = s.stance;
  const Eigen::Vector2d estimate = com_estimator_.com_from_foot(sensors.joint_position, sensors.imu_orientation, stance).head<2>();
  // The rate is differentiated and filtered (T = 10 ms); a change of stance foot restarts it.
  const double dt = params_.rmrc.dt, filter = dt / (0.01 + dt);
  if (!has_estimate_ || stance != estimate_stance_) {
    com_rate_estimate_.setZero();
  } else {
    com_rate_estimate_ += filter * ((estimate - com_estimate_) / dt - com_rate_estimate_);
  }
  com_estimate_ = estimate;
  estimate_stance_ = stance;
  has_estimate_ = true;
  const Eigen::Matrix2d to_heading = yaw_rotation(-s.heading).topLeftCorner<2, 2>();
  const FootReference& foot = s.feet[index_of(stance)];
  const Eigen::Vector2d planned = to_heading * (s.com - foot.position).head<2>();
  const Eigen::Vector2d planned_rate = to_heading * (s.com_velocity - foot.velocity).head<2>();
  status_.com_estimated = foot.position.head<2>() + to_heading.transpose() * com_estimate_;
  error = planned - com_estimate_;
  rate = planned_rate - com_rate_estimate_;
}

Eigen::Matrix3d WalkingController::heading_frame() const { return yaw_rotation(sample_.heading); }

void WalkingController::step(const SensorData& raw_sensors, const WalkCommand& command, JointCommand& out) {
  if (fsm_.state() != WalkingState::SafeStop) {
    const char* fault = check_sensors(model_, params_.sensor_limits, raw_sensors);
    if (!fault) fault = frozen_.update(raw_sensors, params_.sensor_limits.frozen_cycles);
    if (fault) {
      fsm_.enter_safe_stop();
      status_.fault = true;
      status_.fault_reason = fault;
      faulty_foot_sensor_ = std::strncmp(fault, "left F/T", 8) == 0    ? 0
                            : std::strncmp(fault, "right F/T", 9) == 0 ? 1
                                                                       : -1;
    }
  }
  // After the fault of one F/T sensor the stop keeps stabilizing with the others: that foot's
  // reading is replaced by the wrench the controller asked for (no force error, feed-forward only).
  // After any other fault no sensor is trusted: the stop runs on the pattern and eq. (21) alone.
  const bool use_sensors = !status_.fault || faulty_foot_sensor_ >= 0;
  const SensorData* used = &raw_sensors;
  if (status_.fault && faulty_foot_sensor_ >= 0) {
    substituted_sensors_ = raw_sensors;
    substituted_sensors_.foot_wrench[faulty_foot_sensor_] = stabilizer_.desired()[faulty_foot_sensor_];
    used = &substituted_sensors_;
  }
  const SensorData& sensors = *used;

  const double t = sensors.time - start_time_;
  bool saturated = false;
  const VelocityCommand v = saturate({command.vx, command.vy, command.omega}, params_.limits, saturated);
  status_.command_saturated = saturated;
  const bool commanded = !command.stop && (std::abs(v.vx) + std::abs(v.vy) + std::abs(v.omega) > 1e-3);
  // Too fast to stop in one step: keep walking and slow down first.
  const bool wants_to_walk = commanded || std::abs(planned_vx_) > max_speed_change() + 1e-9;
  const bool at_touchdown = num_planned_ > 0 && t >= pattern_.next_touchdown() - 1e-9;
  if (at_touchdown) {
    feet_[index_of(planned_[0].side)] = planned_[0];
    ++status_.steps_completed;
  }
  replan(t, fsm_.update(wants_to_walk, at_touchdown), commanded ? v : VelocityCommand{});

  pattern_.sample(t, sample_);
  // Finding the ground needs both F/T sensors; after a fault the footholds keep their heights.
  if (params_.stabilizer && !status_.fault) {
    // Where each standing foot's ground is, in the frame of the commanded heights: its height
    // modification (eq. 20) and its sole's deflection under the measured load (eq. 11).
    const auto& m = stabilizer_.modification();
    const double compliance = 1.0 / stabilizer_.contact_stiffness();
    terrain_.step(params_.rmrc.dt, sample_, sensors.foot_wrench, stabilizer_.desired(),
                  {m[0].offset[0] + compliance * std::max(0.0, sensors.foot_wrench[0].force.z()),
                   m[1].offset[0] + compliance * std::max(0.0, sensors.foot_wrench[1].force.z())});
  }
  if (status_.fault) terrain_.hold(params_.rmrc.dt);
  task_reference(sample_);
  using Clock = std::chrono::steady_clock;
  const auto stabilizer_start = Clock::now();
  if (params_.stabilizer && use_sensors) {
    Eigen::Vector2d com_err, com_rate_err;
    com_error(sensors, sample_, com_err, com_rate_err);
    stabilizer_.update_contact_model(sensors.joint_position, sensors.foot_wrench);
    stabilizer_.step(params_.rmrc.dt, sample_.contact_wrench, {sample_.feet[0].in_contact, sample_.feet[1].in_contact},
                     sample_.load_share, sensors.foot_wrench, sensors.imu_orientation, sensors.imu_angular_rate,
                     com_err, com_rate_err);
    stabilizer_modification(sample_);
  } else if (!use_sensors) {
    // Without force feedback the feet's modifications return to the plan.
    const double decay = std::exp(-params_.stabilization.position_gain * params_.rmrc.dt);
    delta_x_ *= decay;
    delta_xdot_.setZero();
  }
  const auto rmrc_start = Clock::now();
  rmrc_.step(x_id_, xdot_id_, yaw_rotation(sample_.heading), delta_x_, delta_xdot_);
  timing_.rmrc_us = std::chrono::duration<double, std::micro>(Clock::now() - rmrc_start).count();
  timing_.stabilizer_us = std::chrono::duration<double, std::micro>(rmrc_start - stabilizer_start).count();
  if (!rmrc_.fault() && rmrc_.joint_positions().allFinite()) last_setpoint_ = rmrc_.joint_positions();
  out.position = last_setpoint_;

  status_.com_desired = sample_.com;
  status_.zmp_desired = sample_.zmp;
  status_.desired_wrench = params_.stabilizer && use_sensors ? stabilizer_.desired() : sample_.contact_wrench;
  status_.contact_stiffness = params_.stabilizer ? stabilizer_.contact_stiffness() : 0.0;
  status_.state = name_of(fsm_.state());
  status_.com_estimate_valid = params_.stabilizer && use_sensors;
  status_.num_planned_steps = num_planned_;
  for (int k = 0; k < 2; ++k) {
    status_.foot_height_offset[k] = terrain_.foot_offset(k);
    status_.foot_tilt[k] = terrain_.foot_tilt(k);
  }
  for (int i = 0; i < num_planned_; ++i) {
    const Footstep& f = planned_[i];
    status_.planned_steps[i] = {f.side, f.position, f.yaw, f.touchdown};
  }
}

}  // namespace biped
