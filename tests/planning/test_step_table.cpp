#include "planning/step_table.hpp"

#include <gtest/gtest.h>

namespace biped {
namespace {

TEST(StepTable, InterpolatesBetweenRowsAndHoldsBeyondTheEnds) {
  StepTable table;
  table.rows = {{0.0, 1.0, 0.3, 0.04, 0.05, 0.8}, {0.5, 0.8, 0.2, 0.05, 0.04, 0.8}, {1.0, 0.6, 0.1, 0.05, 0.01, 1.0}};
  StepParameters base;
  base.step_width = 0.21;
  const StepParameters mid = table.lookup(0.25, base);
  EXPECT_NEAR(mid.step_time, 0.9, 1e-12);
  EXPECT_NEAR(mid.swing_travel_share, 0.8, 1e-12);
  EXPECT_NEAR(table.lookup(0.75, base).swing_travel_share, 0.9, 1e-12);
  EXPECT_NEAR(mid.double_support_ratio, 0.25, 1e-12);
  EXPECT_NEAR(mid.clearance, 0.045, 1e-12);
  EXPECT_DOUBLE_EQ(mid.step_width, 0.21) << "what the table does not hold is kept";
  EXPECT_NEAR(table.lookup(-0.75, base).step_time, 0.7, 1e-12) << "backwards uses |speed|";
  EXPECT_NEAR(table.lookup(3.0, base).step_time, 0.6, 1e-12);
  EXPECT_NEAR(StepTable{}.lookup(0.5, base).step_time, base.step_time, 1e-12) << "an empty table keeps the base";
}

// The fastest row counts only with more than the required ZMP margin.
TEST(StepTable, FastestFeasibleSpeedNeedsMoreThanTheRequiredMargin) {
  StepTable table;
  table.rows = {{0.0, 0.8, 0.2, 0.04, 0.07}, {0.5, 0.7, 0.2, 0.04, 0.05}, {0.8, 0.6, 0.2, 0.04, 0.03},
                {0.9, 0.55, 0.2, 0.04, 0.01}, {1.0, 0.5, 0.2, 0.04, 0.0005}, {1.1, 0.5, 0.2, 0.04, -0.01}};
  EXPECT_DOUBLE_EQ(fastest_feasible_speed(table), 1.0);
  EXPECT_DOUBLE_EQ(fastest_feasible_speed(table, 0.005), 0.9);
  EXPECT_DOUBLE_EQ(fastest_feasible_speed(table, 0.02), 0.8);
  EXPECT_DOUBLE_EQ(fastest_feasible_speed(table, 0.1), 0.0) << "none";
}

}  // namespace
}  // namespace biped
