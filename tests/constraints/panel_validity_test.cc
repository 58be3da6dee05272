#include "gproj/constraints/panel_validity.h"

#include <gtest/gtest.h>

#include <cmath>

#include "constraint_test_util.h"

namespace gproj {
namespace {

// One quad (four vertex items) with a 10° corner bound and a lower edge bound on v0–v1.
struct OneQuad {
  Problem problem;
  QuadCornerTerm* corners = nullptr;
  EdgeLengthTerm* edge = nullptr;

  explicit OneQuad(const std::array<Eigen::Vector3d, 4>& v) {
    const int block = problem.layout().AddBlock("vertices", 4, 3);
    problem.ResizeToLayout();
    for (int i = 0; i < 4; ++i) problem.x().segment<3>(3 * i) = v[i];
    QuadCornerBounds bounds;
    bounds.min_sine.fill(std::sin(10.0 * M_PI / 180.0));
    const std::vector<std::pair<std::array<int, 4>, QuadCornerBounds>> quads = {
        {{0, 1, 2, 3}, bounds}};
    corners = AddInequalities<QuadCornerBounds, 4, 3, 3, 3, 3>(
        &problem, "corner_angles", QuadCornerResidual{}, quads, [](const auto& q) { return q; });
    const std::vector<std::pair<std::array<int, 2>, EdgeLengthBound>> edges = {
        {{0, 1}, {{1.0, 0.0, 0.0}, 0.5}}};  // at least 0.5 along the x axis
    edge = AddInequalities<EdgeLengthBound, 1, 3, 3>(&problem, "min_edge", EdgeLengthResidual{},
                                                     edges, [](const auto& e) { return e; });
    (void)block;
  }
};

TEST(PanelValidityTest, SlacksOfASquareAreTheRootsOfTheMargins) {
  OneQuad q({Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(1, 1, 0),
             Eigen::Vector3d(0, 1, 0)});
  const VariableLayout& layout = q.problem.layout();
  const int slack = layout.FindBlock("corner_angles_slack");
  ASSERT_GE(slack, 0);
  const double margin = 1.0 - std::sin(10.0 * M_PI / 180.0);
  for (int i = 0; i < 4; ++i)
    EXPECT_NEAR(q.problem.x()[layout.Index(slack, 0, i)], std::sqrt(margin), 1e-12);
  const int edge_slack = layout.FindBlock("min_edge_slack");
  EXPECT_NEAR(q.problem.x()[layout.Index(edge_slack, 0, 0)], std::sqrt(1.0 - 0.5), 1e-12);
}

TEST(PanelValidityTest, GradientsMatchFiniteDifferences) {
  OneQuad q({Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1.2, 0.1, 0.2),
             Eigen::Vector3d(0.9, 1, -0.1), Eigen::Vector3d(-0.1, 0.8, 0.3)});
  ExpectGradientMatchesFiniteDifferences(
      *q.corners, 0, {0, 0, 0, 1.2, 0.1, 0.2, 0.9, 1, -0.1, -0.1, 0.8, 0.3, 0.5, 0.4, 0.3, 0.2});
  ExpectGradientMatchesFiniteDifferences(*q.edge, 0, {0, 0, 0, 1.2, 0.1, 0.2, 0.7});
}

TEST(PanelValidityTest, AViolatedCornerPullsAndAFoldedQuadHasNegativeRows) {
  // A bow-tie (v1, v2 swapped): two corners have negative sines, so their slacks are 0 and the
  // rows equal g = sin − s_min < 0.
  OneQuad q({Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 0), Eigen::Vector3d(1.2, 0, 0),
             Eigen::Vector3d(0, 1.1, 0)});
  double x_local[16], phi[4], jac[64];
  for (int i = 0; i < 12; ++i) x_local[i] = q.problem.x()[i];
  const int slack = q.problem.layout().FindBlock("corner_angles_slack");
  int negative = 0;
  for (int i = 0; i < 4; ++i) {
    x_local[12 + i] = q.problem.x()[q.problem.layout().Index(slack, 0, i)];
    negative += x_local[12 + i] == 0.0 ? 1 : 0;
  }
  EXPECT_GE(negative, 2);
  q.corners->EvaluateElement(0, x_local, phi, jac);
  int violated = 0;
  for (int i = 0; i < 4; ++i) violated += phi[i] < 0.0 ? 1 : 0;
  EXPECT_EQ(violated, negative);
}

}  // namespace
}  // namespace gproj
