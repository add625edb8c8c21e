#include "control/contact_model.hpp"

#include <Eigen/Geometry>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>

#include "math/rotations.hpp"
#include "model/kinematics.hpp"

namespace biped {
namespace {

// The sole's profile in the sensor frame's x–z plane: the mean of an edge's two corners (elements
// first and first + 1).
Eigen::Vector2d edge(const ContactElements& e, int first) {
  const Eigen::Vector3d mean = 0.5 * (e.position[first] + e.position[first + 1]);
  return {mean.x(), mean.z()};
}

// Height of a point above the line through a and b (a behind b) in the x–z plane.
double elevation(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector3d& p) {
  const Eigen::Vector2d direction = (b - a).normalized();
  return (Eigen::Vector2d(p.x(), p.z()) - a).dot(Eigen::Vector2d(-direction.y(), direction.x()));
}

}  // namespace

// Corners in the order (x_min, y_min), (x_min, y_max), (x_max, y_min), (x_max, y_max) per segment:
// elements 4s, 4s + 1 are segment s's rear edge, 4s + 2, 4s + 3 its front edge.
void place_contact_elements(const FootInfo& foot, const ContactModelParams& params, double toe_angle,
                            ContactElements& elements) {
  const double q = std::isfinite(toe_angle) ? toe_angle : 0.0;
  elements.count = 0;
  elements.normal = Eigen::Vector3d::UnitZ();
  for (int s = 0; s < foot.num_segments; ++s) {
    const SoleSegment& segment = foot.segments[s];
    const double share = foot.num_segments == 1 ? 1.0 : s == 0 ? params.heel_share : 1.0 - params.heel_share;
    const Eigen::Matrix3d turn =
        segment.joint < 0 ? Eigen::Matrix3d::Identity() : Eigen::AngleAxisd(q, segment.axis).toRotationMatrix();
    for (double x : {segment.x_min, segment.x_max}) {
      for (double y : {segment.y_min, segment.y_max}) {
        const int i = elements.count++;
        elements.position[i] = segment.axis_point + turn * (Eigen::Vector3d(x, y, segment.z) - segment.axis_point);
        elements.stiffness[i] = 0.25 * share * params.stiffness;
        elements.segment[i] = s;
        elements.in_contact[i] = true;
      }
    }
  }
}

// A two-segment sole bent at the toe joint beyond the sole's deflection under the measured load
// plus the tolerance rests on one edge of its profile's lower convex hull. Bent up (Λ): on the heel
// or on the toe segment, whichever the measured CoP lies over (neither can carry a CoP beyond the
// joint; without params.toe_contact always the heel); the other segment is out of contact as a
// whole: of a real, evenly stiff pad tilted against the ground only a sliver at the joint touches,
// while its lumped corners would keep half its stiffness on the joint line. Bent down (V): on the
// heel's rear edge and the toe's tip, the elements within the deflection plus the tolerance of that
// plane. Bent less: every element.
void contact_elements(const FootInfo& foot, const ContactModelParams& params, double toe_angle, const Wrench& measured,
                      ContactElements& elements) {
  place_contact_elements(foot, params, toe_angle, elements);
  if (foot.num_segments < 2) return;
  const double fz = measured.force.z() > 0.0 ? measured.force.z() : 0.0;  // also NaN → 0
  const double tolerance = params.tolerance + fz / params.stiffness;
  const Eigen::Vector2d heel_rear = edge(elements, 0), heel_front = edge(elements, 2);
  const Eigen::Vector2d toe_rear = edge(elements, 4), toe_tip = edge(elements, 6);
  double lowest = 0.0, highest = 0.0;  // of the toe elements above the heel plane
  for (int i = 4; i < elements.count; ++i) {
    const double e = elevation(heel_rear, heel_front, elements.position[i]);
    lowest = std::min(lowest, e);
    highest = std::max(highest, e);
  }
  Eigen::Vector2d a = heel_rear, b = heel_front;
  if (lowest < -tolerance) {
    b = toe_tip;
    for (int i = 0; i < elements.count; ++i) elements.in_contact[i] = elevation(a, b, elements.position[i]) <= tolerance;
  } else if (highest > tolerance) {
    const bool on_toe =
        params.toe_contact && fz > 0.0 && -measured.torque.y() > foot.segments[1].axis_point.x() * fz;
    if (on_toe) {
      a = toe_rear;
      b = toe_tip;
    }
    for (int i = 0; i < elements.count; ++i) elements.in_contact[i] = elements.segment[i] == (on_toe ? 1 : 0);
  }
  const Eigen::Vector2d direction = (b - a).normalized();
  elements.normal = Eigen::Vector3d(-direction.y(), 0.0, direction.x());
}

// Linearization of eq. (11) about the foot resting on a ground plane with normal u (sensor frame):
// δ = (z, φ_x, φ_y) deepens element i by −(z + φ·(r_i × u)) and the ground pushes back with
// C_i times that along u, so (F_z, T_x, T_y) = −K δ with K = Σ C_i a_i b_iᵀ over the elements in
// contact, m_i = r_i × u, a_i = (u_z, m_x, m_y), b_i = (1, m_x, m_y); for u = e_z, a_i = b_i =
// (1, y_i, −x_i).
Eigen::Matrix3d point_contact_stiffness(const ContactElements& elements) {
  const Eigen::Vector3d& u = elements.normal;
  Eigen::Matrix3d K = Eigen::Matrix3d::Zero();
  for (int i = 0; i < elements.count; ++i) {
    if (!elements.in_contact[i]) continue;
    const Eigen::Vector3d m = elements.position[i].cross(u);
    K += elements.stiffness[i] * Eigen::Vector3d(u.z(), m.x(), m.y()) * Eigen::Vector3d(1.0, m.x(), m.y()).transpose();
  }
  return K;
}

Eigen::Matrix3d point_contact_stiffness(const FootInfo& foot, const ContactModelParams& params) {
  ContactElements elements;
  place_contact_elements(foot, params, 0.0, elements);
  return point_contact_stiffness(elements);
}

// eq. (11): F = Σ C_i d_i, T = Σ Δr_i × C_i d_i over the elements in contact; d_i is the element's
// depth below the ground plane along the world z axis (no friction), Δr_i the element relative to
// the sensor point. Both are expressed in the sensor frame.
Eigen::Vector3d point_contact_wrench(const FootInfo& foot, const ContactModelParams& params, double toe_angle,
                                     const Eigen::Vector3d& sensor_position, const Eigen::Matrix3d& sensor_rotation,
                                     double ground_height) {
  ContactElements elements;
  place_contact_elements(foot, params, toe_angle, elements);
  Eigen::Vector3d force = Eigen::Vector3d::Zero(), torque = Eigen::Vector3d::Zero();
  const Eigen::Vector3d up = sensor_rotation.transpose().col(2);  // world z in the sensor frame
  for (int i = 0; i < elements.count; ++i) {
    const Eigen::Vector3d& r = elements.position[i];
    const double depth = ground_height - (sensor_position + sensor_rotation * r).z();
    const Eigen::Vector3d f = elements.stiffness[i] * std::max(depth, 0.0) * up;
    force += f;
    torque += r.cross(f);
  }
  return {force.z(), torque.x(), torque.y()};
}

double toe_angle(const RobotModel& model, const FootInfo& foot, const Eigen::VectorXd& qpos) {
  for (int s = 0; s < foot.num_segments; ++s) {
    if (foot.segments[s].joint >= 0) return qpos[model.joints()[foot.segments[s].joint].qpos_adr];
  }
  return 0.0;
}

std::array<Eigen::Vector3d, 2> point_contact_wrenches(const RobotModel& model, RobotData& data,
                                                      const Eigen::VectorXd& qpos, const ContactModelParams& params,
                                                      double ground_height) {
  data.qpos() = qpos;
  forward_kinematics(model, data);
  std::array<Eigen::Vector3d, 2> lambda;
  for (Side side : kSides) {
    const FootInfo& foot = model.foot(side);
    lambda[index_of(side)] = point_contact_wrench(foot, params, toe_angle(model, foot, qpos), data.site_position(foot.sensor_site),
                                                  data.site_rotation(foot.sensor_site), ground_height);
  }
  return lambda;
}

FootRows contact_jacobian(const RobotModel& model, const Eigen::VectorXd& qpos, const ContactModelParams& params,
                          double ground_height, double h) {
  RobotData data(model);
  FootRows G(6, model.nv());
  for (int i = 0; i < model.nv(); ++i) {
    Eigen::VectorXd direction = Eigen::VectorXd::Zero(model.nv());
    direction[i] = 1.0;
    Eigen::VectorXd q_plus = qpos, q_minus = qpos;
    integrate_configuration(model, direction, h, q_plus);
    integrate_configuration(model, direction, -h, q_minus);
    const auto plus = point_contact_wrenches(model, data, q_plus, params, ground_height);
    const auto minus = point_contact_wrenches(model, data, q_minus, params, ground_height);
    for (int k = 0; k < 2; ++k) G.col(i).segment<3>(3 * k) = (plus[k] - minus[k]) / (2.0 * h);
  }
  return G;
}

FootRows selected_task_rows(const TaskSpace& space, const TaskSpaceData& data) {
  const TaskLayout& L = space.layout();
  FootRows rows(6, space.nv());
  for (Side side : kSides) {
    const int k = index_of(side);
    const Eigen::Vector3d phi = data.x.segment<3>(L.foot_orientation[k]);
    // The x/y rows of the task's rotation vector rates (upper-body frame) are not foot-frame tilts
    // once the foot is yawed against the upper body; this rotates them there (the controller's
    // stabilizer_modification uses yaw(ψ_foot − ψ_heading) for it).
    const Eigen::Matrix3d to_foot = math::so3::exp(phi).transpose() * math::so3::inverse_left_jacobian(phi).inverse();
    rows.row(3 * k) = data.J.row(L.foot_position[k] + 2);
    rows.middleRows<2>(3 * k + 1) = (to_foot * data.J.middleRows<3>(L.foot_orientation[k])).topRows<2>();
  }
  return rows;
}

// eq. (20): the map S_λ∇_qλ(S̄_x∇_q x)^† whose pseudo-inverse turns the force law into the
// modification Δẋ_λ. The task rows do not depend on R_ref (only the upper-body rows do).
Eigen::Matrix<double, 6, 6> general_force_position_map(const TaskSpace& space, const Eigen::VectorXd& qpos,
                                                       const ContactModelParams& params, double ground_height) {
  TaskSpaceData data(space);
  evaluate(space, qpos, Eigen::Matrix3d::Identity(), data);
  const FootRows selected = selected_task_rows(space, data);
  const FootRows G = contact_jacobian(space.model(), qpos, params, ground_height);
  return G * selected.completeOrthogonalDecomposition().pseudoInverse();
}

}  // namespace biped
