// One replanning of the walking pattern generator (three steps ahead: ZMP reference, leg
// trajectories at the collocation points, the collocation system's factorization and two solves),
// and one sample of the plan (what every control cycle evaluates).
#include <benchmark/benchmark.h>

#include <cmath>

#include "planning/step_sequence_planner.hpp"
#include "planning/walking_pattern_generator.hpp"

namespace biped {
namespace {

// Three steps at 0.8 m/s turning a little, from feet side by side, the body moving.
struct ThreeSteps {
  RobotModel model;
  WalkingPatternGenerator generator;
  StepParameters params;
  std::array<Footstep, 2> feet{Footstep{Side::Left, {0.0, 0.09}, 0.0, 0.0}, Footstep{Side::Right, {0.0, -0.09}, 0.0, 0.0}};
  std::array<Footstep, 3> steps;
  AxisState x, y;

  explicit ThreeSteps(const char* path)
      : model(RobotModel::load(path, 5.0 * M_PI / 180.0)), generator(simplified_model_of(model)) {
    plan_steps(feet[0], {0.8, 0.0, 0.1}, params, params.step_time, 3, steps);
    x.velocity = 0.6;
  }
  void replan() { generator.replan(0.0, feet, steps, 3, params, x, y, Eigen::Vector2d(0.05, 0.0)); }
};

void BM_PatternReplan(benchmark::State& state, const char* path) {
  ThreeSteps walk(path);
  for (auto _ : state) {
    walk.replan();
    benchmark::ClobberMemory();
  }
}

void BM_PatternSample(benchmark::State& state, const char* path) {
  ThreeSteps walk(path);
  walk.replan();
  WalkingPatternGenerator& generator = walk.generator;
  PatternSample sample;
  double t = 0.0;
  for (auto _ : state) {
    generator.sample(t, sample);
    t = t > 2.0 ? 0.0 : t + 0.001;
    benchmark::DoNotOptimize(sample.com.data());
  }
}

BENCHMARK_CAPTURE(BM_PatternReplan, lola, BIPED_SOURCE_DIR "/models/lola/lola.xml")->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_PatternSample, lola, BIPED_SOURCE_DIR "/models/lola/lola.xml")->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace biped
