#include "gproj/problems/circular/closed_canal.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "gproj/problems/circular/circular_mesh.h"

namespace gproj::circular {
namespace {

// A sphere or plane: a |x|² + b·x + c = 0.
struct GeneralSphere {
  double a = 0.0;
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  double c = 0.0;
};

// The sphere (or plane) through a circle and a point off it: the member of the pencil spanned by
// the circle's sphere |x − centre|² − r² and its plane n·(x − centre) that passes the point.
GeneralSphere SphereThrough(const Circle& circle, const Eigen::Vector3d& point) {
  const Eigen::Vector3d d = point - circle.centre;
  const double lambda = circle.normal.dot(d);
  const double mu = -(d.squaredNorm() - circle.radius * circle.radius);
  GeneralSphere s;
  s.a = lambda;
  s.b = -2.0 * lambda * circle.centre + mu * circle.normal;
  s.c = lambda * (circle.centre.squaredNorm() - circle.radius * circle.radius) -
        mu * circle.normal.dot(circle.centre);
  return s;
}

double DistanceTo(const GeneralSphere& s, const Eigen::Vector3d& x) {
  if (s.a == 0.0) return std::abs(s.b.dot(x) + s.c) / s.b.norm();
  const Eigen::Vector3d centre = -s.b / (2.0 * s.a);
  const double r2 = centre.squaredNorm() - s.c / s.a;
  return std::abs((x - centre).norm() - std::sqrt(std::max(0.0, r2)));
}

std::string Name(const char* letter, int k) {
  return std::string(letter) + "_" + std::to_string(k);
}

// The second point where the closing circle (in the plane of normal `plane_normal`; `closing`
// when already known) meets `circle` besides `on`: on the line through `on` in both planes, or,
// when the planes agree (a flat strip), the mirror image of `on` in the line of the two centres.
// Throws when the circles agree or only touch.
Eigen::Vector3d SecondIntersection(const Circle& circle, const Eigen::Vector3d& on,
                                   const Eigen::Vector3d& plane_normal, const Circle* closing,
                                   const std::string& what, double scale) {
  const Eigen::Vector3d d = circle.normal.cross(plane_normal.normalized());
  Eigen::Vector3d x;
  if (d.norm() > 1e-12) {
    const double s = -2.0 * d.dot(on - circle.centre) / d.squaredNorm();
    x = on + s * d;
  } else {
    Eigen::Vector3d axis = Eigen::Vector3d::Zero();
    if (closing != nullptr) axis = closing->centre - circle.centre;
    if (!(axis.norm() > 1e-12 * scale))
      throw InputError("the closing circle lies on " + what + ": the closed strip degenerates");
    const Eigen::Vector3d u = axis.normalized(), r = on - circle.centre;
    x = circle.centre + 2.0 * r.dot(u) * u - r;
  }
  if (!((x - on).norm() > 1e-9 * scale))
    throw InputError("the closing circle only touches " + what +
                     ": change the first point or the lengths");
  return x;
}

double MeanEdge(const CircularStrip& strip) {
  const int count = static_cast<int>(strip.p.size());
  double sum = 0.0;
  for (int k = 0; k < count; ++k) {
    const int next = (k + 1) % count;
    sum += (strip.p[next] - strip.p[k]).norm() + (strip.q[next] - strip.q[k]).norm() +
           (strip.q[k] - strip.p[k]).norm();
  }
  return sum / (3 * count);
}

// Throws InputError for fewer than three curve points, lengths not one per point, a negative
// tolerance, non-finite points or two consecutive points that are the same.
void CheckClosedStripInput(const CircularStripInput& input, double cospherical_tolerance) {
  const int count = static_cast<int>(input.curve.size());
  if (count < 3) throw InputError("a closed strip needs at least three curve points");
  if (static_cast<int>(input.lengths.size()) != count)
    throw InputError("the strip needs one length per curve point (" + std::to_string(count) +
                     "), got " + std::to_string(input.lengths.size()));
  if (!(cospherical_tolerance >= 0.0)) throw InputError("the co-sphericity tolerance must be ≥ 0");
  for (int k = 0; k < count; ++k) {
    if (!input.curve[k].allFinite())
      throw InputError("curve point " + std::to_string(k) + " is not finite");
    const int next = (k + 1) % count;
    if (input.curve[k] == input.curve[next])
      throw InputError(
          "curve points " + std::to_string(k) + " and " + std::to_string(next) + " are the same" +
          (next == 0 ? " (list a closed curve's points once, without repeating P_0)" : ""));
  }
  if (!input.first_point.allFinite()) throw InputError("the first point is not finite");
}

// Throws InputError when the closing circle folds quad 0, the one before the last, or the
// last (the others are the open strip's).
void CheckClosingQuads(const CircularStrip& strip, const ClosedCircularStrip& result) {
  const int count = static_cast<int>(strip.p.size());
  const std::array<int, 3> checked = {0, count - 2, count - 1};
  for (int k : checked) {
    const int next = (k + 1) % count;
    if (!IsConvexQuad({strip.p[k], strip.p[next], strip.q[next], strip.q[k]})) {
      char shift[96] = "";
      if (result.closing_case == 2)
        std::snprintf(shift, sizeof(shift), " (case 2 moves Q_0 by %.4g)", result.start_shift);
      throw InputError("the closing circle folds quad " + std::to_string(k) + " (" + Name("P", k) +
                       ", " + Name("P", next) + ", " + Name("Q", next) + ", " + Name("Q", k) + ")" +
                       shift + ": change the first point or the lengths");
    }
  }
}

}  // namespace

ClosedCircularStrip BuildClosedCircularStrip(const CircularStripInput& input,
                                             double cospherical_tolerance) {
  CheckClosedStripInput(input, cospherical_tolerance);
  const int count = static_cast<int>(input.curve.size());
  // The construction runs about P_0 (spheres and planes of far-away points lose digits).
  const Eigen::Vector3d origin = input.curve[0];
  CircularStripInput open = input;
  for (Eigen::Vector3d& p : open.curve) p -= origin;
  open.first_point -= origin;
  const std::vector<Eigen::Vector3d> curve = open.curve;
  // Q_0..Q_{N−2}: the open strip on P_0..P_{N−2}.
  open.curve.pop_back();
  open.lengths.pop_back();
  const CircularStrip first = BuildCircularStrip(open);
  ClosedCircularStrip result;
  CircularStrip strip;
  strip.p = curve;
  strip.q = first.q;
  strip.q.push_back(strip.p[count - 1]);  // Q_{N−1}, set below
  const int last = count - 1, before = count - 2;
  const Eigen::Vector3d &p0 = strip.p[0], &pl = strip.p[last];
  const Circle gamma0 = CircleThrough<double>(p0, strip.p[1], strip.q[0]);
  const Circle gammal = CircleThrough<double>(strip.p[before], pl, strip.q[before]);
  if (!std::isfinite(gammal.radius) || !(gammal.radius > 0.0))
    throw InputError("P_" + std::to_string(before) + ", P_" + std::to_string(last) + " and Q_" +
                     std::to_string(before) + " are collinear");
  double scale = 0.0;
  for (int k = 0; k < count; ++k) scale = std::max(scale, (strip.p[k] - p0).norm());
  const GeneralSphere sa = SphereThrough(gamma0, pl), sb = SphereThrough(gammal, p0);
  // Mean edge of the open part, for the relative measures.
  const double edge = MeanEdge({strip.p, strip.q});
  result.cosphericity =
      std::max(DistanceTo(sa, strip.p[before]), DistanceTo(sa, strip.q[before])) / edge;
  Eigen::Vector3d plane_normal;
  const Eigen::Vector3d asked_q0 = strip.q[0];
  if (result.cosphericity <= cospherical_tolerance) {
    result.closing_case = 1;
    plane_normal = (p0 - strip.q[0]).cross(pl - strip.q[0]);
    if (!(plane_normal.norm() > 1e-12 * (p0 - strip.q[0]).norm() * (pl - strip.q[0]).norm()))
      throw InputError("Q_0, P_0 and P_" + std::to_string(last) +
                       " are collinear: they do not fix a closing circle");
  } else {
    result.closing_case = 2;
    plane_normal = sb.a * sa.b - sa.a * sb.b;  // the radical plane of the two spheres
    if (!(plane_normal.norm() >
          1e-12 * std::max(sa.b.norm() * std::abs(sb.a), sb.b.norm() * std::abs(sa.a))))
      throw InputError("the spheres (Γ_0, P_" + std::to_string(last) + ") and (Γ_" +
                       std::to_string(before) +
                       ", P_0) are planes: the closing circle degenerates to a line");
    strip.q[0] =
        SecondIntersection(gamma0, p0, plane_normal, nullptr, "the first circle Γ_0", scale);
  }
  const Circle closing = CircleThrough<double>(pl, p0, strip.q[0]);
  strip.q[last] = SecondIntersection(gammal, pl, plane_normal, &closing,
                                     "the circle Γ_" + std::to_string(before), scale);
  result.start_shift = (strip.q[0] - asked_q0).norm();
  CheckClosingQuads(strip, result);
  result.strip.p = input.curve;
  result.strip.q = strip.q;
  for (Eigen::Vector3d& q : result.strip.q) q += origin;
  result.closing_circle = closing;
  result.closing_circle.centre += origin;
  return result;
}

PolyMesh ClosedStripMesh(const CircularStrip& strip) {
  std::vector<std::vector<Eigen::Vector3d>> rows;
  for (size_t k = 0; k < strip.p.size(); ++k) rows.push_back({strip.p[k], strip.q[k]});
  return RowsMesh(rows, true);
}

Eigen::Matrix3d LoopReflection(const std::vector<Eigen::Vector3d>& closed_curve) {
  Eigen::Matrix3d m = Eigen::Matrix3d::Identity();
  const int count = static_cast<int>(closed_curve.size());
  for (int k = 0; k < count; ++k) {
    const Eigen::Vector3d e = (closed_curve[(k + 1) % count] - closed_curve[k]).normalized();
    m = (Eigen::Matrix3d::Identity() - 2.0 * e * e.transpose()) * m;
  }
  return m;
}

double FrameClosureAngle(const Eigen::Matrix3d& loop, const Frame& frame) {
  // Each reflection reverses the sense of t1 (the arc's direction of travel) and keeps t2 and n.
  const double t1_sense = loop.determinant() < 0.0 ? -1.0 : 1.0;
  double worst = 0.0;
  for (const auto& [v, sense] :
       {std::pair<Eigen::Vector3d, double>{frame.t1, t1_sense}, {frame.t2, 1.0}, {frame.n, 1.0}}) {
    const Eigen::Vector3d w = loop * v;
    worst = std::max(worst, std::atan2(v.cross(w).norm(), sense * v.dot(w)));
  }
  return worst * 180.0 / M_PI;
}

Frame ClosingFrame(const Eigen::Matrix3d& loop, const Frame& start, double* rotation_deg) {
  *rotation_deg = 0.0;
  if (loop.determinant() > 0.0) return start;  // only M = I closes: nothing to turn
  // An odd count: the loop should be the reflection in a plane, whose normal w (the eigenvector
  // of the least eigenvalue) becomes ±t1.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(0.5 * (loop + loop.transpose()));
  const Eigen::Vector3d w = eigen.eigenvectors().col(0);
  const Eigen::Vector3d target = start.t1.dot(w) >= 0.0 ? w : Eigen::Vector3d(-w);
  const Eigen::Matrix3d r = Eigen::Quaterniond::FromTwoVectors(start.t1, target).toRotationMatrix();
  *rotation_deg = Eigen::AngleAxisd(r).angle() * 180.0 / M_PI;
  return {r * start.t1, r * start.t2, r * start.n};
}

bool ClosedCanalOptions::IsValid(std::string* why) const {
  if (segments < 1 || segments > 100000) {
    *why = "segments must be in [1, 100000]";
    return false;
  }
  if (!(cospherical_tolerance >= 0.0) || !(frame_tolerance_deg >= 0.0)) {
    *why = "the co-sphericity and frame tolerances must be ≥ 0";
    return false;
  }
  return true;
}

ClosedCanalSurface BuildClosedCanalSurface(const CircularStripInput& input,
                                           const FrameAngles& angles,
                                           const ClosedCanalOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError("closed canal surface: " + why);
  if (input.curve.size() < 3) throw InputError("a closed strip needs at least three curve points");
  // The construction runs about P_0 and is moved back at the end.
  const Eigen::Vector3d origin = input.curve[0];
  CircularStripInput local = input;
  for (Eigen::Vector3d& p : local.curve) p -= origin;
  local.first_point -= origin;
  ClosedCanalSurface s;
  s.closed = BuildClosedCircularStrip(local, options.cospherical_tolerance);
  const std::vector<Eigen::Vector3d>& curve = s.closed.strip.p;
  const Eigen::Matrix3d loop = LoopReflection(curve);
  CheckFrameNormal(angles, curve[0], curve[1]);
  const Frame asked = FrameOfAngles(curve, angles);
  double rotation = 0.0;
  const Frame frame = options.close_frame ? ClosingFrame(loop, asked, &rotation) : asked;
  const double closure = FrameClosureAngle(loop, frame);
  s.frame_closes = closure <= options.frame_tolerance_deg;
  s.angles = AnglesOfFrame(curve, frame);
  // The net on the curve run once around and back to P_0: its last circle is C_0 as the carried
  // frame sees it, so every quad of the mesh is circular and the seam shows what does not close.
  CircularStrip around = s.closed.strip;
  around.p.push_back(around.p[0]);
  around.q.push_back(around.q[0]);
  s.net = MakeCyclidicStrip(around, s.angles);
  std::vector<std::vector<Eigen::Vector3d>> rows = CanalRows(s.net, options.segments);
  const int count = static_cast<int>(curve.size());
  double gap = 0.0;
  for (int j = 0; j <= options.segments; ++j)
    gap = std::max(gap, (rows[count][j] - rows[0][j]).norm());
  gap /= MeanEdge(s.closed.strip);
  s.welded = s.frame_closes && gap <= kWeldTolerance;
  if (s.welded) rows.pop_back();
  for (auto& row : rows)
    for (Eigen::Vector3d& x : row) x += origin;
  s.mesh = RowsMesh(rows, s.welded);
  s.measures = {{"closing_case", static_cast<double>(s.closed.closing_case)},
                {"cosphericity", s.closed.cosphericity},
                {"start_point_shift", s.closed.start_shift},
                {"last_length", (s.closed.strip.q[count - 1] - curve[count - 1]).norm()},
                {"frame_closure_deg", closure},
                {"frame_rotation_deg", rotation},
                {"seam_gap", gap}};
  for (const NamedValue& v : MeasureCircularMesh(s.mesh)) s.measures.push_back(v);
  // Back to the input's place.
  s.closed.strip.p = input.curve;
  for (Eigen::Vector3d& q : s.closed.strip.q) q += origin;
  s.closed.closing_circle.centre += origin;
  for (auto* row : {&s.net.strip.p, &s.net.strip.q})
    for (Eigen::Vector3d& x : *row) x += origin;
  for (Circle& c : s.net.circles) c.centre += origin;
  return s;
}

Eigen::Vector3d DefaultClosedCanalNormal(const CircularStripInput& input) {
  if (input.curve.size() < 3) throw InputError("a closed strip needs at least three curve points");
  CircularStripInput open = input;
  open.curve.pop_back();
  open.lengths.pop_back();
  return DefaultCanalNormal(BuildCircularStrip(open));
}

RunReport ClosedCanalRunReport(const ClosedCanalSurface& surface, const ClosedCanalOptions& options,
                               const Construction& construction) {
  const NamedValues& m = surface.measures;
  const std::string crossed = CrossedQuadsFault(m, kCrossedQuadsHint);
  RunReport report = construction.Finish({}, m, surface.welded && crossed.empty());
  char why[240];
  if (!surface.frame_closes)
    std::snprintf(why, sizeof(why),
                  "the frame comes back %.3g deg off after the loop (`frame_tolerance` %.1e)",
                  ValueOf(m, "frame_closure_deg"), options.frame_tolerance_deg);
  else if (!surface.welded)
    std::snprintf(why, sizeof(why),
                  "the curvature lines across the circles do not close around the curve (seam "
                  "gap %.3g of the mean edge): the canal mesh is open at P_0",
                  ValueOf(m, "seam_gap"));
  else if (!crossed.empty())
    std::snprintf(why, sizeof(why), "%s", crossed.c_str());
  else
    std::snprintf(why, sizeof(why), "closed");
  report.termination = why;
  return report;
}

nlohmann::json ClosedCanalJson(const ClosedCanalSurface& surface,
                               const ClosedCanalOptions& options) {
  const FrameAngles& a = surface.angles;
  const Eigen::Vector3d n = NormalOf(a);
  nlohmann::json json;
  json["frame"] = {{"lambda", a.lambda}, {"theta", a.theta}, {"psi", a.psi}};
  json["frame"]["normal"] = {n.x(), n.y(), n.z()};
  const Circle& c = surface.closed.closing_circle;
  json["closing_circle"] = {{"centre", {c.centre.x(), c.centre.y(), c.centre.z()}},
                            {"normal", {c.normal.x(), c.normal.y(), c.normal.z()}},
                            {"radius", c.radius}};
  const CircularStrip& strip = surface.closed.strip;
  std::vector<double> lengths;
  for (size_t k = 0; k < strip.p.size(); ++k) lengths.push_back((strip.q[k] - strip.p[k]).norm());
  json["lengths"] = lengths;
  json["mesh"] = {
      {"rows", strip.p.size()}, {"segments", options.segments}, {"closed", surface.welded}};
  return json;
}

}  // namespace gproj::circular
