#pragma once
// RobotModel: the controller's own, read-only model of the robot, loaded from MJCF through MuJoCo.
// It holds the joint map and limits, the foot geometry and the sensor frames. Per-cycle
// computations work on a separate RobotData workspace (Model/Data split as in MuJoCo and Pinocchio).
#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "math/side.hpp"
#include "model/body_tree.hpp"
#include "model/model_map.hpp"

namespace biped {

// Thrown when a model file cannot be used; the message names the file.
class ModelError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct JointInfo {
  std::string name;
  int mj_joint = -1;   // MuJoCo joint id
  int qpos_adr = -1;   // address in qpos
  int dof_adr = -1;    // address in qvel
  double lower = 0.0;  // hard limits [rad] from the MJCF range
  double upper = 0.0;
  double soft_lower = 0.0;  // software limits: hard limits minus a margin
  double soft_upper = 0.0;
  double torque_limit = 0.0;  // [N·m] the actuator's ctrlrange, else ModelMap::torque_limits (0: none)
  bool passive = false;       // ModelMap::passive_joints: no drive, kept out of the controller's tasks
  bool locked = false;        // ModelMap::locked_joints: driven, held at the stand pose, out of the tasks
};

// A rigid part of a sole: the rectangle of the box geoms "*_sole" of one body, in the sensor frame
// with every joint at zero. A segment on a toe joint turns with it about the joint's axis.
struct SoleSegment {
  double x_min = 0.0, x_max = 0.0, y_min = 0.0, y_max = 0.0;
  double z = 0.0;  // height of the segment's sole plane in the sensor frame
  int joint = -1;  // index in RobotModel::joints() of the toe joint carrying it (-1: rigid with the sensor)
  Eigen::Vector3d axis_point = Eigen::Vector3d::Zero();  // the joint's axis in the sensor frame
  Eigen::Vector3d axis = Eigen::Vector3d::UnitY();
};

// A foot below its force/torque sensor. The sole outline is the flat-foot support rectangle,
// expressed in the sensor frame (for LOLA: heel and toe segment together, toe joint at zero).
// `segments` are its rigid parts: first the one rigid with the sensor (LOLA's heel segment,
// JOHNNIE's whole sole), then LOLA's toe segment.
struct FootInfo {
  static constexpr int kMaxSegments = 2;
  int body = -1;         // body directly below the F/T sensor
  int sensor_site = -1;  // F/T sensor frame
  Eigen::Vector3d sensor_position = Eigen::Vector3d::Zero();  // the sensor frame's origin in `body`'s frame
  std::vector<int> bodies_below_sensor;
  std::vector<int> sole_geoms;  // box geoms of the sole (empty: the sole is ModelMap data)
  int force_sensor = -1;        // MuJoCo sensor ids of the F/T sensor's force and torque
  int torque_sensor = -1;
  double mass_below_sensor = 0.0;
  double sole_x_min = 0.0, sole_x_max = 0.0;  // sole rectangle in the sensor frame [m]
  double sole_y_min = 0.0, sole_y_max = 0.0;
  double sole_z = 0.0;  // height of the sole plane in the sensor frame (negative: below)
  std::array<SoleSegment, kMaxSegments> segments;
  int num_segments = 0;
};

class RobotModel {
 public:
  // Loads an MJCF file; throws ModelError naming the file when it cannot be loaded or lacks
  // the bodies, sites and sensors that `map` names (default: the naming contract of models/README.md).
  static RobotModel load(const std::string& mjcf_path, double software_limit_margin_rad, const ModelMap& map = {});
  // Same checks on an already compiled model, which the RobotModel takes over; `origin` names
  // where it came from in error messages.
  static RobotModel adopt(mjModel* compiled, const std::string& origin, double software_limit_margin_rad,
                          const ModelMap& map = {});

  // The compiled MuJoCo model: for model/ and sim/ only (control/ and planning/ use the functions
  // of model/, docs/architecture.md).
  const mjModel* mj() const { return model_.get(); }
  const std::string& path() const { return path_; }
  const std::string& name() const { return name_; }
  int nq() const { return model_->nq; }  // size of a full configuration (floating base included)
  int nv() const { return model_->nv; }  // generalized velocities
  double gravity() const;                // [m/s²], magnitude
  // The kinematic tree for the controller's own forward kinematics (model/body_tree.hpp).
  const BodyTree& tree() const { return tree_; }

  int num_joints() const { return static_cast<int>(joints_.size()); }
  const std::vector<JointInfo>& joints() const { return joints_; }
  // Index in joints() of the joint with that name, or -1.
  int joint_index(std::string_view joint_name) const;
  // The first joint of each leg and of each arm (ModelMap), and the toe joint, as indices in
  // joints(); -1 where the model has none.
  int leg_root_joint(Side s) const { return leg_root_joint_[index_of(s)]; }
  int arm_root_joint(Side s) const { return arm_root_joint_[index_of(s)]; }
  int toe_joint(Side s) const { return toe_joint_[index_of(s)]; }
  // The names this model was loaded with.
  const ModelMap& map() const { return map_; }

  const FootInfo& foot(Side s) const { return feet_[index_of(s)]; }
  int pelvis_body() const { return pelvis_body_; }
  // The body of that name, or, for the role names "upper_body" and "pelvis" where the model names
  // them otherwise (ModelMap), the body in that role; -1 when there is none.
  int body_named(const std::string& name) const;
  int upper_body() const { return upper_body_; }
  int imu_site() const { return imu_site_; }
  // The IMU site's position in the upper body's frame [m].
  Eigen::Vector3d imu_position() const;
  // MuJoCo sensor ids of the IMU's parts (orientation: -1 when the model has no such sensor).
  int imu_orientation_sensor() const { return imu_sensors_[0]; }
  int imu_gyro_sensor() const { return imu_sensors_[1]; }
  int imu_accelerometer_sensor() const { return imu_sensors_[2]; }
  double total_mass() const { return total_mass_; }
  // Weight carried by the two F/T sensors when standing still [N].
  double weight_above_sensors() const;

  // Joint angles of the MJCF keyframe "stand" (the reference standing pose), in joints() order.
  const Eigen::VectorXd& stand_pose() const { return stand_pose_; }
  // Full qpos of the keyframe "stand" (floating base included).
  const Eigen::VectorXd& stand_qpos() const { return stand_qpos_; }

 private:
  struct MjModelDeleter {
    void operator()(mjModel* m) const { mj_deleteModel(m); }
  };
  std::unique_ptr<mjModel, MjModelDeleter> model_;
  std::string path_;
  std::string name_;
  std::vector<JointInfo> joints_;
  std::array<FootInfo, 2> feet_;
  BodyTree tree_;
  std::array<int, 2> leg_root_joint_{-1, -1};
  std::array<int, 2> arm_root_joint_{-1, -1};
  std::array<int, 2> toe_joint_{-1, -1};
  std::array<int, 3> imu_sensors_{-1, -1, -1};
  ModelMap map_;
  int pelvis_body_ = -1;
  int upper_body_ = -1;
  int imu_site_ = -1;
  double total_mass_ = 0.0;
  Eigen::VectorXd stand_pose_;
  Eigen::VectorXd stand_qpos_;
};

// Preallocated workspace for computations on a RobotModel (a MuJoCo mjData). Its configuration is
// set through qpos(); forward_kinematics() (model/kinematics.hpp) then fills the frames read below.
class RobotData {
 public:
  explicit RobotData(const RobotModel& model);
  // For model/ and sim/ only, like RobotModel::mj().
  mjData* mj() { return data_.get(); }
  const mjData* mj() const { return data_.get(); }

  // The configuration (size nq: floating base position, w-x-y-z quaternion, joint angles).
  Eigen::Map<Eigen::VectorXd> qpos();
  // World-frame frames of the last forward_kinematics():
  Eigen::Vector3d body_position(int body) const;     // body frame origin
  Eigen::Matrix3d body_rotation(int body) const;
  Eigen::Quaterniond body_orientation(int body) const;
  Eigen::Vector3d site_position(int site) const;
  Eigen::Matrix3d site_rotation(int site) const;
  Eigen::Vector3d joint_anchor(int joint) const;     // a point on the axis of joints()[joint]
  Eigen::Vector3d subtree_com(int body) const;       // CoM of the body and all below it (needs the CoM pass)

 private:
  struct MjDataDeleter {
    void operator()(mjData* d) const { mj_deleteData(d); }
  };
  const RobotModel* model_;
  std::unique_ptr<mjData, MjDataDeleter> data_;
};

}  // namespace biped
