#include "gproj/problems/circular/c_canal.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>

#include "canal_test_util.h"
#include "gproj/problems/circular/circular_mesh.h"
#include "gproj/problems/circular/combescure.h"
#include "gproj/problems/run/report_json.h"

namespace gproj::circular {
namespace {

CircularStripInput Input(int n = 8) { return BendingStripInput(n); }

// 000 §5.2 (eq. 10): the C-canal keeps the guide curve, its first row is the cross-section (the
// first arc's edges scaled by s_j), every quad stays circular, and after BFGS on the canal's
// lengths the C-canal's own chords |P_k Q'_k| are the asked lengths, which they were not before.
TEST(CCanalTest, BfgsMakesTheCCanalLengthsTheAskedOnes) {
  CCanalOptions options;
  options.segments = 8;
  for (int j = 0; j < options.segments; ++j)
    options.section_scales.push_back(1.0 + 0.3 * std::sin(0.7 * j));
  const FrameAngles angles = AnglesFromNormal(Eigen::Vector3d(0, 0, 1));
  // Lengths a C-canal can have: those of the transform of the canal with lengths ℓ*.
  CircularStripInput in = Input();
  {
    CCanalOptions forward = options;
    forward.max_iterations = 0;
    in.lengths = BuildCCanalSurface(in, angles, forward).lengths;
  }
  const CCanalSurface c = BuildCCanalSurface(in, angles, options);
  std::printf("C-canal: length error %.2e -> %.2e in %d BFGS iterations (%s)\n",
              c.initial_length_error, c.max_length_error, c.iterations, c.message.c_str());
  EXPECT_GT(c.initial_length_error, 1e-2);
  EXPECT_LT(c.max_length_error, 1e-8);
  EXPECT_TRUE(c.converged);
  const NamedValues m = MeasureCircularMesh(c.mesh);
  EXPECT_LT(ValueOf(m, "max_concyclicity"), 1e-9);
  EXPECT_LT(ValueOf(m, "max_planarity"), 1e-9);
  const int cols = options.segments + 1;
  for (size_t k = 0; k < in.curve.size(); ++k) {
    const Eigen::Vector3d p(c.mesh.point(c.mesh.vertex_handle(static_cast<int>(k) * cols)).data());
    EXPECT_LT((p - in.curve[k]).norm(), 1e-10) << k;  // the guide curve is kept
  }
  // The first row: edges parallel to the canal's first arc, scaled by s_j.
  for (int j = 0; j < options.segments; ++j) {
    const Eigen::Vector3d e(
        (c.mesh.point(c.mesh.vertex_handle(j + 1)) - c.mesh.point(c.mesh.vertex_handle(j))).data());
    const Eigen::Vector3d f(
        (c.canal.point(c.canal.vertex_handle(j + 1)) - c.canal.point(c.canal.vertex_handle(j)))
            .data());
    EXPECT_NEAR(e.norm() / f.norm(), options.section_scales[j], 1e-10);
    EXPECT_LT(e.normalized().cross(f.normalized()).norm(), 1e-10);
  }
}

TEST(CCanalTest, RefusesBadScales) {
  CCanalOptions options;
  options.segments = 4;
  options.section_scales = {1, 1, 1};
  EXPECT_THROW(BuildCCanalSurface(Input(), AnglesFromNormal(Eigen::Vector3d(0, 0, 1)), options),
               InputError);
  options.section_scales = {1, 1, -1, 1};
  EXPECT_THROW(BuildCCanalSurface(Input(), AnglesFromNormal(Eigen::Vector3d(0, 0, 1)), options),
               InputError);
}

}  // namespace
}  // namespace gproj::circular
