#include "model/robot_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace biped {
namespace {

int require_id(const mjModel* m, mjtObj type, const std::string& name, const std::string& path,
               const char* what) {
  const int id = mj_name2id(m, type, name.c_str());
  if (id < 0) throw ModelError(path + ": the model has no " + what + " named '" + name + "'");
  return id;
}

bool is_in_subtree(const mjModel* m, int body, int root) {
  for (int b = body; b > 0; b = m->body_parentid[b]) {
    if (b == root) return true;
  }
  return root == 0;
}

bool ends_with(std::string_view s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}

// Sole rectangle of a foot in its sensor frame, from the box geoms named "*_sole" below the
// sensor, evaluated with every joint at zero; and its segments, one per body carrying sole geoms:
// the foot body itself first, then at most one toe body hinged to it.
void measure_sole(const mjModel* m, mjData* d, const std::vector<JointInfo>& joints, FootInfo& foot,
                  const std::string& path, const char* side) {
  if (foot.sole_geoms.empty()) {
    throw ModelError(path + ": no box geom named '*_sole' below the sensor of the " + side + " foot");
  }
  const Eigen::Vector3d site_pos(d->site_xpos + 3 * foot.sensor_site);
  const Eigen::Matrix3d site_rot =
      Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(d->site_xmat + 9 * foot.sensor_site);
  constexpr double inf = std::numeric_limits<double>::infinity();
  std::array<int, FootInfo::kMaxSegments> segment_body;
  segment_body.fill(-1);
  std::array<SoleSegment, FootInfo::kMaxSegments> segments;
  for (SoleSegment& s : segments) {
    s.x_min = s.y_min = s.z = inf;
    s.x_max = s.y_max = -inf;
  }
  int count = 0;
  for (int g : foot.sole_geoms) {
    if (m->geom_type[g] != mjGEOM_BOX) {
      throw ModelError(path + ": sole geom '" + mj_id2name(m, mjOBJ_GEOM, g) + "' must be a box");
    }
    const int body = m->geom_bodyid[g];
    int k = 0;
    while (k < count && segment_body[k] != body) ++k;
    if (k == count) {
      if (count == FootInfo::kMaxSegments) {
        throw ModelError(path + ": the " + side + " foot's sole geoms are on more than " +
                         std::to_string(FootInfo::kMaxSegments) + " bodies");
      }
      segment_body[count++] = body;
    }
    SoleSegment& s = segments[k];
    const Eigen::Vector3d half(m->geom_size + 3 * g);
    const Eigen::Vector3d center(d->geom_xpos + 3 * g);
    const Eigen::Matrix3d rot =
        Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(d->geom_xmat + 9 * g);
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3d local((corner & 1 ? 1 : -1) * half.x(), (corner & 2 ? 1 : -1) * half.y(),
                                  (corner & 4 ? 1 : -1) * half.z());
      const Eigen::Vector3d in_sensor = site_rot.transpose() * (center + rot * local - site_pos);
      s.x_min = std::min(s.x_min, in_sensor.x());
      s.x_max = std::max(s.x_max, in_sensor.x());
      s.y_min = std::min(s.y_min, in_sensor.y());
      s.y_max = std::max(s.y_max, in_sensor.y());
      s.z = std::min(s.z, in_sensor.z());
    }
  }
  // The segment rigid with the sensor comes first; any other must hang on one toe hinge below it.
  const auto rigid = std::find(segment_body.begin(), segment_body.begin() + count, foot.body);
  if (rigid == segment_body.begin() + count) {
    throw ModelError(path + ": the " + side + " foot has no '*_sole' geom on body '" +
                     mj_id2name(m, mjOBJ_BODY, foot.body) + "'");
  }
  std::iter_swap(segment_body.begin(), rigid);
  std::swap(segments[0], segments[rigid - segment_body.begin()]);
  for (int k = 1; k < count; ++k) {
    const int body = segment_body[k];
    const char* name = mj_id2name(m, mjOBJ_BODY, body);
    if (m->body_parentid[body] != foot.body || m->body_jntnum[body] != 1) {
      throw ModelError(path + ": sole body '" + std::string(name) + "' must hang on one hinge from '" +
                       mj_id2name(m, mjOBJ_BODY, foot.body) + "'");
    }
    const int mj_joint = m->body_jntadr[body];
    const auto joint = std::find_if(joints.begin(), joints.end(), [&](const JointInfo& j) { return j.mj_joint == mj_joint; });
    SoleSegment& s = segments[k];
    s.joint = static_cast<int>(joint - joints.begin());
    s.axis_point = site_rot.transpose() * (Eigen::Vector3d(d->xanchor + 3 * mj_joint) - site_pos);
    s.axis = site_rot.transpose() * Eigen::Vector3d(d->xaxis + 3 * mj_joint);
  }
  foot.segments = segments;
  foot.num_segments = count;
  foot.sole_x_min = foot.sole_y_min = foot.sole_z = inf;
  foot.sole_x_max = foot.sole_y_max = -inf;
  for (int k = 0; k < count; ++k) {
    foot.sole_x_min = std::min(foot.sole_x_min, segments[k].x_min);
    foot.sole_x_max = std::max(foot.sole_x_max, segments[k].x_max);
    foot.sole_y_min = std::min(foot.sole_y_min, segments[k].y_min);
    foot.sole_y_max = std::max(foot.sole_y_max, segments[k].y_max);
    foot.sole_z = std::min(foot.sole_z, segments[k].z);
  }
}


// A sole given as data (ModelMap): one segment rigid with the sensor.
void sole_from_rectangle(const SoleRectangle& r, FootInfo& foot) {
  SoleSegment s;
  s.x_min = r.x_min;
  s.x_max = r.x_max;
  s.y_min = r.y_min;
  s.y_max = r.y_max;
  s.z = r.z;
  foot.segments[0] = s;
  foot.num_segments = 1;
  foot.sole_x_min = r.x_min;
  foot.sole_x_max = r.x_max;
  foot.sole_y_min = r.y_min;
  foot.sole_y_max = r.y_max;
  foot.sole_z = r.z;
}

// The standing configuration from a pose given as data: the joints as given (others at their
// qpos0), the base at its qpos0 pose lowered or raised until the lowest sole corner is at z = 0.
Eigen::VectorXd stand_from_pose(const mjModel* m, mjData* d, const std::map<std::string, double>& pose,
                                const std::array<FootInfo, 2>& feet, const std::string& path) {
  Eigen::VectorXd qpos = Eigen::Map<const Eigen::VectorXd>(m->qpos0, m->nq);
  for (const auto& [name, angle] : pose) {
    const int j = mj_name2id(m, mjOBJ_JOINT, name.c_str());
    if (j < 0) throw ModelError(path + ": the stand pose names a joint '" + name + "' the model does not have");
    qpos[m->jnt_qposadr[j]] = angle;
  }
  Eigen::Map<Eigen::VectorXd>(d->qpos, m->nq) = qpos;
  mj_kinematics(m, d);
  double lowest = std::numeric_limits<double>::infinity();
  for (const FootInfo& foot : feet) {
    const Eigen::Vector3d site_pos(d->site_xpos + 3 * foot.sensor_site);
    const Eigen::Matrix3d site_rot =
        Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(d->site_xmat + 9 * foot.sensor_site);
    for (double x : {foot.sole_x_min, foot.sole_x_max}) {
      for (double y : {foot.sole_y_min, foot.sole_y_max}) {
        lowest = std::min(lowest, (site_pos + site_rot * Eigen::Vector3d(x, y, foot.sole_z)).z());
      }
    }
  }
  qpos[2] -= lowest;
  return qpos;
}

}  // namespace

RobotModel RobotModel::load(const std::string& mjcf_path, double software_limit_margin_rad, const ModelMap& map) {
  char error[1000] = "";
  mjModel* raw = mj_loadXML(mjcf_path.c_str(), nullptr, error, sizeof(error));
  if (!raw) throw ModelError(mjcf_path + ": cannot load model: " + error);
  return adopt(raw, mjcf_path, software_limit_margin_rad, map);
}

RobotModel RobotModel::adopt(mjModel* compiled, const std::string& mjcf_path, double software_limit_margin_rad,
                             const ModelMap& map) {
  RobotModel model;
  model.model_.reset(compiled);
  model.path_ = mjcf_path;
  model.map_ = map;
  const mjModel* m = compiled;
  model.name_ = m->names;  // the model name comes first in the names buffer

  if (m->njnt < 1 || m->jnt_type[0] != mjJNT_FREE || m->jnt_bodyid[0] != 1) {
    throw ModelError(mjcf_path + ": the first joint must be the free joint of the root body");
  }
  model.pelvis_body_ = require_id(m, mjOBJ_BODY, map.root_body, mjcf_path, "body");
  if (model.pelvis_body_ != 1) throw ModelError(mjcf_path + ": the root body must be '" + map.root_body + "'");
  model.upper_body_ = require_id(m, mjOBJ_BODY, map.upper_body, mjcf_path, "body");
  model.imu_site_ = require_id(m, mjOBJ_SITE, map.imu_site, mjcf_path, "site");
  if (m->site_bodyid[model.imu_site_] != model.upper_body_) {
    throw ModelError(mjcf_path + ": site '" + map.imu_site + "' must be in body '" + map.upper_body + "'");
  }

  for (int j = 1; j < m->njnt; ++j) {
    if (m->jnt_type[j] != mjJNT_HINGE) {
      throw ModelError(mjcf_path + ": joint '" + std::string(mj_id2name(m, mjOBJ_JOINT, j)) +
                       "' is not a hinge; only the root may have a free joint");
    }
    JointInfo info;
    info.name = mj_id2name(m, mjOBJ_JOINT, j);
    info.mj_joint = j;
    info.qpos_adr = m->jnt_qposadr[j];
    info.dof_adr = m->jnt_dofadr[j];
    if (!m->jnt_limited[j]) throw ModelError(mjcf_path + ": joint '" + info.name + "' has no range");
    info.lower = m->jnt_range[2 * j];
    info.upper = m->jnt_range[2 * j + 1];
    info.soft_lower = info.lower + software_limit_margin_rad;
    info.soft_upper = info.upper - software_limit_margin_rad;
    if (info.soft_lower >= info.soft_upper) {
      throw ModelError(mjcf_path + ": joint '" + info.name + "' range is narrower than twice the software margin");
    }
    for (int a = 0; a < m->nu; ++a) {
      if (m->actuator_trntype[a] == mjTRN_JOINT && m->actuator_trnid[2 * a] == j) {
        info.torque_limit = m->actuator_ctrllimited[a]
                                ? std::max(std::abs(m->actuator_ctrlrange[2 * a]),
                                           std::abs(m->actuator_ctrlrange[2 * a + 1])) *
                                      std::abs(m->actuator_gear[6 * a])
                                : 0.0;
      }
    }
    if (const auto limit = map.torque_limits.find(info.name); limit != map.torque_limits.end()) {
      info.torque_limit = limit->second;
    }
    info.passive =
        std::find(map.passive_joints.begin(), map.passive_joints.end(), info.name) != map.passive_joints.end();
    info.locked = std::find(map.locked_joints.begin(), map.locked_joints.end(), info.name) != map.locked_joints.end();
    model.joints_.push_back(std::move(info));
  }
  for (const auto& [name, limit] : map.torque_limits) {
    if (model.joint_index(name) < 0) {
      throw ModelError(mjcf_path + ": a torque limit is given for a joint '" + name + "' the model does not have");
    }
  }
  for (const std::string& name : map.passive_joints) {
    if (model.joint_index(name) < 0) {
      throw ModelError(mjcf_path + ": the passive joint '" + name + "' is not a joint of the model");
    }
  }
  for (const std::string& name : map.locked_joints) {
    if (model.joint_index(name) < 0) {
      throw ModelError(mjcf_path + ": the locked joint '" + name + "' is not a joint of the model");
    }
  }
  for (Side side : kSides) {
    const LegMap& leg = map.legs[index_of(side)];
    model.leg_root_joint_[index_of(side)] = model.joint_index(leg.root_joint);
    model.arm_root_joint_[index_of(side)] = model.joint_index(leg.arm_root_joint);
    model.toe_joint_[index_of(side)] = leg.toe_joint.empty() ? -1 : model.joint_index(leg.toe_joint);
  }

  for (Side side : kSides) {
    FootInfo& foot = model.feet_[index_of(side)];
    const LegMap& leg = map.legs[index_of(side)];
    foot.body = require_id(m, mjOBJ_BODY, leg.foot_body, mjcf_path, "body");
    foot.sensor_site = require_id(m, mjOBJ_SITE, leg.ft_site, mjcf_path, "site");
    if (m->site_bodyid[foot.sensor_site] != foot.body) {
      throw ModelError(mjcf_path + ": site '" + leg.ft_site + "' must be in body '" + leg.foot_body + "'");
    }
    foot.force_sensor = require_id(m, mjOBJ_SENSOR, leg.ft_force, mjcf_path, "sensor");
    foot.torque_sensor = require_id(m, mjOBJ_SENSOR, leg.ft_torque, mjcf_path, "sensor");
    foot.sensor_position = Eigen::Vector3d(m->site_pos + 3 * foot.sensor_site);
    for (int b = 1; b < m->nbody; ++b) {
      if (!is_in_subtree(m, b, foot.body)) continue;
      foot.bodies_below_sensor.push_back(b);
      foot.mass_below_sensor += m->body_mass[b];
    }
    if (leg.sole) continue;
    for (int g = 0; g < m->ngeom; ++g) {
      const char* geom_name = mj_id2name(m, mjOBJ_GEOM, g);
      if (geom_name && ends_with(geom_name, map.sole_suffix) && is_in_subtree(m, m->geom_bodyid[g], foot.body)) {
        foot.sole_geoms.push_back(g);
      }
    }
  }
  model.imu_sensors_[0] =
      map.imu_orientation.empty() ? -1 : require_id(m, mjOBJ_SENSOR, map.imu_orientation, mjcf_path, "sensor");
  model.imu_sensors_[1] = require_id(m, mjOBJ_SENSOR, map.imu_gyro, mjcf_path, "sensor");
  model.imu_sensors_[2] = require_id(m, mjOBJ_SENSOR, map.imu_accelerometer, mjcf_path, "sensor");

  for (int b = 1; b < m->nbody; ++b) model.total_mass_ += m->body_mass[b];
  model.tree_ = make_body_tree(m, mjcf_path.c_str());

  RobotData data(model);
  mj_kinematics(m, data.mj());
  for (Side side : kSides) {
    FootInfo& foot = model.feet_[index_of(side)];
    const LegMap& leg = map.legs[index_of(side)];
    if (leg.sole) {
      sole_from_rectangle(*leg.sole, foot);
    } else {
      measure_sole(m, data.mj(), model.joints_, foot, mjcf_path, name_of(side));
    }
  }

  if (!map.stand_pose.empty()) {
    model.stand_qpos_ = stand_from_pose(m, data.mj(), map.stand_pose, model.feet_, mjcf_path);
  } else {
    const int key = require_id(m, mjOBJ_KEY, map.stand_keyframe, mjcf_path, "keyframe");
    model.stand_qpos_ = Eigen::Map<const Eigen::VectorXd>(m->key_qpos + key * m->nq, m->nq);
  }
  model.stand_pose_.resize(model.num_joints());
  for (int i = 0; i < model.num_joints(); ++i) {
    model.stand_pose_[i] = model.stand_qpos_[model.joints_[i].qpos_adr];
  }
  return model;
}

int RobotModel::joint_index(std::string_view joint_name) const {
  for (int i = 0; i < num_joints(); ++i) {
    if (joints_[i].name == joint_name) return i;
  }
  return -1;
}

int RobotModel::body_named(const std::string& name) const {
  const int id = mj_name2id(model_.get(), mjOBJ_BODY, name.c_str());
  if (id >= 0) return id;
  if (name == "upper_body") return upper_body_;
  if (name == "pelvis") return pelvis_body_;
  return -1;
}

double RobotModel::gravity() const { return std::abs(model_->opt.gravity[2]); }

Eigen::Vector3d RobotModel::imu_position() const { return Eigen::Vector3d(model_->site_pos + 3 * imu_site_); }

double RobotModel::weight_above_sensors() const {
  return (total_mass_ - feet_[0].mass_below_sensor - feet_[1].mass_below_sensor) * gravity();
}

RobotData::RobotData(const RobotModel& model) : model_(&model), data_(mj_makeData(model.mj())) {}

Eigen::Map<Eigen::VectorXd> RobotData::qpos() { return {data_->qpos, model_->nq()}; }

Eigen::Vector3d RobotData::body_position(int body) const { return Eigen::Vector3d(data_->xpos + 3 * body); }

Eigen::Matrix3d RobotData::body_rotation(int body) const {
  return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(data_->xmat + 9 * body);
}

Eigen::Quaterniond RobotData::body_orientation(int body) const {
  const double* q = data_->xquat + 4 * body;  // w, x, y, z
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
}

Eigen::Vector3d RobotData::site_position(int site) const { return Eigen::Vector3d(data_->site_xpos + 3 * site); }

Eigen::Matrix3d RobotData::site_rotation(int site) const {
  return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(data_->site_xmat + 9 * site);
}

Eigen::Vector3d RobotData::joint_anchor(int joint) const {
  return Eigen::Vector3d(data_->xanchor + 3 * model_->joints()[joint].mj_joint);
}

Eigen::Vector3d RobotData::subtree_com(int body) const { return Eigen::Vector3d(data_->subtree_com + 3 * body); }

}  // namespace biped
