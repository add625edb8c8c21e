#pragma once
// A run observer for closed-loop tests: the largest foothold height offset the terrain adaptation
// reports over a run (ControllerStatus::foot_height_offset, both feet).
#include <algorithm>
#include <cmath>

#include "sim/closed_loop.hpp"

namespace biped::test {

struct LargestFootholdOffset final : public RunObserver {
  double largest = 0.0;
  void record(const Simulation&, const SensorData&, const JointCommand&, const ControllerStatus& status,
              double) override {
    for (double offset : status.foot_height_offset) largest = std::max(largest, std::abs(offset));
  }
};

}  // namespace biped::test
