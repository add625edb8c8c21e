// The sensor calibration on synthetic readings with known errors (misalignment, gyro bias, F/T
// offsets), its robustness to NaN, and in closed loop: a misaligned IMU walks with it.
#include "control/sensor_calibration.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "control/com_estimator.hpp"
#include "control/contact_model.hpp"
#include "io/robot_config.hpp"
#include "io/scenario.hpp"
#include "math/rotations.hpp"
#include "model/kinematics.hpp"
#include "studies/scenario_runner.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

constexpr double kDeg = M_PI / 180.0;

Eigen::Quaterniond roll_pitch(double roll, double pitch) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()) *
                            Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()));
}

// LOLA standing in the stand pose on level ground, read through an IMU with known errors. Its
// soles give as eq. (11)'s contact model says: each carries half the weight with the feet turned
// by `sole_pitch(t)` (the whole robot with them), the F/T sensors reading −K(z, 0, φ_y).
struct StandingRobot {
  RobotModel model = test::load_model("lola");
  ContactModelParams contact;
  SensorData sensors{model.num_joints()};
  PatternSample plan;
  Eigen::Quaterniond upper_body;
  Eigen::Quaterniond mounting = roll_pitch(1.4 * kDeg, -1.0 * kDeg);
  Eigen::Vector3d gyro_bias{0.004, -0.003, 0.002};
  std::array<Wrench, 2> offset;
  double pitch_offset = 0.0, pitch_amplitude = 0.0, pitch_frequency = 2.0;  // [rad], [rad], [Hz]
  EncoderKinematics encoders{model};

  StandingRobot() {
    sensors.joint_position = model.stand_pose();
    CoMEstimator kinematics(model);
    upper_body = kinematics.upper_body_on_flat_foot(sensors.joint_position, Side::Left, 0.0);
    offset[0].force = {2.0, -3.0, 4.0};
    offset[0].torque = {0.3, -0.2, 0.1};
    offset[1].force = {-1.0, 2.5, -5.0};
    offset[1].torque = {-0.25, 0.15, 0.05};
  }
  // The readings at time t (a small deterministic noise on the gyro).
  const SensorData& at(double t) {
    const double w = 2.0 * M_PI * pitch_frequency;
    const double pitch = pitch_offset + pitch_amplitude * std::sin(w * t);
    const Eigen::Vector3d rate(0.0, pitch_amplitude * w * std::cos(w * t), 0.0);  // about the world's y
    const Eigen::Quaterniond body = Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) * upper_body;
    sensors.time = t;
    sensors.imu_orientation = body * mounting;
    sensors.imu_angular_rate = sensors.imu_orientation.conjugate() * rate + gyro_bias +
                               0.005 * Eigen::Vector3d(std::sin(37.0 * t), std::cos(53.0 * t), std::sin(71.0 * t));
    sensors.imu_acceleration = sensors.imu_orientation.conjugate() * Eigen::Vector3d(0.0, 0.0, model.gravity());
    for (int k = 0; k < 2; ++k) {
      // −K(z, 0, φ) with the sink z that gives half the weight.
      const Eigen::Matrix3d K = point_contact_stiffness(model.foot(kSides[k]), contact);
      const double z = -(0.5 * model.weight_above_sensors() + K(0, 2) * pitch) / K(0, 0);
      const Eigen::Vector3d lambda = -K * Eigen::Vector3d(z, 0.0, pitch);
      sensors.foot_wrench[k].force = Eigen::Vector3d(0.0, 0.0, lambda[0]) + offset[k].force;
      sensors.foot_wrench[k].torque = Eigen::Vector3d(lambda[1], lambda[2], 0.0) + offset[k].torque;
    }
    return sensors;
  }
};

SensorCalibrationParams without_filter_model() {
  SensorCalibrationParams p;
  p.ahrs_time_constant = 0.0;  // the synthetic IMU reports the misaligned frame exactly
  return p;
}

SensorCalibrationParams with_filter_model() {
  SensorCalibrationParams p;
  p.ahrs_time_constant = 3.0;
  return p;
}

// One cycle as the controller runs it: the encoders' kinematics, then the calibration.
const SensorData& apply(SensorCalibration& calibration, StandingRobot& robot, const SensorData& s,
                        const CalibrationContext& context) {
  robot.encoders.update(s.joint_position);
  return calibration.apply(s, context, robot.encoders.frames(), 0.001);
}

TEST(SensorCalibration, RecoversMisalignmentAndGyroBiasWhileStanding) {
  StandingRobot robot;
  SensorCalibration calibration(robot.model, without_filter_model(), robot.contact);
  calibration.reset(0.0);
  CalibrationContext context;
  context.standing = true;
  context.plan = &robot.plan;
  const SensorData* out = nullptr;
  for (int i = 0; i <= 1100; ++i) out = &apply(calibration, robot, robot.at(0.001 * i), context);
  EXPECT_TRUE(calibration.startup_done());
  const Eigen::Vector3d expected = math::so3::log(robot.mounting);
  EXPECT_NEAR(calibration.misalignment().x(), expected.x(), 0.01 * kDeg);
  EXPECT_NEAR(calibration.misalignment().y(), expected.y(), 0.01 * kDeg);
  EXPECT_LT((calibration.gyro_bias() - robot.gyro_bias).norm(), 2e-4);
  // What the controller sees: the upper body's orientation and rate, not the IMU's.
  EXPECT_LT(out->imu_orientation.angularDistance(robot.upper_body), 0.02 * kDeg);
  EXPECT_LT(out->imu_angular_rate.norm(), 0.006);
  // On two feet only the summed force is observable: it matches the weight above the sensors.
  const double total = out->foot_wrench[0].force.z() + out->foot_wrench[1].force.z();
  EXPECT_NEAR(total, robot.model.weight_above_sensors(), 0.01);
}

// The soles give under the load: the robot stands turned 0.5° toes down with its feet and rocks
// ±0.2° at 2 Hz on them. Taken as flat-footed, that reads as half a degree more misalignment and
// the rocking as gyro bias; with each foot turned by −K⁻¹λ of its reading, neither.
TEST(SensorCalibration, TheSolesDeflectionIsNotTakenForMisalignmentOrBias) {
  StandingRobot robot;
  robot.pitch_offset = 0.5 * kDeg;
  robot.pitch_amplitude = 0.2 * kDeg;
  SensorCalibration calibration(robot.model, without_filter_model(), robot.contact);
  calibration.reset(0.0);
  CalibrationContext context;
  context.standing = true;
  context.plan = &robot.plan;
  for (int i = 0; i <= 1100; ++i) apply(calibration, robot, robot.at(0.001 * i), context);
  const Eigen::Vector3d expected = math::so3::log(robot.mounting);
  EXPECT_NEAR(calibration.misalignment().x(), expected.x(), 0.02 * kDeg);
  EXPECT_NEAR(calibration.misalignment().y(), expected.y(), 0.02 * kDeg);
  EXPECT_LT((calibration.gyro_bias() - robot.gyro_bias).norm(), 3e-4);
}

TEST(SensorCalibration, PredictsTheAttitudeFiltersBiasError) {
  // An attitude filter with time constant τ started at rest settles τ·b⊥ off in roll and pitch.
  StandingRobot robot;
  robot.mounting = Eigen::Quaterniond::Identity();
  SensorCalibration calibration(robot.model, with_filter_model(), robot.contact);
  calibration.reset(0.0);
  CalibrationContext context;
  context.standing = true;
  context.plan = &robot.plan;
  const double tau = with_filter_model().ahrs_time_constant;
  Eigen::Vector3d bias_perp = robot.gyro_bias;
  bias_perp.z() = 0.0;
  const SensorData* out = nullptr;
  for (int i = 0; i <= 20000; ++i) {
    const double t = 0.001 * i;
    SensorData s = robot.at(t);
    s.imu_orientation = robot.upper_body * Eigen::Quaterniond(math::so3::exp(tau * (1.0 - std::exp(-t / tau)) * bias_perp));
    out = &apply(calibration, robot, s, context);
  }
  EXPECT_LT(out->imu_orientation.angularDistance(robot.upper_body), 0.02 * kDeg);
  EXPECT_NEAR(calibration.bias_tilt().head<2>().norm(), tau * bias_perp.norm(), 0.05 * tau * bias_perp.norm());
}

TEST(SensorCalibration, ZeroesEachForceSensorInItsSwing) {
  StandingRobot robot;
  SensorCalibration calibration(robot.model, without_filter_model(), robot.contact);
  calibration.reset(0.0);
  CalibrationContext context;
  context.plan = &robot.plan;
  for (int i = 0; i < 10; ++i) apply(calibration, robot, robot.at(0.001 * i), context);  // not standing: start-up ends
  // The left foot swings 5 cm above the right one: its sensor reads the weight of the foot below it.
  const FootInfo& foot = robot.model.foot(Side::Left);
  Eigen::VectorXd qpos = robot.model.stand_qpos();
  for (int i = 0; i < 7; ++i) qpos[i] = i == 3 ? 1.0 : 0.0;
  BodyFrames frames(robot.model.tree());
  forward_kinematics(robot.model.tree(), qpos, frames);
  subtree_coms(robot.model.tree(), frames);
  const Eigen::Matrix3d& sole = frames.rotation[foot.body];
  const Eigen::Vector3d lever =
      sole.transpose() * (frames.subtree_com[foot.body] - frames.position[foot.body] - sole * foot.sensor_position);
  const Eigen::Vector3d weight(0.0, 0.0, -foot.mass_below_sensor * robot.model.gravity());
  robot.plan.feet[0].in_contact = false;
  robot.plan.feet[0].position.z() = 0.05;
  for (int i = 10; i < 300; ++i) {
    SensorData s = robot.at(0.001 * i);
    s.imu_orientation = robot.upper_body * robot.mounting;
    s.foot_wrench[0].force = weight + robot.offset[0].force;
    s.foot_wrench[0].torque = lever.cross(weight) + robot.offset[0].torque;
    apply(calibration, robot, s, context);
  }
  EXPECT_EQ(calibration.swing_rezeros(), 0);  // not until the swing ends
  robot.plan.feet[0].in_contact = true;
  robot.plan.feet[0].position.z() = 0.0;
  const SensorData& out = apply(calibration, robot, robot.at(0.3), context);
  EXPECT_EQ(calibration.swing_rezeros(), 1);
  // The misalignment is unknown here (no start-up): the foot's small tilt costs a little accuracy.
  EXPECT_LT((calibration.ft_offset()[0].force - robot.offset[0].force).norm(), 0.5);
  EXPECT_LT((calibration.ft_offset()[0].torque - robot.offset[0].torque).norm(), 0.02);
  EXPECT_NEAR(out.foot_wrench[0].force.z(), 0.5 * robot.model.weight_above_sensors(), 0.5);
}

TEST(SensorCalibration, NonFiniteReadingsNeverEnterTheEstimates) {
  StandingRobot robot;
  SensorCalibration calibration(robot.model, with_filter_model(), robot.contact);
  calibration.reset(0.0);
  CalibrationContext context;
  context.standing = true;
  context.plan = &robot.plan;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int i = 0; i <= 1500; ++i) {
    SensorData s = robot.at(0.001 * i);
    if (i % 100 == 7) {
      s.imu_orientation.coeffs().setConstant(nan);
      s.imu_angular_rate.x() = nan;
      s.foot_wrench[0].force.z() = nan;
      s.joint_position[3] = nan;
    }
    context.standing = i < 1200;
    const SensorData& out = apply(calibration, robot, s, context);
    if (i % 100 != 7) {
      EXPECT_TRUE(out.imu_orientation.coeffs().allFinite()) << i;
      EXPECT_TRUE(out.imu_angular_rate.allFinite()) << i;
      EXPECT_TRUE(out.foot_wrench[0].force.allFinite() && out.foot_wrench[1].torque.allFinite()) << i;
    }
  }
  EXPECT_TRUE(calibration.misalignment().allFinite() && calibration.gyro_bias().allFinite() &&
              calibration.drift().allFinite() && calibration.bias_tilt().allFinite());
  EXPECT_GT(calibration.misalignment().norm(), 1.0 * kDeg);
}

TEST(SensorCalibration, DisabledPassesTheReadingsThrough) {
  StandingRobot robot;
  SensorCalibrationParams p;
  p.enabled = false;
  SensorCalibration calibration(robot.model, p, robot.contact);
  calibration.reset(0.0);
  CalibrationContext context;
  context.standing = true;
  context.plan = &robot.plan;
  const SensorData& s = robot.at(0.5);
  EXPECT_EQ(&apply(calibration, robot, s, context), &s);
}

// Closed loop: LOLA walking with its IMU mounted 1.4° off in roll and pitch (with the other
// realistic sensor errors): the stabilizer drives the tilt it is given to zero, so without the
// calibration the real upper body leans by the misalignment.
TEST(SensorCalibration, MisalignedImuWalksWithTheCalibration) {
  double lean[2] = {0.0, 0.0};
  bool fell[2] = {false, false};
  for (int on = 0; on < 2; ++on) {
    const Scenario scenario =
        load_scenario(test::source_path("config/scenarios/lola-walk.yaml"),
                      {"duration=6", "sensors.imu.misalignment_deg=[1.4,1.4,0]",
                       std::string("controller.calibration.enabled=") + (on ? "true" : "false")});
    const ScenarioResult r = run_scenario(scenario, make_run_config(scenario), "");
    fell[on] = r.summary["fell"].get<bool>();
    const auto& tilt = r.summary["upper_body_tilt_deg"];
    lean[on] = std::hypot(tilt["rms_x"].get<double>(), tilt["rms_y"].get<double>());
  }
  EXPECT_FALSE(fell[1]);
  EXPECT_TRUE(fell[0] || lean[0] > lean[1] + 0.8) << "tilt RMS off " << lean[0] << "°, on " << lean[1] << "°";
}

}  // namespace
}  // namespace biped
