#pragma once
// Detects a signal that stopped changing. A working F/T sensor or IMU always shows some noise, so
// `frozen_cycles` bit-identical readings in a row mean a dead channel (cable, converter, driver).
// Encoders are not watched: quantized, they rightly repeat while a joint stands still.
#include <array>

#include "interface/fault.hpp"
#include "interface/sensor_data.hpp"

namespace biped {

class FrozenSignalDetector {
 public:
  void reset(const SensorData& first);
  // Adds every frozen signal (check Frozen) to `out`; `frozen_cycles` 0 switches the check off.
  void update(const SensorData& s, int frozen_cycles, FaultList& out);

 private:
  std::array<Wrench, 2> last_wrench_;
  Eigen::Vector3d last_rate_ = Eigen::Vector3d::Zero(), last_acceleration_ = Eigen::Vector3d::Zero();
  std::array<int, 2> wrench_repeats_ = {0, 0};
  int imu_repeats_ = 0;
};

}  // namespace biped
