#include "sim/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <mutex>

namespace biped {
namespace {

// The soles touch the ground through SoleContact, not through MuJoCo's contacts. Where a sole is
// given as data, not as box geoms, the foot's own collision geoms stand for it and are switched off.
RobotModel build_plant(const SimulationParams& p) {
  RobotModel plant =
      RobotModel::adopt(build_world(p.world), p.world.robot_mjcf, p.software_limit_margin_rad, p.world.model_map);
  mjModel* m = const_cast<mjModel*>(plant.mj());
  for (Side side : kSides) {
    const FootInfo& foot = plant.foot(side);
    for (int g : foot.sole_geoms) m->geom_contype[g] = m->geom_conaffinity[g] = 0;
    if (!foot.sole_geoms.empty()) continue;
    for (int g = 0; g < m->ngeom; ++g) {
      const int body = m->geom_bodyid[g];
      if (std::find(foot.bodies_below_sensor.begin(), foot.bodies_below_sensor.end(), body) !=
          foot.bodies_below_sensor.end()) {
        m->geom_contype[g] = m->geom_conaffinity[g] = 0;
      }
    }
  }
  return plant;
}

std::vector<int> map_joints(const RobotModel& plant, const RobotModel& controller_model) {
  std::vector<int> plant_joint_of;
  for (const JointInfo& j : controller_model.joints()) {
    const int p = plant.joint_index(j.name);
    if (p < 0) {
      throw ModelError(plant.path() + ": the simulated robot has no joint '" + j.name + "' of the controller's model");
    }
    plant_joint_of.push_back(p);
  }
  return plant_joint_of;
}

SensorEmulationParams sensor_params(const SimulationParams& p, const RobotModel& plant) {
  SensorEmulationParams s;
  for (const JointInfo& j : plant.joints()) {
    const auto it = p.encoder_bits_of.find(j.name);
    s.encoder_bits.push_back(it != p.encoder_bits_of.end() ? it->second : p.encoder_bits);
  }
  s.noise = p.sensor_noise;
  s.noise_levels = p.noise_levels;
  s.errors = p.sensor_errors;
  s.delay_cycles = p.sensor_delay_cycles;
  s.faults = p.faults;
  s.seed = p.seed;
  return s;
}

// The corners of a sole face where its body is now (world frame).
std::array<Eigen::Vector3d, 4> face_corners(const SoleFace& f, const mjData* d) {
  const Eigen::Vector3d origin(d->xpos + 3 * f.body);
  const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> rot(d->xmat + 9 * f.body);
  std::array<Eigen::Vector3d, 4> corners;
  for (int c = 0; c < 4; ++c) {  // in order around the face
    const double u = c == 1 || c == 2 ? 1.0 : -1.0, v = c >= 2 ? 1.0 : -1.0;
    corners[c] = origin + rot * (f.center + u * f.half_u * f.axes.col(0) + v * f.half_v * f.axes.col(1));
  }
  return corners;
}

// Lowest point of the soles above the ground, with the robot at its current qpos.
double sole_clearance(const std::vector<SoleFace>& faces, const mjData* d, const Terrain& terrain) {
  double clearance = std::numeric_limits<double>::infinity();
  for (const SoleFace& f : faces) {
    for (const Eigen::Vector3d& corner : face_corners(f, d)) {
      clearance = std::min(clearance, corner.z() - terrain.height(corner.head<2>()));
    }
  }
  return clearance;
}

}  // namespace

Simulation::Simulation(const SimulationParams& params, const RobotModel& controller_model)
    : params_(params),
      terrain_(params.world.terrain),
      plant_(build_plant(params)),
      model_(const_cast<mjModel*>(plant_.mj())),
      data_(mj_makeData(model_)),
      plant_joint_of_(map_joints(plant_, controller_model)),
      drives_(plant_, params.drives),
      sensors_(plant_, plant_joint_of_, sensor_params(params, plant_)),
      sole_contact_(plant_, terrain_, params.sole_contact),
      collision_gate_(model_, terrain_),
      pushes_(plant_, params.pushes),
      plant_setpoint_(plant_.stand_pose()),
      fall_detector_(plant_, terrain_, 1.0) {
  // MuJoCo's default handler appends its warnings to MUJOCO_LOG.TXT in the working directory. A
  // diverged state is reported by advance() itself; the other warnings go to stderr.
  static std::once_flag warning_handler;
  std::call_once(warning_handler, [] {
    mju_user_warning = [](const char* message) {
      if (std::strstr(message, "Nan, Inf or huge value") == nullptr) std::fprintf(stderr, "MuJoCo: %s\n", message);
    };
  });
  const double ratio = params.control_period / params.world.timestep;
  steps_per_period_ = static_cast<int>(std::lround(ratio));
  if (steps_per_period_ < 1 || std::abs(ratio - steps_per_period_) > 1e-9) {
    throw ModelError("the control period must be a whole number of physics steps");
  }
  reset();
}

void Simulation::reset() {
  mjModel* m = model_;
  mjData* d = data_.get();
  m->opt.disableflags &= ~mjDSBL_CONTACT;
  mj_resetData(m, d);
  Eigen::Map<Eigen::VectorXd>(d->qpos, m->nq) = plant_.stand_qpos();
  d->qpos[0] = 0.0;
  d->qpos[1] = 0.0;
  mj_kinematics(m, d);
  // Start in static equilibrium: the soles sunk by the deflection that carries the weight.
  const double sink = plant_.total_mass() * std::abs(m->opt.gravity[2]) / (2.0 * params_.sole_contact.stiffness_per_foot);
  d->qpos[2] -= sole_clearance(sole_contact_.faces(), d, terrain_) + sink;
  sole_contact_.reset();
  sensors_.reset();
  mj_forward(m, d);
  sole_contact_.apply(m, d);
  mj_forward(m, d);  // sensors now see the contact forces
  standing_pelvis_height_ = d->xpos[3 * plant_.pelvis_body() + 2] - terrain_.height(Eigen::Vector2d::Zero());
  fall_detector_ = FallDetector(plant_, terrain_, standing_pelvis_height_);
  plant_setpoint_ = plant_.stand_pose();
  drives_.reset();
  drives_.set_targets(plant_setpoint_, params_.control_period);
  collision_gate_.reset(m, d);
  gait_.reset();
  pushes_.reset();
  fall_reason_ = nullptr;
  fall_time_ = 0.0;
}

std::vector<Simulation::SoleOutline> Simulation::sole_outlines() const {
  std::vector<SoleOutline> outlines;
  for (const SoleFace& f : sole_contact_.faces()) {
    SoleOutline o{f.side == index_of(Side::Left) ? Side::Left : Side::Right, {}};
    const std::array<Eigen::Vector3d, 4> corners = face_corners(f, data_.get());
    for (int c = 0; c < 4; ++c) o.corners[c] = corners[c].head<2>();
    outlines.push_back(o);
  }
  return outlines;
}

void Simulation::read_sensors(SensorData& out) { sensors_.sample(data_.get(), data_->time, out); }

void Simulation::command(const JointCommand& setpoints) {
  for (std::size_t i = 0; i < plant_joint_of_.size(); ++i) plant_setpoint_[plant_joint_of_[i]] = setpoints.position[i];
  drives_.set_targets(plant_setpoint_, params_.control_period);
}

void Simulation::advance() {
  mjModel* m = model_;
  mjData* d = data_.get();
  for (int step = 0; step < steps_per_period_; ++step) {
    if (params_.collision_gate) collision_gate_.update(m, d);
    mj_step1(m, d);
    mju_zero(d->xfrc_applied, 6 * m->nbody);
    // The gait events from the last step's sole forces, then the pushes they time.
    gait_.update(d->time, {sole_contact_.normal_force(Side::Left), sole_contact_.normal_force(Side::Right)});
    pushes_.apply(d, gait_);
    sole_contact_.apply(m, d);
    drives_.apply(m, d, m->opt.timestep);
    const double t = d->time;
    mj_step2(m, d);
    // MuJoCo resets a diverged state to the model's rest pose and counts a warning; going on would
    // simulate a robot that jumped back to the start.
    for (const int w : {mjWARN_BADQPOS, mjWARN_BADQVEL, mjWARN_BADQACC}) {
      if (d->warning[w].number > 0) {
        char text[256];
        std::snprintf(text, sizeof text,
                      "the simulation diverged at t = %.3f s (MuJoCo found NaN, Inf or a huge value in the "
                      "state): a push, terrain, model error or simulation parameter beyond the physical?", t);
        throw SimulationDiverged(text);
      }
    }
  }
  if (!fall_reason_) {
    fall_reason_ = fall_detector_.check(d);
    if (fall_reason_) fall_time_ = d->time;
  }
}

double Simulation::foot_contact_force(Side side) const {
  const mjModel* m = plant_.mj();
  const mjData* d = data_.get();
  const auto& bodies = plant_.foot(side).bodies_below_sensor;
  double total = sole_contact_.normal_force(side);
  for (int i = 0; i < d->ncon; ++i) {
    const int b1 = m->geom_bodyid[d->contact[i].geom1];
    const int b2 = m->geom_bodyid[d->contact[i].geom2];
    const int robot_body = b1 == 0 ? b2 : (b2 == 0 ? b1 : -1);
    if (robot_body <= 0 || std::find(bodies.begin(), bodies.end(), robot_body) == bodies.end()) continue;
    mjtNum force[6];
    mj_contactForce(m, d, i, force);
    total += force[0];
  }
  return total;
}

}  // namespace biped
