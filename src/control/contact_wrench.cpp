#include "control/contact_wrench.hpp"

namespace biped {

// The ground's force F acting at p = (px, py, sole_z) gives the torque p × F at the sensor origin:
// τx = py Fz − sole_z Fy and τy = sole_z Fx − px Fz.
Eigen::Vector2d center_of_pressure(const Wrench& w, double sole_z) {
  const Eigen::Vector3d& f = w.force;
  const Eigen::Vector3d& t = w.torque;
  return {(sole_z * f.x() - t.y()) / f.z(), (t.x() + sole_z * f.y()) / f.z()};
}

}  // namespace biped
