#include "io/robot_config.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include "io/parameter_table.hpp"
#include "io/step_table_file.hpp"
#include "io/yaml_reader.hpp"

namespace fs = std::filesystem;

namespace biped {
namespace {

std::string resolve(const std::string& path, const std::string& relative_to_file) {
  const fs::path p(path);
  if (p.is_absolute()) return p.string();
  return (fs::path(relative_to_file).parent_path() / p).lexically_normal().string();
}

// simulation
const ParameterTable<WorldSpec> kWorldParameters = {
    {"timestep", &WorldSpec::timestep, "s", kPositive, "physics step"},
    {"ground_friction", &WorldSpec::ground_friction, "", kPositive,
     "Coulomb friction of the soles and other bodies with the ground"},
    {"contact_timeconst", &WorldSpec::contact_timeconst, "s", kPositive,
     "MuJoCo soft contact (solref) of the non-sole bodies: time constant, at least twice the timestep"},
    {"contact_dampratio", &WorldSpec::contact_dampratio, "", kPositive,
     "MuJoCo soft contact of the non-sole bodies: damping ratio"},
};
const ParameterTable<SimulationParams> kSimulationParameters = {
    {"control_period", &SimulationParams::control_period, "s", kPositive,
     "controller cycle, a whole multiple of the timestep"},
};
const ParameterTable<SoleContactParams> kSoleContactParameters = {
    {"sole_stiffness_per_foot", &SoleContactParams::stiffness_per_foot, "N/m", kPositive,
     "sole contact per foot: normal stiffness, also of the friction bristles"},
    {"sole_damping_per_foot", &SoleContactParams::damping_per_foot, "N·s/m", kNonNegative,
     "sole contact per foot: normal damping, also of the friction bristles"},
    {"sole_stiffness_by_point_area", &SoleContactParams::stiffness_by_point_area, "", {},
     "sole contact: each point's share of the stiffness by the area it represents (a uniformly compliant sole), not equal"},
};

const ParameterTable<DriveParams> kDriveParameters = {
    {"bandwidth_hz", &DriveParams::bandwidth_hz, "Hz", kPositive, "joint servos: position-loop bandwidth ω_p/2π"},
    {"velocity_loop_ratio", &DriveParams::velocity_loop_ratio, "", kPositive, "joint servos: ω_v/ω_p"},
    {"integral_ratio", &DriveParams::integral_ratio, "", kNonNegative,
     "joint servos: integral corner of the velocity loop ω_i/ω_v"},
    {"no_load_speed", &DriveParams::no_load_speed, "rad/s", kPositive,
     "drive speed–torque envelope: joint speed at which the motor voltage leaves no torque"},
    {"voltage_stall_ratio", &DriveParams::voltage_stall_ratio, "", kPositive,
     "drive speed–torque envelope: stall torque at full voltage / peak (current-limited) torque"},
};

const ParameterTable<SimulationParams> kEncoderParameters = {
    {"bits", &SimulationParams::encoder_bits, "bit", kPositive,
     "link-side encoder resolution 2π/2^bits (per joint: `encoders.bits_of: {JOINT: bits}`)"},
};

const ParameterTable<SensorNoiseParams> kSensorNoiseParameters = {
    {"imu_misalignment_deg", Degrees<SensorNoiseParams>{&SensorNoiseParams::imu_misalignment_rad}, "deg",
     kNonNegative, "IMU mounting misalignment against the upper body (roll, pitch, yaw)"},
    {"gyro_noise_rad_s", &SensorNoiseParams::gyro_noise_rad_s, "rad/s", kNonNegative, "gyroscope: white noise"},
    {"gyro_bias_rad_s", &SensorNoiseParams::gyro_bias_rad_s, "rad/s", kNonNegative, "gyroscope: bias at the start"},
    {"gyro_bias_walk", &SensorNoiseParams::gyro_bias_walk, "rad/s/√s", kNonNegative,
     "gyroscope: random walk of the bias (not drawn: this rate)"},
    {"accel_noise_m_s2", &SensorNoiseParams::accel_noise_m_s2, "m/s²", kNonNegative, "accelerometer: white noise"},
    {"accel_bias_m_s2", &SensorNoiseParams::accel_bias_m_s2, "m/s²", kNonNegative, "accelerometer: bias"},
    {"ft_force_noise_n", &SensorNoiseParams::ft_force_noise_n, "N", kNonNegative, "F/T sensors: force white noise"},
    {"ft_force_bias_n", &SensorNoiseParams::ft_force_bias_n, "N", kNonNegative, "F/T sensors: force offset"},
    {"ft_torque_noise_nm", &SensorNoiseParams::ft_torque_noise_nm, "N·m", kNonNegative,
     "F/T sensors: torque white noise"},
    {"ft_torque_bias_nm", &SensorNoiseParams::ft_torque_bias_nm, "N·m", kNonNegative, "F/T sensors: torque offset"},
    {"ft_scale_error", &SensorNoiseParams::ft_scale_error, "", kNonNegative,
     "F/T sensors: error of the gain, each axis (0.01: 1 %)"},
    {"ft_force_drift_walk", &SensorNoiseParams::ft_force_drift_walk, "N/√s", kNonNegative,
     "F/T sensors: random walk of the force offset (not drawn: this rate)"},
    {"ft_torque_drift_walk", &SensorNoiseParams::ft_torque_drift_walk, "N·m/√s", kNonNegative,
     "F/T sensors: random walk of the torque offset (not drawn: this rate)"},
    {"ft_thermal_force_n", &SensorNoiseParams::ft_thermal_force_n, "N", kNonNegative,
     "F/T sensors: force offset the warm-up adds"},
    {"ft_thermal_torque_nm", &SensorNoiseParams::ft_thermal_torque_nm, "N·m", kNonNegative,
     "F/T sensors: torque offset the warm-up adds"},
    {"ft_thermal_time_s", &SensorNoiseParams::ft_thermal_time_s, "s", kPositive,
     "F/T sensors: time constant of the warm-up (not drawn)"},
    {"encoder_offset_deg", Degrees<SensorNoiseParams>{&SensorNoiseParams::encoder_offset_rad}, "deg", kNonNegative,
     "joint encoders: zero-position calibration error"},
};

// controller
const ParameterTable<ControllerConfig> kControllerParameters = {
    {"stabilizer", &ControllerConfig::stabilizer, "", {},
     "walking controller: stabilizing control on, or off (the open-loop baseline)"},
    {"software_limit_margin_deg", Degrees<ControllerConfig>{&ControllerConfig::software_limit_margin_rad}, "deg",
     kNonNegative, "software joint limits = hard limits minus this"},
    {"step_table_relaxed_zmp_window", &ControllerConfig::step_table_relaxed_zmp_window, "s", kNonNegative,
     "biped tables: speeds above the fastest row that passed by each instant's multibody ZMP are searched again with it averaged over this window (0: never)"},
    {"step_table_prefer_short_steps", &ControllerConfig::step_table_prefer_short_steps, "", {},
     "biped tables: among gaits within 5 mm of the largest ZMP margin, the shortest steps (else the longest)"},
};
const ParameterTable<StepParameters> kStepParameters = {
    {"step_time", &StepParameters::step_time, "s", kPositive,
     "walking pattern without a step table: one step, single plus double support"},
    {"double_support_ratio", &StepParameters::double_support_ratio, "", positive_below(0.8),
     "walking pattern without a step table: share of the step time on both feet"},
    {"clearance", &StepParameters::clearance, "m", kNonNegative,
     "walking pattern without a step table: swing-foot lift"},
    {"swing_travel_share", &StepParameters::swing_travel_share, "", positive_at_most(1.0, "share of the swing time"),
     "swing foot travels horizontally in this share of the swing, then comes down vertically; biped tables keeps it in the rows where it costs at most 5 mm of ZMP margin, else 1; with a table its rows' value"},
};
const ParameterTable<WalkingPlanParams> kWalkingPlanParameters = {
    {"start_shift", &WalkingPlanParams::start_shift, "s", kNonNegative,
     "extra double support before the first step from standing"},
    {"arm_swing_gain", &WalkingPlanParams::arm_swing_gain, "", kNonNegative,
     "arm CoM forward offset per metre of foot separation"},
};
const ParameterTable<ResolvedMotionRateControlParams> kRmrcParameters = {
    {"task_gain", &ResolvedMotionRateControlParams::task_gain, "", positive_at_most(1.0, "fraction of the error per cycle"),
     "eq. (21): K_x, fraction of the task error removed per cycle"},
    {"null_space_gain", &ResolvedMotionRateControlParams::null_space_gain, "1/s", kNonNegative, "eq. (21): α_N"},
    {"joint_velocity_limit", &ResolvedMotionRateControlParams::joint_velocity_limit, "rad/s", kPositive,
     "eq. (21): joint rate limit, every joint"},
};
const ParameterTable<StandingControllerParams> kStandingParameters = {
    {"ramp_time", &StandingControllerParams::ramp_time, "s", kNonNegative,
     "standing controller: time to move into the reference pose"},
};
const ParameterTable<WeightShiftParams> kWeightShiftParameters = {
    {"lift_height", &WeightShiftParams::lift_height, "m", kNonNegative, "weight-shift controller: lift of the free foot"},
    {"shift_time", &WeightShiftParams::shift_time, "s", kPositive,
     "weight-shift controller: CoM over the stance foot (and back)"},
    {"lift_time", &WeightShiftParams::lift_time, "s", kPositive, "weight-shift controller: foot up (and down)"},
    {"hold_time", &WeightShiftParams::hold_time, "s", kNonNegative, "weight-shift controller: on one foot"},
};

const ParameterTable<CommandLimits> kCommandLimitParameters = {
    {"vx_min", &CommandLimits::vx_min, "m/s",
     Check{Check::Lower::None, 0.0, true, "a zero command must stay standing, not be saturated to walking"},
     "feasible commands (beyond them saturated): slowest forward speed (backward: negative)"},
    {"vx_max", &CommandLimits::vx_max, "m/s", kNonNegative,
     "fastest forward speed (a step table lowers it to its fastest row with min_zmp_margin, unless given)"},
    {"min_zmp_margin", &CommandLimits::min_zmp_margin, "m", kNonNegative,
     "a step table lowers vx_max to its fastest row with more than this ZMP margin"},
    {"lateral_vx_share", &CommandLimits::lateral_vx_share, "", Check{Check::Lower::NonNegative, 1.0, true, "a share"},
     "share of vx_max left to the forward speed at the full sideways speed or turn rate (1: no combined bound)"},
    {"vx_rate", &CommandLimits::vx_rate, "m/s²", kPositive,
     "the gait's forward speed changes by at most this × step time per step"},
    {"vy_max", &CommandLimits::vy_max, "m/s", kNonNegative, "sideways speed, either side"},
    {"omega_max", &CommandLimits::omega_max, "rad/s", kNonNegative, "turn rate, either side"},
    {"vy_rate", &CommandLimits::vy_rate, "m/s²", kPositive, "the gait's sideways speed changes by at most this × step time per step"},
    {"omega_rate", &CommandLimits::omega_rate, "rad/s²", kPositive,
     "the gait's turn rate changes by at most this × step time per step"},
};

const ParameterTable<StabilizerParams> kStabilizerParameters = {
    {"tilt_gain", &StabilizerParams::tilt_gain, "N·m/rad", kNonNegative, "eq. (10): K_P on the upper-body tilt"},
    {"tilt_rate_gain", &StabilizerParams::tilt_rate_gain, "N·m·s/rad", kNonNegative,
     "eq. (10): K_D on the upper-body tilt"},
    {"com_gain", &StabilizerParams::com_gain, "N·m/m", kNonNegative,
     "eq. (10): K_P on the CoM relative to the stance foot"},
    {"com_rate_gain", &StabilizerParams::com_rate_gain, "N·m·s/m", kNonNegative,
     "eq. (10): K_D on the CoM relative to the stance foot"},
    {"force_gain", &StabilizerParams::force_gain, "1/s", kNonNegative, "eq. (14): K_λ"},
    {"feedforward_gain", &StabilizerParams::feedforward_gain, "", kNonNegative, "eq. (14): K_λ,ff"},
    {"pitch_gain_scale", &StabilizerParams::pitch_gain_scale, "", kNonNegative, "eq. (14): scale of the T_y row"},
    {"position_gain", &StabilizerParams::position_gain, "1/s", kPositive,
     "eq. (20): K_λx, return of a foot's modification without contact"},
    {"contact_stiffness", &StabilizerParams::contact_stiffness, "N/m", kPositive, "eq. (11): C per foot"},
    {"heel_stiffness_share", &StabilizerParams::heel_stiffness_share, "",
     positive_below(1.0, "the toe elements need stiffness"),
     "eq. (11), feet with a toe segment: share of C on the heel segment's elements"},
    {"contact_tolerance", &StabilizerParams::contact_tolerance, "m", kNonNegative,
     "lift beyond the sole's deflection at which an element leaves contact"},
    {"toe_contact", &StabilizerParams::toe_contact, "", {},
     "recognize rolling on the toe (CoP ahead of the toe joint)"},
    {"cop_margin", &StabilizerParams::cop_margin, "m", kNonNegative,
     "eq. (10) sat: the desired CoP stays this far inside the sole"},
    {"contact_filter_time", &StabilizerParams::contact_filter_time, "s", kPositive,
     "α_λ of eq. (20): filter of the measured normal force"},
    {"contact_force_low", &StabilizerParams::contact_force_low, "N", kNonNegative,
     "α_λ of eq. (20): force control starts above this filtered normal force"},
    {"contact_force_high", &StabilizerParams::contact_force_high, "N", kPositive,
     "α_λ of eq. (20): force control is complete above this (above contact_force_low)"},
    {"max_tilt", &StabilizerParams::max_tilt, "rad", kPositive, "bound of a foot's tilt modification Δx_λ"},
    {"max_height", &StabilizerParams::max_height, "m", kPositive, "bound of a foot's height modification Δx_λ"},
    {"force_integral_gain", &StabilizerParams::force_integral_gain, "1/s²", kNonNegative,
     "extension of eq. (14): K_λ,INT (0: off)"},
    {"stiffness_adaptation", &StabilizerParams::stiffness_adaptation, "", {},
     "extension of eq. (11): on-line estimate of C"},
    {"adaptation_time", &StabilizerParams::adaptation_time, "s", kPositive, "stiffness adaptation: estimator memory"},
    {"adaptation_min_scale", &StabilizerParams::adaptation_min_scale, "", kPositive,
     "stiffness adaptation: lower bound of the estimate as a multiple of C (at most 1)"},
    {"adaptation_max_scale", &StabilizerParams::adaptation_max_scale, "", kPositive,
     "stiffness adaptation: upper bound of the estimate as a multiple of C (at least 1)"},
};

const ParameterTable<SensorCalibrationParams> kSensorCalibrationParameters = {
    {"enabled", &SensorCalibrationParams::enabled, "", {},
     "estimate and remove the IMU's misalignment, gyro bias and drift and the F/T offsets"},
    {"startup_time", &SensorCalibrationParams::startup_time, "s", kNonNegative,
     "start-up estimation while standing after the reset (ends earlier with the first walking command)"},
    {"sole_deflection", &SensorCalibrationParams::sole_deflection, "", {},
     "start-up estimates with each standing foot turned by its sole's deflection (eq. 11), else flat"},
    {"ahrs_time_constant", &SensorCalibrationParams::ahrs_time_constant, "s", kNonNegative,
     "the IMU attitude filter's time constant, to predict its tilt error from the gyro bias (0: none)"},
    {"drift_time", &SensorCalibrationParams::drift_time, "s", kNonNegative,
     "time constant of the tilt drift tracking on the loaded stance foot (0: off)"},
    {"max_drift_deg", Degrees<SensorCalibrationParams>{&SensorCalibrationParams::max_drift}, "deg", kNonNegative,
     "bound of the drift tracking's correction"},
    {"max_misalignment_deg", Degrees<SensorCalibrationParams>{&SensorCalibrationParams::max_misalignment}, "deg",
     kNonNegative, "a larger start-up estimate of the IMU's misalignment is not used"},
    {"min_misalignment_deg", Degrees<SensorCalibrationParams>{&SensorCalibrationParams::min_misalignment}, "deg",
     kNonNegative, "a smaller start-up estimate of the IMU's misalignment is not used (the flat-foot reference's accuracy)"},
    {"max_gyro_bias", &SensorCalibrationParams::max_gyro_bias, "rad/s", kNonNegative,
     "a larger start-up estimate of the gyro bias is not used"},
    {"ft_swing_rezero", &SensorCalibrationParams::ft_swing_rezero, "", {}, "re-zero each F/T sensor in its foot's swing"},
    {"swing_clearance", &SensorCalibrationParams::swing_clearance, "m", kNonNegative,
     "F/T re-zeroing: planned swing height above the stance foot from which readings count"},
    {"swing_force_band", &SensorCalibrationParams::swing_force_band, "N", kPositive,
     "F/T re-zeroing: a swing reading further from the foot's weight touches something and is left out"},
    {"max_force_offset", &SensorCalibrationParams::max_force_offset, "N", kNonNegative,
     "a larger F/T force offset estimate is not used"},
    {"max_torque_offset", &SensorCalibrationParams::max_torque_offset, "N·m", kNonNegative,
     "a larger F/T torque offset estimate is not used"},
};

const ParameterTable<AttitudeEstimatorParams> kAttitudeEstimatorParameters = {
    {"enabled", &AttitudeEstimatorParams::enabled, "", {},
     "roll and pitch from the gyro and the accelerometer aided by the stance leg's kinematics (else the IMU unit's)"},
    {"bandwidth", &AttitudeEstimatorParams::bandwidth, "rad/s", kPositive, "ω_n of the tilt correction"},
    {"damping", &AttitudeEstimatorParams::damping, "", kPositive, "ζ of the tilt correction"},
    {"bias_gain", &AttitudeEstimatorParams::bias_gain, "1/s", kNonNegative,
     "κ of the gyro bias tracking from the tilt correction (0: off)"},
    {"max_bias", &AttitudeEstimatorParams::max_bias, "rad/s", kNonNegative, "bound of the tracked gyro bias"},
    {"min_load_share", &AttitudeEstimatorParams::min_load_share, "", kNonNegative,
     "a stance foot for the kinematics carries this share of the weight above the F/T sensors"},
    {"cop_margin", &AttitudeEstimatorParams::cop_margin, "m", kNonNegative,
     "a stance foot for the kinematics has its centre of pressure this far inside its sole"},
    {"max_gap", &AttitudeEstimatorParams::max_gap, "s", kPositive,
     "without a stance foot this long, the velocity restarts from the kinematics'"},
    {"restart_time", &AttitudeEstimatorParams::restart_time, "s", kPositive,
     "the restart: this long the velocity follows the kinematics' and the tilt is not corrected"},
};

const ParameterTable<SensorLimits> kSensorLimitParameters = {
    {"max_force", &SensorLimits::max_force, "N", kPositive, "out of range: F/T force, per axis"},
    {"max_torque", &SensorLimits::max_torque, "N·m", kPositive, "out of range: F/T torque, per axis"},
    {"max_angular_rate", &SensorLimits::max_angular_rate, "rad/s", kPositive, "out of range: gyroscope"},
    {"max_acceleration", &SensorLimits::max_acceleration, "m/s²", kPositive, "out of range: accelerometer"},
    {"encoder_margin", &SensorLimits::encoder_margin, "rad", kNonNegative, "out of range: encoder beyond the hard limits"},
    {"frozen_cycles", &SensorLimits::frozen_cycles, "", kNonNegative,
     "identical F/T or IMU readings in a row that mean a dead sensor (0: off)"},
    {"encoder_jump", &SensorLimits::encoder_jump, "rad", kPositive,
     "an encoder moving farther than this in one cycle has jumped"},
    {"encoder_frozen_motion", &SensorLimits::encoder_frozen_motion, "rad", kPositive,
     "an encoder identical for frozen_cycles while its set-point moved this far is frozen"},
    {"recovery_time", &SensorLimits::recovery_time, "s", kNonNegative,
     "a failed F/T sensor or IMU healthy again this long is trusted again (0: faults last the run)"},
};

const ParameterTable<WalkingControllerParams> kWalkingControllerParameters = {
    {"fall_tilt_deg", Degrees<WalkingControllerParams>{&WalkingControllerParams::fall_tilt}, "deg", kPositive,
     "walking controller: upper-body tilt (IMU) beyond recovery, the fallen state"},
};

const ParameterTable<TerrainAdaptationParams> kTerrainAdaptationParameters = {
    {"enabled", &TerrainAdaptationParams::enabled, "", {}, "adaptation to unexpected terrain (with the stabilizer)"},
    {"contact_force", &TerrainAdaptationParams::contact_force, "N", kPositive,
     "filtered normal force that means ground contact"},
    {"filter_time", &TerrainAdaptationParams::filter_time, "s", kPositive, "filter of the normal force"},
    {"search_speed", &TerrainAdaptationParams::search_speed, "m/s", kPositive,
     "descent of a foot that finds no ground at the planned touchdown"},
    {"search_delay", &TerrainAdaptationParams::search_delay, "s", kNonNegative,
     "the descent starts this long after the planned touchdown"},
    {"measure_step_height", &TerrainAdaptationParams::measure_step_height, "", {},
     "each new foothold's height measured against the other foot's by the encoders and the IMU in the double support; all commanded heights shift together to that level"},
    {"step_height_max_lean", &TerrainAdaptationParams::step_height_max_lean, "rad", kPositive,
     "not measured while the upper body leans more than this from its command"},
    {"max_step", &TerrainAdaptationParams::max_step, "m", kPositive,
     "bound of a foothold's height against the other foot's"},
    {"level_standing_feet", &TerrainAdaptationParams::level_standing_feet, "", {},
     "standing (after a stop or a safe stop), the feet's heights against each other follow the measured step between them (at any lean)"},
    {"standing_level_dead_band", &TerrainAdaptationParams::standing_level_dead_band, "m", kNonNegative,
     "... the difference beyond this"},
    {"standing_level_time", &TerrainAdaptationParams::standing_level_time, "s", kPositive,
     "... with this time constant"},
    {"standing_level_speed", &TerrainAdaptationParams::standing_level_speed, "m/s", kPositive,
     "... at most this fast"},
    {"com_follow_time", &TerrainAdaptationParams::com_follow_time, "s", kPositive,
     "time constant of the CoM height following the footholds"},
    {"cop_band", &TerrainAdaptationParams::cop_band, "m", kPositive,
     "partial support at touchdown: CoP error that starts the foot's turn"},
    {"cop_filter_time", &TerrainAdaptationParams::cop_filter_time, "s", kPositive,
     "partial support: filter of that CoP error"},
    {"tilt_search_speed", &TerrainAdaptationParams::tilt_search_speed, "rad/s", kPositive,
     "partial support: turn rate of the foot about its edge"},
    {"max_tilt", &TerrainAdaptationParams::max_tilt, "rad", kPositive, "partial support: bound of a foot's tilt"},
    {"tilt_search_roll", &TerrainAdaptationParams::tilt_search_roll, "", {},
     "partial support: the foot also rolls, towards the desired centre of pressure sideways (an edge crossed at an angle)"},
    {"predict_slope", &TerrainAdaptationParams::predict_slope, "", {},
     "downhill: the swing foot takes the slope the stance foot stands on"},
    {"take_side_slope", &TerrainAdaptationParams::take_side_slope, "", {},
     "not downhill: the swing foot still rolls to the side slope the stance foot stands on"},
    {"side_slope_height", &TerrainAdaptationParams::side_slope_height, "", {},
     "without the downhill prediction: a foot landing lower aims at the drop the side slope gives sideways"},
    {"min_slope", &TerrainAdaptationParams::min_slope, "rad", kNonNegative, "downhill: shallower slopes are taken for level ground"},
    {"max_slope", &TerrainAdaptationParams::max_slope, "rad", kPositive, "downhill: bound of that slope"},
    {"slope_tolerance", &TerrainAdaptationParams::slope_tolerance, "m", kPositive,
     "downhill: the footholds' heights agree with the slope within this plus half its height"},
};

const ParameterTable<StepAdaptationParams> kStepAdaptationParameters = {
    {"enabled", &StepAdaptationParams::enabled, "", {}, "step adaptation from the measured DCM (with the stabilizer)"},
    {"gain", &StepAdaptationParams::gain, "", kNonNegative, "share of the DCM error predicted at touchdown taken up by the step"},
    {"cop_reach_share", &StepAdaptationParams::cop_reach_share, "", kNonNegative,
     "share of the stance sole's CoP reach counted on to absorb a DCM error before a step is shifted"},
    {"dead_band_forward", &StepAdaptationParams::dead_band_forward, "m", kNonNegative,
     "DCM error along the heading left to the stabilizer (the estimate's scatter in undisturbed walking)"},
    {"dead_band_sideways", &StepAdaptationParams::dead_band_sideways, "m", kNonNegative, "... sideways"},
    {"max_forward", &StepAdaptationParams::max_forward, "m", kNonNegative, "largest shift of a landing point forward"},
    {"max_backward", &StepAdaptationParams::max_backward, "m", kNonNegative, "... backward"},
    {"max_outward", &StepAdaptationParams::max_outward, "m", kNonNegative, "... sideways away from the stance foot"},
    {"max_inward", &StepAdaptationParams::max_inward, "m", kNonNegative, "... sideways towards the stance foot"},
    {"min_width", &StepAdaptationParams::min_width, "m", kPositive, "the feet's centres stay this far apart sideways"},
    {"filter_time", &StepAdaptationParams::filter_time, "s", kNonNegative, "filter of the landing point's shift"},
    {"max_rate", &StepAdaptationParams::max_rate, "m/s", kPositive, "the landing point moves at most this fast"},
    {"freeze_time", &StepAdaptationParams::freeze_time, "s", kNonNegative, "the landing point is held this long before touchdown"},
    {"replan", &StepAdaptationParams::replan, "", {},
     "step adaptation: at a touchdown, replan from the measured CoM when the DCMs differ by more than replan_threshold"},
    {"replan_threshold", &StepAdaptationParams::replan_threshold, "m", kNonNegative,
     "step adaptation with replan: the DCM difference beyond which a touchdown replans from the measured CoM"},
    {"quick_step_time", &StepAdaptationParams::quick_step_time, "s", kNonNegative,
     "step timing: the steps planned at a touchdown after a large DCM error last at most this (0: off)"},
    {"quick_step_error", &StepAdaptationParams::quick_step_error, "m", kNonNegative,
     "step timing: DCM error beyond the dead band at the end of a swing that makes the next steps quick"},
    {"balance_steps", &StepAdaptationParams::balance_steps, "", kNonNegative,
     "balance before a stop: at most this many more steps while the DCM error is too large to stand (0: off)"},
    {"balance_error", &StepAdaptationParams::balance_error, "m", kNonNegative,
     "balance before a stop: DCM error beyond the dead band at a touchdown above which the robot steps on"},
    {"standing_step", &StepAdaptationParams::standing_step, "", {},
     "recovery step from standing: a DCM at the edge of the feet's support starts steps at once"},
    {"standing_step_margin", &StepAdaptationParams::standing_step_margin, "m", kNonNegative,
     "recovery step from standing: the DCM this close to the support's edge (or beyond) steps"},
};

const ParameterTable<UpperBodyLeanParams> kUpperBodyLeanParameters = {
    {"enabled", &UpperBodyLeanParams::enabled, "", {}, "hip strategy: the upper body leans towards a large DCM error (with the stabilizer)"},
    {"gain", &UpperBodyLeanParams::gain, "rad/m", kNonNegative, "lean per metre of DCM error beyond the dead band"},
    {"dead_band_forward", &UpperBodyLeanParams::dead_band_forward, "m", kNonNegative,
     "DCM error along the heading that does not lean the upper body"},
    {"dead_band_sideways", &UpperBodyLeanParams::dead_band_sideways, "m", kNonNegative, "... sideways"},
    {"max_angle", &UpperBodyLeanParams::max_angle, "rad", kNonNegative, "bound of the lean about each axis"},
    {"frequency", &UpperBodyLeanParams::frequency, "rad/s", kPositive,
     "natural frequency of the critically damped filter the lean follows"},
    {"return_frequency", &UpperBodyLeanParams::return_frequency, "rad/s", kPositive,
     "... when the lean goes back towards upright"},
    {"max_rate", &UpperBodyLeanParams::max_rate, "rad/s", kPositive, "bound of the lean's rate about each axis"},
};

ParameterSection simulation_section(SimulationParams& p) {
  return {"simulation",
          {{kWorldParameters, p.world}, {kSimulationParameters, p}, {kSoleContactParameters, p.sole_contact}},
          {}};
}
ParameterSection drives_section(DriveParams& p) { return {"drives", {{kDriveParameters, p}}, {}}; }
ParameterSection encoders_section(SimulationParams& p) { return {"encoders", {{kEncoderParameters, p}}, {"bits_of"}}; }
ParameterSection sensor_noise_section(SensorNoiseParams& p) {
  return {"sensor_noise", {{kSensorNoiseParameters, p}}, {}};
}
ParameterSection controller_section(ControllerConfig& p) {
  WalkingControllerParams& w = p.walking;
  return {"controller",
          {{kControllerParameters, p},
           {kWalkingControllerParameters, w},
           {kStepParameters, w.plan.step},
           {kWalkingPlanParameters, w.plan},
           {kRmrcParameters, w.rmrc},
           {kStandingParameters, p.standing},
           {kWeightShiftParameters, p.weight_shift}},
          {"type", "model", "stance", "step_table", "limits", "stabilization", "sensor_limits", "terrain_adaptation",
           "step_adaptation", "upper_body_lean", "calibration", "attitude_estimation"}};
}
ParameterSection command_limits_section(CommandLimits& p) {
  return {"controller.limits", {{kCommandLimitParameters, p}}, {}};
}
ParameterSection stabilization_section(StabilizerParams& p) {
  return {"controller.stabilization", {{kStabilizerParameters, p}}, {}};
}
ParameterSection sensor_limits_section(SensorLimits& p) {
  return {"controller.sensor_limits", {{kSensorLimitParameters, p}}, {}};
}
ParameterSection calibration_section(SensorCalibrationParams& p) {
  return {"controller.calibration", {{kSensorCalibrationParameters, p}}, {}};
}
ParameterSection attitude_section(AttitudeEstimatorParams& p) {
  return {"controller.attitude_estimation", {{kAttitudeEstimatorParameters, p}}, {}};
}
ParameterSection terrain_adaptation_section(TerrainAdaptationParams& p) {
  return {"controller.terrain_adaptation", {{kTerrainAdaptationParameters, p}}, {}};
}
ParameterSection step_adaptation_section(StepAdaptationParams& p) {
  return {"controller.step_adaptation", {{kStepAdaptationParameters, p}}, {}};
}
ParameterSection upper_body_lean_section(UpperBodyLeanParams& p) {
  return {"controller.upper_body_lean", {{kUpperBodyLeanParameters, p}}, {}};
}

void read_simulation(const YamlReader& r, const YAML::Node& sim, SimulationParams& p) {
  read_section(r, sim, simulation_section(p));
  p.sole_contact.friction = p.world.ground_friction;
  p.sole_contact.tangential_stiffness_per_foot = p.sole_contact.stiffness_per_foot;
  p.sole_contact.tangential_damping_per_foot = p.sole_contact.damping_per_foot;
  if (p.world.contact_timeconst < 2.0 * p.world.timestep) {
    r.fail(sim["contact_timeconst"] ? sim["contact_timeconst"] : sim, "simulation.contact_timeconst",
           "must be at least twice simulation.timestep for a stable contact");
  }
  const double ratio = p.control_period / p.world.timestep;
  if (std::abs(ratio - std::round(ratio)) > 1e-9 || ratio < 0.5) {
    r.fail(sim["control_period"] ? sim["control_period"] : sim, "simulation.control_period",
           "must be a whole multiple of simulation.timestep");
  }
}

void read_stabilization(const YamlReader& r, const YAML::Node& n, StabilizerParams& p) {
  const ParameterSection section = stabilization_section(p);
  read_section(r, n, section);
  if (p.contact_force_high <= p.contact_force_low) {
    r.fail(n["contact_force_high"] ? n["contact_force_high"] : n, section.where + ".contact_force_high",
           "must be above contact_force_low");
  }
  if (p.adaptation_min_scale > 1.0 || p.adaptation_max_scale < 1.0) {
    r.fail(n, section.where, "adaptation_min_scale must be at most 1 and adaptation_max_scale at least 1");
  }
}

void read_controller(const YamlReader& r, const YAML::Node& c, ControllerConfig& p,
                     MissingStepTable missing = MissingStepTable::Error) {
  read_section(r, c, controller_section(p));
  p.type = r.text_or(c, "controller", "type", p.type);
  if (p.type != "walking" && p.type != "standing" && p.type != "weight_shift") {
    r.fail(c["type"], "controller.type", "unknown controller '" + p.type + "' (known: walking, standing, weight_shift)");
  }
  WeightShiftParams& ws = p.weight_shift;
  const std::string stance = r.text_or(c, "controller", "stance", ws.stance == Side::Left ? "left" : "right");
  if (stance != "left" && stance != "right") r.fail(c["stance"], "controller.stance", "must be left or right");
  ws.stance = stance == "left" ? Side::Left : Side::Right;
  WalkingControllerParams& w = p.walking;
  const YAML::Node limits = r.mapping(c, "controller", "limits");
  read_section(r, limits, command_limits_section(w.plan.limits));
  if (limits["vx_max"]) p.vx_max_given = true;
  bool table_read = false;
  if (c["step_table"]) {
    const std::string table = resolve(r.text(c, "controller", "step_table"), r.file());
    if (fs::exists(table)) {
      w.plan.table = read_step_table(table);
      table_read = true;
    } else if (missing == MissingStepTable::Error) {
      r.fail(c["step_table"], "controller.step_table", "no such file: " + table + " (make it: biped tables --robot NAME)");
    }
  }
  // The table bounds vx_max (again when a later file changes the margin it asks for), unless a file
  // gave vx_max: a scenario's may go beyond the table.
  if (!p.vx_max_given && !w.plan.table.empty() && (table_read || limits["min_zmp_margin"])) {
    w.plan.limits.vx_max = std::min(CommandLimits{}.vx_max, fastest_feasible_speed(w.plan.table, w.plan.limits.min_zmp_margin));
  }
  if (c["model"]) {
    p.model_path = resolve(r.text(c, "controller", "model"), r.file());
    if (!fs::exists(p.model_path)) r.fail(c["model"], "controller.model", "no such file: " + p.model_path);
  }
  p.walking.stabilizer = p.stabilizer;
  read_stabilization(r, r.mapping(c, "controller", "stabilization"), w.stabilization);
  read_section(r, r.mapping(c, "controller", "sensor_limits"), sensor_limits_section(w.sensor_limits));
  read_section(r, r.mapping(c, "controller", "terrain_adaptation"), terrain_adaptation_section(w.terrain));
  read_section(r, r.mapping(c, "controller", "step_adaptation"), step_adaptation_section(w.step_adaptation));
  read_section(r, r.mapping(c, "controller", "upper_body_lean"), upper_body_lean_section(w.upper_body_lean));
  read_section(r, r.mapping(c, "controller", "calibration"), calibration_section(w.calibration));
  read_section(r, r.mapping(c, "controller", "attitude_estimation"), attitude_section(w.attitude));
}

std::vector<double> read_interval(const YamlReader& r, const YAML::Node& map, const std::string& where, const char* key) {
  const Eigen::VectorXd v = r.numbers(map, where, key, 2);
  if (!(v[0] < v[1])) r.fail(map[key], YamlReader::join(where, key), "must be [min, max] with min < max");
  return {v[0], v[1]};
}

// "none" names a part the model does not have.
std::string optional_name(const std::string& name) { return name == "none" ? "" : name; }

// `model_map:` the names of the robot's parts in its MJCF file (model/model_map.hpp); keys left
// out keep the naming contract of models/README.md.
void read_model_map(const YamlReader& r, const YAML::Node& n, ModelMap& map) {
  if (!n.IsDefined() || n.IsNull()) return;
  const std::string where = "model_map";
  r.expect_keys(n, where, {"root_body", "upper_body", "imu", "sole_suffix", "legs", "arms", "stand_keyframe",
                           "stand_pose_deg", "torque_limits", "passive_joints", "locked_joints"});
  map.root_body = r.text_or(n, where, "root_body", map.root_body);
  map.upper_body = r.text_or(n, where, "upper_body", map.upper_body);
  map.sole_suffix = r.text_or(n, where, "sole_suffix", map.sole_suffix);
  map.stand_keyframe = r.text_or(n, where, "stand_keyframe", map.stand_keyframe);
  const YAML::Node imu = r.mapping(n, where, "imu");
  r.expect_keys(imu, "model_map.imu", {"site", "orientation", "gyro", "accelerometer"});
  map.imu_site = r.text_or(imu, "model_map.imu", "site", map.imu_site);
  map.imu_orientation = optional_name(r.text_or(imu, "model_map.imu", "orientation", map.imu_orientation));
  map.imu_gyro = r.text_or(imu, "model_map.imu", "gyro", map.imu_gyro);
  map.imu_accelerometer = r.text_or(imu, "model_map.imu", "accelerometer", map.imu_accelerometer);
  const YAML::Node legs = r.mapping(n, where, "legs");
  const YAML::Node arms = r.mapping(n, where, "arms");
  r.expect_keys(legs, "model_map.legs", {"left", "right"});
  r.expect_keys(arms, "model_map.arms", {"left", "right"});
  for (Side side : kSides) {
    LegMap& leg = map.legs[index_of(side)];
    const std::string at = std::string("model_map.legs.") + name_of(side);
    const YAML::Node l = r.mapping(legs, "model_map.legs", name_of(side));
    r.expect_keys(l, at, {"root_joint", "toe_joint", "foot_body", "ft_site", "ft_force", "ft_torque", "sole"});
    leg.root_joint = r.text_or(l, at, "root_joint", leg.root_joint);
    leg.toe_joint = optional_name(r.text_or(l, at, "toe_joint", leg.toe_joint));
    leg.foot_body = r.text_or(l, at, "foot_body", leg.foot_body);
    leg.ft_site = r.text_or(l, at, "ft_site", leg.ft_site);
    leg.ft_force = r.text_or(l, at, "ft_force", leg.ft_force);
    leg.ft_torque = r.text_or(l, at, "ft_torque", leg.ft_torque);
    leg.arm_root_joint = r.text_or(arms, "model_map.arms", name_of(side), leg.arm_root_joint);
    if (const YAML::Node sole = r.mapping(l, at, "sole"); sole.IsMap()) {
      const std::string s = at + ".sole";
      r.expect_keys(sole, s, {"x", "y", "z"});
      const std::vector<double> x = read_interval(r, sole, s, "x");
      const std::vector<double> y = read_interval(r, sole, s, "y");
      const double z = r.number(sole, s, "z");
      if (z >= 0.0) r.fail(sole["z"], s + ".z", "the sole must be below the F/T sensor (z < 0)");
      if (x[0] >= 0.0 || x[1] <= 0.0 || y[0] >= 0.0 || y[1] <= 0.0) {
        r.fail(sole, s, "the sole rectangle must lie around the point below the F/T sensor");
      }
      leg.sole = SoleRectangle{x[0], x[1], y[0], y[1], z};
    }
  }
  const YAML::Node pose = r.mapping(n, where, "stand_pose_deg");
  for (const auto& entry : pose) {
    const std::string joint = entry.first.Scalar();
    map.stand_pose[joint] = r.number(pose, "model_map.stand_pose_deg", joint.c_str()) * M_PI / 180.0;
  }
  const YAML::Node limits = r.mapping(n, where, "torque_limits");
  for (const auto& entry : limits) {
    const std::string joint = entry.first.Scalar();
    map.torque_limits[joint] = r.positive_or(limits, "model_map.torque_limits", joint.c_str(), 0.0);
  }
  for (const char* key : {"passive_joints", "locked_joints"}) {
    std::vector<std::string>& list = std::string(key) == "passive_joints" ? map.passive_joints : map.locked_joints;
    for (const auto& joint : r.sequence(n, where, key)) {
      if (!joint.IsScalar()) r.fail(joint, YamlReader::join(where, key), "must be a list of joint names");
      list.push_back(joint.Scalar());
    }
  }
}

// `include:` of a robot file: one path or a list, relative to the robot file, each applied over the
// robot file's own values in order (apply_include_file).
void read_includes(const YamlReader& r, const YAML::Node& root, RunConfig& config) {
  const YAML::Node include = root["include"];
  if (!include) return;
  if (!include.IsScalar() && !include.IsSequence()) r.fail(include, "include", "expected a path or a list of paths");
  const std::size_t count = include.IsScalar() ? 1 : include.size();
  for (std::size_t i = 0; i < count; ++i) {
    const YAML::Node entry = include.IsScalar() ? include : include[i];
    const std::string key = include.IsScalar() ? "include" : "include." + std::to_string(i);
    if (!entry.IsScalar() || entry.Scalar().empty()) r.fail(entry, key, "expected a path");
    const std::string path = resolve(entry.Scalar(), r.file());
    if (!fs::is_regular_file(path)) r.fail(entry, key, "no such file: " + path);
    apply_include_file(path, config);
  }
}

void read_robot_file(const std::string& file, RunConfig& config, MissingStepTable missing) {
  const YAML::Node root = load_yaml_file(file);
  const YamlReader r(file);
  r.expect_keys(root, "", {"model", "model_map", "include", "simulation", "drives", "encoders", "sensors",
                           "sensor_noise", "controller"});
  config.sim.world.robot_mjcf = resolve(r.text(root, "", "model"), file);
  if (!fs::exists(config.sim.world.robot_mjcf)) {
    r.fail(root["model"], "model", "no such file: " + config.sim.world.robot_mjcf);
  }
  read_model_map(r, r.mapping(root, "", "model_map"), config.sim.world.model_map);
  read_simulation(r, r.mapping(root, "", "simulation"), config.sim);
  read_section(r, r.mapping(root, "", "drives"), drives_section(config.sim.drives));

  const YAML::Node encoders = r.mapping(root, "", "encoders");
  read_section(r, encoders, encoders_section(config.sim));
  const YAML::Node per_joint = r.mapping(encoders, "encoders", "bits_of");
  for (const auto& entry : per_joint) {
    const std::string joint = entry.first.Scalar();
    config.sim.encoder_bits_of[joint] = *read_integer(r, per_joint, "encoders.bits_of", joint.c_str(), kPositive);
  }

  read_sensor_settings(r, r.mapping(root, "", "sensors"), false, config.sim);
  read_section(r, r.mapping(root, "", "sensor_noise"), sensor_noise_section(config.sim.noise_levels));
  read_controller(r, r.mapping(root, "", "controller"), config.controller, missing);
  read_includes(r, root, config);
}

}  // namespace

void apply_include_file(const std::string& path, RunConfig& config) {
  const YAML::Node root = load_yaml_file(path);
  const YamlReader r(path);
  r.expect_keys(root, "", {"controller", "simulation", "drives"});
  read_simulation(r, r.mapping(root, "", "simulation"), config.sim);
  read_section(r, r.mapping(root, "", "drives"), drives_section(config.sim.drives));
  read_controller(r, r.mapping(root, "", "controller"), config.controller);
}

std::string data_directory() {
  if (const char* env = std::getenv("BIPED_DATA_DIR"); env && *env) return env;
  return BIPED_SOURCE_DIR;
}

std::vector<std::string> known_robots() {
  std::vector<std::string> names;
  const fs::path dir = fs::path(data_directory()) / "config" / "robots";
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    if (entry.path().extension() == ".yaml") names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

std::vector<ParameterDoc> parameter_reference() {
  SimulationParams sim;
  ControllerConfig controller;
  WalkingControllerParams& w = controller.walking;
  return document_sections({simulation_section(sim), drives_section(sim.drives), encoders_section(sim),
                            sensor_noise_section(sim.noise_levels), controller_section(controller),
                            command_limits_section(w.plan.limits), stabilization_section(w.stabilization),
                            sensor_limits_section(w.sensor_limits), terrain_adaptation_section(w.terrain),
                            step_adaptation_section(w.step_adaptation), upper_body_lean_section(w.upper_body_lean),
                            calibration_section(w.calibration),
                            attitude_section(w.attitude)});
}

RunConfig make_run_config(const Scenario& s, MissingStepTable missing) {
  RunConfig config;
  const YamlReader r(s.file);
  const auto has_extension = [&](const char* extension) { return fs::path(s.robot).extension() == extension; };
  if (has_extension(".yaml")) {
    // A robot file outside config/robots/ (a robot being brought in: docs/new-robot.md).
    config.robot_file = resolve(s.robot, s.file);
    if (!fs::exists(config.robot_file)) {
      throw InputError(s.file + ": key 'robot': no such robot file: " + config.robot_file);
    }
    config.robot = fs::path(s.robot).stem().string();
    read_robot_file(config.robot_file, config, missing);
  } else if (has_extension(".xml")) {
    config.sim.world.robot_mjcf = resolve(s.robot, s.file);
    if (!fs::exists(config.sim.world.robot_mjcf)) {
      throw InputError(s.file + ": key 'robot': no such model file: " + config.sim.world.robot_mjcf);
    }
    config.robot = fs::path(s.robot).stem().string();
  } else {
    const fs::path file = fs::path(data_directory()) / "config" / "robots" / (s.robot + ".yaml");
    if (s.robot.find('/') != std::string::npos || !fs::exists(file)) {
      std::string list;
      for (const auto& name : known_robots()) list += (list.empty() ? "" : ", ") + name;
      throw InputError(s.file + ": key 'robot': unknown robot '" + s.robot + "' (known: " + list +
                       ", or a path to a robot file .yaml or an MJCF file .xml)");
    }
    config.robot = s.robot;
    config.robot_file = file.string();
    read_robot_file(config.robot_file, config, missing);
  }
  read_simulation(r, s.simulation, config.sim);
  read_controller(r, s.controller, config.controller);
  if (config.controller.model_path.empty()) config.controller.model_path = config.sim.world.robot_mjcf;

  config.sim.world.terrain = s.terrain;
  config.sim.world.model_error = s.model_error;
  config.sim.pushes = s.pushes;
  read_sensor_settings(r, s.sensors, true, config.sim);
  if (s.ideal_sensors) {
    config.sim.sensor_noise = false;
    config.sim.sensor_delay_cycles = 0;
    config.sim.sensor_errors = SensorErrorSpec{};
  }
  config.sim.faults = s.faults;
  config.sim.seed = s.seed;
  config.sim.software_limit_margin_rad = config.controller.software_limit_margin_rad;
  config.controller.walking.rmrc.dt = config.sim.control_period;
  config.controller.weight_shift.rmrc = config.controller.walking.rmrc;
  return config;
}

}  // namespace biped
