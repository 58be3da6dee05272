#include "gproj/geometry/surface/bspline_surface.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>

namespace gproj {
namespace {

// A clamped knot vector over [lo, hi] for `count` control points with jittered interior knots.
std::vector<double> JitteredKnots(int count, int degree, double lo, double hi, std::mt19937& rng) {
  std::vector<double> knots = UniformClampedKnots(count, degree);
  const int spans = count - degree;
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  for (int k = degree + 1; k < count; ++k) knots[k] += jitter(rng) / spans;
  for (double& t : knots) t = lo + (hi - lo) * t;
  return knots;
}

// A random surface of the given bi-degree over [0.5, 2] × [−1, 0.25], non-uniform knots.
BSplineSurface RandomSurface(int du, int dv, int nu, int nv, unsigned seed) {
  std::mt19937 rng(seed);
  BSplineSurface s;
  s.degree_u = du;
  s.degree_v = dv;
  s.nu = nu;
  s.nv = nv;
  s.knots_u = JitteredKnots(nu, du, 0.5, 2.0, rng);
  s.knots_v = JitteredKnots(nv, dv, -1.0, 0.25, rng);
  std::uniform_real_distribution<double> noise(-0.2, 0.2);
  s.control.resize(nu * nv, 3);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j)
      s.control.row(s.Index(i, j)) =
          Eigen::RowVector3d(i + noise(rng), j + noise(rng), std::sin(i + 2.0 * j) + noise(rng));
  ValidateBSpline(s);
  return s;
}

bool NearAKnot(const std::vector<double>& knots, double t, double gap) {
  for (double k : knots)
    if (std::abs(k - t) < gap) return true;
  return false;
}

// Mean and Gaussian curvature from the derivatives at (u, v).
struct Curvatures {
  double h = 0.0, k = 0.0;
};
Curvatures CurvaturesAt(const BSplineSurface& s, double u, double v) {
  const auto d = s.Derivatives(u, v);
  const double e = d[1].dot(d[1]), f = d[1].dot(d[2]), g = d[2].dot(d[2]);
  const double delta = e * g - f * f;
  const Eigen::Vector3d n = d[1].cross(d[2]) / std::sqrt(delta);
  const double l = d[3].dot(n), m = d[4].dot(n), nn = d[5].dot(n);
  return {(l * g - 2.0 * m * f + nn * e) / (2.0 * delta), (l * nn - m * m) / delta};
}

std::string Scientific(double x) {
  std::ostringstream s;
  s << std::scientific << std::setprecision(2) << x;
  return s.str();
}

double NetSize(const BSplineSurface& s) {
  return (s.control.colwise().maxCoeff() - s.control.colwise().minCoeff()).norm();
}

std::string MessageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

#define EXPECT_MESSAGE_HAS(message, text) \
  EXPECT_NE((message).find(text), std::string::npos) << (message)

void ExpectDerivativesMatchFiniteDifferences(const BSplineSurface& s, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uu(s.u_min(), s.u_max()), vv(s.v_min(), s.v_max());
  const double h1 = 1e-5, h2 = 1e-4, scale = NetSize(s);
  int checked = 0;
  while (checked < 25) {
    const double u = uu(rng), v = vv(rng);
    if (NearAKnot(s.knots_u, u, 3 * h2) || NearAKnot(s.knots_v, v, 3 * h2)) continue;
    ++checked;
    const auto d = s.Derivatives(u, v);
    const auto p = [&](double du, double dv) { return s.Point(u + du, v + dv); };
    EXPECT_LT((d[0] - p(0, 0)).norm(), 1e-14 * scale);
    const Eigen::Vector3d su = (p(h1, 0) - p(-h1, 0)) / (2 * h1);
    const Eigen::Vector3d sv = (p(0, h1) - p(0, -h1)) / (2 * h1);
    const Eigen::Vector3d suu = (p(h2, 0) - 2 * p(0, 0) + p(-h2, 0)) / (h2 * h2);
    const Eigen::Vector3d svv = (p(0, h2) - 2 * p(0, 0) + p(0, -h2)) / (h2 * h2);
    const Eigen::Vector3d suv = (p(h2, h2) - p(h2, -h2) - p(-h2, h2) + p(-h2, -h2)) / (4 * h2 * h2);
    EXPECT_LT((d[1] - su).norm(), 1e-6 * (1 + d[1].norm())) << "s_u at " << u << ", " << v;
    EXPECT_LT((d[2] - sv).norm(), 1e-6 * (1 + d[2].norm())) << "s_v at " << u << ", " << v;
    EXPECT_LT((d[3] - suu).norm(), 1e-4 * (1 + d[3].norm())) << "s_uu at " << u << ", " << v;
    EXPECT_LT((d[4] - suv).norm(), 1e-4 * (1 + d[4].norm())) << "s_uv at " << u << ", " << v;
    EXPECT_LT((d[5] - svv).norm(), 1e-4 * (1 + d[5].norm())) << "s_vv at " << u << ", " << v;
  }
}

TEST(BSplineSurfaceTest, DerivativesMatchFiniteDifferencesDegree44) {
  const BSplineSurface s = RandomSurface(4, 4, 9, 8, 1);
  ExpectDerivativesMatchFiniteDifferences(s, 11);
  // The second derivatives are not trivially zero.
  EXPECT_GT(s.Derivatives(1.1, -0.4)[3].norm(), 1e-2);
}

TEST(BSplineSurfaceTest, DerivativesMatchFiniteDifferencesDegree32) {
  ExpectDerivativesMatchFiniteDifferences(RandomSurface(3, 2, 7, 6, 2), 12);
  ExpectDerivativesMatchFiniteDifferences(RandomSurface(2, 5, 5, 9, 3), 13);
}

TEST(BSplineSurfaceTest, DegreeOneIsBilinear) {
  BSplineSurface s;
  s.degree_u = s.degree_v = 1;
  s.nu = s.nv = 2;
  s.knots_u = s.knots_v = {0, 0, 1, 1};
  s.control.resize(4, 3);
  s.control << 0, 0, 0, 0, 1, 0.5, 1, 0, -0.25, 1, 1, 2;
  const auto d = s.Derivatives(0.3, 0.6);
  const Eigen::Vector3d c00 = s.control.row(0), c01 = s.control.row(1), c10 = s.control.row(2),
                        c11 = s.control.row(3);
  const Eigen::Vector3d expected =
      0.7 * 0.4 * c00 + 0.7 * 0.6 * c01 + 0.3 * 0.4 * c10 + 0.3 * 0.6 * c11;
  EXPECT_LT((d[0] - expected).norm(), 1e-15);
  EXPECT_LT((d[1] - (0.4 * (c10 - c00) + 0.6 * (c11 - c01))).norm(), 1e-15);
  EXPECT_EQ(d[3], Eigen::Vector3d::Zero());
  EXPECT_EQ(d[5], Eigen::Vector3d::Zero());
  EXPECT_LT((d[4] - (c11 - c10 - c01 + c00)).norm(), 1e-15);
  // Degree 1 in one direction only.
  ExpectDerivativesMatchFiniteDifferences(RandomSurface(1, 3, 5, 6, 4), 14);
}

TEST(BSplineSurfaceTest, ClampedCornersAndDomainEnd) {
  const BSplineSurface s = RandomSurface(3, 2, 7, 6, 5);
  EXPECT_LT((s.Point(s.u_min(), s.v_min()) - s.control.row(0).transpose()).norm(), 1e-14);
  EXPECT_LT((s.Point(s.u_max(), s.v_max()) - s.control.row(s.Index(6, 5)).transpose()).norm(),
            1e-13);
  EXPECT_LT((s.Point(s.u_max(), s.v_min()) - s.control.row(s.Index(6, 0)).transpose()).norm(),
            1e-13);
  // At u_max the last span is used: derivatives are the limits from inside.
  const auto end = s.Derivatives(s.u_max(), 0.0);
  const auto inside = s.Derivatives(s.u_max() - 1e-9, 0.0);
  for (int k = 0; k < 6; ++k) EXPECT_LT((end[k] - inside[k]).norm(), 1e-5) << k;
  EXPECT_GT(end[1].norm(), 0.1);
}

TEST(BSplineSurfaceTest, PartitionOfUnity) {
  BSplineSurface s = RandomSurface(4, 3, 8, 7, 6);
  const Eigen::RowVector3d c(1.5, -2.0, 0.25);
  s.control.rowwise() = c;
  for (double u : {0.5, 0.77, 1.3, 2.0})
    for (double v : {-1.0, -0.31, 0.25}) {
      const auto d = s.Derivatives(u, v);
      EXPECT_LT((d[0] - c.transpose()).norm(), 1e-14);
      for (int k = 1; k < 6; ++k) EXPECT_LT(d[k].norm(), 1e-11) << k;
    }
}

TEST(BSplineSurfaceTest, SampleMapsReproduceDerivatives) {
  for (const auto& [du, dv] : {std::pair{4, 4}, std::pair{3, 2}, std::pair{1, 2}}) {
    const BSplineSurface s = RandomSurface(du, dv, 8, 7, 7 + du);
    const SampleMaps maps = MakeSampleMaps(s, 9, 6);
    ASSERT_EQ(maps.num_samples(), 54);
    EXPECT_NEAR(maps.u[0], s.u_min() + 0.5 * (s.u_max() - s.u_min()) / 9, 1e-15);
    EXPECT_NEAR(maps.v[5], s.v_max() - 0.5 * (s.v_max() - s.v_min()) / 6, 1e-15);
    for (int k = 0; k < 6; ++k) {
      ASSERT_EQ(maps.d[k].rows(), 54);
      ASSERT_EQ(maps.d[k].cols(), s.num_control_points());
      EXPECT_EQ(maps.d[k].nonZeros(), 54 * (du + 1) * (dv + 1));
      const Eigen::MatrixX3d values = maps.d[k] * s.control;
      for (int a = 0; a < maps.su; ++a)
        for (int b = 0; b < maps.sv; ++b) {
          const Eigen::Vector3d expected = s.Derivatives(maps.u[a], maps.v[b])[k];
          EXPECT_LT((values.row(maps.Index(a, b)).transpose() - expected).norm(),
                    1e-12 * (1 + expected.norm()))
              << "map " << k << " sample " << a << ", " << b;
        }
    }
  }
}

TEST(BSplineSurfaceTest, LargeSampleMapsArePartitionsOfUnity) {
  BSplineSurface s;
  s.degree_u = s.degree_v = 3;
  s.nu = s.nv = 100;
  s.knots_u = s.knots_v = UniformClampedKnots(100, 3);
  s.control = Eigen::MatrixX3d::Random(100 * 100, 3);
  const SampleMaps maps = MakeSampleMaps(s, 200, 200);
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(s.num_control_points());
  EXPECT_EQ(maps.d[0].nonZeros(), 200 * 200 * 16);
  EXPECT_LT(((maps.d[0] * ones).array() - 1.0).abs().maxCoeff(), 1e-13);
  for (int k = 1; k < 6; ++k) EXPECT_LT((maps.d[k] * ones).cwiseAbs().maxCoeff(), 1e-8) << k;
  const int a = 137, b = 59;
  const Eigen::Vector3d suv = s.Derivatives(maps.u[a], maps.v[b])[4];
  EXPECT_LT((maps.d[4].row(maps.Index(a, b)) * s.control - suv.transpose()).norm(),
            1e-12 * suv.norm());
  EXPECT_GT(suv.norm(), 1.0);
}

TEST(BSplineSurfaceTest, FitReproducesPolynomials) {
  const auto f = [](double u, double v) {
    return Eigen::Vector3d(u * u * u - v, u * v * v + 2.0, u * u * v * v * v);
  };
  const BSplineSurface s = FitBSpline(f, 3, 3, 6, 5);
  EXPECT_EQ(s.num_control_points(), 30);
  for (double u : {0.0, 0.13, 0.5, 0.91, 1.0})
    for (double v : {0.0, 0.37, 0.64, 1.0}) EXPECT_LT((s.Point(u, v) - f(u, v)).norm(), 1e-12);
  // A degree too low cannot reproduce it.
  EXPECT_GT((FitBSpline(f, 2, 2, 3, 3).Point(0.3, 0.3) - f(0.3, 0.3)).norm(), 1e-4);
}

TEST(BSplineSurfaceTest, FitsALargeNet) {
  const auto f = [](double u, double v) {
    return Eigen::Vector3d(u, v, 0.2 * std::sin(6 * u) * std::cos(5 * v));
  };
  const BSplineSurface s = FitBSpline(f, 4, 4, 40, 40);
  EXPECT_EQ(s.num_control_points(), 1600);
  double worst = 0.0;
  for (int a = 0; a <= 50; ++a)
    for (int b = 0; b <= 50; ++b)
      worst = std::max(worst, (s.Point(a / 50.0, b / 50.0) - f(a / 50.0, b / 50.0)).norm());
  EXPECT_LT(worst, 1e-8);
}

TEST(BSplineSurfaceTest, FittedSphereHasConstantCurvatures) {
  const double r = 2.0;
  const auto sphere = [r](double u, double v) {
    const double theta = -0.5 + u, phi = v;
    return Eigen::Vector3d(r * std::cos(theta) * std::cos(phi), r * std::cos(theta) * std::sin(phi),
                           r * std::sin(theta));
  };
  const BSplineSurface s = FitBSpline(sphere, 4, 4, 12, 12);
  double max_h = 0.0, max_k = 0.0;
  for (int a = 1; a < 10; ++a)
    for (int b = 1; b < 10; ++b) {
      const Curvatures c = CurvaturesAt(s, a / 10.0, b / 10.0);
      max_k = std::max(max_k, std::abs(c.k * r * r - 1.0));
      max_h = std::max(max_h, std::abs(std::abs(c.h) * r - 1.0));
    }
  EXPECT_LT(max_k, 1e-4);
  EXPECT_LT(max_h, 1e-4);
  RecordProperty("sphere_relative_error_K", Scientific(max_k));
  RecordProperty("sphere_relative_error_H", Scientific(max_h));
}

TEST(BSplineSurfaceTest, FittedCylinderHasConstantCurvatures) {
  const double r = 1.5;
  const auto cylinder = [r](double u, double v) {
    return Eigen::Vector3d(r * std::cos(1.2 * u), r * std::sin(1.2 * u), 2.0 * v);
  };
  const BSplineSurface s = FitBSpline(cylinder, 4, 4, 12, 12);
  double max_h = 0.0, max_k = 0.0;
  for (int a = 1; a < 10; ++a)
    for (int b = 1; b < 10; ++b) {
      const Curvatures c = CurvaturesAt(s, a / 10.0, b / 10.0);
      max_k = std::max(max_k, std::abs(c.k) * r * r);
      max_h = std::max(max_h, std::abs(std::abs(c.h) * 2.0 * r - 1.0));
    }
  EXPECT_LT(max_k, 1e-4);
  EXPECT_LT(max_h, 1e-4);
  RecordProperty("cylinder_abs_error_K_R2", Scientific(max_k));
  RecordProperty("cylinder_relative_error_H", Scientific(max_h));
}

TEST(BSplineSurfaceTest, KnotInsertionKeepsTheSurface) {
  for (const auto& [du, dv] : {std::pair{3, 2}, std::pair{4, 4}, std::pair{1, 3}}) {
    const BSplineSurface s = RandomSurface(du, dv, 7, 6, 20 + du);
    const BSplineSurface t = InsertKnotsUniform(s, 2);
    ValidateBSpline(t);
    EXPECT_EQ(t.nu, s.nu + 2 * (s.nu - du));
    EXPECT_EQ(t.nv, s.nv + 2 * (s.nv - dv));
    EXPECT_EQ(t.u_min(), s.u_min());
    EXPECT_EQ(t.v_max(), s.v_max());
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> uu(s.u_min(), s.u_max()), vv(s.v_min(), s.v_max());
    for (int k = 0; k < 100; ++k) {
      const double u = k == 0 ? s.u_max() : uu(rng), v = k == 0 ? s.v_max() : vv(rng);
      EXPECT_LT((t.Point(u, v) - s.Point(u, v)).norm(), 1e-12)
          << du << dv << " at " << u << ", " << v;
      EXPECT_LT((t.Derivatives(u, v)[1] - s.Derivatives(u, v)[1]).norm(), 1e-10);
    }
    // The new net is a different, denser net.
    EXPECT_GT((t.control.row(t.Index(1, 1)) - s.control.row(s.Index(1, 1))).norm(), 1e-3);
  }
  const BSplineSurface s = RandomSurface(3, 3, 6, 6, 30);
  const BSplineSurface same = InsertKnotsUniform(s, 0);
  EXPECT_EQ(same.control, s.control);
}

TEST(BSplineSurfaceTest, JsonRoundTrip) {
  const BSplineSurface s = RandomSurface(4, 2, 7, 5, 40);
  const BSplineSurface t = ParseBSplineJson(BSplineToJson(s));
  EXPECT_EQ(t.degree_u, 4);
  EXPECT_EQ(t.degree_v, 2);
  EXPECT_EQ(t.nu, 7);
  EXPECT_EQ(t.nv, 5);
  EXPECT_EQ(t.knots_u, s.knots_u);
  EXPECT_EQ(t.knots_v, s.knots_v);
  EXPECT_EQ(t.control, s.control);

  const auto dir = std::filesystem::path(::testing::TempDir()) / "gproj_bspline_json";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "surface.json").string();
  WriteBSplineJson(s, path);
  const BSplineSurface read = ReadBSplineJson(path);
  EXPECT_EQ(read.control, s.control);
  EXPECT_EQ(read.knots_v, s.knots_v);
  std::filesystem::remove_all(dir);
}

TEST(BSplineSurfaceTest, JsonFollowsTheSpecLayout) {
  const std::string text = R"({"degree": [1, 2], "knots_u": [0, 0, 1, 1],
    "knots_v": [0, 0, 0, 1, 1, 1],
    "control_points": [[[0, 0, 0], [0, 1, 1], [0, 2, 0]], [[1, 0, 0], [1, 1, 3], [1, 2, 0]]]})";
  const BSplineSurface s = ParseBSplineJson(text);
  EXPECT_EQ(s.nu, 2);
  EXPECT_EQ(s.nv, 3);
  EXPECT_EQ(s.control.row(s.Index(1, 1)), Eigen::RowVector3d(1, 1, 3));
  EXPECT_LT((s.Point(1.0, 0.5) - Eigen::Vector3d(1, 1, 1.5)).norm(), 1e-15);
}

TEST(BSplineSurfaceTest, EveryValidationRuleIsRefused) {
  const BSplineSurface good = RandomSurface(4, 3, 9, 7, 50);
  EXPECT_NO_THROW(ValidateBSpline(good));
  const auto refused = [&](const std::function<void(BSplineSurface&)>& change) {
    BSplineSurface s = good;
    change(s);
    return MessageOf([&] { ValidateBSpline(s); });
  };
  EXPECT_MESSAGE_HAS(refused([](auto& s) { s.degree_u = 0; }), "degree_u must be ≥ 1");
  EXPECT_MESSAGE_HAS(refused([](auto& s) { s.degree_v = -1; }), "degree_v must be ≥ 1");
  EXPECT_MESSAGE_HAS(refused([](auto& s) { s.nv = 3; }), "needs at least 4 (degree + 1)");
  EXPECT_EQ(refused([](auto& s) { s.knots_u.resize(12); }),
            "knots_u has 12 values; 9 control points of degree 4 need 14 (count + degree + 1)");
  EXPECT_MESSAGE_HAS(refused([](auto& s) { s.knots_v[5] = std::nan(""); }),
                     "knots_v[5] is not finite");
  EXPECT_MESSAGE_HAS(refused([](auto& s) { s.knots_v[5] = s.knots_v[4] - 0.01; }),
                     "knots_v decreases at index 5");
  EXPECT_MESSAGE_HAS(refused([](auto& s) { s.knots_u[0] -= 0.1; }),
                     "knots_u is not clamped: the first 5 values must be equal");
  EXPECT_MESSAGE_HAS(refused([](auto& s) { s.knots_v.back() += 0.1; }),
                     "knots_v is not clamped: the last 4 values must be equal");
  EXPECT_MESSAGE_HAS(refused([](auto& s) { std::fill(s.knots_u.begin(), s.knots_u.end(), 1.0); }),
                     "knots_u has an empty domain");
  EXPECT_MESSAGE_HAS(refused([](auto& s) { s.control.conservativeResize(62, 3); }),
                     "control has 62 rows; nu × nv = 9 × 7 needs 63");
  EXPECT_MESSAGE_HAS(refused([](auto& s) { s.control(s.Index(3, 2), 1) = INFINITY; }),
                     "control_points[3][2] is not finite");
  // `where` is named first.
  const std::string named = MessageOf([&] {
    BSplineSurface s = good;
    s.degree_u = 0;
    ValidateBSpline(s, "net.json");
  });
  EXPECT_EQ(named.rfind("net.json: degree_u", 0), 0u) << named;
}

TEST(BSplineSurfaceTest, JsonErrorsNameTheField) {
  const nlohmann::json good = nlohmann::json::parse(BSplineToJson(RandomSurface(2, 2, 5, 8, 60)));
  const auto refused = [&](const std::function<void(nlohmann::json&)>& change) {
    nlohmann::json j = good;
    change(j);
    return MessageOf([&] { ParseBSplineJson(j.dump(), "s.json"); });
  };
  const std::string broken = MessageOf([] { ParseBSplineJson("{\"degree\": [3, 3],", "s.json"); });
  EXPECT_EQ(broken.rfind("s.json: ", 0), 0u) << broken;
  EXPECT_MESSAGE_HAS(broken, "invalid JSON");
  EXPECT_MESSAGE_HAS(
      MessageOf([&] { ParseBSplineJson(good.dump() + std::string(1, '\0'), "s.json"); }),
      "s.json: a NUL byte at byte");
  EXPECT_MESSAGE_HAS(MessageOf([] { ParseBSplineJson("[1, 2]", "s.json"); }), "JSON object");
  EXPECT_MESSAGE_HAS(refused([](auto& j) { j.erase("knots_v"); }), "missing field \"knots_v\"");
  EXPECT_MESSAGE_HAS(refused([](auto& j) { j["degree"] = nlohmann::json::array({3}); }),
                     "degree must be");
  EXPECT_MESSAGE_HAS(refused([](auto& j) {
                       j["degree"] = nlohmann::json::array({3, 2.5});
                     }),
                     "degree must be");
  EXPECT_MESSAGE_HAS(refused([](auto& j) { j["knots_u"] = 3; }), "knots_u must be an array");
  EXPECT_MESSAGE_HAS(refused([](auto& j) { j["knots_u"][2] = "0"; }), "knots_u[2] is not a number");
  EXPECT_MESSAGE_HAS(refused([](auto& j) { j["control_points"] = "none"; }),
                     "control_points must be an array");
  EXPECT_MESSAGE_HAS(refused([](auto& j) { j["control_points"][2] = 1; }),
                     "control_points[2] must be an array");
  EXPECT_EQ(refused([](auto& j) { j["control_points"][4].erase(7); }),
            "s.json: control_points[4] has 7 points, control_points[0] has 8");
  EXPECT_MESSAGE_HAS(refused([](auto& j) {
                       j["control_points"][1][2] = nlohmann::json::array({1, 2});
                     }),
                     "control_points[1][2] must be an array of three numbers");
  EXPECT_MESSAGE_HAS(refused([](auto& j) { j["control_points"][1][2][0] = nullptr; }),
                     "control_points[1][2][0] is not a number");
  // Rule violations found after parsing carry the path too.
  const std::string decreasing = refused([](auto& j) { j["knots_v"][4] = -5.0; });
  EXPECT_EQ(decreasing.rfind("s.json: knots_v decreases at index 4", 0), 0u) << decreasing;
  EXPECT_MESSAGE_HAS(refused([](auto& j) { j["degree"][0] = 0; }), "s.json: degree_u must be ≥ 1");
  // A number that overflows a double is refused by the parser, with the path.
  std::string text = good.dump();
  const std::string first = good["control_points"][3][2][1].dump();
  text.replace(text.find(first, text.find("control_points")), first.size(), "1e999");
  const std::string overflow = MessageOf([&] { ParseBSplineJson(text, "s.json"); });
  EXPECT_EQ(overflow.rfind("s.json: invalid JSON", 0), 0u) << overflow;
  EXPECT_MESSAGE_HAS(overflow, "1e999");
  EXPECT_MESSAGE_HAS(MessageOf([] { ReadBSplineJson("/nonexistent/dir/b.json"); }),
                     "/nonexistent/dir/b.json");
}

// A surface's JSON with `nu` × `nv` control points of degree 3, uniform knots.
std::string GridJson(int nu, int nv) {
  std::ostringstream out;
  const auto knots = [&](int n) {
    out << '[';
    const std::vector<double> k = UniformClampedKnots(n, 3);
    for (size_t i = 0; i < k.size(); ++i) out << (i ? "," : "") << k[i];
    out << ']';
  };
  out << "{\"degree\": [3, 3], \"knots_u\": ";
  knots(nu);
  out << ", \"knots_v\": ";
  knots(nv);
  out << ", \"control_points\": [";
  for (int i = 0; i < nu; ++i) {
    out << (i ? ",[" : "[");
    for (int j = 0; j < nv; ++j) out << (j ? "," : "") << '[' << i << ',' << j << ",0]";
    out << ']';
  }
  out << "]}";
  return out.str();
}

TEST(BSplineSurfaceTest, HugeDegreeIsRefusedWithoutOverflow) {
  std::string text = GridJson(5, 5);
  text.replace(text.find("[3, 3]"), 6, "[2147483647, 4]");
  EXPECT_EQ(MessageOf([&] { ParseBSplineJson(text, "d.json"); }),
            "d.json: degree_u must be ≤ 11 (got 2147483647)");
  text.replace(text.find("2147483647"), 10, "18446744073709551615");
  EXPECT_EQ(MessageOf([&] { ParseBSplineJson(text, "d.json"); }),
            "d.json: degree_u must be ≤ 11 (got 18446744073709551615)");
  text.replace(text.find("18446744073709551615"), 20, "-9223372036854775808");
  EXPECT_EQ(MessageOf([&] { ParseBSplineJson(text, "d.json"); }),
            "d.json: degree_u must be ≥ 1 (got -9223372036854775808)");
  // Through the validation of a surface built in code, degree + 1 does not overflow either.
  BSplineSurface s = MakeWavyBSpline(4, 4, 3);
  s.degree_v = std::numeric_limits<int>::max();
  EXPECT_EQ(MessageOf([&] { ValidateBSpline(s); }),
            "nv = 4 control points along v; degree 2147483647 needs at least 2147483648 "
            "(degree + 1)");
}

TEST(BSplineSurfaceTest, MillionControlPointsAreRefusedWhileParsing) {
  EXPECT_EQ(ParseBSplineJson(GridJson(6, 7)).num_control_points(), 42);
  EXPECT_EQ(MessageOf([] { ParseBSplineJson(GridJson(1000, 1000), "m.json"); }),
            "m.json: control_points has more than 40000 points; gproj reads B-spline surfaces "
            "of at most that many");
  // Values other than control points are bounded too.
  std::string padded = "{\"pad\": [";
  for (int i = 0; i < 320001; ++i) padded += "0,";
  padded += "0]}";
  EXPECT_EQ(MessageOf([&] { ParseBSplineJson(padded, "p.json"); }),
            "p.json: the file has more than 320000 JSON values; a B-spline surface of at most "
            "40000 control points has fewer");
}

TEST(BSplineSurfaceTest, ByteOrderMarkAndCrlfAreAccepted) {
  std::string text = GridJson(4, 5);
  for (size_t i = text.find(','); i != std::string::npos; i = text.find(',', i + 3)) {
    text.insert(i + 1, "\r\n");
  }
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "gproj_bspline_bom.json";
  std::ofstream(path, std::ios::binary) << "\xEF\xBB\xBF" << text;
  const BSplineSurface s = ReadBSplineJson(path.string());
  EXPECT_EQ(s.nu, 4);
  EXPECT_EQ(s.control(s.Index(3, 4), 1), 4.0);
}

TEST(BSplineSurfaceTest, RefitOntoANestedNetIsExact) {
  BSplineSurface s = RandomSurface(3, 3, 6, 6, 70);
  s.knots_u = s.knots_v = UniformClampedKnots(6, 3);  // spans of 1/3
  const BSplineSurface t = RefitBSpline(s, 12, 15);   // spans of 1/9 and 1/12
  EXPECT_EQ(t.nu, 12);
  EXPECT_EQ(t.nv, 15);
  double worst = 0.0;
  for (int a = 0; a <= 40; ++a)
    for (int b = 0; b <= 40; ++b)
      worst = std::max(worst, (t.Point(a / 40.0, b / 40.0) - s.Point(a / 40.0, b / 40.0)).norm());
  EXPECT_LT(worst, 1e-10 * NetSize(s));
}

TEST(BSplineSurfaceTest, RefitOntoADenserNetReproducesTheSurface) {
  // A fitted surface on a non-[0, 1] domain, refitted onto a net whose knots are not nested.
  BSplineSurface s = FitBSpline(
      [](double u, double v) {
        return Eigen::Vector3d(u + 0.1 * std::sin(3 * v), v, 0.3 * std::cos(2 * u) * std::sin(v));
      },
      4, 4, 8, 8);
  for (double& k : s.knots_u) k = 2.0 + 3.0 * k;
  const BSplineSurface t = RefitBSpline(s, 15, 17);
  double worst = 0.0;
  for (int a = 0; a <= 40; ++a)
    for (int b = 0; b <= 40; ++b)
      worst = std::max(
          worst, (t.Point(a / 40.0, b / 40.0) - s.Point(2.0 + 3.0 * a / 40.0, b / 40.0)).norm());
  EXPECT_LT(worst, 1e-6 * NetSize(s));
  RecordProperty("refit_relative_error", Scientific(worst / NetSize(s)));
}

TEST(BSplineSurfaceTest, MeshesAreQuadGridsInGridOrder) {
  const BSplineSurface s = RandomSurface(3, 2, 5, 4, 80);
  const PolyMesh net = ControlNetMesh(s);
  EXPECT_EQ(net.n_vertices(), 20u);
  EXPECT_EQ(net.n_faces(), 12u);
  const auto p = net.point(PolyMesh::VertexHandle(s.Index(2, 3)));
  EXPECT_EQ(Eigen::RowVector3d(p[0], p[1], p[2]), s.control.row(s.Index(2, 3)));
  std::vector<int> corners;
  for (auto v : net.fv_range(PolyMesh::FaceHandle(0))) corners.push_back(v.idx());
  EXPECT_EQ(corners, (std::vector<int>{0, 4, 5, 1}));

  const PolyMesh sampled = SampleSurfaceMesh(s, 6, 3);
  EXPECT_EQ(sampled.n_vertices(), 28u);
  EXPECT_EQ(sampled.n_faces(), 18u);
  corners.clear();
  for (auto v : sampled.fv_range(PolyMesh::FaceHandle(4))) corners.push_back(v.idx());
  EXPECT_EQ(corners, (std::vector<int>{5, 9, 10, 6}));  // face (1, 1)
  const auto q = sampled.point(PolyMesh::VertexHandle(27));
  EXPECT_LT((Eigen::Vector3d(q[0], q[1], q[2]) - s.Point(s.u_max(), s.v_max())).norm(), 1e-14);
  const auto m = sampled.point(PolyMesh::VertexHandle(2 * 4 + 1));
  const Eigen::Vector3d expected =
      s.Point(s.u_min() + (s.u_max() - s.u_min()) / 3, s.v_min() + (s.v_max() - s.v_min()) / 3);
  EXPECT_LT((Eigen::Vector3d(m[0], m[1], m[2]) - expected).norm(), 1e-14);
}

}  // namespace
}  // namespace gproj

namespace gproj {
namespace {

// A cuspidal edge (u², v, u³), u ∈ [−1, 1]: s_u = 0 along u = 0 and the normal turns over
// there; a smooth wavy surface keeps neighbouring normals together.
TEST(MinNormalCosineTest, FindsTheFoldOfACuspidalEdge) {
  const BSplineSurface cusp = FitBSpline(
      [](double u, double v) {
        const double t = 2.0 * u - 1.0;
        return Eigen::Vector3d(t * t, v, t * t * t);
      },
      3, 3, 6, 4);
  const NormalTurn turn = MinNormalCosine(cusp, 41, 10);
  EXPECT_LT(turn.min_cosine, -0.9);
  EXPECT_NEAR(turn.u, 0.5, 0.03);  // the fold is at u = ½ of the parameter domain
  EXPECT_GT(MinNormalCosine(MakeWavyBSpline(10, 10, 4), 40, 40).min_cosine, 0.99);
}

}  // namespace
}  // namespace gproj
