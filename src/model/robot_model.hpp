#pragma once
// RobotModel: the controller's own, read-only model of the robot, loaded from MJCF through MuJoCo.
// It holds the joint map and limits, the foot geometry and the sensor frames. Per-cycle
// computations work on a separate RobotData workspace (Model/Data split as in MuJoCo and Pinocchio).
#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <array>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace biped {

// Thrown when a model file cannot be used; the message names the file.
class ModelError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class Side { Left = 0, Right = 1 };
inline constexpr std::array<Side, 2> kSides = {Side::Left, Side::Right};
inline constexpr int index_of(Side s) { return static_cast<int>(s); }
inline constexpr const char* name_of(Side s) { return s == Side::Left ? "left" : "right"; }

struct JointInfo {
  std::string name;
  int mj_joint = -1;   // MuJoCo joint id
  int qpos_adr = -1;   // address in qpos
  int dof_adr = -1;    // address in qvel
  double lower = 0.0;  // hard limits [rad] from the MJCF range
  double upper = 0.0;
  double soft_lower = 0.0;  // software limits: hard limits minus a margin
  double soft_upper = 0.0;
  double torque_limit = 0.0;  // [N·m] from the actuator's ctrlrange (0: no actuator)
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
  std::vector<int> bodies_below_sensor;
  std::vector<int> sole_geoms;
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
  // the bodies, sites and sensors of the naming contract (models/README.md).
  static RobotModel load(const std::string& mjcf_path, double software_limit_margin_rad);
  // Same checks on an already compiled model, which the RobotModel takes over; `origin` names
  // where it came from in error messages.
  static RobotModel adopt(mjModel* compiled, const std::string& origin, double software_limit_margin_rad);

  const mjModel* mj() const { return model_.get(); }
  const std::string& path() const { return path_; }
  const std::string& name() const { return name_; }

  int num_joints() const { return static_cast<int>(joints_.size()); }
  const std::vector<JointInfo>& joints() const { return joints_; }
  // Index in joints() of the joint with that name, or -1.
  int joint_index(std::string_view joint_name) const;

  const FootInfo& foot(Side s) const { return feet_[index_of(s)]; }
  int pelvis_body() const { return pelvis_body_; }
  int upper_body() const { return upper_body_; }
  int imu_site() const { return imu_site_; }
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
  int pelvis_body_ = -1;
  int upper_body_ = -1;
  int imu_site_ = -1;
  double total_mass_ = 0.0;
  Eigen::VectorXd stand_pose_;
  Eigen::VectorXd stand_qpos_;
};

// Preallocated MuJoCo workspace for computations on a RobotModel.
class RobotData {
 public:
  explicit RobotData(const RobotModel& model);
  mjData* mj() { return data_.get(); }
  const mjData* mj() const { return data_.get(); }

 private:
  struct MjDataDeleter {
    void operator()(mjData* d) const { mj_deleteData(d); }
  };
  std::unique_ptr<mjData, MjDataDeleter> data_;
};

}  // namespace biped
