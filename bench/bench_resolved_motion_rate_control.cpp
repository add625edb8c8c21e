// One resolved motion rate control cycle (kinematics, task Jacobian, eq. (21), integration):
// Klein & Huang form against the explicit SVD pseudo-inverse / null-space projector, same inputs.
// Run: biped_benchmarks --benchmark_filter=Rmrc --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cmath>

#include "control/resolved_motion_rate_control.hpp"
#include "control/resolved_motion_rate_control_svd.hpp"

namespace biped {
namespace {

template <class Rmrc>
void BM_RmrcCycle(benchmark::State& state, const char* path) {
  const RobotModel model = RobotModel::load(path, 5.0 * M_PI / 180.0);
  const TaskSpace space(model);
  Rmrc rmrc(model, space, ResolvedMotionRateControlParams{});

  // A walking-like cycle: the swing foot 1 cm up and moving, the CoM moving sideways.
  TaskSpaceData task(space);
  const Eigen::Matrix3d R_ref = Eigen::Matrix3d::Identity();
  evaluate(space, model.stand_qpos(), R_ref, task);
  Eigen::VectorXd x_id = task.x;
  Eigen::VectorXd xdot_id = Eigen::VectorXd::Zero(space.dim());
  const int swing_z = space.layout().foot_position[index_of(Side::Left)] + 2;
  x_id[swing_z] += 0.01;
  xdot_id[swing_z] = 0.2;
  xdot_id[space.layout().com + 1] = 0.1;

  for (auto _ : state) {
    rmrc.reset(model.stand_qpos());  // same state every iteration, for both implementations
    benchmark::DoNotOptimize(rmrc.step(x_id, xdot_id, R_ref).data());
    benchmark::ClobberMemory();
  }
}

const char* const kLola = BIPED_SOURCE_DIR "/models/lola/lola.xml";
const char* const kJohnnie = BIPED_SOURCE_DIR "/models/johnnie/johnnie.xml";

void BM_RmrcKleinHuang(benchmark::State& state, const char* path) {
  BM_RmrcCycle<ResolvedMotionRateControl>(state, path);
}
void BM_RmrcSvd(benchmark::State& state, const char* path) { BM_RmrcCycle<ResolvedMotionRateControlSvd>(state, path); }

BENCHMARK_CAPTURE(BM_RmrcKleinHuang, lola, kLola)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_RmrcSvd, lola, kLola)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_RmrcKleinHuang, johnnie, kJohnnie)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_RmrcSvd, johnnie, kJohnnie)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace biped
