// The run recorder on short closed-loop runs of LOLA: log.csv has DESIGN.md's columns and a full row
// per logged instant, its ground-truth columns agree with each other, and summary.json's figures
// follow from the logged rows (distance, tilt RMS) and from ground-truth contact (steps).
#include "io/run_recorder.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "control/standing_controller.hpp"
#include "control/walking_controller.hpp"
#include "io/robot_config.hpp"
#include "io/scenario.hpp"
#include "math/rotations.hpp"
#include "math/side.hpp"
#include "model/kinematics.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

// Feeds the loop's calls to two recorders: one writing the CSV, one gathering figures only.
struct Both final : public RunObserver {
  RunObserver* a;
  RunObserver* b;
  Both(RunObserver* first, RunObserver* second) : a(first), b(second) {}
  void record(const Simulation& sim, const SensorData& s, const JointCommand& c, const ControllerStatus& st,
              double us) override {
    a->record(sim, s, c, st, us);
    b->record(sim, s, c, st, us);
  }
};

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  for (std::string field; std::getline(in, field, ',');) fields.push_back(field);
  return fields;
}

struct Log {
  std::vector<std::string> header;
  std::map<std::string, int> column;
  std::vector<std::vector<std::string>> rows;
  double at(std::size_t row, const std::string& name) const { return std::stod(rows[row][column.at(name)]); }
};

Log parse(const std::string& csv) {
  Log log;
  std::stringstream in(csv);
  std::string line;
  std::getline(in, line);
  log.header = split(line);
  for (std::size_t i = 0; i < log.header.size(); ++i) log.column[log.header[i]] = static_cast<int>(i);
  while (std::getline(in, line)) log.rows.push_back(split(line));
  return log;
}

// One run of a shipped scenario, shortened, recorded with and without a CSV.
struct RecordedRun {
  Scenario scenario;
  RunConfig config;
  RobotModel model;
  Simulation sim;
  std::unique_ptr<Controller> controller;
  std::ostringstream csv;
  RunRecorder recorder;
  RunRecorder figures_only;
  RunResult result;

  // Ideal sensors: the touchdowns are compared with the plan's steps (with the realistic sensor
  // errors the feet also bounce at touchdown and lift-off, README "Status").
  RecordedRun(const char* file, double duration, const std::string& extra = "")
      : scenario(load_scenario(test::source_path(std::string("config/scenarios/") + file),
                               extra.empty() ? std::vector<std::string>{"duration=" + std::to_string(duration), "sensors.ideal=true"}
                                             : std::vector<std::string>{"duration=" + std::to_string(duration),
                                                                        "sensors.ideal=true", extra})),
        config(make_run_config(scenario)),
        model(RobotModel::load(config.controller.model_path, config.controller.software_limit_margin_rad)),
        sim(config.sim, model),
        recorder(sim, &csv),
        figures_only(sim, nullptr) {
    if (config.controller.type == "standing") {
      controller = std::make_unique<StandingController>(model, config.controller.standing);
    } else {
      controller = std::make_unique<WalkingController>(model, config.controller.walking);
    }
    RunOptions options;
    options.duration = scenario.duration;
    options.log_period = 1.0 / scenario.log_rate_hz;
    Both both(&recorder, &figures_only);
    result = run_closed_loop(sim, *controller, scenario.commands, options, &both);
  }
  nlohmann::json summary(const RunRecorder& r) const {
    return r.summary(config.robot, scenario.name, result, controller->status());
  }
};

// LOLA starts walking at 1 s and makes its first steps; shared by the tests below (deterministic).
const RecordedRun& walk() {
  static const RecordedRun run("lola-walk.yaml", 4.0);
  return run;
}

TEST(RunRecorder, LogHasTheDesignColumnsAndFullRows) {
  const Log log = parse(walk().csv.str());
  std::vector<std::string> required = {"t", "state", "base_x", "base_y", "base_z", "phi_x_deg", "phi_y_deg",
                                       "com_x", "com_y", "com_z", "cycle_us"};
  for (const char* side : {"left", "right"}) {
    for (const char* signal : {"Fz", "Tx", "Ty"}) {
      required.push_back(std::string(side) + "_" + signal + "_des");
      required.push_back(std::string(side) + "_" + signal);
    }
  }
  for (const std::string& name : required) EXPECT_EQ(log.column.count(name), 1u) << name;
  EXPECT_EQ(log.header.size(), log.column.size()) << "column names are unique";
  // The generalized position closes the row, in order.
  const int nq = walk().sim.plant().nq();
  ASSERT_GE(log.header.size(), static_cast<std::size_t>(nq));
  for (int i = 0; i < nq; ++i) {
    EXPECT_EQ(log.header[log.header.size() - nq + i], "qpos_" + std::to_string(i));
  }
  ASSERT_EQ(log.rows.size(), 400u) << "4 s at 100 Hz";
  for (std::size_t r = 0; r < log.rows.size(); ++r) {
    ASSERT_EQ(log.rows[r].size(), log.header.size()) << "row " << r;
    EXPECT_NEAR(log.at(r, "t"), 0.01 * static_cast<double>(r), 1e-9) << "row " << r;
  }
  EXPECT_EQ(log.rows.front()[log.column.at("state")], "standing");
  EXPECT_EQ(log.rows.back()[log.column.at("state")], "walking");
  EXPECT_EQ(walk().recorder.samples().size(), log.rows.size());
}

// The base and CoM columns are what the logged generalized position gives. They come from the
// simulator's frames, which MuJoCo computes at the start of a physics step, while qpos is the state
// after its integration: the two are one physics step apart, less than 1 mm at walking speeds.
TEST(RunRecorder, BaseAndComColumnsFollowFromTheLoggedQpos) {
  const double one_step = 1.0 * 0.001;  // [m] 1 m/s over one physics step
  const Log log = parse(walk().csv.str());
  const RobotModel& plant = walk().sim.plant();
  RobotData data(plant);
  const int first_qpos = log.column.at("qpos_0");
  for (std::size_t r = 0; r < log.rows.size(); r += 37) {
    for (int i = 0; i < plant.nq(); ++i) data.qpos()[i] = std::stod(log.rows[r][first_qpos + i]);
    forward_kinematics_with_com(plant, data);
    const Eigen::Vector3d base = data.body_position(plant.pelvis_body());
    const Eigen::Vector3d com = data.subtree_com(plant.pelvis_body());
    const char* axes[] = {"x", "y", "z"};
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(log.at(r, std::string("base_") + axes[a]), base[a], one_step) << "row " << r;
      EXPECT_NEAR(log.at(r, std::string("com_") + axes[a]), com[a], one_step) << "row " << r;
    }
  }
}

// Each foot's columns are its F/T sensor frame as the logged generalized position places it (one
// physics step apart, as above: the swing foot peaks at about 3.5 m/s, so 5 mm and 0.5°).
TEST(RunRecorder, FootColumnsFollowFromTheLoggedQpos) {
  const double one_step = 5.0 * 0.001, one_step_deg = 0.5;
  const Log log = parse(walk().csv.str());
  const mjModel* m = walk().sim.plant().mj();
  mjData* d = mj_makeData(m);
  const int first_qpos = log.column.at("qpos_0");
  double largest_roll = 0.0;
  for (std::size_t r = 0; r < log.rows.size(); r += 7) {
    for (int i = 0; i < m->nq; ++i) d->qpos[i] = std::stod(log.rows[r][first_qpos + i]);
    mj_kinematics(m, d);
    for (Side side : kSides) {
      const std::string p = name_of(side);
      const int site = walk().sim.plant().foot(side).sensor_site;
      const Eigen::Matrix3d R = math::mat_from_mujoco(d->site_xmat + 9 * site);
      const Eigen::Vector3d forward = R.col(0), left = R.col(1);
      EXPECT_NEAR(log.at(r, p + "_foot_x"), d->site_xpos[3 * site], one_step) << p << " row " << r;
      EXPECT_NEAR(log.at(r, p + "_foot_y"), d->site_xpos[3 * site + 1], one_step) << p << " row " << r;
      EXPECT_NEAR(log.at(r, p + "_foot_z"), d->site_xpos[3 * site + 2], one_step) << p << " row " << r;
      // Toes down and the left edge up, as the axes' heights give them.
      EXPECT_NEAR(log.at(r, p + "_foot_pitch_deg"), std::asin(-forward.z()) * kRadToDeg, one_step_deg) << p;
      const double roll = std::asin(left.z() / std::cos(std::asin(-forward.z())));
      EXPECT_NEAR(log.at(r, p + "_foot_roll_deg"), roll * kRadToDeg, one_step_deg) << p << " row " << r;
      largest_roll = std::max(largest_roll, std::abs(roll));
      EXPECT_EQ(log.at(r, p + "_terrain_roll_deg"), 0.0) << "level ground: no roll taken";
    }
  }
  mj_deleteData(d);
  // Rolls beyond the tolerance's half: a roll of the wrong sign would be caught.
  EXPECT_GT(largest_roll * kRadToDeg, 0.3) << "the feet rolled a little while walking";
}

// The terrain adaptation's roll of each foot is the controller's, by side.
TEST(RunRecorder, TerrainRollColumnsAreTheControllersByFoot) {
  std::ostringstream csv;
  RunRecorder recorder(walk().sim, &csv);
  ControllerStatus status;
  status.foot_roll = {0.1, -0.2};
  recorder.record(walk().sim, SensorData{}, JointCommand{}, status, 0.0);
  const Log log = parse(csv.str());
  ASSERT_EQ(log.rows.size(), 1u);
  EXPECT_NEAR(log.at(0, std::string(name_of(Side::Left)) + "_terrain_roll_deg"),
              status.foot_roll[index_of(Side::Left)] * kRadToDeg, 1e-3);
  EXPECT_NEAR(log.at(0, std::string(name_of(Side::Right)) + "_terrain_roll_deg"),
              status.foot_roll[index_of(Side::Right)] * kRadToDeg, 1e-3);
}

TEST(RunRecorder, DistanceAndTiltRmsFollowFromTheLoggedRows) {
  const Log log = parse(walk().csv.str());
  const nlohmann::json summary = walk().summary(walk().recorder);
  const std::size_t last = log.rows.size() - 1;
  const double distance =
      std::hypot(log.at(last, "base_x") - log.at(0, "base_x"), log.at(last, "base_y") - log.at(0, "base_y"));
  EXPECT_GT(distance, 0.1) << "the robot walked";
  EXPECT_NEAR(summary["distance_m"].get<double>(), distance, 3e-6);  // %.6f columns
  EXPECT_NEAR(summary["mean_speed_mps"].get<double>(), distance / summary["sim_time_s"].get<double>(), 1e-6);
  const char* axes[] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(summary["final_base_position"][a].get<double>(), log.at(last, std::string("base_") + axes[a]), 1e-6);
  }

  double sum_x = 0.0, sum_y = 0.0;
  for (std::size_t r = 0; r < log.rows.size(); ++r) {
    sum_x += std::pow(log.at(r, "phi_x_deg"), 2);
    sum_y += std::pow(log.at(r, "phi_y_deg"), 2);
  }
  const double n = static_cast<double>(log.rows.size());
  const nlohmann::json& tilt = summary["upper_body_tilt_deg"];
  EXPECT_GT(tilt["rms_x"].get<double>(), 0.0);
  EXPECT_NEAR(tilt["rms_x"].get<double>(), std::sqrt(sum_x / n), 1e-4);  // %.4f columns
  EXPECT_NEAR(tilt["rms_y"].get<double>(), std::sqrt(sum_y / n), 1e-4);
  double largest = 0.0;
  for (std::size_t r = 0; r < log.rows.size(); ++r) {
    largest = std::max({largest, std::abs(log.at(r, "phi_x_deg")), std::abs(log.at(r, "phi_y_deg"))});
  }
  EXPECT_GE(tilt["max"].get<double>(), largest - 1e-4) << "the total tilt is at least either plane's";
}

// The figures do not depend on whether a CSV is written.
TEST(RunRecorder, SummaryIsTheSameWithoutACsv) {
  EXPECT_EQ(walk().summary(walk().recorder), walk().summary(walk().figures_only));
  EXPECT_EQ(walk().recorder.samples().size(), walk().figures_only.samples().size());
}

// Touchdowns from the simulator's contact forces: every touchdown the plan has completed is one on
// the ground (give or take the one under way at the end), and standing still makes none.
TEST(RunRecorder, StepsCountGroundTruthTouchdowns) {
  const nlohmann::json walking = walk().summary(walk().recorder);
  const int planned = walk().controller->status().steps_completed;
  EXPECT_GE(planned, 2);
  EXPECT_NEAR(walking["steps"].get<int>(), planned, 1);

  const RecordedRun standing("lola-stand.yaml", 1.0);
  EXPECT_EQ(standing.summary(standing.recorder)["steps"].get<int>(), 0);
}

// LOLA's open loop at 0.4 m/s falls (at about 6.1 s); the run goes on for two seconds after it, its
// feet bouncing and its IMU shaken by the impact. Steps end at the fall, and the impact's sensor
// fault is reported as a consequence of the fall, not as the run's fault.
TEST(RunRecorder, AFallEndsTheStepsAndItsImpactFaultIsNotTheCause) {
  const RecordedRun fall("lola-walk-open-loop.yaml", 8.0, "commands.1.vx=0.4");
  ASSERT_TRUE(fall.result.fell);
  const nlohmann::json s = fall.summary(fall.recorder);
  // The same run ended at the moment of the fall (deterministic: the same touchdowns until then).
  const RecordedRun until_fall("lola-walk-open-loop.yaml", fall.result.fall_time, "commands.1.vx=0.4");
  EXPECT_GE(s["steps"].get<int>(), 4);
  EXPECT_EQ(s["steps"], until_fall.summary(until_fall.recorder)["steps"]);
  ASSERT_TRUE(fall.controller->status().fault) << "the impact trips the sensor check";
  EXPECT_TRUE(s["fault"].is_null()) << s["fault"];
  EXPECT_EQ(s["fault_after_fall"], describe(fall.controller->status().first_fault));
  EXPECT_GE(s["fault_time_s"].get<double>(), fall.result.fall_time);
  ASSERT_FALSE(s["sensor_faults"].empty());
  for (const nlohmann::json& f : s["sensor_faults"]) EXPECT_TRUE(f["after_fall"].get<bool>()) << f;
}

// A fault that comes before any fall stays the run's fault.
TEST(RunRecorder, AFaultBeforeAnyFallIsTheRunsFault) {
  const RecordedRun nan("lola-ft-nan.yaml", 6.0);
  ASSERT_FALSE(nan.result.fell);
  const nlohmann::json s = nan.summary(nan.recorder);
  EXPECT_EQ(s["fault"], "left F/T sensor");
  EXPECT_TRUE(s["fault_after_fall"].is_null());
  EXPECT_LT(s["fault_time_s"].get<double>(), 6.0);
  EXPECT_TRUE(walk().summary(walk().recorder)["fault_time_s"].is_null());
  EXPECT_TRUE(walk().summary(walk().recorder)["sensor_faults"].empty());
}

// Every fault is listed in the order found, a joint encoder's with its joint: the F/T NaN at 5 s,
// then the left knee's encoder frozen from 5.5 s while the safe stop moves the leg.
TEST(RunRecorder, EveryFaultIsListedWithItsTimeAndJoint) {
  const RecordedRun two("lola-ft-nan.yaml", 8.0,
                        "sensors.faults=[{t: 5.0, sensor: ft_left, value: nan}, "
                        "{t: 5.5, sensor: left_knee, value: freeze, duration: 2.5}]");
  const nlohmann::json s = two.summary(two.recorder);
  ASSERT_EQ(s["sensor_faults"].size(), 2u) << s["sensor_faults"];
  EXPECT_EQ(s["sensor_faults"][0]["sensor"], "left F/T sensor");
  EXPECT_NEAR(s["sensor_faults"][0]["t"].get<double>(), 5.0, 0.01);
  EXPECT_EQ(s["sensor_faults"][1]["sensor"], "joint encoder frozen");
  EXPECT_EQ(s["sensor_faults"][1]["joint"], "left_knee");
  EXPECT_GT(s["sensor_faults"][1]["t"].get<double>(), 5.5);
  EXPECT_EQ(s["fault"], "left F/T sensor") << "the first fault stays the run's";
  ASSERT_FALSE(two.result.fell);
  for (const nlohmann::json& f : s["sensor_faults"]) EXPECT_FALSE(f["after_fall"].get<bool>()) << f;
}

}  // namespace
}  // namespace biped
