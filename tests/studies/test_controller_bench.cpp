// `biped bench` on a short walk: the JSON of DESIGN.md's contract, timings that are consistent with
// each other (never absolute values), no fall, and no allocation in the controller's cycle.
#include "studies/controller_bench.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "apps/allocation_counter.hpp"
#include "io/yaml_reader.hpp"

namespace biped {
namespace {

bool positive_finite(const nlohmann::json& v) { return v.is_number() && std::isfinite(v.get<double>()) && v.get<double>() > 0.0; }

TEST(ControllerBench, ReportsTheContractsFiguresWithoutFallOrAllocation) {
  ControllerBenchOptions options;
  options.robot = "lola";
  options.duration = 1.5;  // starts walking at 1 s: the weight shift before the first step
  const nlohmann::json j = run_controller_bench(options, heap_allocations);

  EXPECT_EQ(j["robot"], "lola");
  EXPECT_EQ(j["cycles"].get<long>(), 1500);
  EXPECT_FALSE(j["fell"].get<bool>());
  for (const char* part : {"cycle_us", "stabilizer_us", "rmrc_us", "svd_baseline_us"}) {
    ASSERT_TRUE(j.contains(part)) << part;
    EXPECT_TRUE(positive_finite(j[part]["median"])) << part;
    EXPECT_TRUE(positive_finite(j[part]["p99"])) << part;
    EXPECT_LE(j[part]["median"].get<double>(), j[part]["p99"].get<double>()) << part;
  }
  // The stabilizer and eq. (21) are timed inside the cycle, so in every cycle each part took no
  // longer than the whole; order statistics keep that order: median ≤ median, p99 ≤ p99.
  for (const char* part : {"stabilizer_us", "rmrc_us"}) {
    for (const char* stat : {"median", "p99"}) {
      EXPECT_LE(j[part][stat].get<double>(), j["cycle_us"][stat].get<double>()) << part << ' ' << stat;
    }
  }
  ASSERT_TRUE(positive_finite(j["speedup_vs_svd"]));
  EXPECT_DOUBLE_EQ(j["speedup_vs_svd"].get<double>(),
                   j["svd_baseline_us"]["median"].get<double>() / j["rmrc_us"]["median"].get<double>());
  EXPECT_TRUE(positive_finite(j["realtime_factor"]));
  EXPECT_EQ(j["allocations_per_cycle"].get<double>(), 0.0);
}

// The figure is the counter's increase across the controller's step(), per cycle: a counter that
// goes up by one between each pair of readings gives exactly one.
TEST(ControllerBench, AllocationsPerCycleIsTheCountersIncreaseOverEachStep) {
  ControllerBenchOptions options;
  options.duration = 0.1;
  long calls = 0;
  const nlohmann::json j = run_controller_bench(options, [&calls] { return calls++; });
  EXPECT_EQ(j["allocations_per_cycle"].get<double>(), 1.0);
  EXPECT_EQ(calls, 2 * j["cycles"].get<long>());
}

TEST(ControllerBench, UnknownRobotIsBadInput) {
  ControllerBenchOptions options;
  options.robot = "no-such-robot";
  EXPECT_THROW(run_controller_bench(options, heap_allocations), InputError);
}

}  // namespace
}  // namespace biped
