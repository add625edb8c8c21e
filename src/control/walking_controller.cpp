#include "control/walking_controller.hpp"

#include <chrono>
#include <cmath>

#include <Eigen/Geometry>

#include "control/initial_configuration.hpp"
#include "math/rotations.hpp"

namespace biped {
namespace {

Eigen::Matrix3d yaw_rotation(double yaw) {
  return Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

}  // namespace

WalkingController::WalkingController(const RobotModel& model, const WalkingControllerParams& params)
    : model_(model),
      params_(params),
      space_(model),
      rmrc_(model, space_, params.rmrc),
      plan_(model, params.plan),
      reference_(space_),
      stabilizer_(model, params.stabilization),
      terrain_(model, params.terrain),
      step_adaptation_(params.step_adaptation),
      lean_(params.upper_body_lean),
      com_estimator_(model),
      encoders_(model),
      monitor_(model, params.sensor_limits),
      calibration_(model, params.calibration, stabilizer_.contact_params()),
      attitude_(model, params.attitude),
      last_setpoint_(model.stand_pose()),
      substituted_sensors_(model.num_joints()) {}

void WalkingController::reset(const SensorData& first) {
  start_time_ = first.time;
  status_ = ControllerStatus{};
  stabilizer_.reset();
  terrain_.reset();
  step_adaptation_.reset();
  lean_.reset();
  monitor_.reset(first);
  calibration_.reset(first.time);
  attitude_.reset();
  last_time_ = first.time;
  com_estimator_.reset();

  // The controller's own frame: the stand keyframe's base with the measured joint angles, shifted
  // so the soles are at z = 0.
  Eigen::VectorXd q = initial_configuration(model_, params_.sensor_limits, first);
  TaskSpaceData data(space_);
  evaluate(space_, q, Eigen::Matrix3d::Identity(), data);
  const double ankle_height = plan_.pattern_generator().params().ankle_height;
  const double ground = 0.5 * (data.foot_position[0].z() + data.foot_position[1].z()) - ankle_height;
  q[2] -= ground;
  evaluate(space_, q, Eigen::Matrix3d::Identity(), data);
  rmrc_.reset(q);

  std::array<Footstep, 2> feet;
  for (Side side : kSides) {
    const int k = index_of(side);
    feet[k].side = side;
    feet[k].position = data.foot_position[k].head<2>();
    feet[k].yaw = math::heading_of(data.frames().rotation[space_.foot_body(side)]);
    feet[k].touchdown = 0.0;
  }
  plan_.reset(feet, data.com);
  reference_.reset(data, math::wrap_angle(feet[0].yaw + 0.5 * math::wrap_angle(feet[1].yaw - feet[0].yaw)));
  for (int i = 0; i < model_.num_joints(); ++i) last_setpoint_[i] = q[model_.joints()[i].qpos_adr];
  status_.state = name_of(plan_.state());
}

Eigen::Matrix3d WalkingController::heading_frame() const { return yaw_rotation(plan_.sample().heading); }

void WalkingController::step(const SensorData& raw_sensors, const WalkCommand& command, JointCommand& out) {
  const SensorData& checked = detect_faults(raw_sensors);
  // One kinematics pass of the encoders for the calibration, the attitude and the CoM estimates.
  encoders_.update(checked.joint_position);
  CalibrationContext context;
  context.standing = plan_.state() == WalkingState::Standing;
  context.plan = &plan_.sample();
  context.imu_healthy = health().imu;
  context.ft_healthy = health().force_torque;
  const SensorData& calibrated = calibration_.apply(checked, context, encoders_.frames(), params_.rmrc.dt);
  const SensorData& sensors =
      attitude_.apply(calibrated, context.imu_healthy, context.ft_healthy, encoders_.frames(), params_.rmrc.dt);
  const math::TiltAngles tilt = math::tilt_against_gravity(sensors.imu_orientation.toRotationMatrix());
  status_.upper_body_tilt = {tilt.sagittal, tilt.lateral};
  status_.imu_misalignment = calibration_.misalignment();
  status_.gyro_bias = calibration_.gyro_bias();
  status_.ft_offset = calibration_.ft_offset();
  // The fall is judged on the IMU unit's orientation (after calibration): a reading beyond
  // recovery stops the walk whatever the estimate, which follows it only at its bandwidth.
  if (plan_.state() == WalkingState::Fallen || detect_fall(calibrated)) {
    out.position = last_setpoint_;
    publish_status();
    return;
  }
  adapt_steps(sensors);
  const PatternSample& sample = plan_.advance(sensors.time - start_time_, command);
  adapt_to_terrain(sensors);
  reference_.update(sample, terrain_, lean_, rmrc_.task());
  stabilize(sensors);
  resolve_rates(out);
  publish_status();
}

const SensorData& WalkingController::detect_faults(const SensorData& raw) {
  monitor_.update(raw, last_setpoint_, new_faults_);
  for (int k = 0; k < new_faults_.count; ++k) {
    if (!status_.fault) status_.first_fault = new_faults_.items[k];
    status_.fault = true;
    status_.faults.add(new_faults_.items[k]);
    plan_.enter_safe_stop();
  }
  // A recovered sensor is used again; the safe stop goes on (walking resumes only by a restart).
  for (int k = 0; k < monitor_.recovered().count; ++k) status_.recovered.add(monitor_.recovered().items[k]);
  const SensorHealth& h = health();
  if (h.all_good()) {
    last_time_ = raw.time;
    return raw;
  }
  SensorData& s = substituted_sensors_;
  s = raw;
  if (!h.time) s.time = last_time_ + params_.rmrc.dt;
  last_time_ = s.time;
  for (int i = 0; i < model_.num_joints(); ++i) {
    if (h.encoder_failed[i]) s.joint_position[i] = last_setpoint_[i];
  }
  if (!h.imu) {
    const PatternSample& plan = plan_.sample();
    s.imu_orientation = com_estimator_.upper_body_on_flat_foot(s.joint_position, plan.stance,
                                                               plan.feet[index_of(plan.stance)].yaw);
    s.imu_angular_rate.setZero();
    s.imu_acceleration = s.imu_orientation.conjugate() * Eigen::Vector3d(0.0, 0.0, model_.gravity());
  }
  for (int k = 0; k < 2; ++k) {
    if (!h.force_torque[k]) s.foot_wrench[k] = stabilizer_.desired()[k];
  }
  return s;
}

bool WalkingController::detect_fall(const SensorData& sensors) {
  // The upper body's own lean (the hip strategy) is not a fall.
  if (math::tilt_from_vertical(sensors.imu_orientation.toRotationMatrix()) <= params_.fall_tilt + lean_.angle().norm())
    return false;
  plan_.enter_fallen();
  return true;
}

void WalkingController::adapt_steps(const SensorData& sensors) {
  const PatternSample& s = plan_.sample();
  const bool estimate = params_.stabilizer && status_.com_estimate_valid && params_.step_adaptation.enabled;
  {
    const FootReference& stance = s.feet[index_of(s.stance)];
    const Eigen::Matrix2d to_world = yaw_rotation(s.heading).topLeftCorner<2, 2>();
    plan_.set_measured_com(stance.position.head<2>() + to_world * com_estimator_.estimate(),
                           stance.velocity.head<2>() + to_world * com_estimator_.rate(),
                           params_.step_adaptation.replan_threshold, estimate && params_.step_adaptation.replan);
  }
  const int swing = !s.feet[0].in_contact ? 0 : !s.feet[1].in_contact ? 1 : -1;
  if (swing < 0 || !estimate || plan_.num_planned_steps() == 0) {
    step_adaptation_.idle();
    plan_.shift_landing(Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero());
    plan_.limit_next_step_time(0.0);
    plan_.keep_stepping(false, params_.step_adaptation.balance_steps);
    Side first = Side::Right;
    const bool needed = estimate && needs_standing_step(s, first);
    plan_.step_from_standing(needed, first);
    return;
  }
  plan_.step_from_standing(false, Side::Right);
  const FootReference& stance = s.feet[1 - swing];
  const Eigen::Matrix2d to_heading = yaw_rotation(-s.heading).topLeftCorner<2, 2>();
  StepAdaptationInput in;
  in.swing = swing == 0 ? Side::Left : Side::Right;
  in.time_to_touchdown = s.feet[swing].time_to_touchdown;
  in.planned_com = to_heading * (s.com - stance.position).head<2>();
  in.planned_com_rate = to_heading * (s.com_velocity - stance.velocity).head<2>();
  in.measured_com = com_estimator_.estimate();
  in.measured_com_rate = com_estimator_.rate();
  in.planned_landing = to_heading * (plan_.planned_step(0).position - stance.position.head<2>());
  in.com_height = s.com.z() - stance.position.z() + plan_.pattern_generator().params().ankle_height;
  // The stance sole around the planned centre of pressure (the pattern's ZMP point of the foot).
  const FootInfo& foot = model_.foot(in.swing == Side::Left ? Side::Right : Side::Left);
  const double zmp_x = plan_.pattern_generator().params().zmp_offset_x;
  const double margin = params_.stabilization.cop_margin;
  in.cop_forward = std::max(0.0, foot.sensor_position.x() + foot.sole_x_max - margin - zmp_x);
  in.cop_backward = std::max(0.0, zmp_x - foot.sensor_position.x() - foot.sole_x_min - margin);
  in.cop_sideways = std::max(0.0, std::min(foot.sole_y_max, -foot.sole_y_min) - margin);
  in.gravity = model_.gravity();
  // A foot that has met the ground before its planned touchdown is not moved any more: it carries
  // load, and dragging it would push the robot off its feet.
  in.swing_foot_on_ground = sensors.foot_wrench[swing].force.z() > params_.terrain.contact_force;
  step_adaptation_.update(params_.rmrc.dt, in);
  const Eigen::Matrix2d to_world = to_heading.transpose();
  plan_.shift_landing(to_world * step_adaptation_.shift(), to_world * step_adaptation_.shift_rate());
  plan_.limit_next_step_time(step_adaptation_.max_next_step_time());
  plan_.keep_stepping(step_adaptation_.unbalanced(), params_.step_adaptation.balance_steps);
}

bool WalkingController::needs_standing_step(const PatternSample& s, Side& swing) const {
  const StepAdaptationParams& p = params_.step_adaptation;
  if (!p.standing_step || p.balance_steps == 0 || !plan_.standing()) return false;
  // Heading frame, relative to the stance foot, as the CoM estimate.
  const FootReference& stance = s.feet[index_of(s.stance)];
  const Eigen::Matrix2d to_heading = yaw_rotation(-s.heading).topLeftCorner<2, 2>();
  const double com_height = s.com.z() - stance.position.z() + plan_.pattern_generator().params().ankle_height;
  const Eigen::Vector2d dcm =
      com_estimator_.estimate() + com_estimator_.rate() / std::sqrt(model_.gravity() / std::max(com_height, 1e-3));
  if (!dcm.allFinite()) return false;
  // The box around both soles' corners: the support, up to the gap between the feet's toes or
  // heels when they stand staggered.
  Eigen::Vector2d low = Eigen::Vector2d::Constant(INFINITY), high = Eigen::Vector2d::Constant(-INFINITY);
  for (Side side : kSides) {
    const FootReference& f = s.feet[index_of(side)];
    const FootInfo& foot = model_.foot(side);
    const Eigen::Matrix2d turn = yaw_rotation(f.yaw - s.heading).topLeftCorner<2, 2>();
    const Eigen::Vector2d ankle = to_heading * (f.position - stance.position).head<2>();
    for (const double x : {foot.sole_x_min, foot.sole_x_max}) {
      for (const double y : {foot.sole_y_min, foot.sole_y_max}) {
        const Eigen::Vector2d corner = ankle + turn * (foot.sensor_position.head<2>() + Eigen::Vector2d(x, y));
        low = low.cwiseMin(corner);
        high = high.cwiseMax(corner);
      }
    }
  }
  const Eigen::Vector2d beyond = (low.array() + p.standing_step_margin - dcm.array())
                                     .max(dcm.array() - high.array() + p.standing_step_margin)
                                     .matrix();
  if (beyond.maxCoeff() <= 0.0) return false;
  // Out sideways: the foot on that side steps out. Out only forward or backward: the foot farther
  // from the DCM, which carries less of the weight.
  const bool towards_left = dcm.y() > 0.5 * (low.y() + high.y());
  const bool left = beyond.y() > 0.0 ? towards_left : !towards_left;
  swing = left ? Side::Left : Side::Right;
  return true;
}

void WalkingController::adapt_to_terrain(const SensorData& sensors) {
  if (!params_.stabilizer) return;
  // Where each standing foot's ground is, in the frame of the commanded heights: its height
  // modification (eq. 20) and its sole's deflection under the measured load (eq. 11). A foot
  // whose F/T sensor has failed finds no ground; the other goes on finding its own.
  const auto& m = stabilizer_.modification();
  const double compliance = 1.0 / stabilizer_.contact_stiffness();
  // Standing also at the end of a safe stop: a foothold latched centimetres off during its steps
  // tilts the robot standing on one foot (JVRC-1 after a transient F/T fault).
  const bool standing = plan_.standing() && params_.terrain.level_standing_feet &&
                        health().force_torque[0] && health().force_torque[1];
  std::array<double, 2> ground = {NAN, NAN};
  if (params_.terrain.measure_step_height || standing) {
    ground = {measured_ground(Side::Left, sensors), measured_ground(Side::Right, sensors)};
  }
  // The lean from the commanded orientation: cos of its angle is the commanded vertical's z in the
  // world. Beyond step_height_max_lean the steps are not measured: in larger motions the attitude
  // estimate lags.
  const Eigen::Matrix3d lean =
      sensors.imu_orientation.toRotationMatrix() * rmrc_.task().frames().rotation[model_.upper_body()].transpose();
  const bool measure_steps =
      params_.terrain.measure_step_height && lean(2, 2) >= std::cos(params_.terrain.step_height_max_lean);
  terrain_.step(params_.rmrc.dt, plan_.sample(), sensors.foot_wrench, stabilizer_.desired(),
                {m[0].offset[0] + compliance * std::max(0.0, sensors.foot_wrench[0].force.z()),
                 m[1].offset[0] + compliance * std::max(0.0, sensors.foot_wrench[1].force.z())},
                health().force_torque, {m[0].offset.tail<2>(), m[1].offset.tail<2>()},
                measure_steps ? ground : std::array<double, 2>{NAN, NAN});
  if (standing) terrain_.level_standing_feet(params_.rmrc.dt, ground);
}

double WalkingController::measured_ground(Side side, const SensorData& sensors) const {
  if (!health().imu || health().encoder_failed.any()) return NAN;
  const Eigen::Matrix3d upper_body = sensors.imu_orientation.toRotationMatrix();
  // The encoders' kinematics have the base at the origin, unrotated; the measured upper-body
  // orientation turns the whole chain (as in the CoM estimate).
  const BodyFrames& measured = encoders_.frames();
  const Eigen::Matrix3d base = upper_body * measured.rotation[model_.upper_body()].transpose();
  const FootInfo& foot = model_.foot(side);
  const Eigen::Vector3d sole = measured.rotation[foot.body] * (foot.sensor_position + Eigen::Vector3d(0.0, 0.0, foot.sole_z)) +
                               measured.position[foot.body];
  const double deflection = stabilizer_.sole_deflection(side, sensors.foot_wrench[index_of(side)]).x();
  return (base * (sole - measured.position[model_.pelvis_body()])).z() + deflection;
}

void WalkingController::stabilize(const SensorData& sensors) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const PatternSample& s = plan_.sample();
  if (params_.stabilizer && uses_sensors()) {
    // eq. (10)'s Δr_CoM: planned − estimated CoM relative to the stance foot, heading frame.
    com_estimator_.update(sensors, encoders_.frames(), s.stance, params_.rmrc.dt);
    const Eigen::Matrix2d to_heading = yaw_rotation(-s.heading).topLeftCorner<2, 2>();
    const FootReference& foot = s.feet[index_of(s.stance)];
    StabilizerInput in;
    in.com_error = to_heading * (s.com - foot.position).head<2>() - com_estimator_.estimate();
    in.com_rate_error = to_heading * (s.com_velocity - foot.velocity).head<2>() - com_estimator_.rate();
    status_.com_estimated = foot.position.head<2>() + to_heading.transpose() * com_estimator_.estimate();
    in.ideal = s.contact_wrench;
    in.planned_contact = {s.feet[0].in_contact, s.feet[1].in_contact};
    in.load_share = s.load_share;
    in.measured = sensors.foot_wrench;
    in.imu_orientation = sensors.imu_orientation;
    in.imu_rate = sensors.imu_angular_rate;
    // The lean follows this cycle's DCM error (measured − planned, relative to the stance foot,
    // with the rate carried over changes of stance foot); the task reference takes it up in the
    // next cycle, eq. (10)'s tilt error now.
    const double com_height = s.com.z() - foot.position.z() + plan_.pattern_generator().params().ankle_height;
    const double omega = std::sqrt(model_.gravity() / std::max(com_height, 1e-3));
    const Eigen::Vector2d planned_rate = to_heading * (s.com_velocity - foot.velocity).head<2>();
    lean_.update(params_.rmrc.dt, -in.com_error + (com_estimator_.carried_rate() - planned_rate) / omega, true);
    in.upper_body_lean = lean_.angle();
    in.upper_body_lean_rate = lean_.rate();
    stabilizer_.update_contact_model(sensors.joint_position, sensors.foot_wrench);
    stabilizer_.step(params_.rmrc.dt, in);
    reference_.set_modification(s, stabilizer_.modification());
  } else {
    lean_.update(params_.rmrc.dt, Eigen::Vector2d::Zero(), false);
    // Without force feedback the feet's modifications return to the plan.
    if (!uses_sensors()) reference_.decay_modification(std::exp(-params_.stabilization.position_gain * params_.rmrc.dt));
  }
  timing_.stabilizer_us = std::chrono::duration<double, std::micro>(Clock::now() - start).count();
}

void WalkingController::resolve_rates(JointCommand& out) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  rmrc_.step(reference_.x(), reference_.rate(), heading_frame(), reference_.modification(),
             reference_.modification_rate());
  timing_.rmrc_us = std::chrono::duration<double, std::micro>(Clock::now() - start).count();
  if (!rmrc_.fault() && rmrc_.joint_positions().allFinite()) last_setpoint_ = rmrc_.joint_positions();
  out.position = last_setpoint_;
}

void WalkingController::publish_status() {
  const PatternSample& s = plan_.sample();
  const bool stabilizing = params_.stabilizer && uses_sensors();
  status_.command_saturated = plan_.command_saturated();
  status_.steps_completed = plan_.steps_completed();
  status_.com_desired = s.com;
  status_.zmp_desired = s.zmp;
  status_.desired_wrench = stabilizing ? stabilizer_.desired() : s.contact_wrench;
  status_.contact_stiffness = params_.stabilizer ? stabilizer_.contact_stiffness() : 0.0;
  status_.state = name_of(plan_.state());
  status_.com_estimate_valid = stabilizing;
  status_.num_planned_steps = plan_.num_planned_steps();
  status_.dcm_error = step_adaptation_.dcm_error();
  status_.landing_shift = step_adaptation_.shift();
  status_.upper_body_lean = lean_.angle();
  for (int k = 0; k < 2; ++k) {
    status_.foot_height_offset[k] = terrain_.foot_offset(k);
    status_.foot_tilt[k] = terrain_.foot_tilt(k);
    status_.foot_roll[k] = terrain_.foot_roll(k);
  }
  for (int i = 0; i < plan_.num_planned_steps(); ++i) {
    const Footstep& f = plan_.planned_step(i);
    status_.planned_steps[i] = {f.side, f.position, f.yaw, f.touchdown};
  }
}

}  // namespace biped
