// The closed loop's bookkeeping, with fake controllers in the controller slot: the joystick timeline
// reaches the controller in time order, the sensor readings carry the simulator's time, the
// observers are called at their rates, every cycle is timed, and a fall ends the run
// `run_on_after_fall` later.
#include "sim/closed_loop.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "test_support.hpp"

namespace biped {
namespace {

// Holds the stand pose (or another fixed pose) and records what each call hands it, together with
// the simulator's own time at that moment.
class RecordingController final : public Controller {
 public:
  struct Call {
    double sensor_time;
    double sim_time;
    WalkCommand command;
  };

  RecordingController(const Simulation& sim, Eigen::VectorXd pose) : sim_(sim), pose_(std::move(pose)) {}

  void reset(const SensorData& first) override {
    ++resets;
    reset_sensor_time = first.time;
    reset_sim_time = sim_.time();
    EXPECT_TRUE(calls.empty()) << "reset() comes before the first step()";
  }
  void step(const SensorData& sensors, const WalkCommand& command, JointCommand& out) override {
    calls.push_back({sensors.time, sim_.time(), command});
    out.position = pose_;
  }
  const ControllerStatus& status() const override { return status_; }

  int resets = 0;
  double reset_sensor_time = -1.0, reset_sim_time = -1.0;
  std::vector<Call> calls;

 private:
  const Simulation& sim_;
  Eigen::VectorXd pose_;
  ControllerStatus status_;
};

struct CountingObserver final : public RunObserver {
  struct Record {
    double sim_time;
    double sensor_time;
    double cycle_us;
  };
  std::vector<Record> records;
  std::vector<double> cycle_starts;  // the simulator's time at each call

  void record(const Simulation& sim, const SensorData& sensors, const JointCommand&, const ControllerStatus&,
              double cycle_us) override {
    records.push_back({sim.time(), sensors.time, cycle_us});
  }
  void cycle_start(const Simulation& sim) override { cycle_starts.push_back(sim.time()); }
};

SimulationParams johnnie_params() {
  SimulationParams p;
  p.world.robot_mjcf = test::model_path("johnnie");
  return p;
}

WalkCommand walk(double vx, double vy, double omega, bool stop = false) { return {vx, vy, omega, stop}; }

bool same(const WalkCommand& a, const WalkCommand& b) {
  return a.vx == b.vx && a.vy == b.vy && a.omega == b.omega && a.stop == b.stop;
}

// Every cycle gets the last command whose time has come (two at the same time: the later one),
// and the sensor reading with the simulator's time at the start of the cycle.
TEST(ClosedLoop, CommandsAndSensorTimesReachTheControllerInTimeOrder) {
  const RobotModel model = test::load_model("johnnie");
  Simulation sim(johnnie_params(), model);
  RecordingController controller(sim, model.stand_pose());
  const std::vector<TimedCommand> timeline = {{0.0, walk(0.0, 0.0, 0.0)},
                                              {0.0105, walk(0.1, 0.0, 0.0)},  // between two cycles
                                              {0.02, walk(0.2, 0.05, 0.0)},   // on a cycle
                                              {0.02, walk(0.2, 0.05, 0.1)},   // same time: this one holds
                                              {0.035, walk(0.0, 0.0, 0.0, true)}};
  RunOptions options;
  options.duration = 0.05;
  const RunResult result = run_closed_loop(sim, controller, timeline, options, nullptr);

  EXPECT_EQ(controller.resets, 1);
  EXPECT_DOUBLE_EQ(controller.reset_sensor_time, 0.0);
  EXPECT_DOUBLE_EQ(controller.reset_sim_time, 0.0);
  ASSERT_EQ(controller.calls.size(), 50u);
  for (std::size_t i = 0; i < controller.calls.size(); ++i) {
    const RecordingController::Call& call = controller.calls[i];
    EXPECT_NEAR(call.sensor_time, 0.001 * static_cast<double>(i), 1e-9) << "cycle " << i;
    EXPECT_DOUBLE_EQ(call.sensor_time, call.sim_time) << "cycle " << i;
    const double t = 0.001 * static_cast<double>(i);
    const WalkCommand expected = t < 0.0105 ? timeline[0].command
                                 : t < 0.0199 ? timeline[1].command
                                 : t < 0.0349 ? timeline[3].command
                                              : timeline[4].command;
    EXPECT_TRUE(same(call.command, expected)) << "cycle " << i << ": vx " << call.command.vx << " vy "
                                              << call.command.vy << " omega " << call.command.omega;
  }
  EXPECT_NEAR(result.sim_time, 0.05, 1e-9);
  EXPECT_FALSE(result.fell);
}

// record() at the logging rate, on the cycles that are multiples of it, with that cycle's sensor
// reading and timing; cycle_start() before every cycle; one cycle_us entry per cycle.
TEST(ClosedLoop, ObserversAreCalledAtTheirRatesAndEveryCycleIsTimed) {
  const RobotModel model = test::load_model("johnnie");
  Simulation sim(johnnie_params(), model);
  RecordingController controller(sim, model.stand_pose());
  CountingObserver observer;
  RunOptions options;
  options.duration = 0.1;
  options.log_period = 0.01;
  const RunResult result = run_closed_loop(sim, controller, {}, options, &observer);

  ASSERT_EQ(result.cycle_us.size(), 100u);
  for (double us : result.cycle_us) EXPECT_TRUE(std::isfinite(us) && us >= 0.0) << us;
  ASSERT_EQ(observer.cycle_starts.size(), 100u);
  for (std::size_t i = 0; i < observer.cycle_starts.size(); ++i) {
    EXPECT_DOUBLE_EQ(observer.cycle_starts[i], controller.calls[i].sim_time) << "before cycle " << i << "'s step";
  }
  ASSERT_EQ(observer.records.size(), 10u);
  for (std::size_t k = 0; k < observer.records.size(); ++k) {
    const CountingObserver::Record& r = observer.records[k];
    EXPECT_NEAR(r.sim_time, 0.01 * static_cast<double>(k), 1e-9) << "record " << k;
    EXPECT_DOUBLE_EQ(r.sensor_time, r.sim_time) << "record " << k;
    EXPECT_DOUBLE_EQ(r.cycle_us, result.cycle_us[10 * k]) << "record " << k;
  }
}

// With several physics steps per control period the loop runs one cycle per period, not per
// physics step.
TEST(ClosedLoop, RunsOneCyclePerControlPeriod) {
  const RobotModel model = test::load_model("johnnie");
  SimulationParams p = johnnie_params();
  p.world.timestep = 0.0005;
  p.control_period = 0.002;
  Simulation sim(p, model);
  RecordingController controller(sim, model.stand_pose());
  CountingObserver observer;
  RunOptions options;
  options.duration = 0.1;
  options.log_period = 0.01;
  const RunResult result = run_closed_loop(sim, controller, {}, options, &observer);
  EXPECT_EQ(result.cycle_us.size(), 50u);
  ASSERT_EQ(controller.calls.size(), 50u);
  for (std::size_t i = 0; i < controller.calls.size(); ++i) {
    EXPECT_NEAR(controller.calls[i].sensor_time, 0.002 * static_cast<double>(i), 1e-9) << "cycle " << i;
  }
  EXPECT_EQ(observer.records.size(), 10u);
  EXPECT_NEAR(result.sim_time, 0.1, 1e-9);
}

// A controller that drives every joint to its upper limit topples the robot: the run goes on for
// run_on_after_fall after the fall and then ends, long before the duration.
TEST(ClosedLoop, AFallEndsTheRunAfterRunOnAfterFall) {
  const RobotModel model = test::load_model("johnnie");
  Simulation sim(johnnie_params(), model);
  Eigen::VectorXd extreme(model.num_joints());
  for (int i = 0; i < model.num_joints(); ++i) extreme[i] = model.joints()[i].soft_upper;
  RecordingController controller(sim, extreme);
  RunOptions options;
  options.duration = 10.0;
  options.run_on_after_fall = 0.25;
  const RunResult result = run_closed_loop(sim, controller, {}, options, nullptr);

  ASSERT_TRUE(result.fell);
  EXPECT_STRNE(result.fall_reason, "");
  EXPECT_GT(result.fall_time, 0.0);
  EXPECT_NEAR(result.sim_time, result.fall_time + options.run_on_after_fall, 0.001 + 1e-9);
  EXPECT_LT(result.sim_time, options.duration);
  EXPECT_EQ(result.cycle_us.size(), controller.calls.size());
  EXPECT_NEAR(static_cast<double>(result.cycle_us.size()), result.sim_time / 0.001, 0.5);
}

}  // namespace
}  // namespace biped
