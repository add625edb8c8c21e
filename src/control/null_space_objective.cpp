#include "control/null_space_objective.hpp"

#include <stdexcept>
#include <string>

namespace biped {

NullSpaceObjective::NullSpaceObjective(const RobotModel& model, const NullSpaceObjectiveParams& params)
    : nv_(model.nv()), comfort_weight_(params.comfort_weight), limit_weight_(params.limit_weight) {
  const Eigen::VectorXd& comfort = params.comfort_pose.size() == 0 ? model.stand_pose() : params.comfort_pose;
  if (comfort.size() != model.num_joints()) {
    throw std::invalid_argument("null-space objective: comfort pose has " + std::to_string(comfort.size()) +
                                " entries, the model has " + std::to_string(model.num_joints()) + " joints");
  }
  if (!(params.activation_fraction >= 0.0 && params.activation_fraction <= 0.5)) {
    throw std::invalid_argument("null-space objective: activation_fraction must be in [0, 0.5]");
  }
  for (int i = 0; i < model.num_joints(); ++i) {
    const JointInfo& info = model.joints()[i];
    const double zone = params.activation_fraction * (info.soft_upper - info.soft_lower);
    joints_.push_back({info.qpos_adr, info.dof_adr, comfort[i], info.soft_lower + zone, info.soft_upper - zone});
  }
}

double NullSpaceObjective::limit_zone_depth(int joint, double q) const {
  const Joint& j = joints_[joint];
  if (q < j.zone_lower) return q - j.zone_lower;
  if (q > j.zone_upper) return q - j.zone_upper;
  return 0.0;
}

double NullSpaceObjective::value(const Eigen::VectorXd& qpos) const {
  double h = 0.0;
  for (int i = 0; i < static_cast<int>(joints_.size()); ++i) {
    const double q = qpos[joints_[i].qpos_adr];
    const double to_comfort = q - joints_[i].comfort;
    const double depth = limit_zone_depth(i, q);
    h += 0.5 * comfort_weight_ * to_comfort * to_comfort + 0.5 * limit_weight_ * depth * depth;
  }
  return h;
}

void NullSpaceObjective::gradient(const Eigen::VectorXd& qpos, Eigen::VectorXd& gradient) const {
  gradient.setZero(nv_);
  // Hinge joints: the velocity direction of a joint is its angle, so ∂H/∂v_i = ∂H/∂q_i.
  for (int i = 0; i < static_cast<int>(joints_.size()); ++i) {
    const double q = qpos[joints_[i].qpos_adr];
    gradient[joints_[i].dof_adr] =
        comfort_weight_ * (q - joints_[i].comfort) + limit_weight_ * limit_zone_depth(i, q);
  }
}

}  // namespace biped
