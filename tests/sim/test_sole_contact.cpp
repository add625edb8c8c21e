#include "sim/sole_contact.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <memory>

#include "math/rotations.hpp"
#include "sim/simulation.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

void hold_stand_pose(Simulation& sim, const RobotModel& model, int cycles) {
  JointCommand hold(model.num_joints());
  hold.position = model.stand_pose();
  for (int i = 0; i < cycles; ++i) {
    sim.command(hold);
    sim.advance();
  }
}

Eigen::Vector3d world_point(const mjData* d, int body, const Eigen::Vector3d& local) {
  return Eigen::Vector3d(d->xpos + 3 * body) + math::mat_from_mujoco(d->xmat + 9 * body) * local;
}

Eigen::Vector3d patch_point(const SoleContact& contact, const SoleContact::Patch& p, const mjData* d) {
  const SoleFace& f = contact.faces()[p.face];
  return world_point(d, f.body, f.center + f.axes.col(0) * p.point.x() + f.axes.col(1) * p.point.y());
}

// Velocity (world frame) of the point p (world) moving with a body: the body frame origin's velocity
// plus ω × (p − origin). (mj_objectVelocity of mjOBJ_BODY is centred at the body's centre of mass.)
Eigen::Vector3d point_velocity(const mjModel* m, const mjData* d, int body, const Eigen::Vector3d& p) {
  mjtNum velocity[6];  // angular, linear: at the body frame's origin, world axes
  mj_objectVelocity(m, d, mjOBJ_XBODY, body, velocity, 0);
  const Eigen::Vector3d omega(velocity[0], velocity[1], velocity[2]);
  return Eigen::Vector3d(velocity[3], velocity[4], velocity[5]) + omega.cross(p - Eigen::Vector3d(d->xpos + 3 * body));
}

// The sole sinks by the load it carries divided by its stiffness (N/m, robots.md).
TEST(SoleContact, DeflectionFollowsThePhysicalStiffness) {
  const RobotModel model = test::load_model("lola");
  for (double stiffness : {3e5, 5e5}) {
    SimulationParams p;
    p.world.robot_mjcf = test::model_path("lola");
    p.sole_contact.stiffness_per_foot = stiffness;
    Simulation sim(p, model);
    hold_stand_pose(sim, model, 1500);
    for (Side side : kSides) {
      // The stiffness is shared equally by the grid points: their mean depth is load / stiffness.
      double depth_sum = 0.0;
      int points = 0;
      for (const auto& c : sim.sole_contact().patches()) {
        if (sim.sole_contact().faces()[c.face].side != index_of(side)) continue;
        depth_sum += -patch_point(sim.sole_contact(), c, sim.data()).z();
        ++points;
      }
      const double load = sim.sole_contact().normal_force(side);
      EXPECT_NEAR(load, 0.5 * 9.81 * sim.plant().total_mass(), 0.05 * 9.81 * sim.plant().total_mass());
      EXPECT_NEAR(depth_sum / points, load / stiffness, 0.05 * load / stiffness) << stiffness;
    }
  }
}

// The grid: points at most 0.1 m apart, corners and edges included (LOLA: 3 × 3 on the heel face,
// 2 × 3 on the toe face; JOHNNIE: 4 × 3); each patch reaches halfway to its neighbours, so the
// patches tile the sole; each foot's stiffness is shared equally by its points.
TEST(SoleContact, GridPointsTileTheSoleAndShareTheStiffness) {
  for (const auto& [robot, counts] : std::map<std::string, std::vector<int>>{{"lola", {9, 6}}, {"johnnie", {12}}}) {
    const RobotModel model = test::load_model(robot);
    const SoleContactParams params;
    const SoleContact contact(model, Terrain(), params);
    std::vector<int> per_face(contact.faces().size(), 0);
    std::vector<double> area(contact.faces().size(), 0.0);
    double foot_stiffness = 0.0;
    for (const auto& p : contact.patches()) {
      ++per_face[p.face];
      area[p.face] += p.area;
      if (contact.faces()[p.face].side == index_of(Side::Left)) foot_stiffness += p.stiffness;
    }
    EXPECT_NEAR(foot_stiffness, params.stiffness_per_foot, 1e-6 * params.stiffness_per_foot) << robot;
    for (std::size_t f = 0; f < counts.size(); ++f) {
      EXPECT_EQ(per_face[f], counts[f]) << robot << " face " << f;
      EXPECT_NEAR(area[f], 4.0 * contact.faces()[f].half_u * contact.faces()[f].half_v, 1e-12) << robot << " face " << f;
    }
  }
}

// The velocity of a point moving with a body agrees with the finite difference of its position.
TEST(SoleContact, PointVelocityMatchesFiniteDifferences) {
  const RobotModel model = test::load_model("lola");
  const mjModel* m = model.mj();
  mjData* d = mj_makeData(m);
  mjData* moved = mj_makeData(m);
  Eigen::Map<Eigen::VectorXd>(d->qpos, m->nq) = model.stand_qpos();
  for (int i = 0; i < m->nv; ++i) d->qvel[i] = 0.3 * std::sin(1.7 * i + 0.4);  // every joint and the base moving
  mj_forward(m, d);
  const double h = 1e-7;
  mju_copy(moved->qpos, d->qpos, m->nq);
  mj_integratePos(m, moved->qpos, d->qvel, h);
  mj_kinematics(m, moved);
  for (const int body : {model.foot(Side::Left).body, mj_name2id(m, mjOBJ_BODY, "left_toe")}) {
    const Eigen::Vector3d local(0.15, -0.06, -0.09);  // a sole corner, far from the body's centre of mass
    const Eigen::Vector3d finite_difference = (world_point(moved, body, local) - world_point(d, body, local)) / h;
    const Eigen::Vector3d v = point_velocity(m, d, body, world_point(d, body, local));
    EXPECT_LT((v - finite_difference).norm(), 1e-5 * finite_difference.norm()) << body;
  }
  mj_deleteData(moved);
  mj_deleteData(d);
}

// Each foot's stiffness by the area each point represents: the corners carry a quarter and the
// edges half of an inner point's share, the foot's total is unchanged, and the sole's tilt stiffness
// (Σ k_i r_i² about the face centre) is lower than with the equal split.
TEST(SoleContact, StiffnessByPointAreaFollowsThePatchAreas) {
  const RobotModel model = test::load_model("johnnie");
  SoleContactParams equal_params, area_params;
  area_params.stiffness_by_point_area = true;
  const SoleContact equal(model, Terrain(), equal_params), by_area(model, Terrain(), area_params);
  ASSERT_EQ(equal.patches().size(), by_area.patches().size());
  double total = 0.0, sole_area = 0.0, tilt_equal = 0.0, tilt_area = 0.0;
  for (std::size_t i = 0; i < by_area.patches().size(); ++i) {
    const SoleContact::Patch& p = by_area.patches()[i];
    if (by_area.faces()[p.face].side != index_of(Side::Left)) continue;
    total += p.stiffness;
    sole_area += p.area;
    tilt_equal += equal.patches()[i].stiffness * p.point.squaredNorm();
    tilt_area += p.stiffness * p.point.squaredNorm();
  }
  EXPECT_NEAR(total, area_params.stiffness_per_foot, 1e-6 * total);
  for (const SoleContact::Patch& p : by_area.patches()) {
    EXPECT_NEAR(p.stiffness / area_params.stiffness_per_foot, p.area / sole_area, 1e-12);
    EXPECT_NEAR(p.damping / area_params.damping_per_foot, p.area / sole_area, 1e-12);
  }
  EXPECT_LT(tilt_area, 0.8 * tilt_equal);
}

// A free 20 kg box named "foot" without MuJoCo contacts (`box`: its geom's placement and size),
// written into a fresh folder and loaded; nullptr with the loader's message in `error`.
mjModel* free_box_model(const char* folder, const std::string& box, std::string& error) {
  const std::string file = (test::fresh_dir(folder) / "foot.xml").string();
  std::ofstream(file) << "<mujoco><option timestep=\"0.001\"/><worldbody><body name=\"foot\"><freejoint/>"
                         "<geom type=\"box\" " << box << " mass=\"20\" contype=\"0\" conaffinity=\"0\"/>"
                         "</body></worldbody></mujoco>";
  char message[500] = "";
  mjModel* m = mj_loadXML(file.c_str(), nullptr, message, sizeof(message));
  error = message;
  return m;
}

// The damping acts on each point's own velocity, also where the body's centre of mass is far from
// its frame's origin (a foot rocking about x on its sole, its mass 0.1 m above and 0.08 m beside the
// sole's centre).
TEST(SoleContact, DampingActsOnThePointsOwnVelocity) {
  std::string error;
  mjModel* m = free_box_model("offset-foot", "pos=\"0 0.08 0.1\" size=\"0.1 0.05 0.02\"", error);
  ASSERT_NE(m, nullptr) << error;
  mjData* d = mj_makeData(m);
  d->qpos[2] = -0.001;  // the sole (at the body's origin) 1 mm deep
  d->qvel[3] = 0.5;     // rocking about x [rad/s]: the sole's edges move up and down
  d->qvel[2] = -0.02;
  mj_forward(m, d);
  SoleFace face;
  face.body = 1;
  face.axes.col(2) = -Eigen::Vector3d::UnitZ();
  face.axes.col(1) = -Eigen::Vector3d::UnitY();
  face.half_u = 0.1;
  face.half_v = 0.05;
  SoleContact contact(std::vector<SoleFace>{face}, Terrain(), SoleContactParams{});
  contact.apply(m, d);
  int checked = 0;
  for (const SoleContact::Patch& p : contact.patches()) {
    const Eigen::Vector3d point = world_point(d, 1, face.axes.col(0) * p.point.x() + face.axes.col(1) * p.point.y());
    const double depth = -point.z();
    const double expected = std::max(0.0, p.stiffness * depth - p.damping * point_velocity(m, d, 1, point).z());
    EXPECT_NEAR(p.force.z(), expected, 1e-9 * p.stiffness) << p.point.transpose();
    checked += expected > 0.0;
  }
  EXPECT_GT(checked, 3);
  mj_deleteData(d);
  mj_deleteModel(m);
}

// A loose 20 kg foot: a box with one sole face (0.2 × 0.1 m) under it, free in space, on terrain
// with a step down of 5 cm at x = 0.
struct LooseFoot {
  mjModel* m = nullptr;
  mjData* d = nullptr;
  std::unique_ptr<SoleContact> contact;
  explicit LooseFoot(double x, std::vector<TerrainFeature> terrain, double z = 0.0) {
    std::string error;
    m = free_box_model("loose-foot", "size=\"0.1 0.05 0.02\"", error);
    EXPECT_NE(m, nullptr) << error;
    d = mj_makeData(m);
    d->qpos[0] = x;
    d->qpos[2] = z + 0.02 - 20 * 9.81 / 4e5;  // resting: sunk by weight / stiffness
    SoleFace face;
    face.body = 1;
    face.center = Eigen::Vector3d(0, 0, -0.02);
    face.axes.col(2) = -Eigen::Vector3d::UnitZ();
    face.axes.col(1) = -Eigen::Vector3d::UnitY();  // a right-handed (u, v, outward normal)
    face.half_u = 0.1;
    face.half_v = 0.05;
    contact = std::make_unique<SoleContact>(std::vector<SoleFace>{face}, Terrain(terrain), SoleContactParams{});
    mj_forward(m, d);
  }
  ~LooseFoot() {
    mj_deleteData(d);
    mj_deleteModel(m);
  }
  void step() {
    mj_step1(m, d);
    mju_zero(d->xfrc_applied, 6 * m->nbody);
    contact->apply(m, d);
    mj_step2(m, d);
  }
  double pitch() const { return std::atan2(-d->xmat[9 + 6], d->xmat[9 + 8]); }  // the foot's (body 1) about +y
  // Total contact force and its centre of pressure (x) from the patches.
  double pressure_centre_x() const {
    double fz = 0.0, moment = 0.0;
    for (const auto& p : contact->patches()) {
      fz += p.force.z();
      moment += p.force.z() * p.centre_of_pressure.x();
    }
    return moment / fz;
  }
};

// Centre of mass over the upper level, the front 6 cm of the sole over the drop: the foot stays
// nearly flat (within 2°: the patch across the edge carries only with its supported part, so the
// sole is softer there) and the pressure stays on the supported part; the patches over the drop
// carry nothing.
TEST(SoleContact, FootHalfOnAStepEdgeRestsOnTheSupportedPart) {
  LooseFoot foot(-0.04, {TerrainFeature::step(0.0, -0.05)});
  for (int i = 0; i < 1000; ++i) foot.step();
  EXPECT_LT(std::abs(foot.pitch()), 2.0 * M_PI / 180.0);
  EXPECT_NEAR(foot.d->qpos[0], -0.04, 1e-3);
  EXPECT_NEAR(foot.pressure_centre_x(), -0.04, 2e-3);
  for (const auto& p : foot.contact->patches()) {
    if (p.force.z() > 0.0) {
      EXPECT_LE(p.centre_of_pressure.x(), 1e-9) << "force where the sole has no support";
    }
  }
}

// Centre of mass beyond the edge: the foot tips over the edge and its front comes to rest on the
// lower level (it neither stays level on the edge nor falls through the upper level).
TEST(SoleContact, FootOverAStepEdgeTipsOverTheEdge) {
  LooseFoot foot(0.04, {TerrainFeature::step(0.0, -0.05)});
  double lowest_heel = INFINITY;
  for (int i = 0; i < 400; ++i) {
    foot.step();
    lowest_heel = std::min(lowest_heel, world_point(foot.d, 1, Eigen::Vector3d(-0.1, 0.0, -0.02)).z());
  }
  EXPECT_GT(foot.pitch(), 0.2) << "the front came to rest on the lower level";
  EXPECT_GT(lowest_heel, -0.01) << "the heel stayed on the upper level";
}

// A foot shoved into a riser (5 cm step up at x = 0) below the upper level is stopped by the riser,
// not lifted onto the step.
TEST(SoleContact, ARiserStopsAFootBelowTheUpperLevel) {
  LooseFoot foot(-0.102, {TerrainFeature::step(0.0, 0.05)});  // front 2 mm before the riser
  foot.d->qvel[0] = 0.5;
  const double start_z = foot.d->qpos[2];
  double highest = start_z, hardest_push = 0.0, deepest = -1.0;
  for (int i = 0; i < 300; ++i) {
    foot.step();
    highest = std::max(highest, foot.d->qpos[2]);
    deepest = std::max(deepest, foot.d->qpos[0] + 0.1);
    double fx = 0.0;
    for (const auto& p : foot.contact->patches()) fx += p.force.x();
    hardest_push = std::min(hardest_push, fx);
  }
  EXPECT_LT(hardest_push, -100.0) << "the riser pushed back";
  EXPECT_LT(deepest, 0.01) << "the front went deep into the step";
  EXPECT_LT(highest - start_z, 0.002) << "the foot was lifted onto the step";
  EXPECT_LE(foot.d->qvel[0], 0.01);
}

// Coulomb friction: a steady 30 N horizontal push on the pelvis of the standing robot (weight ~390 N)
// is held by friction with μ = 0.8, but exceeds μ·W with μ = 0.05 and the feet slide.
TEST(SoleContact, FeetStickInsideTheFrictionConeAndSlideOutside) {
  const RobotModel model = test::load_model("johnnie");
  auto foot_travel = [&](double friction) {
    SimulationParams p;
    p.world.robot_mjcf = test::model_path("johnnie");
    p.sole_contact.friction = friction;
    p.pushes.push_back({0.2, 1.0, "pelvis", Eigen::Vector3d(30.0, 0.0, 0.0)});
    Simulation sim(p, model);
    hold_stand_pose(sim, model, 100);
    const double x0 = sim.data()->xpos[3 * model.foot(Side::Left).body];
    hold_stand_pose(sim, model, 1000);
    return std::abs(sim.data()->xpos[3 * model.foot(Side::Left).body] - x0);
  };
  EXPECT_LT(foot_travel(0.8), 0.001);
  EXPECT_GT(foot_travel(0.05), 0.02);
}

// A swing foot above the ground feels nothing.
TEST(SoleContact, NoForceWithoutPenetration) {
  const RobotModel model = test::load_model("johnnie");
  SimulationParams p;
  p.world.robot_mjcf = test::model_path("johnnie");
  Simulation sim(p, model);
  SoleContact contact(sim.plant(), Terrain({TerrainFeature::step(-10.0, -0.1)}), {});
  mjData* d = mj_makeData(sim.plant().mj());
  mju_copy(d->qpos, sim.data()->qpos, sim.plant().mj()->nq);
  mj_forward(sim.plant().mj(), d);
  contact.apply(sim.plant().mj(), d);
  EXPECT_EQ(contact.normal_force(Side::Left), 0.0);
  for (int i = 0; i < 6 * sim.plant().mj()->nbody; ++i) EXPECT_EQ(d->xfrc_applied[i], 0.0);
  mj_deleteData(d);
}

}  // namespace
}  // namespace biped
