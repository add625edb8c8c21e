// The SVD reference of eq. (21): its explicit J^† and N have the defining properties.
// (Its agreement with the Klein & Huang form is tested in test_resolved_motion_rate_control.cpp.)
#include "control/resolved_motion_rate_control_svd.hpp"

#include <gtest/gtest.h>

namespace biped {
namespace {

constexpr double kMargin = 5.0 * M_PI / 180.0;

class RmrcSvdTest : public ::testing::TestWithParam<const char*> {
 protected:
  RmrcSvdTest() : model(RobotModel::load(GetParam(), kMargin)), space(model), task(space) {}
  RobotModel model;
  TaskSpace space;
  TaskSpaceData task;
};

TEST_P(RmrcSvdTest, PseudoInverseAndProjectorAreMoorePenrose) {
  ResolvedMotionRateControlSvd rmrc(model, space, ResolvedMotionRateControlParams{});
  evaluate(space, model.stand_qpos(), Eigen::Matrix3d::Identity(), task);
  Eigen::VectorXd x_id = task.x;
  x_id[2] += 0.01;
  rmrc.step(x_id, Eigen::VectorXd::Zero(space.dim()), Eigen::Matrix3d::Identity());
  ASSERT_EQ(rmrc.damping_squared(), 0.0);
  const Eigen::MatrixXd& J = rmrc.J();
  const Eigen::MatrixXd& pinv = rmrc.pseudo_inverse();
  const Eigen::MatrixXd& N = rmrc.null_space_projector();
  const double scale = 1.0 / rmrc.smallest_singular_value();  // ‖J^†‖
  EXPECT_LT((J * pinv * J - J).cwiseAbs().maxCoeff(), 1e-12 * scale);
  EXPECT_LT((pinv * J * pinv - pinv).cwiseAbs().maxCoeff(), 1e-12 * scale * scale);
  EXPECT_LT((J * N).cwiseAbs().maxCoeff(), 1e-12 * scale);
  EXPECT_LT((N * N - N).cwiseAbs().maxCoeff(), 1e-12 * scale);
  EXPECT_LT((N - N.transpose()).cwiseAbs().maxCoeff(), 1e-12 * scale);
  // Null-space dimension = nv − dim(x) (full row rank).
  EXPECT_NEAR(N.trace(), space.nv() - space.dim(), 1e-9);
}

INSTANTIATE_TEST_SUITE_P(Robots, RmrcSvdTest,
                         ::testing::Values(BIPED_SOURCE_DIR "/models/lola/lola.xml",
                                           BIPED_SOURCE_DIR "/models/johnnie/johnnie.xml"),
                         [](const auto& info) { return std::string(info.index == 0 ? "lola" : "johnnie"); });

}  // namespace
}  // namespace biped
