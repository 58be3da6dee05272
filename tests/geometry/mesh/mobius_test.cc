#include "gproj/geometry/mesh/mobius.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "gproj/geometry/mesh/circle.h"
#include "gproj/geometry/mesh/parametric_grid.h"

namespace gproj {
namespace {

PolyMesh RevolutionGrid(int nu, int nv) {
  ParametricGridOptions o;
  o.nu = nu;
  o.nv = nv;
  return MakeParametricGrid(RevolutionSurface, o);
}

TEST(MobiusTest, InversionIsAnInvolution) {
  const Eigen::Vector3d c(0.5, -2.0, 1.0), p(3.0, 1.0, -0.5);
  const Eigen::Vector3d q = Invert(p, c, 2.5);
  EXPECT_NEAR((q - c).norm() * (p - c).norm(), 2.5, 1e-14);
  EXPECT_LT((Invert(q, c, 2.5) - p).norm(), 1e-14);
}

TEST(MobiusTest, InversionKeepsCircularQuadsCircular) {
  const PolyMesh mesh = RevolutionGrid(9, 12);
  const CircularityMeasures before = MeasureCircularity(mesh);
  EXPECT_LT(before.max_concyclicity, 1e-12);
  const PolyMesh inverted = InvertMesh(mesh, Eigen::Vector3d(4.0, 0.5, 0.3), 9.0);
  const CircularityMeasures after = MeasureCircularity(inverted);
  EXPECT_LT(after.max_concyclicity, 1e-10);
  // The shape did change: a non-trivial map.
  double moved = 0.0;
  for (auto v : mesh.vertices())
    moved = std::max(moved, (mesh.point(v) - inverted.point(v)).norm());
  EXPECT_GT(moved, 0.1);
}

TEST(MobiusTest, InversionDoesNotMakeNonCircularQuadsCircular) {
  ParametricGridOptions o;
  o.nu = o.nv = 6;
  o.jitter = 0.05;
  const PolyMesh mesh = MakeParametricGrid(RevolutionSurface, o);
  EXPECT_GT(
      MeasureCircularity(InvertMesh(mesh, Eigen::Vector3d(4, 0.5, 0.3), 9.0)).max_concyclicity,
      1e-4);
}

TEST(MobiusTest, VertexAtTheCentreIsRefused) {
  const PolyMesh mesh = RevolutionGrid(3, 3);
  const auto& p = mesh.point(PolyMesh::VertexHandle(4));
  try {
    InvertMesh(mesh, Eigen::Vector3d(p[0], p[1], p[2]), 1.0);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("vertex 4"), std::string::npos) << e.what();
  }
  EXPECT_THROW(InvertMesh(mesh, Eigen::Vector3d(9, 9, 9), 0.0), InputError);
}

// 000 §5.1: for t > 0, both centres make the image of the quad an isosceles trapezoid:
// z2' − z1' = t (z3' − z4'), concyclic, equal diagonals. For t < 0 the roots lie on the quad's
// own circle (images collinear).
TEST(MobiusTest, MRevolutionCentresMakeIsoscelesTrapezoids) {
  const std::complex<double> c0(0.2, -0.1);
  const double r = 1.3, angles[4] = {0.3, 1.4, 2.2, 4.0};
  std::complex<double> z[4];
  for (int j = 0; j < 4; ++j) z[j] = c0 + std::polar(r, angles[j]);
  for (double t : {-2.0, -0.5}) {
    for (const auto& zc : MRevolutionCentres(z[0], z[1], z[2], z[3], t))
      EXPECT_NEAR(std::abs(zc - c0), r, 1e-9) << "t = " << t;
  }
  for (double t : {0.3, 0.7, 1.5, 4.0}) {
    const auto centres = MRevolutionCentres(z[0], z[1], z[2], z[3], t);
    for (const auto& zc : centres) {
      ASSERT_TRUE(std::isfinite(zc.real()) && std::isfinite(zc.imag()));
      std::complex<double> w[4];
      for (int j = 0; j < 4; ++j) w[j] = zc + 1.0 / std::conj(z[j] - zc);  // 000 eq. 2, k = 1
      const std::complex<double> ratio = (w[1] - w[0]) / (w[2] - w[3]);
      EXPECT_NEAR(ratio.real(), t, 1e-9 * std::abs(t)) << "t = " << t;
      EXPECT_NEAR(ratio.imag(), 0.0, 1e-9) << "t = " << t;
      // Isosceles: equal diagonals of a cyclic quad with parallel sides.
      EXPECT_NEAR(std::abs(w[2] - w[0]), std::abs(w[3] - w[1]), 1e-9 * std::abs(w[2] - w[0]));
    }
    EXPECT_GT(std::abs(centres[0] - centres[1]), 1e-6);
  }
}

TEST(MobiusTest, MRevolutionCentresInSpace) {
  const Eigen::Vector3d n = Eigen::Vector3d(0.2, 0.1, 1.0).normalized();
  const Eigen::Vector3d e1 = n.unitOrthogonal(), e2 = n.cross(e1), c(1, 2, 3);
  std::array<Eigen::Vector3d, 4> quad;
  const double angles[4] = {0.3, 1.4, 2.2, 4.0};
  for (int j = 0; j < 4; ++j)
    quad[j] = c + 2.0 * (std::cos(angles[j]) * e1 + std::sin(angles[j]) * e2);
  const auto centres = MRevolutionCentres(quad, 0.8);
  EXPECT_EQ(centres.size(), 2u);
  for (const auto& centre : centres) {
    std::array<Eigen::Vector3d, 4> image;
    for (int j = 0; j < 4; ++j) image[j] = Invert(quad[j], centre, 1.0);
    const Eigen::Vector3d a = image[1] - image[0], b = image[2] - image[3];
    EXPECT_LT(a.normalized().cross(b.normalized()).norm(), 1e-9);
    EXPECT_LT(QuadConcyclicity(image) / a.norm(), 1e-9);
  }
  EXPECT_THROW(MRevolutionCentres(quad, -1.0), InputError);
  quad[2] += 0.05 * n;
  EXPECT_THROW(MRevolutionCentres(quad, 0.8), InputError);
}

}  // namespace
}  // namespace gproj
