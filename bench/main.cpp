// Runs the benchmarks and, after the usual table, prints the speed-up of each Klein–Huang
// resolved-motion-rate cycle over the explicit-SVD implementation (median against median).
#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <string>

#include "studies/controller_bench.hpp"

namespace {

class MedianRecorder : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      const std::string name = run.benchmark_name();
      // With repetitions the aggregates are named "<name>_median"; without, the single run counts.
      if (run.run_type == Run::RT_Aggregate && run.aggregate_name == "median") {
        medians_[run.run_name.str()] = run.GetAdjustedRealTime();
      } else if (run.run_type == Run::RT_Iteration && !medians_.count(run.run_name.str())) {
        medians_[run.run_name.str()] = run.GetAdjustedRealTime();
      }
    }
    ConsoleReporter::ReportRuns(runs);
  }
  const std::map<std::string, double>& medians() const { return medians_; }

 private:
  std::map<std::string, double> medians_;
};

}  // namespace

int main(int argc, char** argv) {
  // Google Benchmark's header gives the date and the clock rate; the CPU model names the machine.
  benchmark::AddCustomContext("cpu_model", biped::cpu_model());
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  MedianRecorder reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  const auto& m = reporter.medians();
  for (const char* robot : {"lola", "johnnie"}) {
    const auto fast = m.find(std::string("BM_RmrcKleinHuang/") + robot);
    const auto slow = m.find(std::string("BM_RmrcSvd/") + robot);
    if (fast == m.end() || slow == m.end()) continue;
    std::printf("eq. (21) %-8s Klein-Huang %.1f us, explicit SVD %.1f us: %.1fx faster\n", robot, fast->second,
                slow->second, slow->second / fast->second);
  }
  return 0;
}
