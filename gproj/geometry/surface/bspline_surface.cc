#include "gproj/geometry/surface/bspline_surface.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "gproj/geometry/io/text_input.h"
#include "gproj/geometry/surface/bspline_basis.h"

namespace gproj {
namespace {

std::string Prefix(const std::string& where) { return where.empty() ? "" : where + ": "; }

std::string Num(double x) {
  std::ostringstream s;
  s.precision(17);
  s << x;
  return s.str();
}

// The knot span k (degree ≤ k ≤ count − 1) with knots[k] ≤ t < knots[k + 1]; t is clamped to the
// domain, and at t = u_max the last non-empty span is used (NURBS Book A2.1).
int FindSpan(const std::vector<double>& knots, int degree, int count, double t) {
  const double lo = knots[degree], hi = knots[count];
  if (!(t > lo)) t = lo;  // NaN too: a valid span (the basis values are then NaN)
  if (t >= hi) {
    int k = count - 1;
    while (k > degree && knots[k] == knots[k + 1]) --k;
    return k;
  }
  // First knot > t among knots[degree + 1 .. count], minus one.
  const auto it = std::upper_bound(knots.begin() + degree + 1, knots.begin() + count + 1, t);
  return static_cast<int>(it - knots.begin()) - 1;
}

// Non-zero basis functions N_{span − degree + r}(t), r = 0..degree, and their first and second
// derivatives: ders(k, r) is the k-th derivative (NURBS Book A2.3 with n = 2).
struct Basis {
  int span = 0;
  Eigen::Matrix<double, 3, Eigen::Dynamic> ders;
};

Basis EvaluateBasis(const std::vector<double>& knots, int degree, int count, double t) {
  const int p = degree;
  Basis b;
  b.span = FindSpan(knots, p, count, t);
  t = std::clamp(t, knots[p], knots[count]);
  const int n = std::min(2, p);
  std::vector<double> scratch(BasisScratchSize(p)), ders((n + 1) * (p + 1));
  BasisFunctionDerivatives([&](int i) { return knots[i]; }, p, b.span, t, n, scratch.data(),
                           ders.data());
  b.ders.setZero(3, p + 1);
  for (int k = 0; k <= n; ++k)
    for (int r = 0; r <= p; ++r) b.ders(k, r) = ders[k * (p + 1) + r];
  return b;
}

std::vector<double> UniformSamples(double lo, double hi, int count) {
  std::vector<double> t(count);
  for (int a = 0; a < count; ++a) t[a] = lo + (a + 0.5) * (hi - lo) / count;
  return t;
}

// Dense collocation matrix: row a holds N_i(t_a), i = 0..count − 1.
Eigen::MatrixXd Collocation(const std::vector<double>& knots, int degree, int count,
                            const std::vector<double>& t) {
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(static_cast<int>(t.size()), count);
  for (int a = 0; a < static_cast<int>(t.size()); ++a) {
    const Basis basis = EvaluateBasis(knots, degree, count, t[a]);
    for (int r = 0; r <= degree; ++r) b(a, basis.span - degree + r) = basis.ders(0, r);
  }
  return b;
}

// Knot refinement of a curve (NURBS Book A5.4): inserts the sorted knots x into `knots`;
// the rows of `points` (count × dim) are the control points. Returns the new control points and
// replaces `knots` by the refined vector.
Eigen::MatrixXd RefineKnotVector(std::vector<double>& knots, int p, const Eigen::MatrixXd& points,
                                 const std::vector<double>& x) {
  if (x.empty()) return points;
  const int n = static_cast<int>(points.rows()) - 1;
  const int m = n + p + 1;
  const int r = static_cast<int>(x.size()) - 1;
  const std::vector<double>& u = knots;
  const int a = FindSpan(u, p, n + 1, x.front());
  const int b = FindSpan(u, p, n + 1, x.back()) + 1;
  Eigen::MatrixXd q(n + r + 2, points.cols());
  std::vector<double> ubar(m + r + 2);
  for (int j = 0; j <= a - p; ++j) q.row(j) = points.row(j);
  for (int j = b - 1; j <= n; ++j) q.row(j + r + 1) = points.row(j);
  for (int j = 0; j <= a; ++j) ubar[j] = u[j];
  for (int j = b + p; j <= m; ++j) ubar[j + r + 1] = u[j];
  int i = b + p - 1, k = b + p + r;
  for (int j = r; j >= 0; --j) {
    while (x[j] <= u[i] && i > a) {
      q.row(k - p - 1) = points.row(i - p - 1);
      ubar[k] = u[i];
      --k;
      --i;
    }
    q.row(k - p - 1) = q.row(k - p);
    for (int l = 1; l <= p; ++l) {
      const int ind = k - p + l;
      double alpha = ubar[k + l] - x[j];
      if (alpha == 0.0) {
        q.row(ind - 1) = q.row(ind);
      } else {
        alpha /= ubar[k + l] - u[i - p + l];
        q.row(ind - 1) = alpha * q.row(ind - 1) + (1.0 - alpha) * q.row(ind);
      }
    }
    ubar[k] = x[j];
    --k;
  }
  knots = std::move(ubar);
  return q;
}

std::vector<double> UniformInsertions(const std::vector<double>& knots, int per_span) {
  std::vector<double> x;
  for (size_t k = 0; k + 1 < knots.size(); ++k) {
    const double lo = knots[k], hi = knots[k + 1];
    if (!(hi > lo)) continue;
    for (int r = 1; r <= per_span; ++r) x.push_back(lo + (hi - lo) * r / (per_span + 1));
  }
  return x;
}

void ValidateKnots(const std::vector<double>& knots, const std::string& name, int degree, int count,
                   const std::string& where) {
  const long long needed = count + degree + 1LL;  // count > degree: validated before
  if (static_cast<long long>(knots.size()) != needed)
    throw InputError(Prefix(where) + name + " has " + std::to_string(knots.size()) + " values; " +
                     std::to_string(count) + " control points of degree " + std::to_string(degree) +
                     " need " + std::to_string(needed) + " (count + degree + 1)");
  for (long long k = 0; k < needed; ++k)
    if (!std::isfinite(knots[k]))
      throw InputError(Prefix(where) + name + "[" + std::to_string(k) + "] is not finite");
  for (long long k = 1; k < needed; ++k)
    if (knots[k] < knots[k - 1])
      throw InputError(Prefix(where) + name + " decreases at index " + std::to_string(k) + " (" +
                       Num(knots[k]) + " after " + Num(knots[k - 1]) + ")");
  for (int k = 1; k <= degree; ++k) {
    if (knots[k] != knots[0])
      throw InputError(Prefix(where) + name + " is not clamped: the first " +
                       std::to_string(degree + 1) + " values must be equal");
    if (knots[needed - 1 - k] != knots[needed - 1])
      throw InputError(Prefix(where) + name + " is not clamped: the last " +
                       std::to_string(degree + 1) + " values must be equal");
  }
  if (!(knots[count] > knots[degree]))
    throw InputError(Prefix(where) + name + " has an empty domain: " + name + "[" +
                     std::to_string(degree) + "] = " + name + "[" + std::to_string(count) +
                     "] = " + Num(knots[degree]));
}

void AddQuad(PolyMesh& mesh, const std::vector<PolyMesh::VertexHandle>& v, int rows, int cols) {
  for (int i = 0; i + 1 < rows; ++i)
    for (int j = 0; j + 1 < cols; ++j)
      mesh.add_face(
          {v[i * cols + j], v[(i + 1) * cols + j], v[(i + 1) * cols + j + 1], v[i * cols + j + 1]});
}

using Json = nlohmann::json;

const Json& Field(const Json& root, const char* name, const std::string& prefix) {
  const auto it = root.find(name);
  if (it == root.end()) throw InputError(prefix + "missing field \"" + name + "\"");
  return *it;
}

std::vector<double> ParseNumbers(const Json& value, const std::string& name,
                                 const std::string& prefix) {
  if (!value.is_array()) throw InputError(prefix + name + " must be an array of numbers");
  std::vector<double> out;
  out.reserve(value.size());
  for (size_t k = 0; k < value.size(); ++k) {
    if (!value[k].is_number())
      throw InputError(prefix + name + "[" + std::to_string(k) + "] is not a number");
    out.push_back(value[k].get<double>());
  }
  return out;
}

std::string JsonNumber(double x) { return Json(x).dump(); }

// Limits of the B-spline JSON reader, so that a file gproj cannot solve is refused before it
// takes the memory. `gproj weingarten` (default samples, bicubic) was measured at about 200 KB
// per control point, growing faster than linearly (310 MB at 40 × 40, 1.4 GB at 80 × 80), so
// 40000 control points (200 × 200) need about 8 GB or more. Degrees above 11 are rare in
// design data and costly here: every sample's rows touch
// (du + 1)(dv + 1) control points, so memory grows with the square of the degree and the time
// per iteration with its fourth power (33 × 33 control points: 1.7 s at bi-degree 3, 16 s at
// 8, 90 s and 2 GB at 16). The file size bounds the text held at once.
constexpr long long kMaxBSplineControlPoints = 40000;
constexpr int kMaxBSplineDegree = 11;
constexpr std::uintmax_t kMaxBSplineJsonBytes = 64u << 20;
// Every number and array of the file: control points take four each, knots one.
constexpr long long kMaxBSplineJsonValues = 8 * kMaxBSplineControlPoints;

// Parses, refusing more control points or JSON values than the limits while parsing (before
// the whole document is held in memory).
Json ParseBoundedJson(const std::string& text, const std::string& pre) {
  long long values = 0, points = 0;
  std::string key;
  const auto bound = [&](int depth, Json::parse_event_t event, Json& parsed) {
    if (event == Json::parse_event_t::key && depth == 1) key = parsed.get<std::string>();
    if (event == Json::parse_event_t::array_end && depth == 3 && key == "control_points" &&
        ++points > kMaxBSplineControlPoints)
      throw InputError(pre + "control_points has more than " +
                       std::to_string(kMaxBSplineControlPoints) +
                       " points; gproj reads B-spline surfaces of at most that many");
    if ((event == Json::parse_event_t::value || event == Json::parse_event_t::array_start) &&
        ++values > kMaxBSplineJsonValues)
      throw InputError(pre + "the file has more than " + std::to_string(kMaxBSplineJsonValues) +
                       " JSON values; a B-spline surface of at most " +
                       std::to_string(kMaxBSplineControlPoints) + " control points has fewer");
    return true;
  };
  RefuseNulByte(text, pre);
  try {
    return Json::parse(text, bound);
  } catch (const Json::exception& e) {  // parse_error, or out_of_range for number overflow
    throw InputError(pre + "invalid JSON: " + e.what());
  }
}

void ParseDegrees(const Json& degree, const std::string& pre, BSplineSurface* s) {
  if (!degree.is_array() || degree.size() != 2 || !degree[0].is_number_integer() ||
      !degree[1].is_number_integer())
    throw InputError(pre + "degree must be an array of two integers [du, dv]");
  // JSON keeps non-negative integers unsigned and negative ones signed, at 64 bits.
  const auto to_degree = [&](const Json& d, const char* name) {
    if (!d.is_number_unsigned() || d.get<std::uint64_t>() < 1)
      throw InputError(pre + name + " must be ≥ 1 (got " + d.dump() + ")");
    if (d.get<std::uint64_t>() > kMaxBSplineDegree)
      throw InputError(pre + name + " must be ≤ " + std::to_string(kMaxBSplineDegree) + " (got " +
                       d.dump() + ")");
    return static_cast<int>(d.get<std::uint64_t>());
  };
  s->degree_u = to_degree(degree[0], "degree_u");
  s->degree_v = to_degree(degree[1], "degree_v");
}

void ParseControlPoints(const Json& points, const std::string& pre, BSplineSurface* s) {
  if (!points.is_array())
    throw InputError(pre + "control_points must be an array of nu rows of nv points");
  s->nu = static_cast<int>(points.size());
  for (int i = 0; i < s->nu; ++i)
    if (!points[i].is_array())
      throw InputError(pre + "control_points[" + std::to_string(i) +
                       "] must be an array of points [x, y, z]");
  s->nv = s->nu > 0 ? static_cast<int>(points[0].size()) : 0;
  for (int i = 1; i < s->nu; ++i)
    if (static_cast<int>(points[i].size()) != s->nv)
      throw InputError(pre + "control_points[" + std::to_string(i) + "] has " +
                       std::to_string(points[i].size()) + " points, control_points[0] has " +
                       std::to_string(s->nv));
  s->control.resize(static_cast<Eigen::Index>(s->nu) * s->nv, 3);
  for (int i = 0; i < s->nu; ++i)
    for (int j = 0; j < s->nv; ++j) {
      const Json& p = points[i][j];
      const std::string name =
          "control_points[" + std::to_string(i) + "][" + std::to_string(j) + "]";
      if (!p.is_array() || p.size() != 3)
        throw InputError(pre + name + " must be an array of three numbers [x, y, z]");
      for (int c = 0; c < 3; ++c) {
        if (!p[c].is_number())
          throw InputError(pre + name + "[" + std::to_string(c) + "] is not a number");
        s->control(s->Index(i, j), c) = p[c].get<double>();
      }
    }
}

}  // namespace

Eigen::Vector3d BSplineSurface::Point(double u, double v) const {
  const Basis bu = EvaluateBasis(knots_u, degree_u, nu, u);
  const Basis bv = EvaluateBasis(knots_v, degree_v, nv, v);
  Eigen::Vector3d s = Eigen::Vector3d::Zero();
  for (int r = 0; r <= degree_u; ++r) {
    Eigen::Vector3d row = Eigen::Vector3d::Zero();
    const int i = bu.span - degree_u + r;
    for (int c = 0; c <= degree_v; ++c)
      row += bv.ders(0, c) * control.row(Index(i, bv.span - degree_v + c)).transpose();
    s += bu.ders(0, r) * row;
  }
  return s;
}

std::array<Eigen::Vector3d, 6> BSplineSurface::Derivatives(double u, double v) const {
  const Basis bu = EvaluateBasis(knots_u, degree_u, nu, u);
  const Basis bv = EvaluateBasis(knots_v, degree_v, nv, v);
  // Orders (k_u, k_v) of the six outputs.
  static constexpr int kOrder[6][2] = {{0, 0}, {1, 0}, {0, 1}, {2, 0}, {1, 1}, {0, 2}};
  std::array<Eigen::Vector3d, 6> d;
  for (auto& x : d) x.setZero();
  for (int r = 0; r <= degree_u; ++r) {
    const int i = bu.span - degree_u + r;
    // Partial sums along v for each v-derivative order.
    Eigen::Vector3d along_v[3] = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                                  Eigen::Vector3d::Zero()};
    for (int c = 0; c <= degree_v; ++c) {
      const Eigen::Vector3d p = control.row(Index(i, bv.span - degree_v + c)).transpose();
      for (int k = 0; k < 3; ++k) along_v[k] += bv.ders(k, c) * p;
    }
    for (int o = 0; o < 6; ++o) d[o] += bu.ders(kOrder[o][0], r) * along_v[kOrder[o][1]];
  }
  return d;
}

void ValidateBSpline(const BSplineSurface& s, const std::string& where) {
  const std::string pre = Prefix(where);
  if (s.degree_u < 1)
    throw InputError(pre + "degree_u must be ≥ 1 (got " + std::to_string(s.degree_u) + ")");
  if (s.degree_v < 1)
    throw InputError(pre + "degree_v must be ≥ 1 (got " + std::to_string(s.degree_v) + ")");
  // In long long: degree + 1 overflows int for the largest degrees.
  if (s.nu < s.degree_u + 1LL)
    throw InputError(pre + "nu = " + std::to_string(s.nu) + " control points along u; degree " +
                     std::to_string(s.degree_u) + " needs at least " +
                     std::to_string(s.degree_u + 1LL) + " (degree + 1)");
  if (s.nv < s.degree_v + 1LL)
    throw InputError(pre + "nv = " + std::to_string(s.nv) + " control points along v; degree " +
                     std::to_string(s.degree_v) + " needs at least " +
                     std::to_string(s.degree_v + 1LL) + " (degree + 1)");
  ValidateKnots(s.knots_u, "knots_u", s.degree_u, s.nu, where);
  ValidateKnots(s.knots_v, "knots_v", s.degree_v, s.nv, where);
  if (s.control.rows() != static_cast<Eigen::Index>(s.nu) * s.nv)
    throw InputError(pre + "control has " + std::to_string(s.control.rows()) +
                     " rows; nu × nv = " + std::to_string(s.nu) + " × " + std::to_string(s.nv) +
                     " needs " + std::to_string(s.nu * s.nv));
  for (int i = 0; i < s.nu; ++i)
    for (int j = 0; j < s.nv; ++j)
      if (!s.control.row(s.Index(i, j)).allFinite())
        throw InputError(pre + "control_points[" + std::to_string(i) + "][" + std::to_string(j) +
                         "] is not finite");
}

BSplineSurface ParseBSplineJson(const std::string& text, const std::string& path) {
  const std::string pre = Prefix(path);
  const Json root = ParseBoundedJson(text, pre);
  if (!root.is_object()) throw InputError(pre + "the top level must be a JSON object");
  BSplineSurface s;
  ParseDegrees(Field(root, "degree", pre), pre, &s);
  s.knots_u = ParseNumbers(Field(root, "knots_u", pre), "knots_u", pre);
  s.knots_v = ParseNumbers(Field(root, "knots_v", pre), "knots_v", pre);
  ParseControlPoints(Field(root, "control_points", pre), pre, &s);
  ValidateBSpline(s, path);
  return s;
}

BSplineSurface ReadBSplineJson(const std::string& path) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec && size > kMaxBSplineJsonBytes)
    throw InputError(path + ": the file has " + std::to_string(size) +
                     " bytes; a B-spline JSON file may have at most " +
                     std::to_string(kMaxBSplineJsonBytes) + " (" +
                     std::to_string(kMaxBSplineControlPoints) + " control points at most)");
  CheckRegularFile(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(path + ": read error");
  return ParseBSplineJson(text.str(), path);
}

std::string BSplineToJson(const BSplineSurface& s) {
  ValidateBSpline(s);
  std::ostringstream out;
  const auto list = [&](const std::vector<double>& values) {
    out << '[';
    for (size_t k = 0; k < values.size(); ++k) out << (k ? ", " : "") << JsonNumber(values[k]);
    out << ']';
  };
  out << "{\n  \"degree\": [" << s.degree_u << ", " << s.degree_v << "],\n  \"knots_u\": ";
  list(s.knots_u);
  out << ",\n  \"knots_v\": ";
  list(s.knots_v);
  out << ",\n  \"control_points\": [\n";
  for (int i = 0; i < s.nu; ++i) {
    out << "    [";
    for (int j = 0; j < s.nv; ++j) {
      const auto p = s.control.row(s.Index(i, j));
      out << (j ? ", " : "") << '[' << JsonNumber(p(0)) << ", " << JsonNumber(p(1)) << ", "
          << JsonNumber(p(2)) << ']';
    }
    out << (i + 1 < s.nu ? "],\n" : "]\n");
  }
  out << "  ]\n}\n";
  return out.str();
}

void WriteBSplineJson(const BSplineSurface& surface, const std::string& path) {
  try {
    ValidateBSpline(surface);
  } catch (const InputError& e) {
    throw InputError(path + ": refusing to write an invalid B-spline: " + e.what());
  }
  WriteTextFileAtomically(path, BSplineToJson(surface));
}

std::vector<double> UniformClampedKnots(int count, int degree) {
  if (degree < 1 || count < degree + 1)
    throw InputError("a clamped knot vector of degree " + std::to_string(degree) + " needs " +
                     "degree ≥ 1 and at least degree + 1 control points (got " +
                     std::to_string(count) + ")");
  std::vector<double> knots(count + degree + 1);
  const int spans = count - degree;
  for (int k = 0; k < static_cast<int>(knots.size()); ++k)
    knots[k] = std::clamp(static_cast<double>(k - degree) / spans, 0.0, 1.0);
  return knots;
}

SampleMaps MakeSampleMaps(const BSplineSurface& surface, int su, int sv) {
  ValidateBSpline(surface);
  if (su < 1 || sv < 1)
    throw InputError("sample grid must be at least 1 × 1 (got " + std::to_string(su) + " × " +
                     std::to_string(sv) + ")");
  SampleMaps maps;
  maps.su = su;
  maps.sv = sv;
  maps.u = UniformSamples(surface.u_min(), surface.u_max(), su);
  maps.v = UniformSamples(surface.v_min(), surface.v_max(), sv);
  std::vector<Basis> bu, bv;
  bu.reserve(su);
  bv.reserve(sv);
  for (double u : maps.u)
    bu.push_back(EvaluateBasis(surface.knots_u, surface.degree_u, surface.nu, u));
  for (double v : maps.v)
    bv.push_back(EvaluateBasis(surface.knots_v, surface.degree_v, surface.nv, v));
  const int pu = surface.degree_u, pv = surface.degree_v;
  const int per_row = (pu + 1) * (pv + 1);
  const int rows = su * sv, cols = surface.num_control_points();
  static constexpr int kOrder[6][2] = {{0, 0}, {1, 0}, {0, 1}, {2, 0}, {1, 1}, {0, 2}};
  // Every row has exactly (du + 1)(dv + 1) entries with increasing column indices, so the
  // compressed row storage is written directly (no triplet sort needed).
  for (int o = 0; o < 6; ++o) {
    auto& m = maps.d[o];
    m.resize(rows, cols);
    m.resizeNonZeros(static_cast<Eigen::Index>(rows) * per_row);
    int* outer = m.outerIndexPtr();
    int* inner = m.innerIndexPtr();
    double* value = m.valuePtr();
    const int ku = kOrder[o][0], kv = kOrder[o][1];
    for (int a = 0; a < su; ++a)
      for (int b = 0; b < sv; ++b) {
        const int row = maps.Index(a, b);
        int e = row * per_row;
        outer[row] = e;
        for (int r = 0; r <= pu; ++r) {
          const int i = bu[a].span - pu + r;
          for (int c = 0; c <= pv; ++c, ++e) {
            inner[e] = surface.Index(i, bv[b].span - pv + c);
            value[e] = bu[a].ders(ku, r) * bv[b].ders(kv, c);
          }
        }
      }
    outer[rows] = rows * per_row;
  }
  return maps;
}

BSplineSurface FitBSpline(const std::function<Eigen::Vector3d(double, double)>& f, int degree_u,
                          int degree_v, int nu, int nv, int samples_per_control) {
  if (samples_per_control < 1)
    throw InputError("samples_per_control must be ≥ 1 (got " + std::to_string(samples_per_control) +
                     ")");
  BSplineSurface s;
  s.degree_u = degree_u;
  s.degree_v = degree_v;
  s.nu = nu;
  s.nv = nv;
  s.knots_u = UniformClampedKnots(nu, degree_u);
  s.knots_v = UniformClampedKnots(nv, degree_v);
  // Samples on a grid including the domain boundary.
  const auto grid = [](int count) {
    std::vector<double> t(count);
    for (int a = 0; a < count; ++a) t[a] = static_cast<double>(a) / (count - 1);
    return t;
  };
  const std::vector<double> tu = grid(std::max(2, samples_per_control * nu));
  const std::vector<double> tv = grid(std::max(2, samples_per_control * nv));
  const int mu = static_cast<int>(tu.size()), mv = static_cast<int>(tv.size());
  // Tensor-product least squares: F ≈ Bu C Bv^T per coordinate, whose solution is
  // C = Bu⁺ F (Bv⁺)^T (the pseudo-inverse of a Kronecker product factors).
  const Eigen::MatrixXd bu = Collocation(s.knots_u, degree_u, nu, tu);
  const Eigen::MatrixXd bv = Collocation(s.knots_v, degree_v, nv, tv);
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qu(bu), qv(bv);
  if (qu.rank() < nu || qv.rank() < nv)
    throw InputError("B-spline fit is rank deficient; use more samples per control point");
  s.control.resize(static_cast<Eigen::Index>(nu) * nv, 3);
  Eigen::MatrixXd values(mu, mv);
  std::vector<Eigen::Vector3d> points(static_cast<size_t>(mu) * mv);
  for (int a = 0; a < mu; ++a)
    for (int b = 0; b < mv; ++b) points[static_cast<size_t>(a) * mv + b] = f(tu[a], tv[b]);
  for (int c = 0; c < 3; ++c) {
    for (int a = 0; a < mu; ++a)
      for (int b = 0; b < mv; ++b) values(a, b) = points[static_cast<size_t>(a) * mv + b][c];
    const Eigen::MatrixXd left = qu.solve(values);                                // nu × mv
    const Eigen::MatrixXd coefficients = qv.solve(left.transpose()).transpose();  // nu × nv
    for (int i = 0; i < nu; ++i)
      for (int j = 0; j < nv; ++j) s.control(s.Index(i, j), c) = coefficients(i, j);
  }
  if (!s.control.allFinite()) throw InputError("B-spline fit produced non-finite control points");
  return s;
}

BSplineSurface RefitBSpline(const BSplineSurface& surface, int nu, int nv) {
  ValidateBSpline(surface);
  const double u0 = surface.u_min(), du = surface.u_max() - u0;
  const double v0 = surface.v_min(), dv = surface.v_max() - v0;
  return FitBSpline([&](double u, double v) { return surface.Point(u0 + u * du, v0 + v * dv); },
                    surface.degree_u, surface.degree_v, nu, nv);
}

BSplineSurface InsertKnotsUniform(const BSplineSurface& surface, int per_span) {
  ValidateBSpline(surface);
  if (per_span < 0)
    throw InputError("knots per span must be ≥ 0 (got " + std::to_string(per_span) + ")");
  BSplineSurface out = surface;
  const int nu = surface.nu, nv = surface.nv;
  // Along u: rows are i, columns (j, coordinate).
  Eigen::MatrixXd pu(nu, 3 * nv);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j)
      pu.block<1, 3>(i, 3 * j) = surface.control.row(surface.Index(i, j));
  const Eigen::MatrixXd qu = RefineKnotVector(out.knots_u, surface.degree_u, pu,
                                              UniformInsertions(surface.knots_u, per_span));
  out.nu = static_cast<int>(qu.rows());
  // Along v: rows are j, columns (i, coordinate).
  Eigen::MatrixXd pv(nv, 3 * out.nu);
  for (int i = 0; i < out.nu; ++i)
    for (int j = 0; j < nv; ++j) pv.block<1, 3>(j, 3 * i) = qu.block<1, 3>(i, 3 * j);
  const Eigen::MatrixXd qv = RefineKnotVector(out.knots_v, surface.degree_v, pv,
                                              UniformInsertions(surface.knots_v, per_span));
  out.nv = static_cast<int>(qv.rows());
  out.control.resize(static_cast<Eigen::Index>(out.nu) * out.nv, 3);
  for (int i = 0; i < out.nu; ++i)
    for (int j = 0; j < out.nv; ++j) out.control.row(out.Index(i, j)) = qv.block<1, 3>(j, 3 * i);
  return out;
}

NormalTurn MinNormalCosine(const BSplineSurface& surface, int m, int n) {
  return GridNormals(surface, m, n).MinCosine(surface.control);
}

GridNormals::GridNormals(const BSplineSurface& surface, int m, int n)
    : m_(m), n_(n), nv_(surface.nv), pu_(surface.degree_u), pv_(surface.degree_v) {
  ValidateBSpline(surface);
  if (m < 1 || n < 1)
    throw InputError("a normal-check grid needs at least 1 x 1 cells (got " + std::to_string(m) +
                     " x " + std::to_string(n) + ")");
  u0_ = surface.u_min();
  v0_ = surface.v_min();
  u_step_ = (surface.u_max() - surface.u_min()) / m;
  v_step_ = (surface.v_max() - surface.v_min()) / n;
  auto tabulate = [](const std::vector<double>& knots, int degree, int count, double t0,
                     double step, int cells, std::vector<int>* first, Eigen::MatrixXd* b,
                     Eigen::MatrixXd* db) {
    first->resize(cells + 1);
    b->resize(cells + 1, degree + 1);
    db->resize(cells + 1, degree + 1);
    for (int a = 0; a <= cells; ++a) {
      const Basis basis = EvaluateBasis(knots, degree, count, t0 + a * step);
      (*first)[a] = basis.span - degree;
      b->row(a) = basis.ders.row(0);
      db->row(a) = basis.ders.row(1);
    }
  };
  tabulate(surface.knots_u, pu_, surface.nu, u0_, u_step_, m, &first_u_, &bu_, &dbu_);
  tabulate(surface.knots_v, pv_, surface.nv, v0_, v_step_, n, &first_v_, &bv_, &dbv_);
  along_u_.resize(static_cast<Eigen::Index>(m + 1) * nv_, 3);
  along_du_.resize(along_u_.rows(), 3);
  normal_.resize(static_cast<size_t>(m + 1) * (n + 1));
}

NormalTurn GridNormals::MinCosine(const Eigen::MatrixX3d& control) {
  // First along u for every control column j, then along v at every grid point.
  for (int a = 0; a <= m_; ++a)
    for (int j = 0; j < nv_; ++j) {
      Eigen::RowVector3d p = Eigen::RowVector3d::Zero(), dp = Eigen::RowVector3d::Zero();
      for (int r = 0; r <= pu_; ++r) {
        const auto c = control.row((first_u_[a] + r) * nv_ + j);
        p += bu_(a, r) * c;
        dp += dbu_(a, r) * c;
      }
      along_u_.row(a * nv_ + j) = p;
      along_du_.row(a * nv_ + j) = dp;
    }
  auto at = [&](int a, int b) -> Eigen::Vector3d& { return normal_[a * (n_ + 1) + b]; };
  for (int a = 0; a <= m_; ++a)
    for (int b = 0; b <= n_; ++b) {
      Eigen::RowVector3d su = Eigen::RowVector3d::Zero(), sv = Eigen::RowVector3d::Zero();
      for (int c = 0; c <= pv_; ++c) {
        const int row = a * nv_ + first_v_[b] + c;
        su += bv_(b, c) * along_du_.row(row);
        sv += dbv_(b, c) * along_u_.row(row);
      }
      const Eigen::Vector3d cross = su.cross(sv).transpose();
      const double length = cross.norm();
      at(a, b) = length > 0.0 && std::isfinite(length) ? Eigen::Vector3d(cross / length)
                                                       : Eigen::Vector3d::Zero();
    }
  NormalTurn turn;
  auto compare = [&](int a, int b, int a2, int b2) {
    const Eigen::Vector3d &p = at(a, b), &q = at(a2, b2);
    const double c = p.isZero() || q.isZero() ? -1.0 : p.dot(q);
    if (c < turn.min_cosine) turn = {c, u0_ + a * u_step_, v0_ + b * v_step_};
  };
  for (int a = 0; a <= m_; ++a)
    for (int b = 0; b <= n_; ++b) {
      if (a < m_) compare(a, b, a + 1, b);
      if (b < n_) compare(a, b, a, b + 1);
    }
  return turn;
}

PolyMesh ControlNetMesh(const BSplineSurface& surface) {
  PolyMesh mesh;
  std::vector<PolyMesh::VertexHandle> v;
  v.reserve(surface.num_control_points());
  for (int k = 0; k < surface.num_control_points(); ++k) {
    const auto p = surface.control.row(k);
    v.push_back(mesh.add_vertex(PolyMesh::Point(p(0), p(1), p(2))));
  }
  AddQuad(mesh, v, surface.nu, surface.nv);
  return mesh;
}

PolyMesh SampleSurfaceMesh(const BSplineSurface& surface, int m, int n) {
  if (m < 1 || n < 1)
    throw InputError("surface sampling needs m, n ≥ 1 (got " + std::to_string(m) + " × " +
                     std::to_string(n) + ")");
  PolyMesh mesh;
  std::vector<PolyMesh::VertexHandle> v;
  v.reserve(static_cast<size_t>(m + 1) * (n + 1));
  for (int i = 0; i <= m; ++i)
    for (int j = 0; j <= n; ++j) {
      const double u = surface.u_min() + (surface.u_max() - surface.u_min()) * i / m;
      const double w = surface.v_min() + (surface.v_max() - surface.v_min()) * j / n;
      const Eigen::Vector3d p = surface.Point(u, w);
      v.push_back(mesh.add_vertex(PolyMesh::Point(p(0), p(1), p(2))));
    }
  AddQuad(mesh, v, m + 1, n + 1);
  return mesh;
}

BSplineSurface MakeWavyBSpline(int nu, int nv, int degree, double amplitude) {
  BSplineSurface s;
  s.degree_u = s.degree_v = degree;
  s.nu = nu;
  s.nv = nv;
  s.knots_u = UniformClampedKnots(nu, degree);
  s.knots_v = UniformClampedKnots(nv, degree);
  s.control.resize(nu * nv, 3);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double x = -1.0 + 2.0 * i / (nu - 1), y = -1.0 + 2.0 * j / (nv - 1);
      s.control.row(s.Index(i, j)) << x, y,
          amplitude * (0.3 * std::sin(2.0 * x) * std::cos(1.5 * y) + 0.2 * x * y + 0.15 * x * x);
    }
  ValidateBSpline(s);
  return s;
}

BSplineSurface MakeBumpBSpline(int n, int degree) {
  BSplineSurface bump = MakeWavyBSpline(n, n, degree);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = bump.control(bump.Index(i, j), 0), y = bump.control(bump.Index(i, j), 1);
      bump.control(bump.Index(i, j), 2) =
          0.15 * (1 - x * x) * (1 - y * y) * (1 + 0.3 * x + 0.2 * y * y);
    }
  return bump;
}

}  // namespace gproj
