#include "io/run_recorder.hpp"

#include <algorithm>
#include <cmath>
#include <charconv>

#include "math/rotations.hpp"

namespace biped {
namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

// A log.csv row built with std::to_chars, which with a precision prints exactly as printf's %.Nf and
// %.Ng do, at a fraction of snprintf's cost (a row has about 100 numbers).
class CsvRow {
 public:
  explicit CsvRow(std::string& text) : text_(text) { text_.clear(); }
  CsvRow& fixed(double v, int digits) { return put(v, std::chars_format::fixed, digits); }
  CsvRow& general(double v, int digits) { return put(v, std::chars_format::general, digits); }
  CsvRow& integer(int v) {
    char buffer[16];
    text_.append(buffer, std::to_chars(buffer, buffer + sizeof(buffer), v).ptr);
    return *this;
  }
  CsvRow& text(const char* v) {
    text_ += v;
    return *this;
  }
  CsvRow& comma() {
    text_ += ',';
    return *this;
  }

 private:
  CsvRow& put(double v, std::chars_format format, int digits) {
    char buffer[64];
    text_.append(buffer, std::to_chars(buffer, buffer + sizeof(buffer), v, format, digits).ptr);
    return *this;
  }
  std::string& text_;
};

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  const std::size_t k = std::min(v.size() - 1, static_cast<std::size_t>(std::floor(p * (v.size() - 1) + 0.5)));
  std::nth_element(v.begin(), v.begin() + static_cast<long>(k), v.end());
  return v[k];
}

// A foot's F/T sensor frame against the horizontal, at any heading [rad]: pitch positive toes down,
// roll positive with its left edge up.
struct SensorFrameTilt {
  double pitch = 0.0, roll = 0.0;
};
SensorFrameTilt sensor_frame_tilt(const mjData* d, int site) {
  const Eigen::Matrix3d R = math::mat_from_mujoco(d->site_xmat + 9 * site);
  return {std::atan2(-R(2, 0), std::hypot(R(0, 0), R(1, 0))), std::atan2(R(2, 1), R(2, 2))};
}

}  // namespace

RunRecorder::RunRecorder(const Simulation& sim, std::ostream* csv) : csv_(csv) {
  for (int i = 0; i < sim.num_controller_joints(); ++i) {
    joint_names_.push_back(sim.plant().joints()[sim.plant_joint_of(i)].name);
  }
  if (!csv_) return;
  std::ostream& o = *csv_;
  o << "t,state,fault,base_x,base_y,base_z,phi_x_deg,phi_y_deg,com_x,com_y,com_z";
  for (Side side : kSides) {
    const std::string p = name_of(side);
    o << ',' << p << "_Fz_des," << p << "_Tx_des," << p << "_Ty_des," << p << "_Fz," << p << "_Tx," << p << "_Ty";
  }
  o << ",com_x_des,com_y_des,com_z_des,zmp_x_des,zmp_y_des,cmd_saturated,steps_completed,contact_stiffness,cycle_us";
  for (Side side : kSides) {
    const std::string p = name_of(side);
    o << ',' << p << "_foot_x," << p << "_foot_z," << p << "_foot_pitch_deg," << p << "_terrain_dz," << p << "_terrain_tilt_deg";
  }
  o << ",imu_phi_x_deg,imu_phi_y_deg";
  o << ",dcm_error_x,dcm_error_y,landing_shift_x,landing_shift_y";
  o << ",est_phi_x_deg,est_phi_y_deg,lean_x_deg,lean_y_deg";
  for (Side side : kSides) {
    const std::string p = name_of(side);
    o << ',' << p << "_foot_y," << p << "_foot_roll_deg," << p << "_terrain_roll_deg";
  }
  for (int i = 0; i < sim.plant().mj()->nq; ++i) o << ",qpos_" << i;
  o << '\n';
}

void RunRecorder::record(const Simulation& sim, const SensorData& sensors, const JointCommand& /*setpoints*/,
                         const ControllerStatus& status, double cycle_us) {
  const mjModel* m = sim.plant().mj();
  const mjData* d = sim.data();
  const double* base = d->xpos + 3 * sim.plant().pelvis_body();
  const Eigen::Matrix3d upper_body = math::mat_from_mujoco(d->xmat + 9 * sim.plant().upper_body());
  const Eigen::Matrix3d pelvis_rot = math::mat_from_mujoco(d->xmat + 9 * sim.plant().pelvis_body());
  const math::TiltAngles tilt = math::tilt_against_gravity(upper_body);
  const double yaw = math::heading_of(pelvis_rot);
  if (!started_) {
    start_x_ = base[0];
    start_y_ = base[1];
    start_yaw_ = yaw;
    std::copy(base, base + 3, final_pos_);
    started_ = true;
  }
  path_length_ += std::hypot(base[0] - final_pos_[0], base[1] - final_pos_[1]);
  std::copy(base, base + 3, final_pos_);
  final_yaw_ = yaw;
  max_tilt_ = std::max(max_tilt_, math::tilt_from_vertical(upper_body));
  samples_.push_back({d->time, base[2], tilt.sagittal, tilt.lateral});
  const bool fallen = sim.fall_reason() != nullptr;
  if (status.fault && !fault_seen_) {
    fault_seen_ = true;
    fault_time_ = d->time;
    fault_after_fall_ = fallen;
  }
  command_saturated_ = command_saturated_ || status.command_saturated;
  // Steps end at the fall: a fallen robot's feet bouncing on the ground are not steps.
  if (!fallen) touchdowns_ = sim.gait_events().touchdowns();
  if (!csv_) return;

  // The CoM of the whole robot is the subtree CoM of the world body.
  const double* com = d->subtree_com;
  CsvRow row(row_);
  row.fixed(d->time, 4).comma().text(status.state).comma().integer(status.fault ? 1 : 0);
  for (int k = 0; k < 3; ++k) row.comma().fixed(base[k], 6);
  row.comma().fixed(tilt.sagittal * kRadToDeg, 4).comma().fixed(tilt.lateral * kRadToDeg, 4);
  for (int k = 0; k < 3; ++k) row.comma().fixed(com[k], 6);
  for (Side side : kSides) {
    const Wrench& des = status.desired_wrench[index_of(side)];
    const Wrench& meas = sensors.foot_wrench[index_of(side)];
    row.comma().fixed(des.force.z(), 3).comma().fixed(des.torque.x(), 4).comma().fixed(des.torque.y(), 4);
    row.comma().fixed(meas.force.z(), 3).comma().fixed(meas.torque.x(), 4).comma().fixed(meas.torque.y(), 4);
  }
  for (int k = 0; k < 3; ++k) row.comma().fixed(status.com_desired[k], 6);
  row.comma().fixed(status.zmp_desired.x(), 6).comma().fixed(status.zmp_desired.y(), 6);
  row.comma().integer(status.command_saturated ? 1 : 0).comma().integer(status.steps_completed);
  row.comma().general(status.contact_stiffness, 4).comma().fixed(cycle_us, 2);
  // The actual foot (the sensor frame of the ground truth) and the terrain adaptation's offset.
  for (Side side : kSides) {
    const FootInfo& foot = sim.plant().foot(side);
    const double* site = d->site_xpos + 3 * foot.sensor_site;
    const double pitch = sensor_frame_tilt(d, foot.sensor_site).pitch;
    row.comma().fixed(site[0], 5).comma().fixed(site[2], 5).comma().fixed(pitch * kRadToDeg, 3);
    row.comma().fixed(status.foot_height_offset[index_of(side)], 5);
    row.comma().fixed(status.foot_tilt[index_of(side)] * kRadToDeg, 3);
  }
  // The upper body's tilt as the controller's IMU reading has it (attitude filter, errors, delay).
  const math::TiltAngles measured = math::tilt_against_gravity(sensors.imu_orientation.toRotationMatrix());
  row.comma().fixed(measured.sagittal * kRadToDeg, 4).comma().fixed(measured.lateral * kRadToDeg, 4);
  row.comma().fixed(status.dcm_error.x(), 5).comma().fixed(status.dcm_error.y(), 5);
  row.comma().fixed(status.landing_shift.x(), 5).comma().fixed(status.landing_shift.y(), 5);
  // The tilt as the controller uses it (after its sensor calibration).
  row.comma().fixed(status.upper_body_tilt[0] * kRadToDeg, 4).comma().fixed(status.upper_body_tilt[1] * kRadToDeg, 4);
  // The upper body's planned lean (hip strategy), sagittal and lateral as the tilts.
  row.comma().fixed(status.upper_body_lean.x() * kRadToDeg, 4).comma().fixed(status.upper_body_lean.y() * kRadToDeg, 4);
  // The foot across the path (sensor frame, ground truth) and the terrain adaptation's roll of it:
  // with the pitch columns above, an edge crossed at an angle.
  for (Side side : kSides) {
    const FootInfo& foot = sim.plant().foot(side);
    const double roll = sensor_frame_tilt(d, foot.sensor_site).roll;
    row.comma().fixed(d->site_xpos[3 * foot.sensor_site + 1], 5).comma().fixed(roll * kRadToDeg, 3);
    row.comma().fixed(status.foot_roll[index_of(side)] * kRadToDeg, 3);
  }
  for (int i = 0; i < m->nq; ++i) row.comma().general(d->qpos[i], 7);
  row_ += '\n';
  *csv_ << row_;
}

nlohmann::json RunRecorder::summary(const std::string& robot, const std::string& scenario, const RunResult& result,
                                    const ControllerStatus& final_status) const {
  double sum_x = 0.0, sum_y = 0.0;
  for (const Sample& s : samples_) {
    sum_x += s.tilt_sagittal * s.tilt_sagittal;
    sum_y += s.tilt_lateral * s.tilt_lateral;
  }
  const double n = std::max<double>(1.0, static_cast<double>(samples_.size()));
  const double distance = std::hypot(final_pos_[0] - start_x_, final_pos_[1] - start_y_);
  nlohmann::json j;
  j["robot"] = robot;
  j["scenario"] = scenario;
  j["sim_time_s"] = result.sim_time;
  j["wall_time_s"] = result.wall_time;
  j["realtime_factor"] = result.wall_time > 0.0 ? result.sim_time / result.wall_time : 0.0;
  j["fell"] = result.fell;
  j["fall_time_s"] = result.fell ? nlohmann::json(result.fall_time) : nlohmann::json(nullptr);
  j["fall_reason"] = result.fall_reason;
  j["distance_m"] = distance;
  j["path_length_m"] = path_length_;
  j["mean_speed_mps"] = result.sim_time > 0.0 ? distance / result.sim_time : 0.0;
  j["steps"] = touchdowns_;
  j["final_base_position"] = {final_pos_[0], final_pos_[1], final_pos_[2]};
  j["heading_change_rad"] = math::wrap_angle(final_yaw_ - start_yaw_);
  j["upper_body_tilt_deg"] = {{"rms_x", std::sqrt(sum_x / n) * kRadToDeg},
                              {"rms_y", std::sqrt(sum_y / n) * kRadToDeg},
                              {"max", max_tilt_ * kRadToDeg}};
  j["controller_cycle_us"] = {{"median", percentile(result.cycle_us, 0.5)},
                              {"p99", percentile(result.cycle_us, 0.99)},
                              {"max", result.cycle_us.empty() ? 0.0
                                                              : *std::max_element(result.cycle_us.begin(),
                                                                                  result.cycle_us.end())}};
  j["final_state"] = final_status.state;
  // A fall's impact trips the controller's sensor checks (typically the IMU's acceleration): such a
  // fault is a consequence, not the cause, and is reported apart.
  const bool fault = final_status.fault;
  const bool after_fall = fault_seen_ ? fault_after_fall_ : result.fell;  // not logged yet: at the very end
  const auto text_if = [&](bool b) { return b ? nlohmann::json(describe(final_status.first_fault)) : nlohmann::json(nullptr); };
  j["fault"] = text_if(fault && !after_fall);
  j["fault_after_fall"] = text_if(fault && after_fall);
  j["fault_time_s"] = fault && fault_seen_ ? nlohmann::json(fault_time_) : nlohmann::json(nullptr);
  // Failed F/T sensors or the IMU the controller trusted again once healthy (SensorLimits::recovery_time).
  j["sensors_recovered"] = nlohmann::json::array();
  for (int k = 0; k < final_status.recovered.count; ++k) {
    const Fault& f = final_status.recovered.items[k];
    j["sensors_recovered"].push_back({{"sensor", describe(f)}, {"t", f.time}});
  }
  // Every fault the controller found, in order: a second fault, or the one that came after a
  // recovered sensor, is what the first alone does not tell.
  j["sensor_faults"] = nlohmann::json::array();
  for (int k = 0; k < final_status.faults.count; ++k) {
    const Fault& f = final_status.faults.items[k];
    nlohmann::json item = {{"sensor", describe(f)}, {"t", f.time}, {"after_fall", result.fell && f.time >= result.fall_time}};
    if (f.signal == FaultSignal::JointEncoder && f.index >= 0 && f.index < static_cast<int>(joint_names_.size())) {
      item["joint"] = joint_names_[f.index];
    }
    j["sensor_faults"].push_back(item);
  }
  j["command_saturated"] = command_saturated_;
  // What the controller's sensor calibration estimated (all zero with it off).
  const auto vec = [](const Eigen::Vector3d& v, double scale) { return nlohmann::json{v.x() * scale, v.y() * scale, v.z() * scale}; };
  j["calibration"] = {{"imu_misalignment_deg", vec(final_status.imu_misalignment, kRadToDeg)},
                      {"gyro_bias_rad_s", vec(final_status.gyro_bias, 1.0)},
                      {"ft_offset_left", {{"force", vec(final_status.ft_offset[0].force, 1.0)},
                                          {"torque", vec(final_status.ft_offset[0].torque, 1.0)}}},
                      {"ft_offset_right", {{"force", vec(final_status.ft_offset[1].force, 1.0)},
                                           {"torque", vec(final_status.ft_offset[1].torque, 1.0)}}}};
  return j;
}

}  // namespace biped
