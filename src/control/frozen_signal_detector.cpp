#include "control/frozen_signal_detector.hpp"

namespace biped {

void FrozenSignalDetector::reset(const SensorData& first) {
  last_wrench_ = first.foot_wrench;
  last_rate_ = first.imu_angular_rate;
  last_acceleration_ = first.imu_acceleration;
  wrench_repeats_ = {0, 0};
  imu_repeats_ = 0;
}

void FrozenSignalDetector::update(const SensorData& s, int frozen_cycles, FaultList& out) {
  for (Side side : kSides) {
    const int k = index_of(side);
    const Wrench& w = s.foot_wrench[k];
    const bool same = w.force == last_wrench_[k].force && w.torque == last_wrench_[k].torque;
    wrench_repeats_[k] = same ? wrench_repeats_[k] + 1 : 0;
    last_wrench_[k] = w;
  }
  const bool imu_same = s.imu_angular_rate == last_rate_ && s.imu_acceleration == last_acceleration_;
  imu_repeats_ = imu_same ? imu_repeats_ + 1 : 0;
  last_rate_ = s.imu_angular_rate;
  last_acceleration_ = s.imu_acceleration;
  if (frozen_cycles <= 0) return;
  for (Side side : kSides) {
    if (wrench_repeats_[index_of(side)] >= frozen_cycles) {
      out.add({FaultSignal::ForceTorque, FaultCheck::Frozen, index_of(side), s.time});
    }
  }
  if (imu_repeats_ >= frozen_cycles) out.add({FaultSignal::Imu, FaultCheck::Frozen, -1, s.time});
}

}  // namespace biped
