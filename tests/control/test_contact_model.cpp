// The point-contact model of eq. (11) and the per-foot simplification of eq. (20): K is a proper
// stiffness and the linearization of the model's wrenches λ(q); in walking configurations the
// general map S_λ∇_qλ(S̄_x∇_q x)^† is compared with blockdiag(−K_left, −K_right).
#include "control/contact_model.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "kinematic_loop.hpp"
#include "math/rotations.hpp"
#include "test_support.hpp"

namespace biped {
namespace {

// The defaults (C = 4e5 N/m per foot, as StabilizerParams), rolling on the toe recognized.
const ContactModelParams kParams = [] {
  ContactModelParams p;
  p.toe_contact = true;
  return p;
}();

class ContactModelTest : public ::testing::TestWithParam<std::string> {
 protected:
  RobotModel model = test::load_model(GetParam());
};

TEST_P(ContactModelTest, StiffnessIsSymmetricPositiveDefinite) {
  for (Side side : kSides) {
    const Eigen::Matrix3d K = point_contact_stiffness(model.foot(side), kParams);
    EXPECT_EQ((K - K.transpose()).norm(), 0.0);
    EXPECT_EQ(K.llt().info(), Eigen::Success) << name_of(side);
    EXPECT_DOUBLE_EQ(K(0, 0), kParams.stiffness);
  }
}

// A foot resting on level ground with its sole plane through elements `a` and `b` (rear and front
// edge: the mean of elements a, a + 1 and of b, b + 1 of place_contact_elements' order), toe at q,
// sensor yawed, pressed `press` into the ground. Returns −∂λ/∂δ by central differences of the
// model's wrenches along δ = (z, φ_x, φ_y) in the foot frame, and fills the contact state the
// controller decides from that configuration's own wrench as the F/T reading.
Eigen::Matrix3d finite_difference_stiffness(const FootInfo& foot, double q, int a, int b, double press,
                                            ContactElements& decided) {
  ContactElements placed;
  place_contact_elements(foot, kParams, q, placed);
  const Eigen::Vector3d edge = 0.5 * (placed.position[b] + placed.position[b + 1] - placed.position[a] -
                                      placed.position[a + 1]);
  const double pitch = std::atan2(edge.z(), edge.x());  // turns the edge level
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
                            Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Vector3d p(0.3, -0.2, 0.1);
  const double ground = (p + R * placed.position[a]).z() + press;
  constexpr double h = 1e-6;
  Eigen::Matrix3d K_fd;
  for (int i = 0; i < 3; ++i) {
    Eigen::Vector3d delta = Eigen::Vector3d::Zero();
    delta[i] = h;
    const auto wrench = [&](double sign) {
      const Eigen::Vector3d tilt(sign * delta[1], sign * delta[2], 0.0);
      return point_contact_wrench(foot, kParams, q, p + Eigen::Vector3d(0, 0, sign * delta[0]), R * math::so3::exp(tilt), ground);
    };
    K_fd.col(i) = -(wrench(1.0) - wrench(-1.0)) / (2.0 * h);
  }
  const Eigen::Vector3d lambda = point_contact_wrench(foot, kParams, q, p, R, ground);
  Wrench measured;
  measured.force.z() = lambda[0];
  measured.torque.x() = lambda[1];
  measured.torque.y() = lambda[2];
  contact_elements(foot, kParams, q, measured, decided);
  return K_fd;
}

int count_in_contact(const ContactElements& e) { return static_cast<int>(std::count(e.in_contact.begin(), e.in_contact.begin() + e.count, true)); }

// K from the elements the controller finds in contact is the linearization of the wrenches of the
// element model: flat foot; LOLA's toe bent within the sole's deflection (all eight elements touch),
// bent up 0.1 rad with the heel flat (heel contact) and with the toe flat (toe contact: heel
// lifted, CoP ahead of the toe joint), and bent down 0.1 rad (heel's rear edge and toe tip).
// The preload adds a geometric term (the normal force tilts with the sensor frame) of about
// preload·|Δr|, below 2e-5 of max|K| here (0.1 mm press or less).
TEST_P(ContactModelTest, StiffnessIsTheLinearizationOfTheWrenches) {
  struct Case {
    const char* name;
    double q;
    int a, b;  // support edges
    double press;
    int in_contact;
  };
  const bool toe = model.foot(Side::Left).num_segments == 2;
  std::vector<Case> cases = {{"flat", 0.0, 0, 2, 1e-4, toe ? 8 : 4}};
  if (toe) {
    cases.push_back({"toe bent 0.001 rad up, within the deflection", -0.001, 0, 2, 1e-4, 8});
    // Pressed less than the 0.05 mm the toe's rear edge rises as the toe turns about its joint 1 cm
    // above the sole, so the model's wrench has the heel segment alone, as the controller decides.
    cases.push_back({"toe bent 0.1 rad up, heel contact", -0.1, 0, 2, 2e-5, 4});
    cases.push_back({"toe bent 0.1 rad up, toe contact", -0.1, 4, 6, 2e-5, 4});
    cases.push_back({"toe bent 0.1 rad down, heel edge and toe tip", 0.1, 0, 6, 1e-4, 4});
  }
  for (Side side : kSides) {
    for (const Case& c : cases) {
      ContactElements decided;
      const Eigen::Matrix3d K_fd = finite_difference_stiffness(model.foot(side), c.q, c.a, c.b, c.press, decided);
      const Eigen::Matrix3d K = point_contact_stiffness(decided);
      EXPECT_EQ(count_in_contact(decided), c.in_contact) << name_of(side) << ", " << c.name;
      EXPECT_LT((K_fd - K).cwiseAbs().maxCoeff() / K.cwiseAbs().maxCoeff(), 2e-5)
          << name_of(side) << ", " << c.name << "\n" << K_fd << "\n" << K;
    }
  }
}

// LOLA, toe bent up 0.1 rad (tip 8 mm above the heel plane) with the load on the heel: only the
// four heel elements count, K is the heel segment's alone. With the CoP ahead of the toe joint the
// foot rolls on the toe: only the toe's elements count.
TEST(ContactModel, LiftedToeLeavesOnlyTheHeelElements) {
  const RobotModel model = test::load_model("lola");
  const FootInfo& foot = model.foot(Side::Left);
  Wrench on_heel;
  on_heel.force.z() = 500.0;  // CoP below the sensor, on the heel segment
  ContactElements e;
  contact_elements(foot, kParams, -0.1, on_heel, e);
  ContactElements heel;
  place_contact_elements(foot, kParams, 0.0, heel);
  for (int i = 0; i < e.count; ++i) {
    EXPECT_EQ(e.in_contact[i], e.segment[i] == 0) << i;
    heel.in_contact[i] = heel.segment[i] == 0;
  }
  EXPECT_EQ(point_contact_stiffness(e), point_contact_stiffness(heel));
  EXPECT_DOUBLE_EQ(point_contact_stiffness(e)(0, 0), kParams.heel_share * kParams.stiffness);

  Wrench on_toe = on_heel;
  on_toe.torque.y() = -(foot.segments[1].axis_point.x() + 0.03) * on_toe.force.z();
  contact_elements(foot, kParams, -0.1, on_toe, e);
  for (int i = 0; i < e.count; ++i) EXPECT_EQ(e.in_contact[i], e.segment[i] == 1) << i;
  // Not recognized (toe_contact off), the bent-up toe counts as lifted whatever the CoP.
  ContactModelParams heel_only = kParams;
  heel_only.toe_contact = false;
  contact_elements(foot, heel_only, -0.1, on_toe, e);
  for (int i = 0; i < e.count; ++i) EXPECT_EQ(e.in_contact[i], e.segment[i] == 0) << i;
  // The sole's deflection counts: a lightly loaded toe bent by 3 mm at the tip is off the ground,
  // the same bend under a load that presses the sole 3 mm is not.
  on_heel.force.z() = 50.0;
  const double q = -0.003 / (foot.segments[1].x_max - foot.segments[1].axis_point.x());
  contact_elements(foot, kParams, q, on_heel, e);
  EXPECT_EQ(count_in_contact(e), 4) << "the heel's";
  on_heel.force.z() = 0.003 * kParams.stiffness;
  contact_elements(foot, kParams, q, on_heel, e);
  EXPECT_EQ(count_in_contact(e), 8);
  // A NaN reading or toe angle gives a finite, regular K.
  on_heel.force.z() = std::numeric_limits<double>::quiet_NaN();
  contact_elements(foot, kParams, std::numeric_limits<double>::quiet_NaN(), on_heel, e);
  EXPECT_TRUE(point_contact_stiffness(e).inverse().allFinite());
}

// JOHNNIE's one rigid sole: the four corners with C/4 each, whatever the toe angle and reading.
TEST(ContactModel, JohnnieIsTheFourCornerSole) {
  const RobotModel model = test::load_model("johnnie");
  for (Side side : kSides) {
    const FootInfo& foot = model.foot(side);
    Eigen::Matrix3d K = Eigen::Matrix3d::Zero();
    for (double x : {foot.sole_x_min, foot.sole_x_max}) {
      for (double y : {foot.sole_y_min, foot.sole_y_max}) {
        const Eigen::Vector3d g(1.0, y, -x);
        K += 0.25 * kParams.stiffness * g * g.transpose();
      }
    }
    Wrench measured;
    measured.force.z() = 300.0;
    measured.torque.y() = -0.15 * 300.0;
    ContactElements e;
    contact_elements(foot, kParams, 0.3, measured, e);
    EXPECT_EQ(e.count, 4);
    EXPECT_LT((point_contact_stiffness(e) - K).norm(), 1e-9 * K.norm());
    EXPECT_LT((point_contact_stiffness(foot, kParams) - K).norm(), 1e-9 * K.norm());
  }
}

// Through q: raising the floating base moves both feet up without tilting them, so the base's z
// column of ∇_qλ is −K's first column per foot (stand pose, soles pressed 0.1 mm).
TEST_P(ContactModelTest, FloatingBaseHeightColumnIsTheStiffness) {
  RobotData data(model);
  const Eigen::VectorXd q = model.stand_qpos();
  point_contact_wrenches(model, data, q, kParams, 0.0);
  double ground = -1.0;
  for (Side side : kSides) {
    const FootInfo& foot = model.foot(side);
    const Eigen::Vector3d p(data.mj()->site_xpos + 3 * foot.sensor_site);
    ground = std::max(ground, p.z() + foot.sole_z + 1e-4);
  }
  const FootRows G = contact_jacobian(model, q, kParams, ground);
  for (Side side : kSides) {
    const int k = index_of(side);
    const Eigen::Vector3d expected = -point_contact_stiffness(model.foot(side), kParams).col(0);
    EXPECT_LT((G.col(2).segment<3>(3 * k) - expected).norm() / expected.norm(), 1e-4) << name_of(side);
  }
}

// The walking controller on its own kinematic loop (as in test_walking_controller.cpp).
using test::KinematicLoop;

// Lowest and highest contact element of a foot in the world at the configuration qpos last passed
// to data.
std::pair<double, double> element_heights(const RobotModel& model, const RobotData& data, const Eigen::VectorXd& qpos,
                                          Side side) {
  const FootInfo& foot = model.foot(side);
  const Eigen::Vector3d p(data.mj()->site_xpos + 3 * foot.sensor_site);
  const Eigen::Matrix3d R = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(data.mj()->site_xmat + 9 * foot.sensor_site);
  ContactElements e;
  place_contact_elements(foot, kParams, toe_angle(model, foot, qpos), e);
  double low = 1e9, high = -1e9;
  for (int i = 0; i < e.count; ++i) {
    const double z = (p + R * e.position[i]).z();
    low = std::min(low, z);
    high = std::max(high, z);
  }
  return {low, high};
}

struct Comparison {
  double worst_difference = 0.0;  // max over samples of ‖M_kk + K_k‖_F / ‖K_k‖_F, feet in contact
  double worst_cross = 0.0;       // max over samples of ‖M_kj‖_F / ‖K_k‖_F, k in contact, j ≠ k
  int samples = 0;
};

TEST_P(ContactModelTest, GeneralMapIsCloseToThePerFootStiffnessWhileWalking) {
  KinematicLoop loop(GetParam());
  const TaskSpace space(loop.model);
  RobotData data(loop.model);
  std::array<Eigen::Matrix3d, 2> K;
  Comparison single, dual, single_full, dual_full, single_feet, dual_feet;
  for (int i = 0; i < 6000; ++i) {
    WalkCommand command;
    command.vx = i > 1000 ? 0.5 : 0.0;
    command.omega = i > 4000 ? 0.3 : 0.0;  // the last part turns: feet yawed against the upper body
    loop.cycle(i * 0.001, command);
    if (i < 1500 || i % 50 != 0) continue;
    const PatternSample& s = loop.controller.pattern();
    const Eigen::VectorXd& q = loop.controller.rmrc().qpos_d();
    point_contact_wrenches(loop.model, data, q, kParams, 0.0);
    // K of each foot with every element in contact, its toe at the sample's angle.
    for (Side side : kSides) {
      ContactElements e;
      place_contact_elements(loop.model.foot(side), kParams, toe_angle(loop.model, loop.model.foot(side), q), e);
      K[index_of(side)] = point_contact_stiffness(e);
    }
    // Contact feet: both in double support, the stance foot in single support. The ground plane is
    // put 1 mm above their highest corner, so all their elements are in contact.
    std::array<bool, 2> contact = {true, true};
    if (!s.double_support) contact[1 - index_of(s.stance)] = false;
    double ground = -1e9;
    for (Side side : kSides) {
      if (contact[index_of(side)]) ground = std::max(ground, element_heights(loop.model, data, q, side).second + 1e-3);
    }
    bool clear = true;  // a swing foot must stay above the plane, or the sample is not single support
    for (Side side : kSides) {
      if (!contact[index_of(side)]) clear = element_heights(loop.model, data, q, side).first > ground + 1e-3;
    }
    if (!clear) continue;
    const Eigen::Matrix<double, 6, 6> M = general_force_position_map(space, q, kParams, ground);
    // The map eq. (21) realizes: the modification is resolved with all task rows, the others held
    // (q̇ = J^† E δ̇, E the task-space directions of δ: J has full row rank, so S̄_x∇x = P J with
    // P = S̄_x∇x J^†, and E = P^†).
    TaskSpaceData task(space);
    evaluate(space, q, Eigen::Matrix3d::Identity(), task);
    const Eigen::MatrixXd J_pinv = task.J.completeOrthogonalDecomposition().pseudoInverse();
    const Eigen::MatrixXd P = selected_task_rows(space, task) * J_pinv;
    const Eigen::MatrixXd resolve = J_pinv * P.completeOrthogonalDecomposition().pseudoInverse();
    FootRows G = contact_jacobian(loop.model, q, kParams, ground);
    const Eigen::MatrixXd M_full = G * resolve;
    // The same without the toe joints' share: J^† moves LOLA's toes a little (their mass is in the
    // CoM rows), and turning a toe presses its elements.
    for (Side side : kSides) {
      const FootInfo& foot = loop.model.foot(side);
      if (foot.num_segments > 1) G.col(loop.model.joints()[foot.segments[1].joint].dof_adr).setZero();
    }
    const Eigen::MatrixXd M_feet = G * resolve;
    Comparison& c = s.double_support ? dual : single;
    Comparison& cf = s.double_support ? dual_full : single_full;
    Comparison& ct = s.double_support ? dual_feet : single_feet;
    ++c.samples;
    for (int k = 0; k < 2; ++k) {
      if (!contact[k]) {
        EXPECT_EQ(M.middleRows<3>(3 * k).norm(), 0.0);  // no contact, no force change
        continue;
      }
      const double scale = K[k].norm();
      c.worst_difference = std::max(c.worst_difference, (M.block<3, 3>(3 * k, 3 * k) + K[k]).norm() / scale);
      c.worst_cross = std::max(c.worst_cross, M.block<3, 3>(3 * k, 3 * (1 - k)).norm() / scale);
      cf.worst_difference = std::max(cf.worst_difference, (M_full.block<3, 3>(3 * k, 3 * k) + K[k]).norm() / scale);
      cf.worst_cross = std::max(cf.worst_cross, M_full.block<3, 3>(3 * k, 3 * (1 - k)).norm() / scale);
      ct.worst_difference = std::max(ct.worst_difference, (M_feet.block<3, 3>(3 * k, 3 * k) + K[k]).norm() / scale);
      ct.worst_cross = std::max(ct.worst_cross, M_feet.block<3, 3>(3 * k, 3 * (1 - k)).norm() / scale);
    }
  }
  std::printf("%s vs blockdiag(-K), worst relative Frobenius difference of the contact feet's blocks / cross-foot blocks:\n"
              "  eq. (20) as written, (S_x grad x)^+ of the 6 rows: single support (%d samples) %.3g / %.3g, "
              "double support (%d) %.3g / %.3g\n"
              "  with all task rows (as eq. (21) resolves it):      single support %.3g / %.3g, double support %.3g / %.3g\n"
              "  the same without the toe joints' motion:            single support %.3g / %.3g, double support %.3g / %.3g\n",
              GetParam().c_str(), single.samples, single.worst_difference, single.worst_cross, dual.samples,
              dual.worst_difference, dual.worst_cross, single_full.worst_difference, single_full.worst_cross,
              dual_full.worst_difference, dual_full.worst_cross, single_feet.worst_difference, single_feet.worst_cross,
              dual_feet.worst_difference, dual_feet.worst_cross);
  EXPECT_GT(single.samples, 20);
  EXPECT_GT(dual.samples, 5);
  // Measured (LOLA / JOHNNIE): as written 0.199 / 0.158 (single), 0.223 / 0.191 (double support),
  // cross-foot 0.265 / 0.227 and 0.218 / 0.185. The min-norm q̇ of the six rows alone moves the CoM,
  // upper body and other leg as well (the height row is against the CoM), so only part of a
  // commanded height/tilt change reaches the ground and some reaches the other foot. These bounds
  // keep that measurement (about 10 % above the worst value).
  for (const Comparison* c : {&single, &dual}) {
    EXPECT_LT(c->worst_difference, 0.25);
    EXPECT_LT(c->worst_cross, 0.30);
  }
  // Measured, LOLA: 0.0063 / 0.0087 (single), 0.0074 / 0.0074 (double support), from the toes'
  // motion in J^†; JOHNNIE (no toes): 5.65e-5 / < 1e-9.
  for (const Comparison* c : {&single_full, &dual_full}) {
    EXPECT_LT(c->worst_difference, 0.01);
    EXPECT_LT(c->worst_cross, 0.01);
  }
  // Without the toes' motion, measured: 7.1e-5 (LOLA) and 5.65e-5 (JOHNNIE), the 1 mm preload's
  // geometric term (the normal force tilts with the sole: about √2·C·1 mm·|sole_z| on the tilt
  // diagonal against ‖K‖); cross-foot below 1e-9. So −K per foot is the map the controller realizes,
  // up to 0.9 % from the toes.
  for (const Comparison* c : {&single_feet, &dual_feet}) {
    EXPECT_LT(c->worst_difference, 1e-4);
    EXPECT_LT(c->worst_cross, 1e-6);
  }
}

INSTANTIATE_TEST_SUITE_P(Robots, ContactModelTest, ::testing::Values("lola", "johnnie"),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace biped
