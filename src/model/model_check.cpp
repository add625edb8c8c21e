#include "model/model_check.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <set>
#include <sstream>

namespace biped {
namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

std::string object_name(const mjModel* m, mjtObj type, int id) {
  const char* name = mj_id2name(m, type, id);
  return name ? name : "#" + std::to_string(id);
}

std::string fixed(double value, int digits) {
  std::ostringstream text;
  text << std::fixed << std::setprecision(digits) << value;
  return text.str();
}

std::string degrees(double rad) { return fixed(rad * kRadToDeg, 1) + "°"; }

bool is_in_subtree(const mjModel* m, int body, int root) {
  for (int b = body; b > 0; b = m->body_parentid[b]) {
    if (b == root) return true;
  }
  return root == 0;
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// Collects problems under robot-file keys.
class Problems {
 public:
  void add(std::string key, std::string message) { list_.push_back({std::move(key), std::move(message)}); }
  // The id of the named object, or -1 after reporting it missing under `key`.
  int require(const mjModel* m, mjtObj type, const std::string& name, const std::string& key, const char* what) {
    const int id = name.empty() ? -1 : mj_name2id(m, type, name.c_str());
    if (id < 0) add(key, std::string("the model has no ") + what + " named '" + name + "'");
    return id;
  }
  std::vector<ModelProblem> take() { return std::move(list_); }

 private:
  std::vector<ModelProblem> list_;
};

// A sensor of the expected type on the expected site; `site` < 0: the site itself was reported.
void require_sensor(const mjModel* m, Problems& p, const std::string& name, const std::string& key, mjtSensor type,
                    const char* type_name, int site) {
  const int s = p.require(m, mjOBJ_SENSOR, name, key, "sensor");
  if (s < 0 || site < 0) return;
  if (m->sensor_type[s] != type) {
    p.add(key, "sensor '" + name + "' is not a " + type_name + " sensor");
  } else if (m->sensor_objtype[s] != mjOBJ_SITE || m->sensor_objid[s] != site) {
    p.add(key, "sensor '" + name + "' is not on site '" + object_name(m, mjOBJ_SITE, site) + "'");
  }
}

// The actuator on a joint (the last one, as the simulator takes it), or -1.
int actuator_of(const mjModel* m, int joint, int* count) {
  int found = -1;
  *count = 0;
  for (int a = 0; a < m->nu; ++a) {
    if (m->actuator_trntype[a] == mjTRN_JOINT && m->actuator_trnid[2 * a] == joint) {
      found = a;
      ++*count;
    }
  }
  return found;
}

bool is_torque_motor(const mjModel* m, int a) {
  return m->actuator_dyntype[a] == mjDYN_NONE && m->actuator_gaintype[a] == mjGAIN_FIXED &&
         m->actuator_gainprm[a * mjNGAIN] == 1.0 && m->actuator_biastype[a] == mjBIAS_NONE;
}

bool coupled_by_equality(const mjModel* m, int joint) {
  for (int e = 0; e < m->neq; ++e) {
    if (m->eq_type[e] == mjEQ_JOINT && m->eq_active[e] && (m->eq_obj1id[e] == joint || m->eq_obj2id[e] == joint)) {
      return true;
    }
  }
  return false;
}

std::string joint_list(const mjModel* m, const std::vector<int>& joints) {
  std::string list;
  for (int j : joints) list += (list.empty() ? "" : ", ") + object_name(m, mjOBJ_JOINT, j);
  return list;
}

// The standing pose's joint angles, and where each comes from, for the software-limit check.
void check_stand_pose(const mjModel* m, const ModelMap& map, double margin, Problems& p) {
  std::vector<double> qpos(m->qpos0, m->qpos0 + m->nq);
  std::string key = "model_map.stand_pose_deg";
  if (map.stand_pose.empty()) {
    key = "model_map.stand_keyframe";
    const int k = mj_name2id(m, mjOBJ_KEY, map.stand_keyframe.c_str());
    if (k < 0) {
      p.add(key, "the model has no keyframe named '" + map.stand_keyframe +
                     "' and model_map.stand_pose_deg does not give the standing pose");
      return;
    }
    std::copy(m->key_qpos + k * m->nq, m->key_qpos + (k + 1) * m->nq, qpos.begin());
  }
  for (const auto& [joint, angle] : map.stand_pose) {
    const int j = mj_name2id(m, mjOBJ_JOINT, joint.c_str());
    if (j < 0 || m->jnt_type[j] != mjJNT_HINGE) {
      p.add(key + "." + joint, "the model has no hinge joint named '" + joint + "'");
      continue;
    }
    qpos[m->jnt_qposadr[j]] = angle;
  }
  for (int j = 0; j < m->njnt; ++j) {
    if (m->jnt_type[j] != mjJNT_HINGE || !m->jnt_limited[j]) continue;
    const std::string joint = object_name(m, mjOBJ_JOINT, j);
    const double q = qpos[m->jnt_qposadr[j]];
    const double lower = m->jnt_range[2 * j] + margin, upper = m->jnt_range[2 * j + 1] - margin;
    if (q >= lower && q <= upper) continue;
    const std::string limits = "the software limits [" + degrees(lower) + ", " + degrees(upper) + "] (the range minus " +
                               degrees(margin) + ", controller.software_limit_margin_deg)";
    if (!map.stand_pose.empty() && map.stand_pose.count(joint)) {
      p.add(key + "." + joint, degrees(q) + " is outside " + limits);
    } else if (!map.stand_pose.empty()) {
      p.add(key, "joint '" + joint + "' is not given and stays at " + degrees(q) + ", outside " + limits);
    } else {
      p.add(key, "joint '" + joint + "' is at " + degrees(q) + " in keyframe '" + map.stand_keyframe + "', outside " +
                     limits);
    }
  }
}

}  // namespace

std::vector<int> leg_chain(const mjModel* m, int root_joint, int foot_body) {
  const int root_body = m->jnt_bodyid[root_joint];
  std::vector<int> bodies;
  int b = foot_body;
  for (; b > 0 && b != root_body; b = m->body_parentid[b]) bodies.push_back(b);
  if (b != root_body) return {};
  bodies.push_back(root_body);
  std::reverse(bodies.begin(), bodies.end());
  std::vector<int> joints;
  for (int body : bodies) {
    for (int j = m->body_jntadr[body]; j >= 0 && j < m->body_jntadr[body] + m->body_jntnum[body]; ++j) {
      if (body != root_body || j >= root_joint) joints.push_back(j);
    }
  }
  return joints;
}

std::vector<int> joints_below(const mjModel* m, int root_joint) {
  const int root_body = m->jnt_bodyid[root_joint];
  std::vector<int> joints;
  for (int j = 0; j < m->njnt; ++j) {
    const int body = m->jnt_bodyid[j];
    if (body == root_body ? j >= root_joint : (body != root_body && is_in_subtree(m, body, root_body))) {
      joints.push_back(j);
    }
  }
  return joints;
}

std::vector<ModelProblem> check_model_map(const mjModel* m, const ModelMap& map, double margin) {
  Problems p;
  // The floating base.
  if (m->njnt < 1 || m->jnt_type[0] != mjJNT_FREE || m->jnt_bodyid[0] != 1) {
    p.add("", "the first body of <worldbody> must be the robot's root with a free joint (<freejoint/>)");
  }
  const int root = p.require(m, mjOBJ_BODY, map.root_body, "model_map.root_body", "body");
  if (root >= 0 && m->njnt > 0 && m->jnt_type[0] == mjJNT_FREE && m->jnt_bodyid[0] != root) {
    p.add("model_map.root_body", "body '" + map.root_body + "' is not the one with the free joint ('" +
                                     object_name(m, mjOBJ_BODY, m->jnt_bodyid[0]) + "' is)");
  }
  for (int g = 0; g < m->ngeom; ++g) {
    if (m->geom_bodyid[g] == 0) {
      p.add("", "geom '" + object_name(m, mjOBJ_GEOM, g) +
                    "' is fixed to the world: the model must not bring its own ground (the simulator adds it)");
    }
  }

  // Joints: hinges with ranges, drives, torque limits.
  const std::set<std::string> passive(map.passive_joints.begin(), map.passive_joints.end());
  for (const std::string& name : map.passive_joints) {
    const int j = mj_name2id(m, mjOBJ_JOINT, name.c_str());
    if (j < 0) p.add("model_map.passive_joints", "the model has no joint named '" + name + "'");
  }
  const std::set<std::string> locked(map.locked_joints.begin(), map.locked_joints.end());
  for (const std::string& name : map.locked_joints) {
    if (mj_name2id(m, mjOBJ_JOINT, name.c_str()) < 0) {
      p.add("model_map.locked_joints", "the model has no joint named '" + name + "'");
    } else if (passive.count(name)) {
      p.add("model_map.locked_joints", "joint '" + name + "' is passive: a locked joint is driven and held at the "
                                       "standing pose");
    }
  }
  for (const auto& [name, limit] : map.torque_limits) {
    if (mj_name2id(m, mjOBJ_JOINT, name.c_str()) < 0) {
      p.add("model_map.torque_limits." + name, "the model has no joint named '" + name + "'");
    }
  }
  for (int j = 1; j < m->njnt; ++j) {
    const std::string name = object_name(m, mjOBJ_JOINT, j);
    if (m->jnt_type[j] != mjJNT_HINGE) {
      p.add("", "joint '" + name + "' is not a hinge: only the root may have a free joint, every other joint is a hinge");
      continue;
    }
    if (!m->jnt_limited[j]) {
      p.add("", "joint '" + name + "' has no range (limited=\"true\" range=\"min max\")");
    } else if (m->jnt_range[2 * j + 1] - m->jnt_range[2 * j] <= 2.0 * margin) {
      p.add("", "joint '" + name + "': its range [" + degrees(m->jnt_range[2 * j]) + ", " +
                    degrees(m->jnt_range[2 * j + 1]) + "] is not wider than twice the software limit margin " +
                    degrees(margin) + " (controller.software_limit_margin_deg)");
    }
    int count = 0;
    const int a = actuator_of(m, j, &count);
    if (passive.count(name)) {
      if (a >= 0 && !coupled_by_equality(m, j)) {
        p.add("model_map.passive_joints", "joint '" + name + "' has the actuator '" + object_name(m, mjOBJ_ACTUATOR, a) +
                                              "' and no equality constraint couples it: drive it (leave it out "
                                              "here) or remove its actuator");
      }
      continue;
    }
    if (a < 0) {
      p.add("", "joint '" + name + "' has no actuator: add <motor joint=\"" + name +
                    "\"/>, or list it in model_map.passive_joints if nothing drives it");
      continue;
    }
    const std::string actuator = object_name(m, mjOBJ_ACTUATOR, a);
    if (count > 1) p.add("", "joint '" + name + "' has " + std::to_string(count) + " actuators; give it one");
    if (!is_torque_motor(m, a)) {
      p.add("", "actuator '" + actuator + "' on joint '" + name +
                    "' is not a torque motor (<motor>, gain 1, no bias): the simulator's drives write torques");
    }
    if (!m->actuator_ctrllimited[a] && !map.torque_limits.count(name)) {
      p.add("model_map.torque_limits", "joint '" + name + "' has no torque limit: its actuator '" + actuator +
                                           "' has no ctrlrange; give the drive's peak torque here [N·m]");
    }
  }

  // The upper body and the IMU.
  const int upper_body = p.require(m, mjOBJ_BODY, map.upper_body, "model_map.upper_body", "body");
  const int imu = p.require(m, mjOBJ_SITE, map.imu_site, "model_map.imu.site", "site");
  if (imu >= 0 && upper_body >= 0 && m->site_bodyid[imu] != upper_body) {
    p.add("model_map.imu.site", "site '" + map.imu_site + "' is in body '" + object_name(m, mjOBJ_BODY, m->site_bodyid[imu]) +
                                    "', not in the upper body '" + map.upper_body + "'");
  }
  require_sensor(m, p, map.imu_gyro, "model_map.imu.gyro", mjSENS_GYRO, "gyro", imu);
  require_sensor(m, p, map.imu_accelerometer, "model_map.imu.accelerometer", mjSENS_ACCELEROMETER, "accelerometer", imu);
  if (!map.imu_orientation.empty()) {
    require_sensor(m, p, map.imu_orientation, "model_map.imu.orientation", mjSENS_FRAMEQUAT, "framequat", imu);
  }

  // The legs, their feet, F/T sensors and soles.
  std::array<int, 2> foot{-1, -1}, ft_site{-1, -1}, leg_root{-1, -1}, toe{-1, -1};
  std::array<std::vector<int>, 2> chain;
  for (Side side : kSides) {
    const int k = index_of(side);
    const LegMap& leg = map.legs[k];
    const std::string at = std::string("model_map.legs.") + name_of(side) + ".";
    foot[k] = p.require(m, mjOBJ_BODY, leg.foot_body, at + "foot_body", "body");
    ft_site[k] = p.require(m, mjOBJ_SITE, leg.ft_site, at + "ft_site", "site");
    if (ft_site[k] >= 0 && foot[k] >= 0 && m->site_bodyid[ft_site[k]] != foot[k]) {
      p.add(at + "ft_site", "site '" + leg.ft_site + "' is in body '" + object_name(m, mjOBJ_BODY, m->site_bodyid[ft_site[k]]) +
                                "', not in the foot body '" + leg.foot_body + "'");
    }
    require_sensor(m, p, leg.ft_force, at + "ft_force", mjSENS_FORCE, "force", ft_site[k]);
    require_sensor(m, p, leg.ft_torque, at + "ft_torque", mjSENS_TORQUE, "torque", ft_site[k]);
    leg_root[k] = p.require(m, mjOBJ_JOINT, leg.root_joint, at + "root_joint", "joint");
    if (leg_root[k] >= 0 && m->jnt_type[leg_root[k]] != mjJNT_HINGE) {
      p.add(at + "root_joint", "joint '" + leg.root_joint + "' is not a hinge");
      leg_root[k] = -1;
    }
    // The default toe joint (models/README.md) is used where the model has it; a named one must exist.
    const bool default_toe = leg.toe_joint == ModelMap{}.legs[k].toe_joint;
    toe[k] = leg.toe_joint.empty() ? -1 : mj_name2id(m, mjOBJ_JOINT, leg.toe_joint.c_str());
    if (!leg.toe_joint.empty() && toe[k] < 0 && !default_toe) {
      p.add(at + "toe_joint", "the model has no joint named '" + leg.toe_joint + "' (none: the foot has no toe joint)");
    }
    if (toe[k] >= 0 && foot[k] >= 0 && (m->jnt_bodyid[toe[k]] == foot[k] || !is_in_subtree(m, m->jnt_bodyid[toe[k]], foot[k]))) {
      p.add(at + "toe_joint", "joint '" + leg.toe_joint + "' is not below the foot body '" + leg.foot_body + "'");
    }
    if (!leg.sole && foot[k] >= 0) {
      std::vector<int> bodies;
      for (int g = 0; g < m->ngeom; ++g) {
        const std::string geom = object_name(m, mjOBJ_GEOM, g);
        if (!ends_with(geom, map.sole_suffix) || !is_in_subtree(m, m->geom_bodyid[g], foot[k])) continue;
        if (m->geom_type[g] != mjGEOM_BOX) p.add("", "sole geom '" + geom + "' must be a box");
        if (std::find(bodies.begin(), bodies.end(), m->geom_bodyid[g]) == bodies.end()) bodies.push_back(m->geom_bodyid[g]);
      }
      if (bodies.empty()) {
        p.add(at + "sole", "no box geom named '*" + map.sole_suffix + "' below the F/T sensor and no sole rectangle " +
                               "given here ({x: [min, max], y: [min, max], z} in the sensor frame)");
      } else if (std::find(bodies.begin(), bodies.end(), foot[k]) == bodies.end()) {
        p.add("", "the " + std::string(name_of(side)) + " foot has no sole geom on its body '" + leg.foot_body + "'");
      }
      for (int body : bodies) {
        if (body != foot[k] && (bodies.size() > 2 || m->body_parentid[body] != foot[k] || m->body_jntnum[body] != 1)) {
          p.add("", "sole geoms on body '" + object_name(m, mjOBJ_BODY, body) + "': a sole is the foot body's geoms and at "
                    "most one toe body hinged to it");
        }
      }
    }
    if (leg_root[k] < 0 || foot[k] < 0) continue;
    chain[k] = leg_chain(m, leg_root[k], foot[k]);
    if (chain[k].empty()) {
      p.add(at + "root_joint", "joint '" + leg.root_joint + "' is not above the foot: body '" + leg.foot_body +
                                   "' is not below its body '" + object_name(m, mjOBJ_BODY, m->jnt_bodyid[leg_root[k]]) + "'");
      continue;
    }
    int driven = 0;
    for (int j : chain[k]) {
      const std::string joint = object_name(m, mjOBJ_JOINT, j);
      if (passive.count(joint)) {
        p.add("model_map.passive_joints", "joint '" + joint + "' is in the " + name_of(side) + " leg: every leg joint needs a drive");
      } else if (locked.count(joint)) {
        p.add("model_map.locked_joints", "joint '" + joint + "' is in the " + name_of(side) + " leg: the leg needs every joint");
      } else if (m->jnt_type[j] == mjJNT_HINGE) {
        ++driven;
      }
    }
    if (driven < 6) {
      p.add(at + "root_joint", "the " + std::string(name_of(side)) + " leg has " + std::to_string(driven) +
                                   " driven joints (" + joint_list(m, chain[k]) + "): a leg needs at least 6");
    }
  }
  for (Side side : kSides) {
    const int k = index_of(side), other = 1 - k;
    if (leg_root[k] < 0 || chain[k].empty()) continue;
    const int body = m->jnt_bodyid[leg_root[k]];
    const std::string at = std::string("model_map.legs.") + name_of(side) + ".root_joint";
    if (foot[other] >= 0 && is_in_subtree(m, foot[other], body)) {
      p.add(at, "the leg below joint '" + map.legs[k].root_joint + "' also holds the " + name_of(side == Side::Left ? Side::Right : Side::Left) +
                    " foot: name the first joint below the branching of the legs");
    } else if (upper_body >= 0 && is_in_subtree(m, upper_body, body)) {
      p.add(at, "the leg below joint '" + map.legs[k].root_joint + "' holds the upper body '" + map.upper_body + "'");
    }
  }
  if (foot[0] >= 0 && foot[0] == foot[1]) p.add("model_map.legs.right.foot_body", "the same body as the left foot's");
  if (ft_site[0] >= 0 && ft_site[0] == ft_site[1]) p.add("model_map.legs.right.ft_site", "the same site as the left foot's");

  // The arms.
  std::array<int, 2> arm{-1, -1};
  for (Side side : kSides) {
    const int k = index_of(side);
    const std::string key = std::string("model_map.arms.") + name_of(side);
    arm[k] = p.require(m, mjOBJ_JOINT, map.legs[k].arm_root_joint, key, "joint");
    if (arm[k] < 0) continue;
    const int body = m->jnt_bodyid[arm[k]];
    for (int f : foot) {
      if (f >= 0 && is_in_subtree(m, f, body)) {
        p.add(key, "joint '" + map.legs[k].arm_root_joint + "' carries a foot: an arm's first joint holds the arm only");
        break;
      }
    }
  }
  if (arm[0] >= 0 && arm[1] >= 0) {
    const std::vector<int> left = joints_below(m, arm[0]);
    if (arm[0] == arm[1] || std::find(left.begin(), left.end(), arm[1]) != left.end() ||
        is_in_subtree(m, m->jnt_bodyid[arm[0]], m->jnt_bodyid[arm[1]])) {
      p.add("model_map.arms.right", "joint '" + map.legs[1].arm_root_joint + "' is not apart from the left arm's '" +
                                        map.legs[0].arm_root_joint + "'");
    }
  }
  if ((toe[0] >= 0) != (toe[1] >= 0)) p.add("model_map.legs.right.toe_joint", "toe joints: on both legs or on neither");

  check_stand_pose(m, map, margin, p);
  return p.take();
}

std::vector<ModelProblem> check_robot_geometry(const RobotModel& model, double max_sole_tilt_rad,
                                               double max_sole_height_difference) {
  Problems p;
  const mjModel* m = model.mj();
  const ModelMap& map = model.map();
  for (Side side : kSides) {
    const FootInfo& foot = model.foot(side);
    const bool given = map.legs[index_of(side)].sole.has_value();
    const std::string key = given ? std::string("model_map.legs.") + name_of(side) + ".sole" : "";
    const std::string what = given ? "the sole" : "the " + std::string(name_of(side)) + " foot's sole geoms";
    for (int s = 0; s < foot.num_segments; ++s) {
      if (foot.segments[s].z >= 0.0) {
        p.add(key, what + " must lie below the F/T sensor '" + map.legs[index_of(side)].ft_site +
                       "' (z < 0 in its frame): z = " + fixed(foot.segments[s].z, 4) + " m");
      }
    }
    if (!(foot.sole_x_min < 0.0 && foot.sole_x_max > 0.0 && foot.sole_y_min < 0.0 && foot.sole_y_max > 0.0)) {
      p.add(key, what + " must surround the point below the F/T sensor '" + map.legs[index_of(side)].ft_site +
                     "' (x = y = 0 in its frame): x [" + fixed(foot.sole_x_min, 3) + ", " + fixed(foot.sole_x_max, 3) +
                     "] m, y [" + fixed(foot.sole_y_min, 3) + ", " + fixed(foot.sole_y_max, 3) + "] m");
    }
  }

  RobotData data(model);
  data.qpos() = model.stand_qpos();
  mj_kinematics(m, data.mj());
  const std::string key = map.stand_pose.empty() ? "model_map.stand_keyframe" : "model_map.stand_pose_deg";
  std::array<double, 2> height{};
  for (Side side : kSides) {
    const FootInfo& foot = model.foot(side);
    const Eigen::Matrix3d r = data.site_rotation(foot.sensor_site);
    height[index_of(side)] = (data.site_position(foot.sensor_site) + r * Eigen::Vector3d(0, 0, foot.sole_z)).z();
    const double roll = std::atan2(r(2, 1), r(2, 2)), pitch = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
    if (std::abs(roll) > max_sole_tilt_rad || std::abs(pitch) > max_sole_tilt_rad) {
      p.add(key, "the standing pose tilts the " + std::string(name_of(side)) + " sole by roll " + degrees(roll) +
                     ", pitch " + degrees(pitch) + " (level within " + degrees(max_sole_tilt_rad) + ")");
    }
  }
  if (std::abs(height[0] - height[1]) > max_sole_height_difference) {
    p.add(key, "the standing pose puts the left sole " + fixed(1e3 * std::abs(height[0] - height[1]), 1) + " mm " +
                   (height[0] > height[1] ? "above" : "below") + " the right one");
  }
  return p.take();
}

RobotDescription describe_robot(const RobotModel& model) {
  const mjModel* m = model.mj();
  RobotDescription d;
  d.name = model.name();
  d.mass = model.total_mass();
  d.nq = m->nq;
  d.nv = m->nv;
  for (const JointInfo& j : model.joints()) {
    (j.passive ? d.passive : d.actuated) += 1;
    d.locked += j.locked;
  }
  d.imu_site = model.map().imu_site;
  d.upper_body = model.map().upper_body;

  RobotData stand(model), stretched(model);
  stand.qpos() = model.stand_qpos();
  stretched.qpos() = model.stand_qpos();
  for (const JointInfo& j : model.joints()) stretched.qpos()[j.qpos_adr] = 0.0;
  for (RobotData* data : {&stand, &stretched}) {
    mj_kinematics(m, data->mj());
    mj_comPos(m, data->mj());
  }
  double sole_height = 0.0;
  for (Side side : kSides) {
    const int k = index_of(side);
    const FootInfo& foot = model.foot(side);
    const LegMap& leg = model.map().legs[k];
    d.ft_sites[k] = leg.ft_site;
    d.foot_bodies[k] = leg.foot_body;
    d.toe_joints[k] = model.toe_joint(side) >= 0 ? model.joints()[model.toe_joint(side)].name : "";
    d.sole_length[k] = foot.sole_x_max - foot.sole_x_min;
    d.sole_width[k] = foot.sole_y_max - foot.sole_y_min;
    const std::vector<int> chain = leg_chain(m, model.joints()[model.leg_root_joint(side)].mj_joint, foot.body);
    for (int j : chain) d.leg_joints[k].push_back(object_name(m, mjOBJ_JOINT, j));
    if (!chain.empty()) {
      const auto length = [&](const RobotData& data) {
        return (Eigen::Vector3d(data.mj()->xanchor + 3 * chain.front()) - Eigen::Vector3d(data.mj()->xanchor + 3 * chain.back())).norm();
      };
      d.leg_length_stand[k] = length(stand);
      d.leg_length_stretched[k] = length(stretched);
    }
    for (int j : joints_below(m, model.joints()[model.arm_root_joint(side)].mj_joint)) {
      const int i = model.joint_index(object_name(m, mjOBJ_JOINT, j));
      if (i >= 0 && !model.joints()[i].passive && !model.joints()[i].locked) ++d.arm_dof[k];
    }
    const Eigen::Matrix3d r = stand.site_rotation(foot.sensor_site);
    sole_height += 0.5 * (stand.site_position(foot.sensor_site) + r * Eigen::Vector3d(0, 0, foot.sole_z)).z();
  }
  d.com_height_stand = stand.subtree_com(model.pelvis_body()).z() - sole_height;
  return d;
}

}  // namespace biped
