#pragma once
// A sensor fault as the controller detected it: which signal, which check failed, and which side
// or joint. Typed, so that a caller (or the controller itself) decides what a fault disables
// without parsing text; describe() gives the text for logs.
#include <array>

namespace biped {

enum class FaultSignal {
  None,
  Time,             // the sensor data's time stamp
  JointEncoder,     // index: the joint (RobotModel::joints() order)
  ImuOrientation,
  ImuAngularRate,
  ImuAcceleration,
  Imu,              // the IMU's rate and acceleration channels together (a dead unit)
  ForceTorque,      // index: the foot (index_of(Side))
};

enum class FaultCheck {
  None,
  Implausible,  // not finite, or outside its physical range
  Frozen,       // bit-identical readings for too many cycles (an encoder: while its set-point moved)
  Jump,         // an encoder reading that moved farther in one cycle than the joint can
};

struct Fault {
  FaultSignal signal = FaultSignal::None;
  FaultCheck check = FaultCheck::None;
  int index = -1;  // side or joint, see FaultSignal; −1 where neither applies
  double time = 0.0;  // [s] the sensor time of the reading it was detected in

  explicit operator bool() const { return signal != FaultSignal::None; }
  bool is_force_torque() const { return signal == FaultSignal::ForceTorque; }
};

// A static text naming the fault, e.g. "left F/T sensor frozen" (never null; "" for no fault).
inline const char* describe(const Fault& f) {
  const bool frozen = f.check == FaultCheck::Frozen;
  switch (f.signal) {
    case FaultSignal::None: return "";
    case FaultSignal::Time: return "time";
    case FaultSignal::JointEncoder:
      return frozen ? "joint encoder frozen" : f.check == FaultCheck::Jump ? "joint encoder jump" : "joint encoder";
    case FaultSignal::ImuOrientation: return "imu orientation";
    case FaultSignal::ImuAngularRate: return "imu angular rate";
    case FaultSignal::ImuAcceleration: return "imu acceleration";
    case FaultSignal::Imu: return frozen ? "imu frozen" : "imu";
    case FaultSignal::ForceTorque:
      if (f.index == 0) return frozen ? "left F/T sensor frozen" : "left F/T sensor";
      return frozen ? "right F/T sensor frozen" : "right F/T sensor";
  }
  return "";
}

// Faults found in one reading (or latched over a run), at most kCapacity of them.
struct FaultList {
  static constexpr int kCapacity = 16;
  std::array<Fault, kCapacity> items;
  int count = 0;
  void add(const Fault& f) {
    if (count < kCapacity) items[count++] = f;
  }
  void clear() { count = 0; }
};

}  // namespace biped
