#include "sim/world.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>

#include "model/robot_model.hpp"

namespace biped {
namespace {

constexpr double kDegToRad = M_PI / 180.0;
constexpr double kTerrainHalfWidth = 20.0;   // [m] lateral extent of terrain blocks
constexpr double kTerrainStart = -20.0;      // [m] terrain blocks cover x from here ...
constexpr double kTerrainEnd = 100.0;        // ... to here
constexpr double kBlockDepth = 0.5;          // [m] thickness of terrain blocks below their surface
// Multiply the ground's checker texture; explicit, or the robot file's default geom colour applies.
constexpr const char* kGroundTint = " rgba=\"1 1 1 1\"";
constexpr const char* kTerrainTint = " rgba=\"0.75 0.85 1 1\"";

struct Segment {
  double x0, x1;  // along x
  double z0, z1;  // ground height at x0 and x1
};

std::vector<TerrainFeature> sorted(std::vector<TerrainFeature> terrain) {
  std::sort(terrain.begin(), terrain.end(), [](const auto& a, const auto& b) { return a.x < b.x; });
  return terrain;
}

// Piecewise-linear ground profile: flat segments between features, inclined ones on slopes.
std::vector<Segment> ground_profile(const std::vector<TerrainFeature>& unsorted) {
  std::vector<Segment> segments;
  double x = kTerrainStart, z = 0.0;
  for (const TerrainFeature& f : sorted(unsorted)) {
    const double start = std::max(f.x, x);
    if (start > x) segments.push_back({x, start, z, z});
    x = start;
    if (f.kind == TerrainFeature::Kind::Step) {
      z += f.height;
    } else {
      const double x1 = x + f.length;
      const double z1 = z + f.length * std::tan(f.angle_deg * kDegToRad);
      segments.push_back({x, x1, z, z1});
      x = x1;
      z = z1;
    }
  }
  segments.push_back({x, kTerrainEnd, z, z});
  return segments;
}

std::string ground_xml(const WorldSpec& spec) {
  std::ostringstream xml;
  xml.precision(10);
  const double mu = spec.ground_friction;
  const std::string common = " contype=\"1\" conaffinity=\"2\" condim=\"3\" friction=\"" + std::to_string(mu) +
                             " 0.005 0.0001\" material=\"ground\"";
  xml << "<light name=\"sun\" pos=\"0 0 6\" dir=\"0 0 -1\" directional=\"true\"/>\n";
  if (spec.terrain.empty()) {
    xml << "<geom name=\"ground\" type=\"plane\" size=\"0 0 1\"" << common << kGroundTint << "/>\n";
    return xml.str();
  }
  int i = 0;
  for (const Segment& s : ground_profile(spec.terrain)) {
    const double dx = s.x1 - s.x0, dz = s.z1 - s.z0;
    const double length = std::hypot(dx, dz);
    const double pitch = std::atan2(dz, dx);
    // Box whose top face runs from (x0, z0) to (x1, z1).
    const double cx = 0.5 * (s.x0 + s.x1) + 0.5 * kBlockDepth * std::sin(pitch);
    const double cz = 0.5 * (s.z0 + s.z1) - 0.5 * kBlockDepth * std::cos(pitch);
    const int k = i++;
    xml << "<geom name=\"terrain_" << k << "\" type=\"box\" pos=\"" << cx << " 0 " << cz << "\" size=\""
        << 0.5 * length << " " << kTerrainHalfWidth << " " << 0.5 * kBlockDepth << "\" quat=\""
        << std::cos(-0.5 * pitch) << " 0 " << std::sin(-0.5 * pitch) << " 0\""
        << common
        // Alternate tints, so every step and slope edge shows in a video.
        << (k % 2 ? kTerrainTint : kGroundTint) << "/>\n";
  }
  return xml.str();
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ModelError(path + ": cannot read the robot model file");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void apply_model_error(mjModel* m, const ModelErrorSpec& error) {
  const int ub = mj_name2id(m, mjOBJ_BODY, "upper_body");
  m->body_mass[ub] *= error.upper_body_mass_scale;
  for (int k = 0; k < 3; ++k) {
    m->body_inertia[3 * ub + k] *= error.upper_body_mass_scale;
    m->body_ipos[3 * ub + k] += error.upper_body_com_offset[k];
  }
}

}  // namespace

double terrain_height(const std::vector<TerrainFeature>& terrain, double x) {
  if (terrain.empty()) return 0.0;
  for (const Segment& s : ground_profile(terrain)) {
    if (x >= s.x0 && x < s.x1) return s.z0 + (x - s.x0) / (s.x1 - s.x0) * (s.z1 - s.z0);
  }
  return 0.0;
}

mjModel* build_world(const WorldSpec& spec) {
  std::string xml = read_text(spec.robot_mjcf);
  const auto end_of_world = xml.rfind("</worldbody>");
  if (end_of_world == std::string::npos) throw ModelError(spec.robot_mjcf + ": no <worldbody> element");
  xml.insert(end_of_world, ground_xml(spec));
  // Looks only (videos, viewers): a checkered ground shows the robot's motion, a sky the horizon.
  // A second <asset> element is valid MJCF, so the robot file keeps its own.
  xml.insert(xml.rfind("<worldbody", end_of_world),
             "<asset>\n"
             "<texture name=\"sky\" type=\"skybox\" builtin=\"gradient\" rgb1=\"0.55 0.7 0.85\" rgb2=\"0.95 0.97 1\""
             " width=\"64\" height=\"384\"/>\n"
             "<texture name=\"checker\" type=\"2d\" builtin=\"checker\" rgb1=\"0.78 0.72 0.62\" rgb2=\"0.6 0.55 0.47\""
             " width=\"256\" height=\"256\" mark=\"edge\" markrgb=\"0.45 0.42 0.36\"/>\n"
             "<material name=\"ground\" texture=\"checker\" texrepeat=\"2 2\" texuniform=\"true\"/>\n"
             "</asset>\n");

  // Compile from memory; the robot file needs no other files (no meshes, no includes).
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  const char* vfs_name = "world.xml";
  if (mj_makeEmptyFileVFS(vfs.get(), vfs_name, static_cast<int>(xml.size())) != 0) {
    throw ModelError(spec.robot_mjcf + ": cannot create the in-memory world file");
  }
  std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), vfs_name)], xml.data(), xml.size());
  char error[1000] = "";
  mjModel* m = mj_loadXML(vfs_name, vfs.get(), error, sizeof(error));
  mj_deleteVFS(vfs.get());
  if (!m) throw ModelError(spec.robot_mjcf + ": cannot compile the world: " + error);
  if (mj_name2id(m, mjOBJ_BODY, "upper_body") < 0) {
    mj_deleteModel(m);
    throw ModelError(spec.robot_mjcf + ": the model has no body named 'upper_body'");
  }
  m->opt.timestep = spec.timestep;
  // Elliptic friction cones and the CG solver: the fastest accurate settings measured for a biped
  // on 2.2.2 (see docs/simulation.md).
  m->opt.cone = mjCONE_ELLIPTIC;
  m->opt.solver = mjSOL_CG;
  for (int g = 0; g < m->ngeom; ++g) {
    m->geom_solref[2 * g] = spec.contact_timeconst;
    m->geom_solref[2 * g + 1] = spec.contact_dampratio;
  }
  apply_model_error(m, spec.model_error);
  return m;
}

}  // namespace biped
