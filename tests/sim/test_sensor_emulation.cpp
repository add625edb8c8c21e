#include "sim/sensor_emulation.hpp"

#include <gtest/gtest.h>

#include "sim/simulation.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

SimulationParams lola_params() {
  SimulationParams p;
  p.world.robot_mjcf = test::model_path("lola");
  return p;
}

// Holds the stand pose for n control periods, collecting each reading.
std::vector<SensorData> run(Simulation& sim, const RobotModel& model, int n) {
  std::vector<SensorData> readings;
  JointCommand hold(model.num_joints());
  hold.position = model.stand_pose();
  for (int i = 0; i < n; ++i) {
    sim.command(hold);
    sim.advance();
    SensorData s(model.num_joints());
    sim.read_sensors(s);
    readings.push_back(s);
  }
  return readings;
}

TEST(SensorEmulation, ForceTorqueSensorsCarryTheWeightWithPositiveNormalForce) {
  const RobotModel model = test::load_model("lola");
  Simulation sim(lola_params(), model);
  const SensorData s = run(sim, model, 500).back();
  for (Side side : kSides) EXPECT_GT(s.foot_wrench[index_of(side)].force.z(), 0.3 * model.weight_above_sensors());
  EXPECT_NEAR(s.foot_wrench[0].force.z() + s.foot_wrench[1].force.z(), model.weight_above_sensors(),
              0.01 * model.weight_above_sensors());
  // At rest the accelerometer measures the specific force: +g along the upper body's z axis.
  EXPECT_NEAR(s.imu_acceleration.z(), 9.81, 0.05);
  EXPECT_LT(s.imu_angular_rate.norm(), 0.05);
}

TEST(SensorEmulation, EncodersAreQuantizedToTheirResolution) {
  const RobotModel model = test::load_model("lola");
  SimulationParams p = lola_params();
  p.encoder_bits = 12;  // coarse, to make the quantization visible
  Simulation sim(p, model);
  const SensorData s = run(sim, model, 20).back();
  const double resolution = 2.0 * M_PI / 4096.0;
  for (int i = 0; i < model.num_joints(); ++i) {
    const double steps = s.joint_position[i] / resolution;
    EXPECT_NEAR(steps, std::round(steps), 1e-6) << model.joints()[i].name;
    const double truth = sim.data()->qpos[model.joints()[i].qpos_adr];
    EXPECT_LE(std::abs(s.joint_position[i] - truth), 0.5 * resolution + 0.01);
  }
}

TEST(SensorEmulation, NoiseIsReproducibleFromTheSeedAndDiffersBetweenSeeds) {
  const RobotModel model = test::load_model("lola");
  SimulationParams p = lola_params();
  p.sensor_noise = true;
  p.seed = 7;
  Simulation a(p, model), b(p, model);
  p.seed = 8;
  Simulation c(p, model);
  const SensorData ra = run(a, model, 50).back();
  const SensorData rb = run(b, model, 50).back();
  const SensorData rc = run(c, model, 50).back();
  EXPECT_EQ(ra.foot_wrench[0].force, rb.foot_wrench[0].force);
  EXPECT_EQ(ra.imu_angular_rate, rb.imu_angular_rate);
  EXPECT_NE(ra.foot_wrench[0].force, rc.foot_wrench[0].force);
  const SensorData clean = a.sensors().latest_clean();
  EXPECT_GT((ra.foot_wrench[0].force - clean.foot_wrench[0].force).norm(), 0.0);
  EXPECT_LT((ra.foot_wrench[0].force - clean.foot_wrench[0].force).norm(), 30.0);
}

TEST(SensorEmulation, DelayDeliversTheReadingOfEarlierCycles) {
  const RobotModel model = test::load_model("lola");
  SimulationParams p = lola_params();
  p.sensor_delay_cycles = 3;
  Simulation delayed(p, model);
  Simulation direct(lola_params(), model);
  const auto late = run(delayed, model, 60);
  const auto now = run(direct, model, 60);
  for (int i = 10; i < 60; ++i) {
    EXPECT_EQ(late[i].foot_wrench[1].force, now[i - 3].foot_wrench[1].force) << i;
    EXPECT_EQ(late[i].joint_position, now[i - 3].joint_position) << i;
  }
}

TEST(SensorEmulation, InjectedNanFaultHitsOneReadingOfOneSensor) {
  const RobotModel model = test::load_model("lola");
  SimulationParams p = lola_params();
  SensorFault fault;
  fault.t = 0.0105;
  fault.sensor = "ft_left";
  fault.mode = SensorFault::Mode::NaN;
  p.faults.push_back(fault);
  Simulation sim(p, model);
  const auto readings = run(sim, model, 30);
  int nan_readings = 0;
  for (const SensorData& s : readings) {
    if (!s.foot_wrench[0].force.allFinite()) {
      ++nan_readings;
      EXPECT_GE(s.time, fault.t);
    }
    EXPECT_TRUE(s.foot_wrench[1].force.allFinite());
    EXPECT_TRUE(s.joint_position.allFinite());
  }
  EXPECT_EQ(nan_readings, 1);
}

TEST(SensorEmulation, FrozenEncoderRepeatsItsLastValue) {
  const RobotModel model = test::load_model("lola");
  SimulationParams p = lola_params();
  p.encoder_bits = 24;
  SensorFault fault;
  fault.t = 0.05;
  fault.duration = 0.1;
  fault.sensor = "left_knee";
  fault.mode = SensorFault::Mode::Freeze;
  p.faults.push_back(fault);
  p.pushes.push_back({0.0, 0.3, "upper_body", Eigen::Vector3d(60, 0, 0)});  // keeps the joints moving
  Simulation sim(p, model);
  const auto readings = run(sim, model, 200);
  const int knee = model.joint_index("left_knee");
  for (std::size_t i = 1; i < readings.size(); ++i) {
    if (readings[i].time > 0.052 && readings[i].time < 0.149) {
      EXPECT_EQ(readings[i].joint_position[knee], readings[i - 1].joint_position[knee]);
    }
  }
  EXPECT_NE(readings[199].joint_position[knee], readings[100].joint_position[knee]);
}

}  // namespace
}  // namespace biped
