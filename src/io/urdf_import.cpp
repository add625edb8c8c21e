#include "io/urdf_import.hpp"

#include <mujoco/mujoco.h>
#include <tinyxml2.h>
#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>

#include "io/output_files.hpp"
#include "io/yaml_reader.hpp"

namespace fs = std::filesystem;

namespace biped {
namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kGuessMargin = 5.0 * kDeg;  // the default software-limit margin

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
using ModelPtr = std::unique_ptr<mjModel, ModelDeleter>;
using DataPtr = std::unique_ptr<mjData, DataDeleter>;

// Compiles XML text as if it were the file `as_path` (its relative paths resolve from there).
ModelPtr compile(const std::string& text, const std::string& as_path, std::string& error_text) {
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  if (mj_makeEmptyFileVFS(vfs.get(), as_path.c_str(), static_cast<int>(text.size())) != 0) {
    error_text = "cannot create the in-memory file";
    return nullptr;
  }
  std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), as_path.c_str())], text.data(), text.size());
  char error[1000] = "";
  ModelPtr m(mj_loadXML(as_path.c_str(), vfs.get(), error, sizeof(error)));
  mj_deleteVFS(vfs.get());
  error_text = error;
  std::replace(error_text.begin(), error_text.end(), '\n', ' ');
  return m;
}

std::string to_text(const tinyxml2::XMLDocument& doc) {
  tinyxml2::XMLPrinter printer;
  doc.Print(&printer);
  return printer.CStr();
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string body_name(const mjModel* m, int b) {
  const char* n = mj_id2name(m, mjOBJ_BODY, b);
  return n ? n : "";
}

std::string joint_name(const mjModel* m, int j) {
  const char* n = mj_id2name(m, mjOBJ_JOINT, j);
  return n ? n : "";
}

double round_to(double value, double step) { return std::round(value / step) * step; }

// What the structure of the compiled URDF suggests, with every joint at zero.
class ModelGuess {
 public:
  explicit ModelGuess(const mjModel* m) : m_(m), d_(mj_makeData(m)) {
    mj_kinematics(m_, d_.get());
    for (int b = 1; b < m_->nbody; ++b) {
      if (m_->body_parentid[b] == 0) top_.push_back(b);
    }
  }
  const std::vector<int>& top_bodies() const { return top_; }

  // Points on the surface of a geom's shape (corners, mesh vertices, extreme points), in the world.
  std::vector<Eigen::Vector3d> geom_points(int g) const {
    const Eigen::Vector3d c(d_->geom_xpos + 3 * g);
    const Eigen::Matrix3d r = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(d_->geom_xmat + 9 * g);
    const double* s = m_->geom_size + 3 * g;
    std::vector<Eigen::Vector3d> points;
    auto ends = [&](double radius, double half, int around) {
      for (double z : {-half, half}) {
        for (int k = 0; k < around; ++k) {
          const double a = 2.0 * M_PI * k / around;
          points.push_back(c + r * Eigen::Vector3d(radius * std::cos(a), radius * std::sin(a), z));
        }
      }
    };
    switch (m_->geom_type[g]) {
      case mjGEOM_BOX:
      case mjGEOM_ELLIPSOID:
        for (int k = 0; k < 8; ++k) {
          points.push_back(c + r * Eigen::Vector3d((k & 1 ? 1 : -1) * s[0], (k & 2 ? 1 : -1) * s[1], (k & 4 ? 1 : -1) * s[2]));
        }
        break;
      case mjGEOM_MESH: {
        const int mesh = m_->geom_dataid[g];
        const float* v = m_->mesh_vert + 3 * m_->mesh_vertadr[mesh];
        for (int k = 0; k < m_->mesh_vertnum[mesh]; ++k) {
          points.push_back(c + r * Eigen::Vector3d(v[3 * k], v[3 * k + 1], v[3 * k + 2]));
        }
        break;
      }
      case mjGEOM_CYLINDER:
        ends(s[0], s[1], 16);
        break;
      case mjGEOM_CAPSULE:
        ends(s[0], s[1], 16);
        for (double z : {-1.0, 1.0}) points.push_back(c + r * Eigen::Vector3d(0, 0, z * (s[1] + s[0])));
        break;
      case mjGEOM_SPHERE:
        for (int axis = 0; axis < 3; ++axis) {
          for (double sign : {-1.0, 1.0}) points.push_back(c + sign * s[0] * Eigen::Vector3d::Unit(axis));
        }
        break;
      default:
        break;
    }
    return points;
  }

  bool collides(int g) const { return m_->geom_contype[g] != 0 || m_->geom_conaffinity[g] != 0; }

  // Lowest point of a body's own colliding geoms (+inf without).
  double lowest(int b) const {
    double z = INFINITY;
    for (int g = 0; g < m_->ngeom; ++g) {
      if (m_->geom_bodyid[g] != b || !collides(g)) continue;
      for (const Eigen::Vector3d& p : geom_points(g)) z = std::min(z, p.z());
    }
    return z;
  }

  bool in_subtree(int b, int root) const {
    for (; b > 0; b = m_->body_parentid[b]) {
      if (b == root) return true;
    }
    return false;
  }
  int depth(int b) const {
    int n = 0;
    for (; b > 0; b = m_->body_parentid[b]) ++n;
    return n;
  }
  // The body itself or its nearest ancestor that moves on a joint of its own (not past the root).
  int jointed(int b) const {
    while (b > 1 && m_->body_jntnum[b] == 0) b = m_->body_parentid[b];
    return b;
  }
  Eigen::Vector3d position(int b) const { return Eigen::Vector3d(d_->xpos + 3 * b); }
  Eigen::Matrix3d rotation(int b) const {
    return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(d_->xmat + 9 * b);
  }

 private:
  const mjModel* m_;
  DataPtr d_;
  std::vector<int> top_;
};

struct LegGuess {
  int foot = -1;       // body
  int toe_joint = -1;  // joint, -1 without
  int root_joint = -1;
  double sole_x[2] = {0, 0}, sole_y[2] = {0, 0}, sole_z = 0;
};

struct Guess {
  std::array<LegGuess, 2> legs;
  std::array<int, 2> arms{-1, -1};  // root joints
  int imu_body = -1;
  Eigen::Vector3d imu_pos = Eigen::Vector3d::Zero();
  Eigen::Quaterniond imu_quat = Eigen::Quaterniond::Identity();
  std::map<std::string, double> stand_pose;  // [deg]
};

Guess guess_parts(const mjModel* m, const ModelGuess& g) {
  Guess guess;
  // Feet: the lowest bodies on each side (y > 0: left), up to the nearest one that moves on a joint;
  // a lowest body named "toe" is a toe segment hinged to the foot.
  double lowest = INFINITY;
  for (int b = 1; b < m->nbody; ++b) lowest = std::min(lowest, g.lowest(b));
  for (int k = 0; k < 2; ++k) {
    int best = -1;
    for (int b = 1; b < m->nbody; ++b) {
      const bool side = k == 0 ? g.position(b).y() > 0.0 : g.position(b).y() < 0.0;
      if (!side || g.lowest(b) > lowest + 0.01) continue;
      if (best < 0 || g.depth(b) < g.depth(best)) best = b;
    }
    if (best < 0) continue;
    int foot = g.jointed(best);
    if (lower(body_name(m, foot)).find("toe") != std::string::npos && foot > 1) {
      guess.legs[k].toe_joint = m->body_jntadr[foot];
      foot = g.jointed(m->body_parentid[foot]);
    }
    guess.legs[k].foot = foot;
  }
  // Leg roots: the first jointed body below the bodies both feet hang from.
  const int left = guess.legs[0].foot, right = guess.legs[1].foot;
  if (left > 1 && right > 1 && left != right) {
    for (int k = 0; k < 2; ++k) {
      std::vector<int> path;  // foot up to (not including) the common ancestor
      const int other = guess.legs[1 - k].foot;
      for (int b = guess.legs[k].foot; b > 0 && !g.in_subtree(other, b); b = m->body_parentid[b]) path.push_back(b);
      for (auto it = path.rbegin(); it != path.rend(); ++it) {
        if (m->body_jntnum[*it] > 0) {
          guess.legs[k].root_joint = m->body_jntadr[*it];
          break;
        }
      }
    }
  }
  // Soles: the lowest points of the foot's colliding geoms, in the foot body's frame (where the F/T
  // site is added); the sole plane within 5 mm of the lowest point.
  for (LegGuess& leg : guess.legs) {
    if (leg.foot < 0) continue;
    std::vector<Eigen::Vector3d> points;
    for (int geom = 0; geom < m->ngeom; ++geom) {
      if (!g.collides(geom) || !g.in_subtree(m->geom_bodyid[geom], leg.foot)) continue;
      for (const Eigen::Vector3d& p : g.geom_points(geom)) {
        points.push_back(g.rotation(leg.foot).transpose() * (p - g.position(leg.foot)));
      }
    }
    if (points.empty()) continue;
    double z = INFINITY;
    for (const Eigen::Vector3d& p : points) z = std::min(z, p.z());
    leg.sole_x[0] = leg.sole_y[0] = INFINITY;
    leg.sole_x[1] = leg.sole_y[1] = -INFINITY;
    for (const Eigen::Vector3d& p : points) {
      if (p.z() > z + 0.005) continue;
      leg.sole_x[0] = std::min(leg.sole_x[0], p.x());
      leg.sole_x[1] = std::max(leg.sole_x[1], p.x());
      leg.sole_y[0] = std::min(leg.sole_y[0], p.y());
      leg.sole_y[1] = std::max(leg.sole_y[1], p.y());
    }
    leg.sole_z = z;
  }
  // Arms: the shoulder joint nearest the root on each side, away from the legs; else the first
  // joint of a body named arm, hand, elbow or wrist.
  auto in_leg = [&](int b) {
    for (const LegGuess& leg : guess.legs) {
      if (leg.root_joint >= 0 && g.in_subtree(b, m->jnt_bodyid[leg.root_joint])) return true;
    }
    return false;
  };
  static const std::vector<std::vector<std::string>> kArmWords = {{"shoulder"}, {"arm", "hand", "elbow", "wrist"}};
  for (int k = 0; k < 2; ++k) {
    for (const std::vector<std::string>& words : kArmWords) {
      int best = -1;
      for (int j = 0; j < m->njnt; ++j) {
        const int b = m->jnt_bodyid[j];
        const bool side = k == 0 ? g.position(b).y() > 0.0 : g.position(b).y() < 0.0;
        if (!side || in_leg(b) || m->jnt_type[j] != mjJNT_HINGE) continue;
        const std::string name = lower(joint_name(m, j)) + " " + lower(body_name(m, b));
        bool named = false;
        for (const std::string& w : words) named = named || name.find(w) != std::string::npos;
        if (named && (best < 0 || g.depth(b) < g.depth(m->jnt_bodyid[best]))) best = j;
      }
      if (best >= 0) {
        guess.arms[k] = best;
        break;
      }
    }
  }
  // The IMU: at a body named imu (in the body it is welded to), else at the root body's origin.
  guess.imu_body = 1;
  for (int b = 1; b < m->nbody; ++b) {
    if (lower(body_name(m, b)).find("imu") == std::string::npos) continue;
    guess.imu_body = g.jointed(b);
    const Eigen::Matrix3d r = g.rotation(guess.imu_body);
    guess.imu_pos = r.transpose() * (g.position(b) - g.position(guess.imu_body));
    guess.imu_quat = Eigen::Quaterniond(r.transpose() * g.rotation(b));
    break;
  }
  // A standing pose: knees bent 40° the way their range allows, hip and ankle pitch half of it the
  // other way (pitch axes alike, as in most models); joints whose zero lies outside their software
  // limits 5° inside them.
  std::array<double, 2> knee_sign{0.0, 0.0};
  for (int j = 0; j < m->njnt; ++j) {
    if (m->jnt_type[j] != mjJNT_HINGE || !m->jnt_limited[j]) continue;
    if (lower(joint_name(m, j)).find("knee") == std::string::npos) continue;
    for (int k = 0; k < 2; ++k) {
      if (guess.legs[k].root_joint >= 0 && g.in_subtree(m->jnt_bodyid[j], m->jnt_bodyid[guess.legs[k].root_joint])) {
        knee_sign[k] = m->jnt_range[2 * j + 1] >= -m->jnt_range[2 * j] ? 1.0 : -1.0;
        guess.stand_pose[joint_name(m, j)] = 40.0 * knee_sign[k];
      }
    }
  }
  for (int j = 0; j < m->njnt; ++j) {
    if (m->jnt_type[j] != mjJNT_HINGE || !m->jnt_limited[j]) continue;
    const std::string name = lower(joint_name(m, j));
    const bool pitch = name.find("pitch") != std::string::npos || (name.size() > 2 && name.substr(name.size() - 2) == "_p");
    for (int k = 0; k < 2; ++k) {
      if (knee_sign[k] == 0.0 || !g.in_subtree(m->jnt_bodyid[j], m->jnt_bodyid[guess.legs[k].root_joint])) continue;
      if (pitch && (name.find("hip") != std::string::npos || name.find("ankle") != std::string::npos)) {
        guess.stand_pose[joint_name(m, j)] = -20.0 * knee_sign[k];
      }
    }
    const double lo = m->jnt_range[2 * j] + kGuessMargin, hi = m->jnt_range[2 * j + 1] - kGuessMargin;
    const auto it = guess.stand_pose.find(joint_name(m, j));
    const double q = (it != guess.stand_pose.end() ? it->second : 0.0) * kDeg;
    if (lo < hi && (q < lo || q > hi)) {  // 5° inside (a joint held at its limit stops the walking controller)
      const double inside = std::min(5.0 * kDeg, 0.5 * (hi - lo));
      guess.stand_pose[joint_name(m, j)] = q < lo ? std::ceil((lo + inside) / kDeg) : std::floor((hi - inside) / kDeg);
    }
  }
  return guess;
}

tinyxml2::XMLElement* find_body(tinyxml2::XMLElement* parent, const std::string& name) {
  for (tinyxml2::XMLElement* b = parent->FirstChildElement("body"); b; b = b->NextSiblingElement("body")) {
    if (const char* n = b->Attribute("name"); n && name == n) return b;
    if (tinyxml2::XMLElement* found = find_body(b, name)) return found;
  }
  return nullptr;
}

std::string vector_text(const Eigen::Vector3d& v) {
  std::ostringstream s;
  s << round_to(v.x(), 1e-6) << ' ' << round_to(v.y(), 1e-6) << ' ' << round_to(v.z(), 1e-6);
  return s.str();
}

void add_site(tinyxml2::XMLDocument& doc, tinyxml2::XMLElement* body, const std::string& name, const Eigen::Vector3d& pos,
              const Eigen::Quaterniond& quat) {
  tinyxml2::XMLElement* site = doc.NewElement("site");
  site->SetAttribute("name", name.c_str());
  site->SetAttribute("pos", vector_text(pos).c_str());
  if (!quat.isApprox(Eigen::Quaterniond::Identity(), 1e-9)) {
    std::ostringstream q;
    q << quat.w() << ' ' << quat.x() << ' ' << quat.y() << ' ' << quat.z();
    site->SetAttribute("quat", q.str().c_str());
  }
  site->SetAttribute("size", "0.01");
  body->InsertEndChild(site);
}

void add_sensor(tinyxml2::XMLDocument& doc, tinyxml2::XMLElement* sensors, const char* type, const std::string& name,
                const std::string& site) {
  tinyxml2::XMLElement* s = doc.NewElement(type);
  s->SetAttribute("name", name.c_str());
  if (std::strcmp(type, "framequat") == 0) {
    s->SetAttribute("objtype", "site");
    s->SetAttribute("objname", site.c_str());
  } else {
    s->SetAttribute("site", site.c_str());
  }
  sensors->InsertEndChild(s);
}

const char* kSideNames[2] = {"left", "right"};

[[noreturn]] void fail(const std::string& urdf_path, const std::string& what) {
  throw InputError(urdf_path + ": " + what);
}

}  // namespace

UrdfImport import_urdf(const std::string& urdf_path, const std::string& mjcf_path, const UrdfImportOptions& options) {
  UrdfImport result;

  // The URDF: its effort limits (MuJoCo does not read them), and MuJoCo's extension block keeping
  // fixed links as bodies (so that the root link is a body that can float).
  tinyxml2::XMLDocument urdf;
  if (urdf.LoadFile(urdf_path.c_str()) != tinyxml2::XML_SUCCESS) fail(urdf_path, std::string("cannot read the URDF: ") + urdf.ErrorStr());
  tinyxml2::XMLElement* robot = urdf.FirstChildElement("robot");
  if (!robot) fail(urdf_path, "not a URDF file (no <robot> element)");
  std::map<std::string, double> effort;
  std::vector<std::string> continuous, mimic;
  for (tinyxml2::XMLElement* j = robot->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint")) {
    const char* name = j->Attribute("name");
    const char* type = j->Attribute("type");
    if (!name || !type) continue;
    if (std::strcmp(type, "continuous") == 0) continuous.push_back(name);
    if (j->FirstChildElement("mimic")) mimic.push_back(name);
    double e = 0.0;
    if (const tinyxml2::XMLElement* limit = j->FirstChildElement("limit");
        limit && limit->QueryDoubleAttribute("effort", &e) == tinyxml2::XML_SUCCESS && e > 0.0) {
      effort[name] = e;
    }
  }
  tinyxml2::XMLElement* block = robot->FirstChildElement("mujoco");
  if (!block) block = robot->InsertFirstChild(urdf.NewElement("mujoco"))->ToElement();
  tinyxml2::XMLElement* compiler = block->FirstChildElement("compiler");
  if (!compiler) compiler = block->InsertEndChild(urdf.NewElement("compiler"))->ToElement();
  if (!compiler->Attribute("fusestatic")) compiler->SetAttribute("fusestatic", "false");
  const fs::path urdf_dir = fs::absolute(urdf_path).parent_path();
  if (!options.meshdir.empty()) compiler->SetAttribute("meshdir", fs::absolute(options.meshdir).string().c_str());
  const fs::path meshdir = compiler->Attribute("meshdir") ? (urdf_dir / compiler->Attribute("meshdir")).lexically_normal()
                                                          : urdf_dir;

  std::string error;
  ModelPtr m = compile(to_text(urdf), (urdf_dir / (fs::path(urdf_path).stem().string() + ".import.urdf")).string(), error);
  if (!m) fail(urdf_path, "MuJoCo cannot compile it: " + error + (error.find("file") != std::string::npos ? " (meshes: --meshdir)" : ""));
  const ModelGuess geometry(m.get());
  if (geometry.top_bodies().size() != 1) {
    fail(urdf_path, "MuJoCo's compiler gives " + std::to_string(geometry.top_bodies().size()) +
         " bodies under the world, not one root link (fusestatic=\"true\" in the URDF's <mujoco> block merges the "
         "root link into the world)");
  }
  const int root = geometry.top_bodies().front();
  const bool has_free_joint = m->njnt > 0 && m->jnt_type[0] == mjJNT_FREE;
  const Guess guess = guess_parts(m.get(), geometry);

  // MuJoCo's MJCF of it, then what a URDF cannot say.
  const fs::path out = fs::absolute(mjcf_path);
  prepare_output_directory(out.parent_path().string());
  const fs::path saved = out.parent_path() / ("." + out.filename().string() + ".saved.xml");
  char save_error[1000] = "";
  if (!mj_saveLastXML(saved.c_str(), m.get(), save_error, sizeof(save_error))) {
    fail(urdf_path, std::string("MuJoCo cannot write it as MJCF: ") + save_error);
  }
  tinyxml2::XMLDocument mjcf;
  const bool loaded = mjcf.LoadFile(saved.c_str()) == tinyxml2::XML_SUCCESS;
  fs::remove(saved);
  if (!loaded) fail(urdf_path, "cannot read back MuJoCo's MJCF");
  tinyxml2::XMLElement* mujoco = mjcf.FirstChildElement("mujoco");
  tinyxml2::XMLElement* worldbody = mujoco->FirstChildElement("worldbody");
  tinyxml2::XMLElement* root_body = find_body(worldbody, body_name(m.get(), root));
  if (tinyxml2::XMLElement* c = mujoco->FirstChildElement("compiler"); c && m->nmesh > 0) {
    const fs::path relative = fs::relative(meshdir, out.parent_path());
    c->SetAttribute("meshdir", (relative.empty() ? "." : relative.string()).c_str());
  }
  const std::string root_name = body_name(m.get(), root);
  auto note = [&](const std::string& text) { result.notes.push_back(text); };
  int hinges = 0;
  double mass = 0.0;
  for (int j = 0; j < m->njnt; ++j) hinges += m->jnt_type[j] == mjJNT_HINGE;
  for (int b = 1; b < m->nbody; ++b) mass += m->body_mass[b];
  {
    std::ostringstream s;
    s << "carried: " << m->nbody - 1 << " links as bodies (fixed links kept), " << hinges << " hinge joints, "
      << round_to(mass, 0.01) << " kg, " << m->ngeom << " geoms, " << m->nmesh << " meshes";
    note(s.str());
  }
  if (!has_free_joint) {
    tinyxml2::XMLElement* free = mjcf.NewElement("freejoint");
    free->SetAttribute("name", "root");
    root_body->InsertFirstChild(free);
    note("added: a free joint 'root' on the root link '" + root_name + "' (a URDF robot is fixed to the world)");
  }
  // Raised so that the lowest sole touches the ground in the viewer (the simulator places it itself).
  const double lowest = std::min(guess.legs[0].foot >= 0 ? geometry.position(guess.legs[0].foot).z() + guess.legs[0].sole_z : 0.0,
                                 guess.legs[1].foot >= 0 ? geometry.position(guess.legs[1].foot).z() + guess.legs[1].sole_z : 0.0);
  root_body->SetAttribute("pos", vector_text(geometry.position(root) - Eigen::Vector3d(0, 0, lowest)).c_str());

  tinyxml2::XMLElement* actuators = mujoco->InsertEndChild(mjcf.NewElement("actuator"))->ToElement();
  std::vector<std::string> no_effort;
  for (int j = 0; j < m->njnt; ++j) {
    if (m->jnt_type[j] != mjJNT_HINGE) continue;
    const std::string name = joint_name(m.get(), j);
    tinyxml2::XMLElement* motor = mjcf.NewElement("motor");
    motor->SetAttribute("name", name.c_str());
    motor->SetAttribute("joint", name.c_str());
    if (const auto e = effort.find(name); e != effort.end()) {
      motor->SetAttribute("ctrllimited", "true");
      std::ostringstream range;
      range << -e->second << ' ' << e->second;
      motor->SetAttribute("ctrlrange", range.str().c_str());
    } else {
      no_effort.push_back(name);
    }
    actuators->InsertEndChild(motor);
  }
  note("added: a torque motor on each of the " + std::to_string(hinges) + " hinge joints, ctrlrange = the URDF's effort limit");
  auto list = [](const std::vector<std::string>& names) {
    std::string text;
    for (const std::string& n : names) text += (text.empty() ? "" : ", ") + n;
    return text;
  };
  if (!no_effort.empty()) note("not carried: no effort limit in the URDF for " + list(no_effort) + ": give model_map.torque_limits");
  if (!continuous.empty()) note("not carried: continuous joints have no range: " + list(continuous) + ": give each a range in the MJCF");
  if (!mimic.empty()) note("not carried: mimic joints " + list(mimic) + ": couple them with <equality><joint .../> and list them in model_map.passive_joints");

  tinyxml2::XMLElement* sensors = mujoco->InsertEndChild(mjcf.NewElement("sensor"))->ToElement();
  const std::string imu_body = body_name(m.get(), guess.imu_body);
  add_site(mjcf, find_body(worldbody, imu_body), "imu", guess.imu_pos, guess.imu_quat);
  add_sensor(mjcf, sensors, "framequat", "imu_quat", "imu");
  add_sensor(mjcf, sensors, "gyro", "imu_gyro", "imu");
  add_sensor(mjcf, sensors, "accelerometer", "imu_accel", "imu");
  note("added (a guess: move it where the robot's IMU is): site 'imu' in body '" + imu_body +
       "' with sensors imu_quat, imu_gyro, imu_accel");
  for (int k = 0; k < 2; ++k) {
    const std::string side = kSideNames[k];
    if (guess.legs[k].foot < 0) {
      note("not found: the " + side + " foot (no lowest body on that side): add site '" + side + "_ft' and its sensors yourself");
      continue;
    }
    const std::string foot = body_name(m.get(), guess.legs[k].foot);
    add_site(mjcf, find_body(worldbody, foot), side + "_ft", Eigen::Vector3d::Zero(), Eigen::Quaterniond::Identity());
    add_sensor(mjcf, sensors, "force", side + "_ft_force", side + "_ft");
    add_sensor(mjcf, sensors, "torque", side + "_ft_torque", side + "_ft");
    note("added (a guess: move it where the robot's F/T sensor is): site '" + side + "_ft' at the origin of body '" + foot +
         "' with sensors " + side + "_ft_force, " + side + "_ft_torque");
  }
  note("not in a URDF: rotor inertia (armature), joint friction and damping: add them (e.g. <default><joint armature=\"0.05\" "
       "damping=\"0.5\"/></default>) or the drives oscillate");
  note("not in a URDF: sites, sensors, actuators, keyframes; the robot file's model_map names the parts (guessed)");

  const std::string text = to_text(mjcf);
  if (!compile(text, out.string(), error)) fail(urdf_path, "the MJCF written does not compile: " + error);
  AtomicOutputFile file(out.string());
  file.stream() << "<!-- " << fs::path(urdf_path).filename().string()
                << " imported by `biped robot import` (MuJoCo 2.2.2's URDF compiler), with a free joint, motors, "
                   "an IMU and F/T sites and sensors added: docs/new-robot.md -->\n"
                << text;
  file.commit();

  // The skeleton robot file.
  const std::string model_path = options.robot_file.empty()
                                     ? out.string()
                                     : fs::relative(out, fs::absolute(options.robot_file).parent_path()).string();
  YAML::Emitter y;
  y.SetDoublePrecision(4);
  y << YAML::Comment("robot file made by `biped robot import` from " + fs::path(urdf_path).filename().string() +
                     ": every name below is a guess; check with `biped robot check` (docs/new-robot.md)");
  y << YAML::BeginMap << YAML::Key << "model" << YAML::Value << model_path;
  y << YAML::Key << "model_map" << YAML::Value << YAML::BeginMap;
  y << YAML::Key << "root_body" << YAML::Value << root_name;
  y << YAML::Key << "upper_body" << YAML::Value << imu_body << YAML::Comment("the body holding the IMU site");
  y << YAML::Key << "imu" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "site" << YAML::Value << "imu"
    << YAML::Key << "orientation" << YAML::Value << "imu_quat" << YAML::Key << "gyro" << YAML::Value << "imu_gyro"
    << YAML::Key << "accelerometer" << YAML::Value << "imu_accel" << YAML::EndMap;
  y << YAML::Key << "legs" << YAML::Value << YAML::BeginMap;
  for (int k = 0; k < 2; ++k) {
    const LegGuess& leg = guess.legs[k];
    const std::string side = kSideNames[k];
    auto or_fill = [&](int id, mjtObj type) { return id >= 0 ? std::string(mj_id2name(m.get(), type, id)) : "FILL_IN"; };
    y << YAML::Key << side << YAML::Value << YAML::Flow << YAML::BeginMap;
    y << YAML::Key << "root_joint" << YAML::Value << or_fill(leg.root_joint, mjOBJ_JOINT);
    y << YAML::Key << "toe_joint" << YAML::Value << (leg.toe_joint >= 0 ? joint_name(m.get(), leg.toe_joint) : "none");
    y << YAML::Key << "foot_body" << YAML::Value << or_fill(leg.foot, mjOBJ_BODY);
    y << YAML::Key << "ft_site" << YAML::Value << side + "_ft" << YAML::Key << "ft_force" << YAML::Value << side + "_ft_force"
      << YAML::Key << "ft_torque" << YAML::Value << side + "_ft_torque";
    if (leg.foot >= 0 && std::isfinite(leg.sole_x[0])) {
      y << YAML::Key << "sole" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "x" << YAML::Value
        << YAML::Flow << YAML::BeginSeq << round_to(leg.sole_x[0], 1e-3) << round_to(leg.sole_x[1], 1e-3) << YAML::EndSeq
        << YAML::Key << "y" << YAML::Value << YAML::Flow << YAML::BeginSeq << round_to(leg.sole_y[0], 1e-3)
        << round_to(leg.sole_y[1], 1e-3) << YAML::EndSeq << YAML::Key << "z" << YAML::Value << round_to(leg.sole_z, 1e-4)
        << YAML::EndMap;
    }
    y << YAML::EndMap;
  }
  y << YAML::EndMap;
  y << YAML::Key << "arms" << YAML::Value << YAML::Flow << YAML::BeginMap;
  for (int k = 0; k < 2; ++k) {
    y << YAML::Key << kSideNames[k] << YAML::Value << (guess.arms[k] >= 0 ? joint_name(m.get(), guess.arms[k]) : "FILL_IN");
  }
  y << YAML::EndMap;
  y << YAML::Key << "stand_pose_deg" << YAML::Value << YAML::Flow << YAML::BeginMap;
  for (const auto& [joint, angle] : guess.stand_pose) y << YAML::Key << joint << YAML::Value << angle;
  y << YAML::EndMap;
  if (!no_effort.empty()) {
    y << YAML::Key << "torque_limits" << YAML::Value << YAML::Flow << YAML::BeginMap;
    for (const std::string& joint : no_effort) y << YAML::Key << joint << YAML::Value << "FILL_IN";
    y << YAML::EndMap;
  }
  y << YAML::EndMap << YAML::EndMap;
  result.robot_file = std::string(y.c_str()) + "\n";
  return result;
}

}  // namespace biped
