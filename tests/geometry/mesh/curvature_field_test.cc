#include "gproj/geometry/mesh/curvature_field.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>

#include "gproj/common/input_error.h"
#include "triangulated_surface_util.h"

namespace gproj {
namespace {

// Largest angle (degrees) between the fitted asymptotic directions and the analytic pair
// (matched either way round), over the vertices whose parameters lie in the inner region.
double WorstAsymptoticError(
    const std::vector<VertexCurvature>& fit, const std::vector<Eigen::Vector2d>& uv,
    const std::function<bool(const Eigen::Vector2d&)>& inner,
    const std::function<std::pair<Eigen::Vector3d, Eigen::Vector3d>(const Eigen::Vector2d&)>& exact,
    int* checked) {
  double worst = 0.0;
  *checked = 0;
  for (size_t k = 0; k < fit.size(); ++k) {
    if (!inner(uv[k])) continue;
    Eigen::Vector3d a, b;
    EXPECT_TRUE(fit[k].Asymptotic(&a, &b)) << k;
    if (!fit[k].Asymptotic(&a, &b)) continue;
    const auto [x, y] = exact(uv[k]);
    const double straight = std::max(LineAngleDeg(a, x), LineAngleDeg(b, y));
    const double crossed = std::max(LineAngleDeg(a, y), LineAngleDeg(b, x));
    worst = std::max(worst, std::min(straight, crossed));
    ++*checked;
  }
  return worst;
}

// z = xy: K < 0 everywhere, the asymptotic lines are the rulings x = const and y = const,
// with tangents (1, 0, y) and (0, 1, x).
TEST(CurvatureFieldTest, AsymptoticDirectionsOfTheHyperbolicParaboloid) {
  std::vector<Eigen::Vector2d> uv;
  const PolyMesh mesh = Triangulate([](double x, double y) { return Eigen::Vector3d(x, y, x * y); },
                                    -1.0, 1.0, -1.0, 1.0, 40, &uv);
  const std::vector<VertexCurvature> fit = FitVertexCurvatures(mesh);
  int checked = 0;
  const double worst = WorstAsymptoticError(
      fit, uv, [](const Eigen::Vector2d& p) { return p.cwiseAbs().maxCoeff() < 0.8; },
      [](const Eigen::Vector2d& p) {
        return std::pair(Eigen::Vector3d(1, 0, p.y()), Eigen::Vector3d(0, 1, p.x()));
      },
      &checked);
  std::printf("z = xy: %d vertices, worst asymptotic direction error %.3f deg\n", checked, worst);
  EXPECT_GT(checked, 900);
  EXPECT_LT(worst, 1.0);
}

// Enneper's surface: a minimal surface whose parameter lines are lines of curvature, so the
// asymptotic directions bisect them: x_u ± x_v.
TEST(CurvatureFieldTest, AsymptoticDirectionsOfEnneperSurface) {
  auto enneper = [](double u, double v) {
    return Eigen::Vector3d(u - u * u * u / 3 + u * v * v, v - v * v * v / 3 + u * u * v,
                           u * u - v * v);
  };
  std::vector<Eigen::Vector2d> uv;
  const PolyMesh mesh = Triangulate(enneper, -0.8, 0.8, -0.8, 0.8, 40, &uv);
  const std::vector<VertexCurvature> fit = FitVertexCurvatures(mesh);
  int checked = 0;
  const double worst = WorstAsymptoticError(
      fit, uv, [](const Eigen::Vector2d& p) { return p.cwiseAbs().maxCoeff() < 0.6; },
      [](const Eigen::Vector2d& p) {
        const double u = p.x(), v = p.y();
        const Eigen::Vector3d xu(1 - u * u + v * v, 2 * u * v, 2 * u);
        const Eigen::Vector3d xv(2 * u * v, 1 - v * v + u * u, -2 * v);
        return std::pair(Eigen::Vector3d(xu + xv), Eigen::Vector3d(xu - xv));
      },
      &checked);
  std::printf("Enneper: %d vertices, worst asymptotic direction error %.3f deg\n", checked, worst);
  EXPECT_GT(checked, 500);
  EXPECT_LT(worst, 1.0);
  // Minimal: H = 0 against |K| (relative).
  double h = 0.0, k = 0.0;
  for (const VertexCurvature& c : fit)
    if (c.fitted) h = std::max(h, std::abs(c.mean())), k = std::max(k, std::sqrt(-c.gaussian()));
  EXPECT_LT(h, 0.05 * k);
}

// An ellipsoid patch (semi-axes 3, 2, 1.5), K > 0: principal directions against the analytic
// ones (eigenvectors of the second fundamental form relative to the first), away from the
// umbilics; no asymptotic directions.
TEST(CurvatureFieldTest, PrincipalDirectionsOfAnEllipsoidPatch) {
  const double a = 3.0, b = 2.0, c = 1.5;
  auto ellipsoid = [=](double u, double v) {
    return Eigen::Vector3d(a * std::cos(u) * std::cos(v), b * std::cos(u) * std::sin(v),
                           c * std::sin(u));
  };
  std::vector<Eigen::Vector2d> uv;
  const PolyMesh mesh = Triangulate(ellipsoid, -0.6, 0.6, -0.6, 0.6, 40, &uv);
  const std::vector<VertexCurvature> fit = FitVertexCurvatures(mesh);
  double worst = 0.0;
  int checked = 0;
  for (size_t k = 0; k < fit.size(); ++k) {
    if (uv[k].cwiseAbs().maxCoeff() > 0.45) continue;
    const double u = uv[k].x(), v = uv[k].y();
    const Eigen::Vector3d xu(-a * std::sin(u) * std::cos(v), -b * std::sin(u) * std::sin(v),
                             c * std::cos(u));
    const Eigen::Vector3d xv(-a * std::cos(u) * std::sin(v), b * std::cos(u) * std::cos(v), 0);
    const Eigen::Vector3d xuu(-a * std::cos(u) * std::cos(v), -b * std::cos(u) * std::sin(v),
                              -c * std::sin(u));
    const Eigen::Vector3d xuv(a * std::sin(u) * std::sin(v), -b * std::sin(u) * std::cos(v), 0);
    const Eigen::Vector3d xvv(-a * std::cos(u) * std::cos(v), -b * std::cos(u) * std::sin(v), 0);
    const Eigen::Vector3d n = xu.cross(xv).normalized();
    Eigen::Matrix2d first, second;
    first << xu.dot(xu), xu.dot(xv), xu.dot(xv), xv.dot(xv);
    second << xuu.dot(n), xuv.dot(n), xuv.dot(n), xvv.dot(n);
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> shape(second, first);
    const double gap = std::abs(shape.eigenvalues()[1] - shape.eigenvalues()[0]);
    if (gap < 0.05) continue;  // near an umbilic the directions are not defined
    const Eigen::Vector2d w = shape.eigenvectors().col(1);
    const Eigen::Vector3d exact = w.x() * xu + w.y() * xv;
    Eigen::Vector3d p, q;
    EXPECT_FALSE(fit[k].Asymptotic(&p, &q)) << k;
    // d1 or d2, whichever belongs to the same eigenvalue (the normal's side may differ).
    const double along = std::min(LineAngleDeg(fit[k].d1, exact), LineAngleDeg(fit[k].d2, exact));
    worst = std::max(worst, along);
    ++checked;
  }
  std::printf("ellipsoid: %d vertices, worst principal direction error %.3f deg\n", checked, worst);
  EXPECT_GT(checked, 300);
  EXPECT_LT(worst, 1.0);
}

// Line fields of known index on a flat irregular triangulation, singular at a point between
// vertices: the indices of the inner vertices sum to the field's index, and only the vertices
// of the face around the singular point carry any.
TEST(CurvatureFieldTest, LineFieldIndicesOfKnownFields) {
  std::vector<Eigen::Vector2d> uv;
  const PolyMesh mesh = Triangulate([](double x, double y) { return Eigen::Vector3d(x, y, 0); }, -1,
                                    1, -1, 1, 20, &uv);
  const Eigen::Vector2d singular(0.031, 0.017);
  struct Case {
    const char* name;
    double turns;  // the line's angle per turn of the position angle
    double index;
  };
  for (const Case& c : {Case{"radial", 1.0, 1.0}, Case{"hyperbolic", -1.0, -1.0},
                        Case{"half", 0.5, 0.5}, Case{"negative half", -0.5, -0.5}}) {
    std::vector<Eigen::Vector3d> lines;
    for (const Eigen::Vector2d& p : uv) {
      const double phi = std::atan2(p.y() - singular.y(), p.x() - singular.x());
      lines.emplace_back(std::cos(c.turns * phi), std::sin(c.turns * phi), 0.0);
    }
    const std::vector<double> index = LineFieldIndices(mesh, lines);
    double sum = 0.0;
    int singular_vertices = 0;
    for (double i : index) {
      sum += i;
      if (std::abs(i) > 1e-9) ++singular_vertices;
    }
    EXPECT_NEAR(sum, c.index, 1e-9) << c.name;
    EXPECT_GE(singular_vertices, 1) << c.name;
    EXPECT_LE(singular_vertices, 3) << c.name;
  }
}

// 004 Theorem 6 on the monkey saddle z = x³ − 3xy²: its flat point at the origin is a
// singularity of index −½ of the jet-fitted principal line field (which bisects the asymptotic
// net); nowhere else is there one. On the curved surface the angle defects matter: without
// them the sum would miss −½ by ∫K/2π ≈ 0.07 here.
TEST(CurvatureFieldTest, MonkeySaddleFlatPointHasIndexMinusHalf) {
  std::vector<Eigen::Vector2d> uv;
  const PolyMesh mesh = Triangulate(
      [](double x, double y) { return Eigen::Vector3d(x, y, x * x * x - 3 * x * y * y); }, -1, 1,
      -1, 1, 40, &uv);
  const std::vector<VertexCurvature> fit = FitVertexCurvatures(mesh);
  std::vector<Eigen::Vector3d> lines;
  for (const VertexCurvature& c : fit) lines.push_back(c.fitted ? c.d1 : Eigen::Vector3d::Zero());
  const std::vector<double> index = LineFieldIndices(mesh, lines);
  double near = 0.0;
  int elsewhere = 0;
  for (size_t k = 0; k < index.size(); ++k) {
    if (uv[k].norm() < 0.3)
      near += index[k];
    else if (uv[k].cwiseAbs().maxCoeff() < 0.8 && std::abs(index[k]) > 0.25)
      ++elsewhere;
  }
  std::printf("monkey saddle: index sum near the flat point %.4f, singular vertices elsewhere %d\n",
              near, elsewhere);
  EXPECT_NEAR(near, -0.5, 0.02);
  EXPECT_EQ(elsewhere, 0);
}

// The principal directions as a cross (4-fold): the umbilic of a paraboloid of revolution has
// index +1 in all, split by the smoothed cross into singularities of index +¼ near it.
TEST(CurvatureFieldTest, PrincipalCrossSplitsAnUmbilicIntoQuarters) {
  std::vector<Eigen::Vector2d> uv;
  const PolyMesh mesh =
      Triangulate([](double x, double y) { return Eigen::Vector3d(x, y, 0.5 * (x * x + y * y)); },
                  -1, 1, -1, 1, 40, &uv, 3);
  const DirectionField field = EstimateDirectionField(mesh, DirectionKind::kPrincipal, {}, 1.0);
  EXPECT_EQ(field.symmetry, 4);
  double total = 0.0;
  for (const Singularity& s : field.singularities) {
    EXPECT_EQ(s.index, 0.25);
    EXPECT_LT(uv[s.vertex].norm(), 0.4);
    total += s.index;
  }
  EXPECT_EQ(total, 1.0);
  // The asymptotic pair of a saddle stays a line field (halves).
  const PolyMesh saddle = Triangulate(
      [](double x, double y) { return Eigen::Vector3d(x, y, x * x * x - 3 * x * y * y); }, -1, 1,
      -1, 1, 40, &uv);
  const DirectionField pair = EstimateDirectionField(saddle, DirectionKind::kAsymptotic, {}, 1.0);
  EXPECT_EQ(pair.symmetry, 2);
  ASSERT_EQ(pair.singularities.size(), 1u);
  EXPECT_EQ(pair.singularities[0].index, -0.5);
}

// Smoothing (Knöppel et al. 2013) on a noisy triangulation of z = xy (heights jittered by
// ±0.004): the principal lines end closer to the analytic ones (the bisectors of the rulings)
// than the fit alone, on average and at the worst vertex.
TEST(CurvatureFieldTest, SmoothingBringsNoisyPrincipalLinesBackToTheAnalyticOnes) {
  std::mt19937 random(3);
  std::uniform_real_distribution<double> noise(-0.004, 0.004);
  std::vector<Eigen::Vector2d> uv;
  PolyMesh mesh = Triangulate([](double x, double y) { return Eigen::Vector3d(x, y, x * y); }, -1,
                              1, -1, 1, 40, &uv);
  for (auto v : mesh.vertices()) {
    auto p = mesh.point(v);
    p[2] += noise(random);
    mesh.set_point(v, p);
  }
  const std::vector<VertexCurvature> fit = FitVertexCurvatures(mesh);
  const std::vector<Eigen::Vector3d> smooth = SmoothPrincipalField(mesh, fit, 1.0);
  auto errors = [&](const std::function<Eigen::Vector3d(size_t)>& line) {
    double worst = 0.0, mean = 0.0;
    int count = 0;
    for (size_t k = 0; k < uv.size(); ++k) {
      if (uv[k].cwiseAbs().maxCoeff() > 0.8) continue;
      const Eigen::Vector3d a = Eigen::Vector3d(1, 0, uv[k].y()).normalized();
      const Eigen::Vector3d b = Eigen::Vector3d(0, 1, uv[k].x()).normalized();
      const double e = std::min(LineAngleDeg(line(k), a + b), LineAngleDeg(line(k), a - b));
      worst = std::max(worst, e);
      mean += e;
      ++count;
    }
    return std::pair(mean / count, worst);
  };
  const auto [fit_mean, fit_worst] = errors([&](size_t k) { return fit[k].d1; });
  const auto [smooth_mean, smooth_worst] = errors([&](size_t k) { return smooth[k]; });
  std::printf(
      "noisy z = xy, principal line error (deg): fit mean %.2f max %.2f; smoothed mean "
      "%.2f max %.2f\n",
      fit_mean, fit_worst, smooth_mean, smooth_worst);
  EXPECT_LT(smooth_mean, 0.5 * fit_mean);
  EXPECT_LT(smooth_worst, 0.5 * fit_worst);
  // The monkey saddle's singularity survives the smoothing.
  uv.clear();
  const PolyMesh saddle = Triangulate(
      [](double x, double y) { return Eigen::Vector3d(x, y, x * x * x - 3 * x * y * y); }, -1, 1,
      -1, 1, 40, &uv);
  const std::vector<double> index =
      LineFieldIndices(saddle, SmoothPrincipalField(saddle, FitVertexCurvatures(saddle), 1.0));
  double near = 0.0;
  int elsewhere = 0;
  for (size_t k = 0; k < index.size(); ++k) {
    if (uv[k].norm() < 0.3)
      near += index[k];
    else if (std::abs(index[k]) > 0.25)
      ++elsewhere;
  }
  EXPECT_NEAR(near, -0.5, 0.02);
  EXPECT_EQ(elsewhere, 0);
}

// Computed at unit scale: the monkey saddle scaled by 1e150 or 1e-150, or moved 1e8 away,
// gives the same single singularity and curvatures scaled accordingly. A tilted plane has no
// asymptotic directions (its fitted curvatures are noise, taken as 0), and its principal
// directions are undefined: no singularities are reported.
TEST(CurvatureFieldTest, ScaleAndPositionDoNotMatterAndPlanesHaveNoField) {
  std::vector<Eigen::Vector2d> uv;
  const PolyMesh saddle = Triangulate(
      [](double x, double y) { return Eigen::Vector3d(x, y, x * x * x - 3 * x * y * y); }, -1, 1,
      -1, 1, 20, &uv);
  const DirectionField reference = EstimateDirectionField(saddle, DirectionKind::kAsymptotic);
  ASSERT_EQ(reference.singularities.size(), 1u);
  for (const auto& [scale, shift] :
       {std::pair{1e150, 0.0}, std::pair{1e-150, 0.0}, std::pair{1.0, 1e8}}) {
    PolyMesh moved = saddle;
    for (auto v : moved.vertices())
      moved.set_point(v, moved.point(v) * scale + PolyMesh::Point(shift, shift, 0));
    const DirectionField f = EstimateDirectionField(moved, DirectionKind::kAsymptotic);
    ASSERT_EQ(f.singularities.size(), 1u) << scale << " " << shift;
    EXPECT_EQ(f.singularities[0].vertex, reference.singularities[0].vertex);
    const VertexCurvature &a = f.curvature[100], &b = reference.curvature[100];
    EXPECT_NEAR(a.k1 * scale, b.k1, 1e-6 * std::abs(b.k1)) << scale << " " << shift;
  }
  uv.clear();
  const PolyMesh plane =
      Triangulate([](double x, double y) { return Eigen::Vector3d(x, y, 0.3 * x + 0.2 * y); }, -1,
                  1, -1, 1, 20, &uv);
  EXPECT_THROW(EstimateDirectionField(plane, DirectionKind::kAsymptotic), InputError);
  const DirectionField principal = EstimateDirectionField(plane, DirectionKind::kPrincipal);
  EXPECT_GT(principal.undefined_area_fraction, 0.99);
  EXPECT_FALSE(principal.singularities_reliable);
  EXPECT_TRUE(principal.singularities.empty());
  CurvatureFitOptions many;
  many.min_points = 1000;
  EXPECT_THROW(EstimateDirectionField(saddle, DirectionKind::kPrincipal, many), InputError);
}

TEST(CurvatureFieldTest, InvalidOptionsAreRefused) {
  std::vector<Eigen::Vector2d> uv;
  const PolyMesh mesh =
      Triangulate([](double x, double y) { return Eigen::Vector3d(x, y, 0); }, 0, 1, 0, 1, 4, &uv);
  CurvatureFitOptions o;
  o.min_points = 5;
  EXPECT_THROW(FitVertexCurvatures(mesh, o), InputError);
  o = CurvatureFitOptions();
  o.monge_degree = 4;
  EXPECT_THROW(FitVertexCurvatures(mesh, o), InputError);
  EXPECT_THROW(FitVertexCurvatures(PolyMesh()), InputError);
}

}  // namespace
}  // namespace gproj
