#include "sim/sensor_emulation.hpp"

#include <gtest/gtest.h>

#include <functional>

#include "math/rotations.hpp"
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

// A reading and the error-free reading of the same instant.
struct Pair {
  SensorData reading, truth;
};

std::vector<Pair> run_with_truth(Simulation& sim, const RobotModel& model, int n,
                                 const std::function<void(int, JointCommand&)>& pose = {}) {
  std::vector<Pair> out;
  JointCommand command(model.num_joints());
  for (int i = 0; i < n; ++i) {
    command.position = model.stand_pose();
    if (pose) pose(i, command);
    sim.command(command);
    sim.advance();
    SensorData s(model.num_joints());
    sim.read_sensors(s);
    out.push_back({s, sim.sensors().latest_clean()});
  }
  return out;
}

// Angle of the rotation between two orientations.
double angle_between(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) { return a.angularDistance(b); }

SimulationParams with_attitude_filter() {
  SimulationParams p = lola_params();
  p.sensor_errors.imu.attitude_filter = true;
  return p;
}

Vector6d stack(const Wrench& w) {
  Vector6d v;
  v << w.force, w.torque;
  return v;
}

const double kDeg = M_PI / 180.0;

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

// Tilt of the reported orientation minus the true one, averaged over readings [from, to): the
// standing robot rocks (±0.4 m/s² at the IMU), which the accelerometer takes for a tilt.
math::TiltAngles mean_tilt_error(const std::vector<Pair>& readings, std::size_t from, std::size_t to) {
  math::TiltAngles mean;
  for (std::size_t i = from; i < to; ++i) {
    const math::TiltAngles reported = math::tilt_against_gravity(readings[i].reading.imu_orientation.toRotationMatrix());
    const math::TiltAngles truth = math::tilt_against_gravity(readings[i].truth.imu_orientation.toRotationMatrix());
    mean.sagittal += (reported.sagittal - truth.sagittal) / (to - from);
    mean.lateral += (reported.lateral - truth.lateral) / (to - from);
  }
  return mean;
}

// Without errors the attitude filter starts at the true orientation and follows it; what remains is
// the accelerometer's view of the rocking of the standing robot, through the filter's 1 s.
TEST(SensorEmulation, AttitudeFilterWithoutErrorsFollowsTheTruth) {
  const RobotModel model = test::load_model("lola");
  Simulation sim(with_attitude_filter(), model);
  const auto readings = run_with_truth(sim, model, 2000);
  EXPECT_LT(angle_between(readings[0].reading.imu_orientation, readings[0].truth.imu_orientation), 1e-4 * kDeg);
  for (const Pair& p : readings) {
    EXPECT_LT(angle_between(p.reading.imu_orientation, p.truth.imu_orientation), 0.25 * kDeg) << p.reading.time;
  }
  const math::TiltAngles mean = mean_tilt_error(readings, 1000, 2000);
  EXPECT_LT(std::abs(mean.sagittal), 0.03 * kDeg);
  EXPECT_LT(std::abs(mean.lateral), 0.03 * kDeg);
}

// A misaligned IMU at rest reports the misalignment as tilt of the upper body, from the first
// reading on (the filter starts from the accelerometer) and after it has settled.
TEST(SensorEmulation, MisalignedImuAtRestReportsTheMisalignmentAsTilt) {
  const RobotModel model = test::load_model("lola");
  SimulationParams p = with_attitude_filter();
  const Eigen::Vector3d misalignment(0.5 * kDeg, -0.3 * kDeg, 0.0);
  p.sensor_errors.imu.misalignment_rad = misalignment;
  Simulation sim(p, model);
  const auto readings = run_with_truth(sim, model, 3000);
  // Roll about x leans the z axis to the right (negative lateral), pitch about y forward.
  const math::TiltAngles first = mean_tilt_error(readings, 0, 1), settled = mean_tilt_error(readings, 2000, 3000);
  EXPECT_NEAR(first.lateral, -misalignment.x(), 0.005 * kDeg);
  EXPECT_NEAR(first.sagittal, misalignment.y(), 0.005 * kDeg);
  EXPECT_NEAR(settled.lateral, -misalignment.x(), 0.03 * kDeg);
  EXPECT_NEAR(settled.sagittal, misalignment.y(), 0.03 * kDeg);
  // Gyro and accelerometer measure in the turned axes too.
  const Eigen::Matrix3d turned = sim.sensors().imu_misalignment();
  for (const Pair& r : readings) {
    EXPECT_LT((r.reading.imu_angular_rate - turned.transpose() * r.truth.imu_angular_rate).norm(), 1e-12);
    EXPECT_LT((r.reading.imu_acceleration - turned.transpose() * r.truth.imu_acceleration).norm(), 1e-12);
  }
  EXPECT_GT((readings.back().reading.imu_acceleration - readings.back().truth.imu_acceleration).norm(), 0.05);
}

// The heading is the gyro's integral alone: it drifts at the gyro's bias; roll and pitch are held
// by the accelerometer at about bias × filter_time_s.
TEST(SensorEmulation, GyroBiasMakesTheHeadingDriftWhileRollAndPitchStayBounded) {
  const RobotModel model = test::load_model("lola");
  SimulationParams p = with_attitude_filter();
  const Eigen::Vector3d bias(0.04, -0.03, 0.02);
  const double time_constant = 0.5;
  p.sensor_errors.imu.gyro_bias = bias;
  p.sensor_errors.imu.filter_time_s = time_constant;
  Simulation sim(p, model);
  const auto readings = run_with_truth(sim, model, 4000);
  const double bound = bias.head<2>().norm() * time_constant;  // 1.4°
  for (const Pair& r : readings) {
    const Eigen::Matrix3d reported = r.reading.imu_orientation.toRotationMatrix();
    const Eigen::Matrix3d truth = r.truth.imu_orientation.toRotationMatrix();
    const double yaw_error = math::wrap_angle(math::heading_of(reported) - math::heading_of(truth));
    EXPECT_NEAR(yaw_error, bias.z() * r.reading.time, 0.03 * bias.z() * r.reading.time + 0.002) << r.reading.time;
    const double tilt_error = std::acos(std::clamp(reported.col(2).dot(truth.col(2)), -1.0, 1.0));
    EXPECT_LT(tilt_error, bound + 0.5 * kDeg) << r.reading.time;
  }
  const math::TiltAngles settled = mean_tilt_error(readings, 3000, 4000);
  EXPECT_NEAR(std::hypot(settled.sagittal, settled.lateral), bound, 0.1 * bound) << "settled at bias × time constant";
  const Pair& last = readings.back();
  EXPECT_TRUE(last.reading.imu_angular_rate.isApprox(last.truth.imu_angular_rate + bias, 1e-9));
}

TEST(SensorEmulation, GyroBiasWalksAtItsRate) {
  const RobotModel model = test::load_model("lola");
  SimulationParams p = with_attitude_filter();
  const double walk = 0.01;  // rad/s/√s
  p.sensor_errors.imu.gyro_bias_walk = walk;
  Simulation sim(p, model);
  std::vector<Eigen::Vector3d> bias;
  JointCommand hold(model.num_joints());
  hold.position = model.stand_pose();
  for (int i = 0; i < 2000; ++i) {
    sim.command(hold);
    sim.advance();
    SensorData s(model.num_joints());
    sim.read_sensors(s);
    bias.push_back(sim.sensors().gyro_bias());
  }
  double sum = 0.0;
  for (std::size_t i = 1; i < bias.size(); ++i) sum += (bias[i] - bias[i - 1]).squaredNorm();
  const double step_sigma = std::sqrt(sum / (3.0 * (bias.size() - 1)));
  EXPECT_NEAR(step_sigma, walk * std::sqrt(0.001), 0.05 * walk * std::sqrt(0.001));
}

// The accelerometer's bias tilts the orientation as the accelerometer sees gravity.
TEST(SensorEmulation, AccelerometerBiasTiltsTheOrientation) {
  const RobotModel model = test::load_model("lola");
  SimulationParams p = with_attitude_filter();
  p.sensor_errors.imu.accel_bias = Eigen::Vector3d(0.1, 0.0, 0.0);
  Simulation sim(p, model);
  const auto readings = run_with_truth(sim, model, 2000);
  // "Up" measured tilted towards +x by 0.1/9.81 rad: the IMU believes it leans back.
  EXPECT_NEAR(mean_tilt_error(readings, 1000, 2000).sagittal, -std::asin(0.1 / 9.81), 0.03 * kDeg);
  EXPECT_NEAR(readings.back().reading.imu_acceleration.x() - readings.back().truth.imu_acceleration.x(), 0.1, 1e-9);
}

// A fast roll of the upper body (pelvis_roll joint), seen by two IMUs on the same motion: with a
// 5 Hz bandwidth the orientation lags the unfiltered IMU's by about rate / (2π · 5 Hz), behind the
// truth, and keeps no offset. (Both also err by the accelerations of the rocking robot, which the
// accelerometer takes for tilt.)
TEST(SensorEmulation, AttitudeFilterLagsAFastRotation) {
  const RobotModel model = test::load_model("lola");
  const double bandwidth = 5.0;
  SimulationParams p = with_attitude_filter();
  Simulation unfiltered_sim(p, model);
  p.sensor_errors.imu.bandwidth_hz = bandwidth;
  Simulation filtered_sim(p, model);
  const int joint = model.joint_index("pelvis_roll");
  const auto roll = [&](int i, JointCommand& c) {
    c.position[joint] += 0.1 * std::clamp((i - 300) / 100.0, 0.0, 1.0);  // 1 rad/s from 0.3 to 0.4 s
  };
  const auto unfiltered = run_with_truth(unfiltered_sim, model, 1500, roll);
  const auto filtered = run_with_truth(filtered_sim, model, 1500, roll);
  const int at = 380;
  const double rate = filtered[at].truth.imu_angular_rate.norm();
  ASSERT_GT(rate, 0.5);
  const double lag = angle_between(filtered[at].reading.imu_orientation, unfiltered[at].reading.imu_orientation);
  EXPECT_GT(lag, 0.7 * rate / (2.0 * M_PI * bandwidth));
  EXPECT_LT(lag, 1.3 * rate / (2.0 * M_PI * bandwidth));
  // Behind: the reported roll has covered less of the motion than the truth.
  const auto roll_of = [](const Eigen::Quaterniond& q) { return math::tilt_against_gravity(q.toRotationMatrix()).lateral; };
  const double reported_turn = roll_of(filtered[at].reading.imu_orientation) - roll_of(filtered[290].reading.imu_orientation);
  const double true_turn = roll_of(filtered[at].truth.imu_orientation) - roll_of(filtered[290].truth.imu_orientation);
  EXPECT_LT(std::abs(reported_turn), std::abs(true_turn) - 0.5 * lag);
  // No lasting offset (1.8° at the peak): while the robot rocks on, the two differ by as much ahead
  // as behind, up to what the accelerometer's correction has not yet removed of the jolt.
  double mean_difference = 0.0;
  for (std::size_t i = 1000; i < 1500; ++i) {
    mean_difference += (roll_of(filtered[i].reading.imu_orientation) - roll_of(unfiltered[i].reading.imu_orientation)) / 500;
  }
  EXPECT_LT(std::abs(mean_difference), 0.1 * kDeg);
}

TEST(SensorEmulation, ForceTorqueOffsetScaleAndThermalDrift) {
  const RobotModel model = test::load_model("lola");
  SimulationParams p = lola_params();
  Vector6d offset, scale, thermal;
  offset << 6, -4, 15, 0.4, -0.3, 0;
  scale << 1.02, 1.0, 0.98, 1.0, 1.01, 0.97;
  thermal << 0, 0, 8, 0, 0.5, 0;
  p.sensor_errors.ft[0].offset = offset;
  p.sensor_errors.ft[0].scale = scale;
  p.sensor_errors.ft[1].thermal_drift = thermal;
  p.sensor_errors.ft[1].thermal_time_s = 1.0;
  Simulation sim(p, model);
  for (const Pair& r : run_with_truth(sim, model, 3000)) {
    const Vector6d left = stack(r.reading.foot_wrench[0]), left_true = stack(r.truth.foot_wrench[0]);
    EXPECT_LT((left - (scale.cwiseProduct(left_true) + offset)).norm(), 1e-9) << r.reading.time;
    const Vector6d right_error = stack(r.reading.foot_wrench[1]) - stack(r.truth.foot_wrench[1]);
    EXPECT_LT((right_error - (1.0 - std::exp(-r.reading.time)) * thermal).norm(), 1e-9) << r.reading.time;
  }
}

TEST(SensorEmulation, ForceTorqueDriftWalksAtItsRate) {
  const RobotModel model = test::load_model("lola");
  SimulationParams p = lola_params();
  Vector6d walk;
  walk << 1.0, 1.0, 1.0, 0.1, 0.1, 0.1;  // [N/√s, N·m/√s]
  p.sensor_errors.ft[1].drift_walk = walk;
  Simulation sim(p, model);
  const auto readings = run_with_truth(sim, model, 2000);
  Vector6d sum = Vector6d::Zero();
  Vector6d previous = Vector6d::Zero();
  for (std::size_t i = 0; i < readings.size(); ++i) {
    const Vector6d error = stack(readings[i].reading.foot_wrench[1]) - stack(readings[i].truth.foot_wrench[1]);
    if (i > 0) sum += (error - previous).cwiseAbs2();
    previous = error;
    EXPECT_EQ(readings[i].reading.foot_wrench[0].force, readings[i].truth.foot_wrench[0].force);
  }
  const Vector6d step_sigma = (sum / (readings.size() - 1.0)).cwiseSqrt();
  for (int a = 0; a < 6; ++a) EXPECT_NEAR(step_sigma[a], walk[a] * std::sqrt(0.001), 0.1 * walk[a] * std::sqrt(0.001)) << a;
}

TEST(SensorEmulation, EncoderOffsetShiftsTheReading) {
  const RobotModel model = test::load_model("lola");
  SimulationParams p = lola_params();
  p.encoder_bits = 24;
  p.sensor_errors.encoder_offset_rad["left_knee"] = 0.3 * kDeg;
  Simulation sim(p, model);
  const int knee = model.joint_index("left_knee"), other = model.joint_index("right_knee");
  for (const Pair& r : run_with_truth(sim, model, 50)) {
    EXPECT_NEAR(r.reading.joint_position[knee] - r.truth.joint_position[knee], 0.3 * kDeg, 1e-6);
    EXPECT_EQ(r.reading.joint_position[other], r.truth.joint_position[other]);
  }
}

TEST(SensorEmulation, EncoderJumpOffsetsTheReadingForItsDuration) {
  const RobotModel model = test::load_model("lola");
  SimulationParams p = lola_params();
  SensorFault jump;
  jump.t = 0.0205;  // between readings, so that no reading sits on an edge of the window
  jump.duration = 0.03;
  jump.sensor = "right_hip_pitch";
  jump.mode = SensorFault::Mode::Jump;
  jump.value = 0.5 * kDeg;
  p.faults.push_back(jump);
  Simulation sim(p, model);
  const int joint = model.joint_index("right_hip_pitch");
  for (const Pair& r : run_with_truth(sim, model, 80)) {
    const bool active = r.reading.time > 0.0205 && r.reading.time < 0.0505;
    EXPECT_NEAR(r.reading.joint_position[joint] - r.truth.joint_position[joint], active ? 0.5 * kDeg : 0.0, 1e-12)
        << r.reading.time;
  }
}

// Several faults at once, overlapping and not, on different and on the same sensor: each acts in
// its own window only.
TEST(SensorEmulation, SeveralFaultsInOneRunActInTheirOwnWindows) {
  const RobotModel model = test::load_model("lola");
  SimulationParams p = lola_params();
  p.encoder_bits = 24;
  p.pushes.push_back({0.0, 0.3, "upper_body", Eigen::Vector3d(60, 0, 0)});  // keeps the signals moving
  auto fault = [&](double t, double duration, const char* sensor, SensorFault::Mode mode, double value = 0.0) {
    SensorFault f;
    f.t = t;
    f.duration = duration;
    f.sensor = sensor;
    f.mode = mode;
    f.value = value;
    p.faults.push_back(f);
  };
  // Windows start between readings (every 1 ms), so that no reading sits on an edge.
  fault(0.0, 0.0105, "left_knee", SensorFault::Mode::Freeze);     // from the first reading
  fault(0.0205, 0.03, "ft_left", SensorFault::Mode::NaN);         // 0.0205 … 0.0505
  fault(0.0405, 0.03, "imu_gyro", SensorFault::Mode::Value, 5.0);  // 0.0405 … 0.0705, overlaps the one before
  fault(0.0605, 0.02, "ft_left", SensorFault::Mode::Freeze);      // 0.0605 … 0.0805, same sensor again
  fault(0.0655, 0.0, "imu_accel", SensorFault::Mode::NaN);        // a single reading
  Simulation sim(p, model);
  const auto readings = run_with_truth(sim, model, 100);
  const int knee = model.joint_index("left_knee");
  EXPECT_EQ(readings[0].reading.joint_position[knee], readings[0].truth.joint_position[knee]) << "frozen at its first";
  int accel_nan = 0;
  for (std::size_t i = 0; i < readings.size(); ++i) {
    const SensorData& s = readings[i].reading;
    const SensorData& truth = readings[i].truth;
    const double t = s.time;
    auto in = [t](double from, double to) { return t > from && t < to; };
    if (t < 0.0105) {
      EXPECT_EQ(s.joint_position[knee], readings[0].reading.joint_position[knee]) << t;
    }
    if (t > 0.0105) {
      EXPECT_EQ(s.joint_position[knee], truth.joint_position[knee]) << t;
    }
    EXPECT_EQ(in(0.0205, 0.0505), !s.foot_wrench[0].force.allFinite()) << t;
    EXPECT_EQ(in(0.0405, 0.0705), s.imu_angular_rate == Eigen::Vector3d::Constant(5.0)) << t;
    if (in(0.0605, 0.0805)) {
      EXPECT_EQ(s.foot_wrench[0].force, readings[i - 1].reading.foot_wrench[0].force) << t;
    }
    if (in(0.0505, 0.0605) || t > 0.0805) {
      EXPECT_EQ(s.foot_wrench[0].force, truth.foot_wrench[0].force) << t;
    }
    accel_nan += !s.imu_acceleration.allFinite();
    EXPECT_TRUE(s.foot_wrench[1].force.allFinite());
    EXPECT_TRUE(s.imu_orientation.coeffs().allFinite());
  }
  EXPECT_EQ(accel_nan, 1);
  EXPECT_NE(readings[50].reading.foot_wrench[0].force, readings[70].reading.foot_wrench[0].force);
}

TEST(SensorEmulation, ExplicitErrorsReplaceTheRandomDrawsOfTheirSensorOnly) {
  const RobotModel model = test::load_model("lola");
  SimulationParams p = lola_params();
  p.sensor_noise = true;
  Simulation drawn(p, model);
  p.sensor_errors.imu.gyro_bias = Eigen::Vector3d(0.0, 0.0, 0.0);
  Simulation given(p, model);
  EXPECT_GT(drawn.sensors().gyro_bias().norm(), 0.0);
  EXPECT_EQ(given.sensors().gyro_bias(), Eigen::Vector3d::Zero());
  EXPECT_TRUE(drawn.sensors().imu_misalignment().isApprox(given.sensors().imu_misalignment(), 0.0));
  EXPECT_GT(Eigen::AngleAxisd(drawn.sensors().imu_misalignment()).angle(), 0.0);
}

TEST(SensorEmulation, AFaultOfAnUnknownSensorIsRefused) {
  const RobotModel model = test::load_model("lola");
  SimulationParams p = lola_params();
  SensorFault fault;
  fault.sensor = "left_kneee";
  p.faults.push_back(fault);
  EXPECT_THROW(Simulation(p, model), ModelError);
  p.faults.clear();
  p.sensor_errors.encoder_offset_rad["no_joint"] = 0.1;
  EXPECT_THROW(Simulation(p, model), ModelError);
}

}  // namespace
}  // namespace biped
