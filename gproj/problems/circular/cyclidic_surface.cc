#include "gproj/problems/circular/cyclidic_surface.h"

#include <ceres/ceres.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "gproj/problems/circular/circular_mesh.h"

namespace gproj::circular {
namespace {

// Mirror image in the plane perpendicular to `edge` (through the origin: vectors only).
Eigen::Vector3d Mirror(const Eigen::Vector3d& v, const Eigen::Vector3d& edge) {
  return v - (2.0 * v.dot(edge) / edge.squaredNorm()) * edge;
}

// The mirror image from p to q (v itself when they coincide).
Eigen::Vector3d Carry(const Eigen::Vector3d& v, const Eigen::Vector3d& p,
                      const Eigen::Vector3d& q) {
  const Eigen::Vector3d edge = q - p;
  return edge.squaredNorm() > 0.0 ? Mirror(v, edge) : v;
}

// The angle between the normals carried to `point` along the two paths a → via1 → point and
// a → via2 → point: zero on the patch's curvature-line net (frames close around its quads).
double PathMismatch(const Eigen::Vector3d& n, const Eigen::Vector3d& a, const Eigen::Vector3d& via1,
                    const Eigen::Vector3d& via2, const Eigen::Vector3d& point) {
  const Eigen::Vector3d n1 = Carry(Carry(n, a, via1), via1, point);
  const Eigen::Vector3d n2 = Carry(Carry(n, a, via2), via2, point);
  return std::atan2(n1.cross(n2).norm(), n1.dot(n2));
}

Frame Mirror(const Frame& f, const Eigen::Vector3d& edge) {
  return {Mirror(f.t1, edge), Mirror(f.t2, edge), Mirror(f.n, edge)};
}

// The plane m·x + offset = 0.
struct Plane {
  Eigen::Vector3d m = Eigen::Vector3d::Zero();
  double offset = 0.0;
  double At(const Eigen::Vector3d& x) const { return m.dot(x) + offset; }
};

Plane PlaneOf(const Arc& arc) { return {arc.normal, -arc.normal.dot(arc.centre)}; }

// The plane of the pencil spanned by p and q that passes through x.
Plane PencilPlane(const Plane& p, const Plane& q, const Eigen::Vector3d& x) {
  const double wp = q.At(x), wq = -p.At(x);
  return {wp * p.m + wq * q.m, wp * p.offset + wq * q.offset};
}

// The fractions of the arc's angle (or length) at which it meets the plane: none, one (a
// line) or two, each as the turn of the circle nearest to the arc.
std::vector<double> CutFractions(const Arc& arc, const Plane& plane) {
  if (arc.straight) {
    const double slope = plane.m.dot(arc.end - arc.start);
    const double f = -plane.At(arc.start) / slope;
    return std::isfinite(f) ? std::vector<double>{f} : std::vector<double>{};
  }
  const Eigen::Vector3d e1 = arc.start - arc.centre, e2 = arc.normal.cross(e1);
  // plane(centre + cos θ e1 + sin θ e2) = a0 + a1 cos θ + a2 sin θ.
  const double a0 = plane.At(arc.centre), a1 = plane.m.dot(e1), a2 = plane.m.dot(e2);
  const double rho = std::hypot(a1, a2);
  if (!(rho > 0.0) || std::abs(a0) > rho * (1.0 + 1e-12)) return {};
  const double base = std::atan2(a2, a1), spread = std::acos(std::clamp(-a0 / rho, -1.0, 1.0));
  std::vector<double> out;
  for (double theta : {base + spread, base - spread}) {
    theta = std::fmod(theta + 4.0 * M_PI, 2.0 * M_PI);
    double f = theta / arc.angle;
    // The arc's start may come out as 2π: take the turn nearest the arc.
    if (f > 1.0 && (2.0 * M_PI - theta) / arc.angle < f - 1.0) f = (theta - 2.0 * M_PI) / arc.angle;
    out.push_back(f);
  }
  return out;
}

// Of the points where the plane meets the arc, the one whose normal closes (PathMismatch below
// 1e-4 rad, far above the rounding of circular input and far below the miss at a wrong point).
// When both close (the other point of a spherical, flat or symmetric cyclide), the one nearer
// to `previous`, the neighbouring sample along the same curvature line (continuity); when neither
// closes, the one that misses least. False when the plane misses the arc's circle.
bool CutPoint(const Arc& arc, const Plane& plane, const Eigen::Vector3d& n,
              const Eigen::Vector3d& a, const Eigen::Vector3d& via1, const Eigen::Vector3d& via2,
              const Eigen::Vector3d& previous, Eigen::Vector3d* point) {
  constexpr double kCloses = 1e-4;
  bool found = false;
  double best_mismatch = 0.0, best_distance = 0.0;
  for (double f : CutFractions(arc, plane)) {
    const Eigen::Vector3d x = arc.At(f);
    const double mismatch = PathMismatch(n, a, via1, via2, x), distance = (x - previous).norm();
    bool better = !found;
    if (found) {
      const bool closes = mismatch < kCloses, best_closes = best_mismatch < kCloses;
      if (closes != best_closes)
        better = closes;
      else if (closes)
        better = distance < best_distance;
      else
        better = mismatch < best_mismatch;
    }
    if (better) {
      found = true;
      best_mismatch = mismatch;
      best_distance = distance;
      *point = x;
    }
  }
  return found;
}

// The inversion in the sphere about `centre` with squared radius `power`, of points and (as
// its differential, a mirror image up to a positive scale) of unit vectors at a point.
struct Inversion {
  Eigen::Vector3d centre;
  double power = 1.0;
  Eigen::Vector3d operator()(const Eigen::Vector3d& x) const {
    const Eigen::Vector3d d = x - centre;
    return centre + (power / d.squaredNorm()) * d;
  }
  Eigen::Vector3d Vector(const Eigen::Vector3d& x, const Eigen::Vector3d& v) const {
    const Eigen::Vector3d d = x - centre;
    return (v - (2.0 * d.dot(v) / d.squaredNorm()) * d).normalized();
  }
};

std::string Where(const std::string& where, const std::string& what) {
  return where.empty() ? what : where + ": " + what;
}

}  // namespace

Eigen::Vector3d Arc::At(double fraction) const {
  if (straight) return start + fraction * (end - start);
  const Eigen::Vector3d e1 = start - centre, e2 = normal.cross(e1);
  const double theta = fraction * angle;
  return centre + std::cos(theta) * e1 + std::sin(theta) * e2;
}

Eigen::Vector3d Arc::Tangent(const Eigen::Vector3d& point) const {
  if (straight) return (end - start).normalized();
  return normal.cross(point - centre).normalized();
}

double Arc::Bend() const {
  if (straight) return 0.0;
  const Eigen::Vector3d chord = (end - start).normalized();
  return Tangent(start).cross(chord).norm();
}

Arc ArcFrom(const Eigen::Vector3d& a, const Eigen::Vector3d& t, const Eigen::Vector3d& b,
            const std::string& what) {
  const Eigen::Vector3d chord = b - a;
  if (!(chord.norm() > 0.0)) throw InputError(what + ": its ends coincide");
  Arc arc;
  arc.start = a;
  arc.end = b;
  const Eigen::Vector3d n = t.cross(chord);
  if (!(n.norm() > 1e-12 * chord.norm())) {
    arc.straight = true;
    arc.normal = t.unitOrthogonal();
    arc.radius = INFINITY;
    return arc;
  }
  arc.normal = n.normalized();
  const Eigen::Vector3d inward = arc.normal.cross(t).normalized();
  const double s = chord.squaredNorm() / (2.0 * chord.dot(inward));
  arc.centre = a + s * inward;
  arc.radius = std::abs(s);
  const Eigen::Vector3d e1 = a - arc.centre, e2 = arc.normal.cross(e1), d = b - arc.centre;
  arc.angle = std::atan2(d.dot(e2), d.dot(e1));
  if (arc.angle <= 0.0) arc.angle += 2.0 * M_PI;
  return arc;
}

namespace {

// The patch's four boundary arcs: a → b along t1, a → d along t2, b → c and d → c along the
// mirror images of t2 and t1.
struct PatchArcs {
  Arc ab, ad, bc, dc;
};
PatchArcs ArcsOf(const CyclidicPatch& patch, const std::string& where) {
  const auto& [a, b, c, d] = patch.corners;
  const Frame& f = patch.frame;
  return {ArcFrom(a, f.t1, b, Where(where, "arc a-b")),
          ArcFrom(a, f.t2, d, Where(where, "arc a-d")),
          ArcFrom(b, Mirror(f.t2, b - a), c, Where(where, "arc b-c")),
          ArcFrom(d, Mirror(f.t1, d - a), c, Where(where, "arc d-c"))};
}

// Whether the pencil construction is ill-conditioned on the patch: an arc bent less than
// `bend` (sin of its tangent-chord angle), or opposite arcs in (nearly) one plane.
bool Degenerate(const Arc& ab, const Arc& ad, const Arc& bc, const Arc& dc, double bend) {
  for (const Arc* arc : {&ab, &ad, &bc, &dc})
    if (arc->Bend() < bend) return true;
  return ab.normal.cross(dc.normal).norm() < bend || ad.normal.cross(bc.normal).norm() < bend;
}

std::vector<std::vector<Eigen::Vector3d>> EvaluatePatch(const CyclidicPatch& patch,
                                                        const std::vector<Eigen::Vector3d>& xs,
                                                        const std::vector<Eigen::Vector3d>& zs,
                                                        const std::string& where, bool inverted);

// The patch evaluated after an inversion about a point off it, mapped back; its boundary
// samples kept exactly.
std::vector<std::vector<Eigen::Vector3d>> EvaluateInverted(
    const CyclidicPatch& patch, const std::vector<Eigen::Vector3d>& xs,
    const std::vector<Eigen::Vector3d>& zs, const std::vector<Eigen::Vector3d>& arc_points,
    const std::string& where) {
  const auto& corners = patch.corners;
  const Eigen::Vector3d mid = 0.25 * (corners[0] + corners[1] + corners[2] + corners[3]);
  const Frame& f = patch.frame;
  // The centre lies well outside the ball around the corners and the boundary arcs.
  double size = 0.0;
  for (const Eigen::Vector3d& x : arc_points) size = std::max(size, (x - mid).norm());
  Inversion inv;
  inv.centre = mid + 3.0 * size * (f.n + 0.37 * f.t1 + 0.23 * f.t2).normalized();
  inv.power = size * size;
  CyclidicPatch p;
  for (int k = 0; k < 4; ++k) p.corners[k] = inv(corners[k]);
  p.frame = {inv.Vector(corners[0], f.t1), inv.Vector(corners[0], f.t2),
             inv.Vector(corners[0], f.n)};
  std::vector<Eigen::Vector3d> ixs, izs;
  for (const Eigen::Vector3d& x : xs) ixs.push_back(inv(x));
  for (const Eigen::Vector3d& z : zs) izs.push_back(inv(z));
  std::vector<std::vector<Eigen::Vector3d>> grid = EvaluatePatch(p, ixs, izs, where, true);
  for (auto& row : grid)
    for (Eigen::Vector3d& x : row) x = inv(x);
  for (size_t i = 0; i < xs.size(); ++i) grid[i][0] = xs[i];
  for (size_t j = 0; j < zs.size(); ++j) grid[0][j] = zs[j];
  grid.back().front() = corners[1];
  grid.back().back() = corners[2];
  grid.front().back() = corners[3];
  return grid;
}

std::vector<std::vector<Eigen::Vector3d>> EvaluatePatch(const CyclidicPatch& patch,
                                                        const std::vector<Eigen::Vector3d>& xs,
                                                        const std::vector<Eigen::Vector3d>& zs,
                                                        const std::string& where, bool inverted) {
  const auto& [a, b, c, d] = patch.corners;
  const Frame& f = patch.frame;
  const auto [ab, ad, bc, dc] = ArcsOf(patch, where);
  if (!inverted && Degenerate(ab, ad, bc, dc, 1e-3)) {
    std::vector<Eigen::Vector3d> arc_points;
    for (const Arc* arc : {&ab, &ad, &bc, &dc})
      for (double t : {0.0, 0.25, 0.5, 0.75, 1.0}) arc_points.push_back(arc->At(t));
    return EvaluateInverted(patch, xs, zs, arc_points, where);
  }
  if (inverted && Degenerate(ab, ad, bc, dc, 1e-9))
    throw InputError(Where(where, "the patch degenerates (straight or flat arcs)"));
  const Plane p_ab = PlaneOf(ab), p_dc = PlaneOf(dc), p_ad = PlaneOf(ad), p_bc = PlaneOf(bc);
  const int nx = static_cast<int>(xs.size()), nz = static_cast<int>(zs.size());
  std::vector<std::vector<Eigen::Vector3d>> grid(nx, std::vector<Eigen::Vector3d>(nz));
  std::vector<Plane> family1(nz);  // pencil planes of the family-1 circles through zs
  for (int j = 0; j < nz; ++j) {
    family1[j] = PencilPlane(p_ab, p_dc, zs[j]);
    grid[0][j] = zs[j];
    if (j == 0 || j == nz - 1) {
      grid[nx - 1][j] = j == 0 ? b : c;
    } else if (!CutPoint(bc, family1[j], f.n, a, zs[j], b, grid[nx - 1][j - 1], &grid[nx - 1][j])) {
      throw InputError(Where(where, "a family-1 curvature circle misses arc b-c"));
    }
  }
  Eigen::Vector3d y = d;
  for (int i = 1; i < nx - 1; ++i) {
    const Eigen::Vector3d& x = xs[i];
    if (!CutPoint(dc, PencilPlane(p_ad, p_bc, x), f.n, a, x, d, Eigen::Vector3d(y), &y))
      throw InputError(Where(where, "a family-2 curvature circle misses arc d-c"));
    const Arc circle = ArcFrom(x, Mirror(f.t2, x - a), y, Where(where, "a family-2 circle"));
    grid[i][0] = x;
    grid[i][nz - 1] = y;
    for (int j = 1; j < nz - 1; ++j)
      if (!CutPoint(circle, family1[j], f.n, a, x, zs[j], grid[i][j - 1], &grid[i][j]))
        throw InputError(Where(where, "the curvature circles do not meet"));
  }
  return grid;
}

}  // namespace

namespace {

std::vector<Eigen::Vector3d> Shifted(std::vector<Eigen::Vector3d> points,
                                     const Eigen::Vector3d& by) {
  for (Eigen::Vector3d& x : points) x += by;
  return points;
}

CyclidicPatch Shifted(CyclidicPatch patch, const Eigen::Vector3d& by) {
  for (Eigen::Vector3d& x : patch.corners) x += by;
  return patch;
}

}  // namespace

std::vector<std::vector<Eigen::Vector3d>> EvaluateCyclidicPatch(
    const CyclidicPatch& patch, const std::vector<Eigen::Vector3d>& xs,
    const std::vector<Eigen::Vector3d>& zs, const std::string& where) {
  // In coordinates about the corner a: the pencil planes' offsets and the circles' centres then
  // carry no far-away translation into the intersections.
  const Eigen::Vector3d origin = patch.corners[0];
  std::vector<std::vector<Eigen::Vector3d>> grid = EvaluatePatch(
      Shifted(patch, -origin), Shifted(xs, -origin), Shifted(zs, -origin), where, false);
  for (auto& row : grid)
    for (Eigen::Vector3d& x : row) x += origin;
  // The samples handed in stay exact (neighbouring patches share them).
  for (size_t i = 0; i < xs.size(); ++i) grid[i].front() = xs[i];
  grid.front() = zs;
  return grid;
}

CyclidicPatch CyclidicNet::Patch(int i, int j) const {
  CyclidicPatch p;
  p.corners = {points[shape.Vertex(i, j)], points[shape.Vertex(i, j + 1)],
               points[shape.Vertex(i + 1, j + 1)], points[shape.Vertex(i + 1, j)]};
  const Frame& f = frames[shape.Vertex(i, j)];
  p.frame = {(j % 2 ? -1.0 : 1.0) * f.t1, (i % 2 ? -1.0 : 1.0) * f.t2, f.n};
  return p;
}

CyclidicNet MakeCyclidicNet(const GridShape& shape, std::vector<Eigen::Vector3d> points,
                            const Frame& start) {
  CyclidicNet net;
  net.shape = shape;
  net.points = std::move(points);
  net.frames.resize(net.points.size());
  net.frames[0] = start;
  for (int i = 0; i <= shape.rows; ++i)
    for (int j = 0; j <= shape.cols; ++j) {
      if (i == 0 && j == 0) continue;
      const int from = i == 0 ? shape.Vertex(0, j - 1) : shape.Vertex(i - 1, j);
      const Eigen::Vector3d edge = net.points[shape.Vertex(i, j)] - net.points[from];
      if (!(edge.norm() > 0.0))
        throw InputError("vertices " + std::to_string(from) + " and " +
                         std::to_string(shape.Vertex(i, j)) + " coincide");
      net.frames[shape.Vertex(i, j)] = Mirror(net.frames[from], edge);
    }
  return net;
}

namespace {

template <typename T>
Vec3<T> MirrorT(const Vec3<T>& v, const Eigen::Vector3d& edge) {
  const Vec3<T> e = edge.cast<T>();
  return v - (T(2) * v.dot(e) / T(edge.squaredNorm())) * e;
}

// The start frame of GridStartFrame with a given t2 sign, on any scalar.
template <typename T>
void StartFrameT(const GridShape& shape, const std::vector<Eigen::Vector3d>& points,
                 const T* angles, double t2_sign, Vec3<T>* t1, Vec3<T>* t2, Vec3<T>* n) {
  using std::cos;
  using std::sin;
  *n = Vec3<T>(cos(angles[0]) * cos(angles[1]), cos(angles[0]) * sin(angles[1]), sin(angles[0]));
  const Vec3<T> chord = (points[shape.Vertex(0, 1)] - points[0]).cast<T>();
  const Vec3<T> projected = chord - chord.dot(*n) * (*n);
  const Vec3<T> u = projected / projected.norm();
  *t1 = cos(angles[2]) * u + sin(angles[2]) * n->cross(u);
  *t2 = T(t2_sign) * n->cross(*t1);
}

double T2Sign(const GridShape& shape, const std::vector<Eigen::Vector3d>& points,
              const FrameAngles& angles) {
  const double a[3] = {angles.lambda, angles.theta, angles.psi};
  Eigen::Vector3d t1, t2, n;
  StartFrameT<double>(shape, points, a, 1.0, &t1, &t2, &n);
  return t2.dot(points[shape.Vertex(1, 0)] - points[0]) < 0.0 ? -1.0 : 1.0;
}

// Eq. 5 over the net's edges: frames carried along row 0, then down every column.
template <typename T>
T GridEnergyT(const GridShape& shape, const std::vector<Eigen::Vector3d>& points, const T* angles,
              double t2_sign) {
  std::vector<Vec3<T>> t1(points.size()), t2(points.size());
  Vec3<T> n;
  StartFrameT<T>(shape, points, angles, t2_sign, &t1[0], &t2[0], &n);
  T energy(0);
  const auto arc = [](const Vec3<T>& t, const Eigen::Vector3d& chord) {
    const double c2 = chord.squaredNorm();
    return T(4) * t.cross(chord.cast<T>()).squaredNorm() / T(c2 * c2);
  };
  for (int i = 0; i <= shape.rows; ++i)
    for (int j = 0; j <= shape.cols; ++j) {
      const int v = shape.Vertex(i, j);
      if (i > 0 || j > 0) {
        const int from = i == 0 ? shape.Vertex(0, j - 1) : shape.Vertex(i - 1, j);
        const Eigen::Vector3d edge = points[v] - points[from];
        t1[v] = MirrorT<T>(t1[from], edge);
        t2[v] = MirrorT<T>(t2[from], edge);
      }
      if (j < shape.cols) energy += arc(t1[v], points[shape.Vertex(i, j + 1)] - points[v]);
      if (i < shape.rows) energy += arc(t2[v], points[shape.Vertex(i + 1, j)] - points[v]);
    }
  return energy;
}

class GridFrameObjective final : public ceres::FirstOrderFunction {
 public:
  GridFrameObjective(const GridShape& shape, const std::vector<Eigen::Vector3d>& points,
                     double t2_sign, double scale)
      : shape_(shape), points_(points), t2_sign_(t2_sign), scale_(scale) {}
  bool Evaluate(const double* x, double* cost, double* gradient) const override {
    using Jet = ceres::Jet<double, 3>;
    Jet a[3];
    for (int k = 0; k < 3; ++k) a[k] = Jet(x[k], k);
    const Jet e = GridEnergyT<Jet>(shape_, points_, a, t2_sign_) * scale_;
    *cost = e.a;
    if (gradient != nullptr)
      for (int k = 0; k < 3; ++k) gradient[k] = e.v[k];
    return std::isfinite(*cost);
  }
  int NumParameters() const override { return 3; }

 private:
  GridShape shape_;
  const std::vector<Eigen::Vector3d>& points_;
  double t2_sign_, scale_;
};

// The frame with t1 turned towards (0, 1) and t2 towards (1, 0), so that the arcs along the first
// edges leave towards their ends (eq. 5 is the same for either sense; the patches are not: the
// other sense runs the arcs the long way round). `psi` follows t1.
Frame TowardsEdges(Frame f, const GridShape& shape, const std::vector<Eigen::Vector3d>& points,
                   double* psi) {
  if (f.t1.dot(points[shape.Vertex(0, 1)] - points[0]) < 0.0) {
    f.t1 = -f.t1;
    *psi = std::remainder(*psi + M_PI, 2.0 * M_PI);
  }
  if (f.t2.dot(points[shape.Vertex(1, 0)] - points[0]) < 0.0) f.t2 = -f.t2;
  return f;
}

}  // namespace

Frame GridStartFrame(const GridShape& shape, const std::vector<Eigen::Vector3d>& points,
                     const FrameAngles& angles) {
  const double a[3] = {angles.lambda, angles.theta, angles.psi};
  Frame f;
  StartFrameT<double>(shape, points, a, T2Sign(shape, points, angles), &f.t1, &f.t2, &f.n);
  double psi = angles.psi;
  return TowardsEdges(f, shape, points, &psi);
}

FrameAngles DefaultGridAngles(const GridShape& shape, const std::vector<Eigen::Vector3d>& points) {
  const Eigen::Vector3d &a = points[0], &b = points[shape.Vertex(0, 1)],
                        &c = points[shape.Vertex(1, 1)], &d = points[shape.Vertex(1, 0)];
  Eigen::Vector3d n = (c - a).cross(d - b);
  if (n.dot((b - a).cross(d - a)) < 0.0) n = -n;
  return AnglesFromNormal(n);
}

double GridNetEnergy(const CyclidicNet& net) {
  double energy = 0.0;
  const GridShape& s = net.shape;
  for (int i = 0; i <= s.rows; ++i)
    for (int j = 0; j <= s.cols; ++j) {
      const int v = s.Vertex(i, j);
      const Frame& f = net.frames[v];
      for (const auto& [t, to] : {std::pair{f.t1, j < s.cols ? s.Vertex(i, j + 1) : -1},
                                  {f.t2, i < s.rows ? s.Vertex(i + 1, j) : -1}}) {
        if (to < 0) continue;
        const Eigen::Vector3d chord = net.points[to] - net.points[v];
        energy += 4.0 * t.cross(chord).squaredNorm() / (chord.squaredNorm() * chord.squaredNorm());
      }
    }
  return energy;
}

namespace {

// Records every iterate of the frame's BFGS and asks the run's callback.
class FairingRecorder final : public ceres::IterationCallback {
 public:
  FairingRecorder(double scale, const RunCallback& callback, GridFrameFairing* out)
      : scale_(scale), callback_(callback), out_(out) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& s) override {
    RunRecord record;
    record.iteration = s.iteration;
    record.energy = s.cost;
    record.step = s.step_norm;
    record.max_constraint = NAN;  // no constraint rows
    record.seconds = s.iteration_time_in_seconds;
    record.measures = {{"smoothness_energy", s.cost / scale_}};
    out_->history.push_back(record);
    if (!callback_ || callback_(record)) return ceres::SOLVER_CONTINUE;
    out_->aborted = true;
    return ceres::SOLVER_ABORT;
  }

 private:
  double scale_;
  const RunCallback& callback_;
  GridFrameFairing* out_;
};

}  // namespace

GridFrameFairing FairGridFrame(const GridShape& shape, const std::vector<Eigen::Vector3d>& points,
                               const FrameAngles& start, int max_iterations,
                               const RunCallback& callback) {
  double edge = 0.0;
  int edges = 0;
  for (int i = 0; i <= shape.rows; ++i)
    for (int j = 0; j <= shape.cols; ++j) {
      if (j < shape.cols)
        edge += (points[shape.Vertex(i, j + 1)] - points[shape.Vertex(i, j)]).norm(), ++edges;
      if (i < shape.rows)
        edge += (points[shape.Vertex(i + 1, j)] - points[shape.Vertex(i, j)]).norm(), ++edges;
    }
  edge /= std::max(edges, 1);
  const double t2_sign = T2Sign(shape, points, start);
  const double scale = edge * edge / std::max(edges, 1);
  double x[3] = {start.lambda, start.theta, start.psi};
  GridFrameFairing out;
  out.initial_energy = GridEnergyT<double>(shape, points, x, t2_sign);
  ceres::GradientProblem problem(new GridFrameObjective(shape, points, t2_sign, scale));
  ceres::GradientProblemSolver::Options options;
  options.line_search_direction_type = ceres::BFGS;
  options.max_num_iterations = max_iterations;
  options.logging_type = ceres::SILENT;
  FairingRecorder recorder(scale, callback, &out);
  options.callbacks.push_back(&recorder);
  ceres::GradientProblemSolver::Summary summary;
  ceres::Solve(options, problem, x, &summary);
  out.angles = {x[0], x[1], x[2]};
  StartFrameT<double>(shape, points, x, t2_sign, &out.frame.t1, &out.frame.t2, &out.frame.n);
  out.frame = TowardsEdges(out.frame, shape, points, &out.angles.psi);
  out.final_energy = GridEnergyT<double>(shape, points, x, t2_sign);
  out.iterations = static_cast<int>(summary.iterations.size()) - 1;
  out.converged = summary.termination_type == ceres::CONVERGENCE;
  out.message = summary.BriefReport();
  return out;
}

CyclidicNet CyclidicNetOfStrip(const CyclidicStrip& strip) {
  GridShape shape;
  shape.rows = 1;
  shape.cols = static_cast<int>(strip.strip.p.size()) - 1;
  std::vector<Eigen::Vector3d> points = strip.strip.p;
  points.insert(points.end(), strip.strip.q.begin(), strip.strip.q.end());
  return MakeCyclidicNet(shape, std::move(points), strip.p_frames[0]);
}

double MaxFaceFrameClosure(const CyclidicNet& net, int* worst_face) {
  double worst = 0.0;
  if (worst_face) *worst_face = -1;
  const GridShape& s = net.shape;
  for (int i = 0; i < s.rows; ++i)
    for (int j = 0; j < s.cols; ++j) {
      const int ring[5] = {s.Vertex(i, j), s.Vertex(i, j + 1), s.Vertex(i + 1, j + 1),
                           s.Vertex(i + 1, j), s.Vertex(i, j)};
      Frame f = net.frames[ring[0]];
      for (int k = 0; k < 4; ++k) f = Mirror(f, net.points[ring[k + 1]] - net.points[ring[k]]);
      const Frame& g = net.frames[ring[0]];
      double angle = 0.0;
      for (const auto& [u, v] : {std::pair{f.t1, g.t1}, {f.t2, g.t2}, {f.n, g.n}})
        angle = std::max(angle, std::atan2(u.cross(v).norm(), u.dot(v)));
      if (angle * 180.0 / M_PI > worst) {
        worst = angle * 180.0 / M_PI;
        if (worst_face) *worst_face = i * s.cols + j;
      }
    }
  return worst;
}

bool CyclidicSurfaceOptions::IsValid(std::string* why) const {
  if (segments < 1 || segments > 1000) {
    *why = "segments must be in [1, 1000]";
    return false;
  }
  return true;
}

namespace {

// Equal-angle samples of an arc, its ends exact.
std::vector<Eigen::Vector3d> Samples(const Arc& arc, const Eigen::Vector3d& end, int segments) {
  std::vector<Eigen::Vector3d> x(segments + 1);
  for (int k = 0; k <= segments; ++k) x[k] = arc.At(static_cast<double>(k) / segments);
  x.front() = arc.start;
  x.back() = end;
  return x;
}

// The angle (degrees) between two normals, with their senses: a patch that folds back across
// an arc turns its normal by about 180°.
double AngleDeg(const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
  return std::atan2(u.cross(v).norm(), u.dot(v)) * 180.0 / M_PI;
}

std::string PatchName(int i, int j) {
  return "patch (" + std::to_string(i) + ", " + std::to_string(j) + ")";
}

// Per patch (row-major), the samples on its arc a-b (xs) and a-d (zs), and its evaluated grid
// grid[u][v]; neighbours share the samples of their common arc.
struct PatchGrids {
  std::vector<std::vector<Eigen::Vector3d>> xs, zs;
  std::vector<std::vector<std::vector<Eigen::Vector3d>>> grids;
};

PatchGrids EvaluatePatches(const CyclidicNet& net, int s) {
  const int rows = net.shape.rows, cols = net.shape.cols;
  PatchGrids g;
  g.xs.resize(rows * cols);
  g.zs.resize(rows * cols);
  g.grids.resize(rows * cols);
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) {
      const int k = i * cols + j;
      const CyclidicPatch p = net.Patch(i, j);
      const std::string name = PatchName(i, j);
      if (i == 0)
        g.xs[k] = Samples(ArcsOf(p, name).ab, p.corners[1], s);
      else
        for (const auto& row : g.grids[k - cols]) g.xs[k].push_back(row.back());
      if (j == 0)
        g.zs[k] = Samples(ArcsOf(p, name).ad, p.corners[3], s);
      else
        g.zs[k] = g.grids[k - 1].back();
      g.grids[k] = EvaluateCyclidicPatch(p, g.xs[k], g.zs[k], name);
    }
  return g;
}

// The angle at m, a point of the arc shared as `near_arc` of the near patch and `far_arc` of the
// far one, between the near patch's plane (the arc and its curvature circle from `from`, which
// leaves along `leave`) and the far patch's (the arc and `far_vector` carried from its corner).
double TangentJump(const Arc& near_arc, const Eigen::Vector3d& from, const Eigen::Vector3d& leave,
                   const Eigen::Vector3d& m, const Arc& far_arc, const Eigen::Vector3d& far_vector,
                   const Eigen::Vector3d& far_corner) {
  const Arc circle = ArcFrom(from, leave, m, "");
  return AngleDeg(near_arc.Tangent(m).cross(circle.Tangent(m)),
                  far_arc.Tangent(m).cross(Carry(far_vector, far_corner, m)));
}

// Tangent planes across shared arcs, at the arc's inner fine vertices: on each side the plane of
// the arc's tangent and the tangent of that patch's curvature circle crossing it (the arriving
// circle's on the near side, the leaving circle's frame vector on the far side), in coordinates
// about the near patch's corner. The largest angle between them (degrees).
double MaxTangentAngle(const CyclidicNet& net, const PatchGrids& g, int s) {
  const GridShape& shape = net.shape;
  const int rows = shape.rows, cols = shape.cols;
  double worst = 0.0;
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) {
      const int k = i * cols + j;
      const Eigen::Vector3d shift = -net.points[shape.Vertex(i, j)];
      const CyclidicPatch p = Shifted(net.Patch(i, j), shift);
      const Eigen::Vector3d& a = p.corners[0];
      const PatchArcs arcs = ArcsOf(p, "");
      if (i + 1 < rows) {  // arc d-c, shared with patch (i + 1, j) as its arc a-b
        const CyclidicPatch q = Shifted(net.Patch(i + 1, j), shift);
        for (int u = 1; u < s; ++u) {
          const Eigen::Vector3d x = g.xs[k][u] + shift;
          worst = std::max(
              worst, TangentJump(arcs.dc, x, Mirror(p.frame.t2, x - a), g.grids[k][u][s] + shift,
                                 ArcsOf(q, "").ab, q.frame.t2, q.corners[0]));
        }
      }
      if (j + 1 < cols) {  // arc b-c, shared with patch (i, j + 1) as its arc a-d
        const CyclidicPatch q = Shifted(net.Patch(i, j + 1), shift);
        for (int v = 1; v < s; ++v) {
          const Eigen::Vector3d z = g.zs[k][v] + shift;
          worst = std::max(
              worst, TangentJump(arcs.bc, z, Mirror(p.frame.t1, z - a), g.grids[k][s][v] + shift,
                                 ArcsOf(q, "").ad, q.frame.t1, q.corners[0]));
        }
      }
    }
  return worst;
}

// The mesh of the fine grid (out->fine_shape), with the last fine column welded onto the first
// when the net is closed around and they coincide (out->welded). Returns the seam's gap per
// mean row edge of the net.
double MeshFineGrid(const CyclidicNet& net, const std::vector<Eigen::Vector3d>& fine,
                    bool weld_closed, CyclidicSurface* out) {
  const GridShape& shape = net.shape;
  double edge = 0.0;
  int edges = 0;
  for (int i = 0; i <= shape.rows; ++i)
    for (int j = 0; j < shape.cols; ++j, ++edges)
      edge += (net.points[shape.Vertex(i, j + 1)] - net.points[shape.Vertex(i, j)]).norm();
  edge /= std::max(edges, 1);
  double seam = 0.0;
  const GridShape& fs = out->fine_shape;
  for (int r = 0; r <= fs.rows; ++r)
    seam = std::max(seam, (fine[fs.Vertex(r, fs.cols)] - fine[fs.Vertex(r, 0)]).norm());
  out->welded = weld_closed && seam <= kSurfaceWeldTolerance * edge;
  std::vector<PolyMesh::VertexHandle> v(fine.size());
  for (int r = 0; r <= fs.rows; ++r)
    for (int q = 0; q <= fs.cols; ++q) {
      const int id = fs.Vertex(r, q);
      if (out->welded && q == fs.cols) {
        v[id] = v[fs.Vertex(r, 0)];
        continue;
      }
      v[id] = out->mesh.add_vertex(PolyMesh::Point(fine[id].x(), fine[id].y(), fine[id].z()));
    }
  for (int r = 0; r < fs.rows; ++r)
    for (int q = 0; q < fs.cols; ++q)
      out->mesh.add_face(
          std::vector<PolyMesh::VertexHandle>{v[fs.Vertex(r, q)], v[fs.Vertex(r + 1, q)],
                                              v[fs.Vertex(r + 1, q + 1)], v[fs.Vertex(r, q + 1)]});
  return seam / edge;
}

// Arcs that run the long way round (beyond 225°: semicircles are a canal's own).
int LongArcs(const CyclidicNet& net) {
  int long_arcs = 0;
  for (int i = 0; i < net.shape.rows; ++i)
    for (int j = 0; j < net.shape.cols; ++j) {
      const PatchArcs arcs = ArcsOf(net.Patch(i, j), "");
      for (const Arc* arc : {&arcs.ab, &arcs.ad, &arcs.bc, &arcs.dc})
        if (!arc->straight && arc->angle > 1.25 * M_PI) ++long_arcs;
    }
  return long_arcs;
}

}  // namespace

CyclidicSurface MeshCyclidicSurface(const CyclidicNet& net, const CyclidicSurfaceOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError("cyclidic surface: " + why);
  const GridShape& shape = net.shape;
  const int s = options.segments, rows = shape.rows, cols = shape.cols;
  const double fine_vertices =
      (static_cast<double>(rows) * s + 1) * (static_cast<double>(cols) * s + 1);
  if (fine_vertices > kMaxFineVertices) {
    char text[160];
    std::snprintf(text, sizeof(text),
                  "the fine mesh would have %.3g vertices (%d x %d patches, %d segments per arc; "
                  "at most %.0e): lower the segments",
                  fine_vertices, rows, cols, s, kMaxFineVertices);
    throw InputError(text);
  }
  const PatchGrids g = EvaluatePatches(net, s);
  // The fine grid: vertex (i s + v, j s + u) = patch (i, j)'s grid[u][v].
  CyclidicSurface out;
  out.fine_shape.rows = rows * s;
  out.fine_shape.cols = cols * s;
  std::vector<Eigen::Vector3d> fine(out.fine_shape.num_vertices());
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j)
      for (int u = 0; u <= s; ++u)
        for (int v = 0; v <= s; ++v)
          fine[out.fine_shape.Vertex(i * s + v, j * s + u)] = g.grids[i * cols + j][u][v];
  const double worst = MaxTangentAngle(net, g, s);
  const double seam_gap = MeshFineGrid(net, fine, options.weld_closed, &out);
  const CircularityMeasures fine_measures = MeasureCircularity(out.mesh);
  out.measures = {{"patches", static_cast<double>(rows * cols)},
                  {"max_tangent_angle_deg", worst},
                  {"max_face_frame_closure_deg", MaxFaceFrameClosure(net)},
                  {"fine_max_concyclicity", fine_measures.max_concyclicity},
                  {"folded_fine_quads", static_cast<double>(fine_measures.folded_quads)},
                  {"long_arcs", static_cast<double>(LongArcs(net))}};
  if (options.weld_closed) out.measures.push_back({"seam_gap", seam_gap});
  return out;
}

bool CyclidicMeshOptions::IsValid(std::string* why) const {
  if (!surface.IsValid(why)) return false;
  if (max_iterations < 1) {
    *why = "max_iterations must be ≥ 1";
    return false;
  }
  if (!(closure_tolerance > 0.0)) {
    *why = "closure_tolerance must be positive";
    return false;
  }
  return true;
}

CyclidicMeshResult CyclidicSurfaceOfMesh(const PolyMesh& mesh, const CyclidicMeshOptions& options,
                                         const std::string& path) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError("cyclidic surface: " + why);
  const GridShape shape = DetectGridShape(mesh, path);
  std::vector<Eigen::Vector3d> points;
  for (auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    points.emplace_back(p[0], p[1], p[2]);
  }
  CyclidicMeshResult r;
  r.given_frame = options.given_frame;
  Frame frame;
  if (options.given_frame) {
    r.angles = options.angles;
    CheckFrameNormal(r.angles, points[0], points[shape.Vertex(0, 1)]);
    frame = GridStartFrame(shape, points, r.angles);
  } else {
    FrameAngles start = DefaultGridAngles(shape, points);
    start.psi = options.angles.psi;
    r.fairing = FairGridFrame(shape, points, start, options.max_iterations, options.callback);
    r.angles = r.fairing.angles;
    frame = r.fairing.frame;
  }
  const CyclidicNet net = MakeCyclidicNet(shape, points, frame);
  int face = -1;
  const double closure = MaxFaceFrameClosure(net, &face);
  if (closure > options.closure_tolerance) {
    char text[200];
    std::snprintf(text, sizeof(text),
                  "face %d is not circular: the frames carried around it miss by %.3g deg "
                  "(`closure_tolerance` %.1e); make the mesh circular first (planarize with "
                  "`circular`)",
                  face, closure, options.closure_tolerance);
    throw InputError(path.empty() ? text : path + ": " + text);
  }
  r.surface = MeshCyclidicSurface(net, options.surface);
  const double energy = GridNetEnergy(net);
  r.initial = {{"smoothness_energy", options.given_frame ? energy : r.fairing.initial_energy}};
  r.final = r.surface.measures;
  r.final.push_back({"smoothness_energy", energy});
  return r;
}

std::string CyclidicSurfaceFault(const NamedValues& measures, double tangent_tolerance) {
  char text[240];
  if (const double folded = ValueOf(measures, "folded_fine_quads"); folded > 0) {
    std::snprintf(text, sizeof(text),
                  "the smooth surface folds or pinches: %.0f fine quads are not convex (the frame "
                  "turns patches through a cone point; try another frame)",
                  folded);
    return text;
  }
  if (const double arcs = ValueOf(measures, "long_arcs"); arcs > 0) {
    std::snprintf(text, sizeof(text),
                  "%.0f patch arcs run more than 225 deg round their circles: the frame points "
                  "away from the edges and the surface wraps round (try the default frame)",
                  arcs);
    return text;
  }
  if (const double angle = ValueOf(measures, "max_tangent_angle_deg"); angle > tangent_tolerance) {
    std::snprintf(text, sizeof(text),
                  "the patches' tangent planes disagree by %.3g deg across a shared arc (tolerance "
                  "%.1e)",
                  angle, tangent_tolerance);
    return text;
  }
  if (const double c = ValueOf(measures, "fine_max_concyclicity"); c > 1e-4) {
    std::snprintf(text, sizeof(text),
                  "fine quads are off their circles by %.3g of the mean edge: the surface was not "
                  "evaluated reliably",
                  c);
    return text;
  }
  return "";
}

RunReport CyclidicRunReport(const CyclidicMeshResult& result, double tangent_tolerance,
                            const Construction& construction) {
  const std::string fault = CyclidicSurfaceFault(result.final, tangent_tolerance);
  RunReport report = construction.Finish(result.initial, result.final, fault.empty());
  report.iterations = result.fairing.iterations;
  report.history = result.fairing.history;
  report.termination =
      fault.empty()
          ? (result.given_frame ? "frame given" : "frame by eq. 5: " + result.fairing.message)
          : fault;
  if (result.fairing.aborted) {
    report.converged = false;
    report.termination = "USER_ABORT: the frame's minimisation was stopped on request";
  }
  return report;
}

nlohmann::json CyclidicJson(const CyclidicMeshResult& result) {
  const FrameAngles& a = result.angles;
  const Eigen::Vector3d n = NormalOf(a);
  nlohmann::json json;
  json["frame"] = {{"lambda", a.lambda}, {"theta", a.theta}, {"psi", a.psi}};
  json["frame"]["normal"] = {n.x(), n.y(), n.z()};
  json["fine_mesh"] = {{"rows", result.surface.fine_shape.rows},
                       {"cols", result.surface.fine_shape.cols}};
  return json;
}

}  // namespace gproj::circular
