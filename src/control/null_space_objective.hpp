#pragma once
// The objective H minimized in the null space of the task Jacobian (the paper's Fig. 5):
//   H = Σ_i ½ w_cmf (q_i − q_cmf,i)²  +  Σ_i ½ w_lim s_i²
// where s_i is how far joint i has entered the activation zone next to one of its software limits
// (zero in the middle of the range). The zones are a fraction of the software range at each end.
#include <Eigen/Core>
#include <vector>

#include "model/robot_model.hpp"

namespace biped {

struct NullSpaceObjectiveParams {
  double comfort_weight = 1.0;        // w_cmf [1]
  double limit_weight = 50.0;         // w_lim [1]: steep, so the limit term wins inside its zone
  double activation_fraction = 0.1;   // zone width as a fraction of the software range, each end
  Eigen::VectorXd comfort_pose;       // q_cmf in RobotModel::joints() order; empty: stand_pose()
};

class NullSpaceObjective {
 public:
  // Throws std::invalid_argument on a comfort pose of the wrong size or a fraction outside [0, 0.5].
  NullSpaceObjective(const RobotModel& model, const NullSpaceObjectiveParams& params);

  // H at the full configuration qpos (size nq).
  double value(const Eigen::VectorXd& qpos) const;
  // ∇H with respect to the generalized velocities (size nv; zero for the floating base).
  // Allocation-free when `gradient` already has size nv.
  void gradient(const Eigen::VectorXd& qpos, Eigen::VectorXd& gradient) const;

  // Signed depth of joint i (RobotModel::joints() order) inside an activation zone:
  // negative in the lower zone, positive in the upper zone, zero in between.
  double limit_zone_depth(int joint, double q) const;

 private:
  struct Joint {
    int qpos_adr;
    int dof_adr;
    double comfort;      // q_cmf,i
    double zone_lower;   // the limit term is active below this angle ...
    double zone_upper;   // ... and above this one
  };
  std::vector<Joint> joints_;
  int nv_;
  double comfort_weight_;
  double limit_weight_;
};

}  // namespace biped
