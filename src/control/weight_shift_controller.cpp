#include "control/weight_shift_controller.hpp"

#include <algorithm>

namespace biped {
namespace {

// Quintic blend over [start, start + duration]: value and rate of 0 → 1.
void blend(double t, double start, double duration, double& s, double& rate) {
  const double tau = std::clamp((t - start) / duration, 0.0, 1.0);
  s = tau * tau * tau * (10.0 + tau * (-15.0 + 6.0 * tau));
  rate = (t > start && t < start + duration) ? 30.0 * tau * tau * (1.0 - tau) * (1.0 - tau) / duration : 0.0;
}

}  // namespace

WeightShiftController::WeightShiftController(const RobotModel& model, const WeightShiftParams& params)
    : model_(model),
      params_(params),
      space_(model),
      rmrc_(model, space_, params.rmrc),
      x_start_(Eigen::VectorXd::Zero(space_.dim())),
      com_shift_(Eigen::Vector3d::Zero()),
      x_id_(Eigen::VectorXd::Zero(space_.dim())),
      xdot_id_(Eigen::VectorXd::Zero(space_.dim())),
      last_setpoint_(model.stand_pose()) {}

double WeightShiftController::duration() const {
  return params_.start_delay + 2.0 * params_.shift_time + 2.0 * params_.lift_time + params_.hold_time;
}

void WeightShiftController::reset(const SensorData& first) {
  start_time_ = first.time;
  status_ = ControllerStatus{};
  status_.state = "standing";
  const Eigen::VectorXd q = initial_configuration(model_, params_.sensor_limits, first);
  last_setpoint_ = initial_joint_pose(model_, params_.sensor_limits, first);
  rmrc_.reset(q);
  TaskSpaceData data(space_);
  evaluate(space_, q, Eigen::Matrix3d::Identity(), data);
  x_start_ = data.x;
  // Over the middle of the stance sole: its centre lies ahead of the ankle by the sole's offset.
  const FootInfo& foot = model_.foot(params_.stance);
  const double sole_centre_x = foot.sensor_position.x() + 0.5 * (foot.sole_x_min + foot.sole_x_max);
  const Eigen::Vector3d target = data.foot_position[index_of(params_.stance)] + Eigen::Vector3d(sole_centre_x, 0.0, 0.0);
  com_shift_ << target.x() - data.com.x(), target.y() - data.com.y(), 0.0;
}

void WeightShiftController::step(const SensorData& sensors, const WalkCommand& /*command*/, JointCommand& out) {
  if (!status_.fault) {
    if (const Fault fault = check_sensors(model_, params_.sensor_limits, sensors)) {
      status_.fault = true;
      status_.first_fault = fault;
      status_.state = "safe_stop";
    }
  }
  if (status_.fault) {
    out.position = last_setpoint_;
    return;
  }
  const double t = sensors.time - start_time_;
  const WeightShiftParams& p = params_;
  const double t_shift = p.start_delay, t_lift = t_shift + p.shift_time, t_down = t_lift + p.lift_time + p.hold_time,
               t_back = t_down + p.lift_time;
  double shift_in, shift_in_rate, shift_out, shift_out_rate, up, up_rate, down, down_rate;
  blend(t, t_shift, p.shift_time, shift_in, shift_in_rate);
  blend(t, t_back, p.shift_time, shift_out, shift_out_rate);
  blend(t, t_lift, p.lift_time, up, up_rate);
  blend(t, t_down, p.lift_time, down, down_rate);
  const double shift = shift_in - shift_out, shift_rate = shift_in_rate - shift_out_rate;
  const double lift = p.lift_height * (up - down), lift_rate = p.lift_height * (up_rate - down_rate);

  const TaskLayout& L = space_.layout();
  x_id_ = x_start_;
  xdot_id_.setZero();
  const Eigen::Vector3d com_offset = shift * com_shift_, com_rate = shift_rate * com_shift_;
  x_id_.segment<3>(L.com) += com_offset;
  xdot_id_.segment<3>(L.com) = com_rate;
  // Feet are held in the world: relative to the CoM they move against it; the swing foot also lifts.
  for (Side side : kSides) {
    const int row = L.foot_position[index_of(side)];
    x_id_.segment<3>(row) -= com_offset;
    xdot_id_.segment<3>(row) = -com_rate;
    if (side == other(p.stance)) {
      x_id_[row + 2] += lift;
      xdot_id_[row + 2] += lift_rate;
    }
  }
  // Arms stay with the upper body: their CoMs move with the CoM.
  rmrc_.step(x_id_, xdot_id_, Eigen::Matrix3d::Identity());
  if (!rmrc_.fault() && rmrc_.joint_positions().allFinite()) last_setpoint_ = rmrc_.joint_positions();
  out.position = last_setpoint_;
  status_.com_desired = x_id_.segment<3>(L.com);
  status_.zmp_desired = status_.com_desired.head<2>();
  status_.state = lift > 1e-4 ? "single_support" : (shift > 1e-4 ? "shifting" : "standing");
  const double weight = model_.weight_above_sensors();
  for (Side side : kSides) {
    const double share = lift > 1e-4 ? (side == p.stance ? 1.0 : 0.0)
                                     : (side == p.stance ? 0.5 + 0.5 * shift : 0.5 - 0.5 * shift);
    status_.desired_wrench[index_of(side)].force.z() = share * weight;
  }
}

}  // namespace biped
