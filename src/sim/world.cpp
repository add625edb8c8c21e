#include "sim/world.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "model/robot_model.hpp"

namespace biped {
namespace {

constexpr double kTerrainHalfWidth = 20.0;   // [m] lateral extent of terrain blocks
constexpr double kTerrainStart = -20.0;      // [m] terrain blocks cover x from here ...
constexpr double kTerrainEnd = 100.0;        // ... to here
constexpr double kBlockDepth = 0.5;          // [m] thickness of terrain blocks below their surface
// Multiply the ground's checker texture; explicit, or the robot file's default geom colour applies.
constexpr const char* kGroundTint = " rgba=\"1 1 1 1\"";
constexpr const char* kTerrainTint = " rgba=\"0.75 0.85 1 1\"";

using Polygon = std::vector<Eigen::Vector2d>;

// The part of a convex polygon on the side of a line where normal·p − offset has the given sign.
Polygon clip(const Polygon& in, const Terrain::Line& line, double sign) {
  Polygon out;
  for (std::size_t i = 0; i < in.size(); ++i) {
    const Eigen::Vector2d& a = in[i];
    const Eigen::Vector2d& b = in[(i + 1) % in.size()];
    const double fa = sign * (line.normal.dot(a) - line.offset), fb = sign * (line.normal.dot(b) - line.offset);
    if (fa >= 0.0) out.push_back(a);
    if ((fa >= 0.0) != (fb >= 0.0)) out.push_back(a + fa / (fa - fb) * (b - a));
  }
  return out;
}

double area_of(const Polygon& p) {
  double twice = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Eigen::Vector2d& a = p[i];
    const Eigen::Vector2d& b = p[(i + 1) % p.size()];
    twice += a.x() * b.y() - b.x() * a.y();
  }
  return 0.5 * twice;
}

// The ground area cut by every terrain line and every friction patch's edge into convex cells, on
// each of which the ground is one plane with one friction coefficient.
std::vector<Polygon> ground_cells(const Terrain& terrain) {
  std::vector<Terrain::Line> lines = terrain.lines();
  for (const TerrainFeature& f : terrain.features()) {
    if (f.kind != TerrainFeature::Kind::Friction) continue;
    const auto c = Terrain::corners(f);
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector2d edge = c[(k + 1) % 4] - c[k];
      const Eigen::Vector2d normal = Eigen::Vector2d(edge.y(), -edge.x()).normalized();
      lines.push_back({normal, normal.dot(c[k]), false});
    }
  }
  std::vector<Polygon> cells = {{{kTerrainStart, -kTerrainHalfWidth},
                                 {kTerrainEnd, -kTerrainHalfWidth},
                                 {kTerrainEnd, kTerrainHalfWidth},
                                 {kTerrainStart, kTerrainHalfWidth}}};
  constexpr double kSmallestCell = 1e-6;  // [m²]
  for (const Terrain::Line& line : lines) {
    std::vector<Polygon> split;
    for (const Polygon& cell : cells) {
      for (double sign : {1.0, -1.0}) {
        Polygon part = clip(cell, line, sign);
        if (part.size() >= 3 && area_of(part) > kSmallestCell) split.push_back(std::move(part));
      }
    }
    cells = std::move(split);
  }
  return cells;
}

// The terrain as MuJoCo geoms: one convex prism (a mesh) per ground cell, its top the ground's plane
// there, kBlockDepth deep below its lowest corner. The meshes go into `assets`, the geoms into `body`.
void terrain_xml(const WorldSpec& spec, const std::string& common, std::ostringstream& assets,
                 std::ostringstream& body) {
  const Terrain terrain(spec.terrain);
  int k = 0;
  for (const Polygon& cell : ground_cells(terrain)) {
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    for (const Eigen::Vector2d& v : cell) centre += v;
    centre /= static_cast<double>(cell.size());
    const Terrain::Surface ground = terrain.surface(centre);
    std::vector<double> top;
    for (const Eigen::Vector2d& v : cell) top.push_back(ground.height + ground.gradient.dot(v - centre));
    const double bottom = *std::min_element(top.begin(), top.end()) - kBlockDepth;
    const int id = k++;
    assets << "<mesh name=\"terrain_" << id << "\" vertex=\"";
    for (std::size_t i = 0; i < cell.size(); ++i) {
      assets << cell[i].x() << ' ' << cell[i].y() << ' ' << top[i] << ' ' << cell[i].x() << ' ' << cell[i].y() << ' '
             << bottom << ' ';
    }
    assets << "\"/>\n";
    const double mu = terrain.friction(centre, spec.ground_friction);
    const bool raised = std::abs(ground.height) > 1e-9 || !ground.gradient.isZero();
    body << "<geom name=\"terrain_" << id << "\" type=\"mesh\" mesh=\"terrain_" << id << "\"" << common
         << " friction=\"" << mu << " 0.005 0.0001\""
         // Tinted where the ground is not level or not the ground's friction, so features show.
         << (raised || mu != spec.ground_friction ? kTerrainTint : kGroundTint) << "/>\n";
  }
}

std::string ground_xml(const WorldSpec& spec, std::string& assets) {
  std::ostringstream xml, mesh_assets;
  xml.precision(10);
  mesh_assets.precision(10);
  const std::string common = " contype=\"1\" conaffinity=\"2\" condim=\"3\" material=\"ground\"";
  xml << "<light name=\"sun\" pos=\"0 0 6\" dir=\"0 0 -1\" directional=\"true\"/>\n";
  if (spec.terrain.empty()) {
    xml << "<geom name=\"ground\" type=\"plane\" size=\"0 0 1\"" << common << " friction=\"" << spec.ground_friction
        << " 0.005 0.0001\"" << kGroundTint << "/>\n";
    return xml.str();
  }
  terrain_xml(spec, common, mesh_assets, xml);
  assets = mesh_assets.str();
  return xml.str();
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ModelError(path + ": cannot read the robot model file");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void apply_model_error(mjModel* m, const ModelErrorSpec& error, const std::string& upper_body) {
  const int ub = mj_name2id(m, mjOBJ_BODY, upper_body.c_str());
  m->body_mass[ub] *= error.upper_body_mass_scale;
  for (int k = 0; k < 3; ++k) {
    m->body_inertia[3 * ub + k] *= error.upper_body_mass_scale;
    m->body_ipos[3 * ub + k] += error.upper_body_com_offset[k];
  }
}

}  // namespace

mjModel* build_world(const WorldSpec& spec) {
  std::string xml = read_text(spec.robot_mjcf);
  const auto end_of_world = xml.rfind("</worldbody>");
  if (end_of_world == std::string::npos) throw ModelError(spec.robot_mjcf + ": no <worldbody> element");
  std::string terrain_meshes;
  xml.insert(end_of_world, ground_xml(spec, terrain_meshes));
  // Looks only (videos, viewers): a checkered ground shows the robot's motion, a sky the horizon.
  // A second <asset> element is valid MJCF, so the robot file keeps its own.
  xml.insert(xml.rfind("<worldbody", end_of_world),
             "<asset>\n"
             "<texture name=\"sky\" type=\"skybox\" builtin=\"gradient\" rgb1=\"0.55 0.7 0.85\" rgb2=\"0.95 0.97 1\""
             " width=\"64\" height=\"384\"/>\n"
             "<texture name=\"checker\" type=\"2d\" builtin=\"checker\" rgb1=\"0.78 0.72 0.62\" rgb2=\"0.6 0.55 0.47\""
             " width=\"256\" height=\"256\" mark=\"edge\" markrgb=\"0.45 0.42 0.36\"/>\n"
             "<material name=\"ground\" texture=\"checker\" texrepeat=\"2 2\" texuniform=\"true\"/>\n" +
                 terrain_meshes + "</asset>\n");

  // Compile from memory, under a name in the robot file's directory, so that the paths of its meshes
  // and includes resolve as they do for the file itself.
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  const std::string vfs_path = (std::filesystem::path(spec.robot_mjcf).parent_path() / "world.xml").string();
  const char* vfs_name = vfs_path.c_str();
  if (mj_makeEmptyFileVFS(vfs.get(), vfs_name, static_cast<int>(xml.size())) != 0) {
    throw ModelError(spec.robot_mjcf + ": cannot create the in-memory world file");
  }
  std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), vfs_name)], xml.data(), xml.size());
  char error[1000] = "";
  mjModel* m = mj_loadXML(vfs_name, vfs.get(), error, sizeof(error));
  mj_deleteVFS(vfs.get());
  if (!m) throw ModelError(spec.robot_mjcf + ": cannot compile the world: " + error);
  if (mj_name2id(m, mjOBJ_BODY, spec.model_map.upper_body.c_str()) < 0) {
    mj_deleteModel(m);
    throw ModelError(spec.robot_mjcf + ": the model has no body named '" + spec.model_map.upper_body + "'");
  }
  m->opt.timestep = spec.timestep;
  // Elliptic friction cones and the Newton solver stopped at a relative improvement of 1e-5: while
  // the robot walks the solver has only the joints' friction-loss rows, which Newton solves in one
  // or two iterations where CG took many (docs/simulation.md: lola-walk 13x -> 23x real time).
  m->opt.cone = mjCONE_ELLIPTIC;
  m->opt.solver = mjSOL_NEWTON;
  m->opt.tolerance = 1e-5;
  for (int g = 0; g < m->ngeom; ++g) {
    m->geom_solref[2 * g] = spec.contact_timeconst;
    m->geom_solref[2 * g + 1] = spec.contact_dampratio;
  }
  apply_model_error(m, spec.model_error, spec.model_map.upper_body);
  return m;
}

}  // namespace biped
