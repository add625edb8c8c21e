#include "control/frozen_signal_detector.hpp"

#include <gtest/gtest.h>

namespace biped {
namespace {

// The frozen signals the detector reports for this reading.
FaultList update(FrozenSignalDetector& d, const SensorData& s, int cycles) {
  FaultList out;
  d.update(s, cycles, out);
  return out;
}

SensorData live_reading() {
  SensorData s(0);
  s.imu_acceleration = Eigen::Vector3d(0, 0, 9.81);
  return s;
}

// A frozen F/T channel is reported after `frozen_cycles` identical readings, not before; a reading
// that changes, however little, restarts the count.
TEST(FrozenSignalDetector, FrozenSignalIsReportedAfterTheConfiguredNumberOfRepeats) {
  FrozenSignalDetector detector;
  SensorData s = live_reading();
  s.foot_wrench[0].force.z() = 300.0;
  detector.reset(s);
  for (int i = 1; i <= 20; ++i) {
    s.foot_wrench[1].force.z() = 300.0 + 1e-9 * i;  // the right sensor and the IMU stay alive
    s.imu_angular_rate.x() = 1e-9 * i;
    const FaultList faults = update(detector, s, 5);
    if (i < 5) {
      EXPECT_EQ(faults.count, 0) << i;
    } else {
      ASSERT_EQ(faults.count, 1) << i;
      const Fault& fault = faults.items[0];
      EXPECT_EQ(fault.signal, FaultSignal::ForceTorque) << i;
      EXPECT_EQ(fault.check, FaultCheck::Frozen) << i;
      EXPECT_EQ(fault.index, index_of(Side::Left)) << i;
      EXPECT_STREQ(describe(fault), "left F/T sensor frozen") << i;
    }
  }
  s.foot_wrench[0].force.z() += 1e-9;
  EXPECT_EQ(update(detector, s, 5).count, 0) << "a changing reading restarts the count";
  for (int i = 0; i < 10; ++i) EXPECT_EQ(update(detector, s, 0).count, 0) << "0 switches the check off";
}

TEST(FrozenSignalDetector, FrozenImuIsReported) {
  FrozenSignalDetector detector;
  SensorData s = live_reading();
  detector.reset(s);
  Fault fault;
  for (int i = 1; i <= 3 && !fault; ++i) {
    s.foot_wrench[0].force.z() = i;
    s.foot_wrench[1].force.z() = i;
    const FaultList faults = update(detector, s, 3);
    if (faults.count > 0) fault = faults.items[0];
  }
  EXPECT_EQ(fault.signal, FaultSignal::Imu);
  EXPECT_EQ(fault.check, FaultCheck::Frozen);
  EXPECT_STREQ(describe(fault), "imu frozen");
}

}  // namespace
}  // namespace biped
