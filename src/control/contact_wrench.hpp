#pragma once
// Quantities derived from a measured foot wrench.
#include <Eigen/Core>

#include "math/wrench.hpp"

namespace biped {

// Centre of pressure on the sole plane z = sole_z (sensor frame), from the wrench the sole exerts
// on the ankle side measured at the sensor origin. Requires force.z() > 0.
Eigen::Vector2d center_of_pressure(const Wrench& w, double sole_z);

}  // namespace biped
