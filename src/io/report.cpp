#include "io/report.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "control/contact_wrench.hpp"
#include "math/rotations.hpp"

namespace biped {
namespace {

constexpr double kRadToDeg = 180.0 / M_PI;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kCopMinForceN = 20.0;      // below this a foot's CoP is not defined (shown as a gap)
constexpr double kSupportMinForceN = 10.0;  // a sole carrying more than this is part of the support polygon
// Two planned footsteps closer than this are the same footprint, replanned.
constexpr double kSameFootprintM = 0.005, kSameFootprintRad = 0.01;

double rounded(double v, int decimals) {
  const double scale = std::pow(10.0, decimals);
  return std::round(v * scale) / scale;
}

// Rounded values; NaN becomes null (a gap in the plots).
nlohmann::json series(const std::vector<double>& values, int decimals) {
  nlohmann::json a = nlohmann::json::array();
  for (double v : values) a.push_back(std::isfinite(v) ? nlohmann::json(rounded(v, decimals)) : nlohmann::json(nullptr));
  return a;
}

nlohmann::json rounded_array(const double* v, int n, int decimals) {
  nlohmann::json a = nlohmann::json::array();
  for (int i = 0; i < n; ++i) a.push_back(rounded(v[i], decimals));
  return a;
}

const char* geom_type_name(int type) {
  switch (type) {
    case mjGEOM_PLANE: return "plane";
    case mjGEOM_SPHERE: return "sphere";
    case mjGEOM_CAPSULE: return "capsule";
    case mjGEOM_ELLIPSOID: return "ellipsoid";
    case mjGEOM_CYLINDER: return "cylinder";
    case mjGEOM_BOX: return "box";
    case mjGEOM_MESH: return "mesh";
    default: return nullptr;  // height fields and others are not drawn
  }
}

// Geom groups 0–2 are the ones MuJoCo's own viewer shows by default.
constexpr int kFirstHiddenGeomGroup = 3;

// A world point on a foot's sole plane, from a point (x, y) of the sole in the sensor frame.
Eigen::Vector3d sole_point(const mjData* d, const FootInfo& foot, double x, double y) {
  const Eigen::Vector3d origin(d->site_xpos + 3 * foot.sensor_site);
  return origin + math::mat_from_mujoco(d->site_xmat + 9 * foot.sensor_site) * Eigen::Vector3d(x, y, foot.sole_z);
}

// Text for an HTML element (the page's <title>).
std::string html_text(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '&') out += "&amp;";
    else if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else out += c;
  }
  return out;
}

}  // namespace

ReportWriter::ReportWriter(const Simulation& sim, double replay_rate_hz)
    : control_period_(sim.plant().mj()->opt.timestep * sim.physics_steps_per_control_period()),
      replay_period_(1.0 / replay_rate_hz) {
  const mjModel* m = sim.plant().mj();
  std::vector<int> index_of_body(m->nbody, -1);
  auto replayed = [&](int body) {
    if (index_of_body[body] < 0) {
      index_of_body[body] = static_cast<int>(replay_bodies_.size());
      replay_bodies_.push_back(body);
    }
    return index_of_body[body];
  };
  const int pelvis = replayed(sim.plant().pelvis_body());
  nlohmann::json geoms = nlohmann::json::array();
  for (int g = 0; g < m->ngeom; ++g) {
    const char* type = geom_type_name(m->geom_type[g]);
    if (!type || m->geom_group[g] >= kFirstHiddenGeomGroup || m->geom_rgba[4 * g + 3] <= 0.0f) continue;
    const int body = m->geom_bodyid[g];
    nlohmann::json geom = {{"type", type},
                           {"body", body == 0 ? -1 : replayed(body)},
                           {"size", rounded_array(m->geom_size + 3 * g, 3, 5)},
                           {"pos", rounded_array(m->geom_pos + 3 * g, 3, 5)},
                           {"quat", rounded_array(m->geom_quat + 4 * g, 4, 6)}};
    const double rgba[4] = {m->geom_rgba[4 * g], m->geom_rgba[4 * g + 1], m->geom_rgba[4 * g + 2], m->geom_rgba[4 * g + 3]};
    geom["rgba"] = rounded_array(rgba, 4, 3);
    if (m->geom_type[g] == mjGEOM_MESH) {
      const int mesh = m->geom_dataid[g];
      std::vector<double> vert(m->mesh_vert + 3 * m->mesh_vertadr[mesh],
                               m->mesh_vert + 3 * (m->mesh_vertadr[mesh] + m->mesh_vertnum[mesh]));
      geom["mesh"] = {{"vert", series(vert, 5)},
                      {"face", std::vector<int>(m->mesh_face + 3 * m->mesh_faceadr[mesh],
                                                m->mesh_face + 3 * (m->mesh_faceadr[mesh] + m->mesh_facenum[mesh]))}};
    }
    geoms.push_back(geom);
  }
  nlohmann::json bodies = nlohmann::json::array();
  for (int body : replay_bodies_) {
    const char* name = mj_id2name(m, mjOBJ_BODY, body);
    bodies.push_back(name ? std::string(name) : "body " + std::to_string(body));
  }
  nlohmann::json soles = nlohmann::json::array();
  for (Side side : kSides) {
    const FootInfo& f = sim.plant().foot(side);
    soles.push_back({{"side", name_of(side)}, {"x_min", f.sole_x_min}, {"x_max", f.sole_x_max},
                     {"y_min", f.sole_y_min}, {"y_max", f.sole_y_max}});
  }
  model_ = {{"bodies", bodies}, {"pelvis", pelvis}, {"geoms", geoms}, {"soles", soles}};
  for (const JointInfo& j : sim.plant().joints()) {
    joints_.push_back({{"name", j.name}, {"lower", rounded(j.lower * kRadToDeg, 2)}, {"upper", rounded(j.upper * kRadToDeg, 2)},
                       {"soft_lower", rounded(j.soft_lower * kRadToDeg, 2)},
                       {"soft_upper", rounded(j.soft_upper * kRadToDeg, 2)}});
  }
}

void ReportWriter::add(const std::string& name, int decimals, double value) {
  Column& c = log_[name];
  c.decimals = decimals;
  c.values.push_back(value);
}

Eigen::Vector2d ReportWriter::to_world(const Eigen::Vector2d& p) const {
  return Eigen::Rotation2Dd(frame_yaw_) * p + frame_offset_;
}

void ReportWriter::register_controller_frame(const Simulation& sim) {
  const Side stance = sim.foot_contact_force(Side::Left) >= sim.foot_contact_force(Side::Right) ? Side::Left : Side::Right;
  if (sim.foot_contact_force(stance) < kSupportMinForceN) return;
  // The foothold the stance foot was planned to have: its side's last footprint already stepped on.
  const auto stepped = std::find_if(footprints_.rbegin(), footprints_.rend(), [&](const Footprint& f) {
    return f.side == stance && f.stepped;
  });
  if (stepped == footprints_.rend()) return;
  const int body = sim.plant().foot(stance).body;
  const mjData* d = sim.data();
  frame_yaw_ = math::heading_of(math::mat_from_mujoco(d->xmat + 9 * body)) - stepped->planned_yaw;
  frame_offset_ = Eigen::Vector2d(d->xpos[3 * body], d->xpos[3 * body + 1]) - Eigen::Rotation2Dd(frame_yaw_) * stepped->planned;
}

void ReportWriter::note_planned_steps(const ControllerStatus& status, double t) {
  // The steps completed since the last record are the first ones of the last plan.
  const int completed = std::min<int>(status.steps_completed - steps_completed_, static_cast<int>(plan_.size()));
  for (int i = 0; i < completed; ++i) footprints_[plan_[i]].stepped = true;
  steps_completed_ = status.steps_completed;
  std::vector<std::size_t> plan;
  for (int i = 0; i < status.num_planned_steps; ++i) {
    const PlannedStep& step = status.planned_steps[i];
    auto same = [&](std::size_t k) {
      const Footprint& f = footprints_[k];
      return f.side == step.side && (f.planned - step.position).norm() < kSameFootprintM &&
             std::abs(std::remainder(f.planned_yaw - step.yaw, 2.0 * M_PI)) < kSameFootprintRad;
    };
    const auto found = std::find_if(plan_.begin(), plan_.end(), same);
    const std::size_t k = found != plan_.end() ? *found : footprints_.size();
    if (found == plan_.end()) {
      footprints_.push_back({step.side, step.position, step.yaw, to_world(step.position), step.yaw + frame_yaw_,
                             step.touchdown, t, t});
    }
    Footprint& f = footprints_[k];
    f.last_planned = t;
    f.touchdown = step.touchdown;
    f.world = to_world(step.position);
    f.world_yaw = step.yaw + frame_yaw_;
    plan.push_back(k);
  }
  for (std::size_t k : plan_) {
    if (!footprints_[k].stepped && std::find(plan.begin(), plan.end(), k) == plan.end()) footprints_[k].superseded = true;
  }
  plan_ = std::move(plan);
}

void ReportWriter::record(const Simulation& sim, const SensorData& sensors, const JointCommand& /*setpoints*/,
                          const ControllerStatus& status, double cycle_us) {
  const RobotModel& plant = sim.plant();
  const mjData* d = sim.data();
  const double t = d->time;
  add("t", 3, t);
  const auto state = std::find(states_.begin(), states_.end(), status.state);
  add("state", 0, static_cast<double>(state - states_.begin()));
  if (state == states_.end()) states_.emplace_back(status.state);

  const math::TiltAngles tilt = math::tilt_against_gravity(math::mat_from_mujoco(d->xmat + 9 * plant.upper_body()));
  add("phi_x", 3, tilt.sagittal * kRadToDeg);
  add("phi_y", 3, tilt.lateral * kRadToDeg);
  register_controller_frame(sim);
  const Eigen::Vector2d com_des = to_world(status.com_desired.head<2>());
  const Eigen::Vector2d com_est = status.com_estimate_valid ? to_world(status.com_estimated)
                                                            : Eigen::Vector2d::Constant(kNaN);
  const Eigen::Vector2d zmp_des = to_world(status.zmp_desired);
  // The CoM of the whole robot is the subtree CoM of the world body.
  for (int k = 0; k < 2; ++k) {
    const std::string axis = k == 0 ? "x" : "y";
    add("com_" + axis, 4, d->subtree_com[k]);
    add("com_des_" + axis, 4, com_des[k]);
    add("com_est_" + axis, 4, com_est[k]);
    add("zmp_des_" + axis, 4, zmp_des[k]);
  }
  add("com_z", 4, d->subtree_com[2]);
  add("com_des_z", 4, status.com_desired.z());

  Eigen::Vector3d cop_sum = Eigen::Vector3d::Zero();
  double fz_sum = 0.0;
  Eigen::AlignedBox2d support;  // of the soles on the ground (empty: none)
  for (Side side : kSides) {
    const std::string p = name_of(side);
    const FootInfo& foot = plant.foot(side);
    const Wrench& des = status.desired_wrench[index_of(side)];
    const Wrench& meas = sensors.foot_wrench[index_of(side)];
    add(p + "_fz_des", 1, des.force.z());
    add(p + "_fz", 1, meas.force.z());
    add(p + "_tx_des", 2, des.torque.x());
    add(p + "_tx", 2, meas.torque.x());
    add(p + "_ty_des", 2, des.torque.y());
    add(p + "_ty", 2, meas.torque.y());
    Eigen::Vector3d cop = Eigen::Vector3d::Constant(kNaN);
    if (meas.force.z() > kCopMinForceN) {
      const Eigen::Vector2d c = center_of_pressure(meas, foot.sole_z);
      cop = sole_point(d, foot, c.x(), c.y());
      cop_sum += meas.force.z() * cop;
      fz_sum += meas.force.z();
    }
    add(p + "_cop_x", 4, cop.x());
    add(p + "_cop_y", 4, cop.y());
    if (sim.foot_contact_force(side) > kSupportMinForceN) {
      for (double x : {foot.sole_x_min, foot.sole_x_max}) {
        for (double y : {foot.sole_y_min, foot.sole_y_max}) {
          support.extend(sole_point(d, foot, x, y).head<2>());
        }
      }
    }
  }
  add("cop_x", 4, fz_sum > 0.0 ? cop_sum.x() / fz_sum : kNaN);
  add("cop_y", 4, fz_sum > 0.0 ? cop_sum.y() / fz_sum : kNaN);
  const bool supported = !support.isEmpty();
  add("support_x_min", 4, supported ? support.min().x() : kNaN);
  add("support_x_max", 4, supported ? support.max().x() : kNaN);
  add("support_y_min", 4, supported ? support.min().y() : kNaN);
  add("support_y_max", 4, supported ? support.max().y() : kNaN);
  for (const JointInfo& j : plant.joints()) add("q:" + j.name, 2, d->qpos[j.qpos_adr] * kRadToDeg);
  add("cycle_us", 1, cycle_us);
  cycle_index_.push_back(std::lround(t / control_period_));
  note_planned_steps(status, t);

  // One frame in each replay period (the first logged instant in it).
  if (t >= next_replay_t_ - 1e-9) {
    next_replay_t_ = (std::floor(t / replay_period_ + 1e-9) + 1.0) * replay_period_;
    replay_t_.push_back(t);
    std::vector<double>& frame = replay_frames_.emplace_back();
    for (int body : replay_bodies_) {
      frame.insert(frame.end(), d->xpos + 3 * body, d->xpos + 3 * body + 3);
      frame.insert(frame.end(), d->xquat + 4 * body, d->xquat + 4 * body + 4);
    }
  }
}

nlohmann::json ReportWriter::data(const nlohmann::json& summary, const std::vector<double>& cycle_us) const {
  nlohmann::json log = {{"states", states_}};
  std::vector<double> longest(cycle_index_.size(), kNaN);
  for (std::size_t i = 0; i < cycle_index_.size(); ++i) {
    const std::size_t begin = std::min<std::size_t>(cycle_index_[i], cycle_us.size());
    const std::size_t end = i + 1 < cycle_index_.size() ? std::min<std::size_t>(cycle_index_[i + 1], cycle_us.size())
                                                        : cycle_us.size();
    if (begin < end) longest[i] = *std::max_element(cycle_us.begin() + begin, cycle_us.begin() + end);
  }
  log["cycle_us_max"] = series(longest, 1);
  nlohmann::json feet = {{"left", {{"side", "left"}}}, {"right", {{"side", "right"}}}};
  for (const auto& [name, column] : log_) {
    if (name.starts_with("q:")) continue;
    const std::string prefix = name.substr(0, name.find('_'));
    if (prefix == "left" || prefix == "right") {
      feet[prefix][name.substr(prefix.size() + 1)] = series(column.values, column.decimals);
    } else {
      log[name] = series(column.values, column.decimals);
    }
  }
  nlohmann::json joints = joints_;
  for (nlohmann::json& j : joints) {
    const Column& c = log_.at("q:" + j["name"].get<std::string>());
    j["q"] = series(c.values, c.decimals);
  }
  nlohmann::json frames = nlohmann::json::array();
  for (const std::vector<double>& frame : replay_frames_) frames.push_back(series(frame, 4));
  nlohmann::json footprints = nlohmann::json::array();
  for (const Footprint& f : footprints_) {
    footprints.push_back({{"side", name_of(f.side)}, {"x", rounded(f.world.x(), 4)}, {"y", rounded(f.world.y(), 4)},
                          {"yaw", rounded(f.world_yaw, 4)}, {"touchdown", rounded(f.touchdown, 3)},
                          {"first", rounded(f.first_planned, 3)}, {"last", rounded(f.last_planned, 3)},
                          {"stepped", f.stepped},
                          {"superseded", f.superseded}});
  }
  return {{"summary", summary},
          {"log", log},
          {"feet", {feet["left"], feet["right"]}},
          {"joints", joints},
          {"model", model_},
          {"replay", {{"t", series(replay_t_, 3)}, {"frames", frames}}},
          {"footprints", footprints}};
}

void ReportWriter::write_html(std::ostream& out, const nlohmann::json& summary,
                              const std::vector<double>& cycle_us) const {
  // Inside a script element "</script" or "<!--" would end or confuse it: '<' occurs in JSON only
  // inside strings, where "\u003c" is the same character.
  std::string json;
  for (char c : data(summary, cycle_us).dump()) {
    if (c == '<') json += "\\u003c";
    else json += c;
  }
  out << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      << "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      << "<title>" << html_text(summary.value("scenario", std::string("run")) + " (" + summary.value("robot", std::string("")) + ")")
      << ": biped run report</title>\n</head>\n<body>\n"
      << "<script type=\"application/json\" id=\"report-data\">" << json << "</script>\n"
      << "<script>" << report_bundle() << "</script>\n</body>\n</html>\n";
}

}  // namespace biped
