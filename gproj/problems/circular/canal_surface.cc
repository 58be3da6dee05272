#include "gproj/problems/circular/canal_surface.h"

#include <ceres/ceres.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>

#include "gproj/problems/circular/circular_mesh.h"
#include "gproj/problems/run/construction.h"

namespace gproj::circular {

CircularStripInput MakeCircularStripInput(std::vector<Eigen::Vector3d> curve,
                                          const Eigen::Vector3d& first_point,
                                          const std::vector<double>& lengths, double length) {
  CircularStripInput input;
  input.curve = std::move(curve);
  input.first_point = first_point;
  const std::size_t n = input.curve.size();
  if (!lengths.empty() && length > 0.0)
    throw InputError("give either `lengths` or `length`, not both");
  if (!lengths.empty()) {
    input.lengths = lengths;
  } else if (length > 0.0) {
    input.lengths.assign(n, length);
  } else {
    throw InputError(
        "give the lengths across the strip (`lengths`, one per curve point, or `length` for all)");
  }
  if (input.lengths.size() != n)
    throw InputError("`lengths` needs one value per curve point (" + std::to_string(n) + "), got " +
                     std::to_string(input.lengths.size()));
  return input;
}
namespace {

using std::acos;
using std::asin;
using std::atan2;
using std::cos;
using std::sin;
using std::sqrt;

template <typename T>
Vec3<T> Cast(const Eigen::Vector3d& v) {
  return Vec3<T>(T(v.x()), T(v.y()), T(v.z()));
}

// x rotated by `angle` about the axis through c with unit direction n.
template <typename T>
Vec3<T> Rotate(const Vec3<T>& x, const Vec3<T>& c, const Vec3<T>& n, const T& angle) {
  const Vec3<T> d = x - c;
  return c + cos(angle) * d + sin(angle) * n.cross(d);
}

// Angle in [0, 2π) from `from` to `to` about the axis (c, n), counter-clockwise seen from n.
template <typename T>
T CcwAngle(const Vec3<T>& from, const Vec3<T>& to, const Vec3<T>& c, const Vec3<T>& n) {
  const Vec3<T> e1 = from - c, e2 = n.cross(e1), d = to - c;
  T angle = atan2(d.dot(e2), d.dot(e1));
  if (angle < T(0)) angle += T(2 * M_PI);
  return angle;
}

// The value of a double or of a Jet (for messages).
double ScalarValue(double value) { return value; }
template <typename T, int N>
double ScalarValue(const ceres::Jet<T, N>& value) {
  return value.a;
}

// Scale-free constructions: the strip, the net and the mesh are computed on the input divided
// by a power of two near its largest coordinate. That is exact (the same results at ordinary
// scales) and keeps squares and cross products from overflowing or underflowing at any finite
// scale, where the construction's relative tests would otherwise give false diagnoses.
int ScaleExponent(const std::vector<Eigen::Vector3d>& a,
                  const std::vector<Eigen::Vector3d>& b = {}) {
  double largest = 0.0;
  for (const auto* points : {&a, &b})
    for (const Eigen::Vector3d& p : *points) largest = std::max(largest, p.cwiseAbs().maxCoeff());
  return largest > 0.0 && std::isfinite(largest) ? std::ilogb(largest) : 0;
}
Eigen::Vector3d Scaled(const Eigen::Vector3d& p, int exponent) {
  return {std::ldexp(p.x(), exponent), std::ldexp(p.y(), exponent), std::ldexp(p.z(), exponent)};
}
std::vector<Eigen::Vector3d> Scaled(std::vector<Eigen::Vector3d> points, int exponent) {
  for (Eigen::Vector3d& p : points) p = Scaled(p, exponent);
  return points;
}
CircularStrip Scaled(const CircularStrip& strip, int exponent) {
  return {Scaled(strip.p, exponent), Scaled(strip.q, exponent)};
}
Circle Scaled(const Circle& c, int exponent) {
  return {Scaled(c.centre, exponent), c.normal, std::ldexp(c.radius, exponent)};
}

// Reflection in the plane perpendicular to `edge`.
template <typename T>
Vec3<T> Reflect(const Vec3<T>& x, const Vec3<T>& edge) {
  return x - (T(2) * x.dot(edge) / edge.squaredNorm()) * edge;
}

// 1 / R² of the arc from a to a + chord with tangent t (unit) at a.
template <typename T>
T InverseRadiusSquared(const Vec3<T>& t, const Vec3<T>& chord) {
  const T c2 = chord.squaredNorm();
  return T(4) * t.cross(chord).squaredNorm() / (c2 * c2);
}

// Q_0..Q_n by propagation (see the header). On failure returns false with a message.
// `unit`: the input's length unit, for the lengths in messages.
template <typename T>
bool BuildStripT(const std::vector<Eigen::Vector3d>& curve, const Eigen::Vector3d& first,
                 const T* lengths, std::vector<Vec3<T>>* q, std::string* error, double unit = 1.0) {
  const auto number = [unit](double x) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.6g", x * unit);
    return std::string(text);
  };
  const int n = static_cast<int>(curve.size()) - 1;
  q->assign(n + 1, Vec3<T>::Zero());
  const CircleT<T> first_circle =
      CircleThrough<T>(Cast<T>(curve[0]), Cast<T>(curve[1]), Cast<T>(first));
  auto point_at_chord = [&](const CircleT<T>& circle, const Vec3<T>& from, const T& length, int k,
                            T* angle) {
    if (!(length > T(0)) || !(length < T(2) * circle.radius)) {
      *error = "length " + std::to_string(k) + " (" + number(ScalarValue(length)) +
               ") must be positive and shorter than the circle's diameter " +
               number(2 * ScalarValue(circle.radius));
      return false;
    }
    *angle = T(2) * asin(length / (T(2) * circle.radius));
    return true;
  };
  {
    // Q_0: from P_0 clockwise (away from P_1, which comes first counter-clockwise).
    T delta;
    if (!point_at_chord(first_circle, Cast<T>(curve[0]), lengths[0], 0, &delta)) return false;
    const T alpha =
        CcwAngle<T>(Cast<T>(curve[0]), Cast<T>(curve[1]), first_circle.centre, first_circle.normal);
    if (!(T(2 * M_PI) - delta > alpha)) {
      *error = "length 0 is so long that Q_0 passes P_1 on the first circle";
      return false;
    }
    (*q)[0] = Rotate<T>(Cast<T>(curve[0]), first_circle.centre, first_circle.normal, -delta);
  }
  for (int k = 0; k < n; ++k) {
    const Vec3<T> pk = Cast<T>(curve[k]), pk1 = Cast<T>(curve[k + 1]);
    const CircleT<T> circle = CircleThrough<T>(pk, pk1, (*q)[k]);
    // Collinear (to 1e-12): the circle through them is wider than 1e12 chords.
    if (!(circle.radius == circle.radius) || !(circle.radius < T(1e12) * (pk1 - pk).norm())) {
      *error = "P_" + std::to_string(k) + ", P_" + std::to_string(k + 1) + " and Q_" +
               std::to_string(k) + " are collinear";
      return false;
    }
    T delta;
    if (!point_at_chord(circle, pk1, lengths[k + 1], k + 1, &delta)) return false;
    const T gamma = CcwAngle<T>(pk1, (*q)[k], circle.centre, circle.normal);
    if (!(delta < gamma)) {
      *error = "length " + std::to_string(k + 1) + " makes Q_" + std::to_string(k + 1) +
               " pass Q_" + std::to_string(k) + " (quad " + std::to_string(k) + " would fold)";
      return false;
    }
    (*q)[k + 1] = Rotate<T>(pk1, circle.centre, circle.normal, delta);
  }
  return true;
}

template <typename T>
Vec3<T> NormalOfAngles(const T& lambda, const T& theta) {
  return Vec3<T>(cos(lambda) * cos(theta), cos(lambda) * sin(theta), sin(lambda));
}

// The frame at P_0 of the unit normal n and the turn ψ of t1 about it.
template <typename T>
void FrameAtStart(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Vec3<T>& normal,
                  const T& psi, Vec3<T>* t1, Vec3<T>* t2, Vec3<T>* n) {
  *n = normal;
  const Vec3<T> chord = Cast<T>(p1) - Cast<T>(p0);
  const Vec3<T> projected = chord - chord.dot(*n) * (*n);
  const Vec3<T> u = projected / projected.norm();
  *t1 = cos(psi) * u + sin(psi) * n->cross(u);
  *t2 = n->cross(*t1);
}

// The frame at P_0 of the angles λ, θ, ψ.
template <typename T>
void FrameAtStart(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const T* angles,
                  Vec3<T>* t1, Vec3<T>* t2, Vec3<T>* n) {
  FrameAtStart<T>(p0, p1, NormalOfAngles<T>(angles[0], angles[1]), angles[2], t1, t2, n);
}

// F of 000 eq. 5 over the strip's edges, and the edge count.
template <typename T>
T StripEnergy(const std::vector<Eigen::Vector3d>& p, const std::vector<Vec3<T>>& q,
              const Vec3<T>& normal, const T& psi) {
  Vec3<T> t1, t2, n;
  FrameAtStart<T>(p[0], p[1], normal, psi, &t1, &t2, &n);
  T energy(0);
  const int last = static_cast<int>(p.size()) - 1;
  for (int k = 0; k <= last; ++k) {
    const Vec3<T> pk = Cast<T>(p[k]);
    const Vec3<T> across = q[k] - pk;
    energy += InverseRadiusSquared<T>(t2, across);
    // Frame at Q_k, and the edge Q_k → Q_{k+1}.
    const Vec3<T> qt1 = Reflect<T>(t1, across);
    if (k < last) {
      energy += InverseRadiusSquared<T>(qt1, q[k + 1] - q[k]);
      const Vec3<T> along = Cast<T>(p[k + 1]) - pk;
      energy += InverseRadiusSquared<T>(t1, along);
      t1 = Reflect<T>(t1, along);
      t2 = Reflect<T>(t2, along);
    }
  }
  return energy;
}

template <typename T>
T StripEnergy(const std::vector<Eigen::Vector3d>& p, const std::vector<Vec3<T>>& q,
              const T* angles) {
  return StripEnergy<T>(p, q, NormalOfAngles<T>(angles[0], angles[1]), angles[2]);
}

// The unit vector along a (divided by its largest component first: no overflow or underflow).
Eigen::Vector3d UnitAxis(const Eigen::Vector3d& a) {
  const double largest = a.cwiseAbs().maxCoeff();
  return largest > 0.0 ? Eigen::Vector3d(a / largest).normalized() : a;
}

// The frame's parameters: λ, θ, ψ; on a cone (options.cone) its turn φ and ψ.
int FrameParameters(const CanalSmoothingOptions& options) {
  return !options.optimize_frame ? 0 : options.cone.enabled ? 2 : 3;
}

// Parameters: [lengths (if optimised)] [the frame's (if optimised)].
class CanalObjective final : public ceres::FirstOrderFunction {
 public:
  CanalObjective(const CircularStripInput& input, const FrameAngles& angles,
                 const CanalSmoothingOptions& options, double edge_scale)
      : input_(input), options_(options), edge_scale_(edge_scale) {
    angles_[0] = angles.lambda;
    angles_[1] = angles.theta;
    angles_[2] = angles.psi;
    num_parameters_ = (options.optimize_lengths ? static_cast<int>(input.lengths.size()) : 0) +
                      FrameParameters(options);
    options.cone.Basis(&e1_, &e2_);
  }

  template <typename T>
  bool Eval(const T* x, T* cost, T* energy_out = nullptr) const {
    const int n = static_cast<int>(input_.lengths.size());
    std::vector<T> lengths(n);
    int k = 0;
    for (int i = 0; i < n; ++i)
      lengths[i] = options_.optimize_lengths ? x[k++] : T(input_.lengths[i]);
    Vec3<T> normal;
    T psi;
    if (options_.optimize_frame && options_.cone.enabled) {
      // n = sin α a + cos α (cos φ e1 + sin φ e2): on the cone whatever φ.
      const double alpha = options_.cone.angle_deg * M_PI / 180.0;
      using std::cos;
      using std::sin;
      const T phi = x[k++];
      normal = Cast<T>(std::sin(alpha) * UnitAxis(options_.cone.axis)) +
               T(std::cos(alpha)) * (cos(phi) * Cast<T>(e1_) + sin(phi) * Cast<T>(e2_));
      psi = x[k++];
    } else {
      T angles[3];
      for (int i = 0; i < 3; ++i) angles[i] = options_.optimize_frame ? x[k++] : T(angles_[i]);
      normal = NormalOfAngles<T>(angles[0], angles[1]);
      psi = angles[2];
    }
    std::vector<Vec3<T>> q;
    std::string error;
    if (!BuildStripT<T>(input_.curve, input_.first_point, lengths.data(), &q, &error)) return false;
    const T energy = StripEnergy<T>(input_.curve, q, normal, psi);
    const int edges = 3 * (n - 1) + 1;
    T regulariser(0);
    for (int i = 0; i < n; ++i) {
      const T r = lengths[i] / T(input_.lengths[i]) - T(1);
      regulariser += r * r;
    }
    *cost =
        energy * T(edge_scale_ * edge_scale_ / edges) + T(options_.length_weight / n) * regulariser;
    if (energy_out) *energy_out = energy;
    using std::isfinite;
    return isfinite(*cost);
  }

  bool Evaluate(const double* parameters, double* cost, double* gradient) const override {
    if (gradient == nullptr) return Eval<double>(parameters, cost);
    // Forward-mode automatic differentiation, eight parameters per pass.
    using Jet = ceres::Jet<double, 8>;
    std::vector<Jet> x(num_parameters_);
    for (int start = 0; start < num_parameters_; start += 8) {
      for (int i = 0; i < num_parameters_; ++i) {
        x[i] = Jet(parameters[i]);
        if (i >= start && i < start + 8) x[i].v[i - start] = 1.0;
      }
      Jet out;
      if (!Eval<Jet>(x.data(), &out)) return false;
      *cost = out.a;
      for (int i = start; i < std::min(start + 8, num_parameters_); ++i)
        gradient[i] = out.v[i - start];
    }
    return true;
  }
  int NumParameters() const override { return num_parameters_; }

 private:
  CircularStripInput input_;
  CanalSmoothingOptions options_;
  double edge_scale_;
  double angles_[3];
  Eigen::Vector3d e1_, e2_;  // the cone's basis
  int num_parameters_ = 0;
};

// The parameters of the objective: [lengths (if optimised)] [λ, θ, ψ, or φ, ψ on a cone (if
// optimised)].
std::vector<double> Pack(const CircularStripInput& input, const FrameAngles& angles,
                         const CanalSmoothingOptions& options) {
  std::vector<double> x;
  if (options.optimize_lengths) x = input.lengths;
  if (options.optimize_frame && options.cone.enabled)
    x.insert(x.end(), {options.cone.Turn(NormalOf(angles)), angles.psi});
  else if (options.optimize_frame)
    x.insert(x.end(), {angles.lambda, angles.theta, angles.psi});
  return x;
}

// The strip input and the frame that parameters x stand for.
void Unpack(const double* x, const CanalSmoothingOptions& options, CircularStripInput* input,
            FrameAngles* angles) {
  int k = 0;
  if (options.optimize_lengths)
    for (auto& l : input->lengths) l = x[k++];
  if (options.optimize_frame && options.cone.enabled) {
    *angles = AnglesFromNormal(options.cone.NormalAt(x[k]));
    angles->psi = x[k + 1];
  } else if (options.optimize_frame) {
    *angles = {x[k], x[k + 1], x[k + 2]};
  }
}

// F of 000 eq. 5 for parameters x.
double EnergyAt(const double* x, const CanalSmoothingOptions& options, CircularStripInput input,
                FrameAngles angles) {
  Unpack(x, options, &input, &angles);
  return MakeCyclidicStrip(BuildCircularStrip(input), angles).energy;
}

// Records every iterate (Ceres updates the parameters first) and asks the run's callback.
class RecordingCallback final : public ceres::IterationCallback {
 public:
  RecordingCallback(std::function<double()> energy, const RunCallback& callback,
                    std::vector<RunRecord>* history)
      : energy_(std::move(energy)), callback_(callback), history_(history) {}
  // Before each solve: its iterations are numbered after `offset` earlier ones; a restart's
  // iteration 0 (the previous solve's last iterate) is not recorded again.
  void Restart(int offset, bool skip_first) {
    offset_ = offset;
    skip_first_ = skip_first;
    calls_ = 0;
  }
  int recorded() const { return calls_; }    // iterates of the current solve seen so far
  bool stopped() const { return stopped_; }  // the run's callback returned false

  ceres::CallbackReturnType operator()(const ceres::IterationSummary& s) override {
    if (calls_++ == 0 && skip_first_) return ceres::SOLVER_CONTINUE;
    RunRecord record;
    record.iteration = offset_ + s.iteration;
    record.energy = s.cost;
    record.step = s.step_norm;
    record.max_constraint = NAN;  // no constraint rows
    record.seconds = s.iteration_time_in_seconds;
    record.measures = {{"smoothness_energy", energy_()}};
    history_->push_back(record);
    if (stopped_) return ceres::SOLVER_ABORT;
    stopped_ = callback_ && !callback_(record);
    return stopped_ ? ceres::SOLVER_ABORT : ceres::SOLVER_CONTINUE;
  }

 private:
  std::function<double()> energy_;
  const RunCallback& callback_;
  std::vector<RunRecord>* history_;
  int offset_ = 0, calls_ = 0;
  bool skip_first_ = false;
  bool stopped_ = false;
};

// The mean edge length of the strip, which makes the objective scale-free.
double MeanEdgeLength(const CircularStrip& strip) {
  double edge_sum = 0.0;
  const int n = static_cast<int>(strip.p.size()) - 1;
  for (int k = 0; k <= n; ++k) {
    edge_sum += (strip.q[k] - strip.p[k]).stableNorm();
    if (k < n)
      edge_sum +=
          (strip.p[k + 1] - strip.p[k]).stableNorm() + (strip.q[k + 1] - strip.q[k]).stableNorm();
  }
  return edge_sum / (3 * n + 1);
}

}  // namespace

CircularStrip BuildCircularStrip(const CircularStripInput& input) {
  const int n = static_cast<int>(input.curve.size()) - 1;
  if (n < 1) throw InputError("the curve needs at least two points");
  if (static_cast<int>(input.lengths.size()) != n + 1)
    throw InputError("the strip needs one length per curve point (" + std::to_string(n + 1) +
                     "), got " + std::to_string(input.lengths.size()));
  for (int k = 0; k <= n; ++k)
    if (!input.curve[k].allFinite())
      throw InputError("curve point " + std::to_string(k) + " is not finite");
  if (!input.first_point.allFinite()) throw InputError("the first point is not finite");
  const int exponent = ScaleExponent(input.curve, {input.first_point});
  const std::vector<Eigen::Vector3d> curve = Scaled(input.curve, -exponent);
  const Eigen::Vector3d first = Scaled(input.first_point, -exponent);
  std::vector<double> lengths = input.lengths;
  for (double& l : lengths) l = std::ldexp(l, -exponent);
  const Eigen::Vector3d a = curve[1] - curve[0], b = first - curve[0];
  if (!(a.cross(b).norm() > 1e-12 * a.norm() * b.norm()))
    throw InputError("P_0, P_1 and the first point are collinear: they do not fix a circle");
  CircularStrip strip;
  strip.p = input.curve;
  std::string error;
  if (!BuildStripT<double>(curve, first, lengths.data(), &strip.q, &error,
                           std::ldexp(1.0, exponent)))
    throw InputError(error);
  strip.q = Scaled(strip.q, exponent);
  return strip;
}

PolyMesh StripMesh(const CircularStrip& strip) {
  PolyMesh mesh;
  const int n = static_cast<int>(strip.p.size()) - 1;
  std::vector<PolyMesh::VertexHandle> v;
  for (const auto* row : {&strip.p, &strip.q})
    for (const auto& x : *row) v.push_back(mesh.add_vertex(PolyMesh::Point(x.x(), x.y(), x.z())));
  for (int k = 0; k < n; ++k)
    mesh.add_face(std::vector<PolyMesh::VertexHandle>{v[k], v[n + 1 + k], v[n + 2 + k], v[k + 1]});
  return mesh;
}

FrameAngles AnglesFromNormal(const Eigen::Vector3d& normal) {
  const Eigen::Vector3d n = normal.normalized();
  FrameAngles angles;
  angles.lambda = std::asin(std::max(-1.0, std::min(1.0, n.z())));
  angles.theta = std::atan2(n.y(), n.x());
  return angles;
}

Eigen::Vector3d NormalOf(const FrameAngles& angles) {
  return NormalOfAngles<double>(angles.lambda, angles.theta);
}

void CheckFrameNormal(const FrameAngles& angles, const Eigen::Vector3d& from,
                      const Eigen::Vector3d& to) {
  const Eigen::Vector3d n = NormalOf(angles), chord = (to - from).normalized();
  if (!n.allFinite() || !std::isfinite(angles.psi))
    throw InputError("the frame's normal is not finite");
  if (!(n.cross(chord).norm() > 1e-6))
    throw InputError(
        "the frame's normal runs along the first edge: its first tangent (the edge projected "
        "across the normal) is undefined; give a normal across the edge");
}

Frame FrameOfAngles(const std::vector<Eigen::Vector3d>& curve, const FrameAngles& angles) {
  const double a[3] = {angles.lambda, angles.theta, angles.psi};
  Frame f;
  FrameAtStart<double>(curve[0], curve[1], a, &f.t1, &f.t2, &f.n);
  return f;
}

FrameAngles AnglesOfFrame(const std::vector<Eigen::Vector3d>& curve, const Frame& frame) {
  FrameAngles angles = AnglesFromNormal(frame.n);
  const Eigen::Vector3d n = NormalOf(angles), chord = curve[1] - curve[0];
  const Eigen::Vector3d u = (chord - chord.dot(n) * n).normalized();
  angles.psi = std::atan2(frame.t1.dot(n.cross(u)), frame.t1.dot(u));
  return angles;
}

CyclidicStrip MakeCyclidicStrip(const CircularStrip& strip, const FrameAngles& angles) {
  if (const int e = ScaleExponent(strip.p, strip.q); e != 0) {
    CyclidicStrip net = MakeCyclidicStrip(Scaled(strip, -e), angles);
    net.strip = strip;
    for (Circle& c : net.circles) c = Scaled(c, e);
    net.energy = std::ldexp(net.energy, -2 * e);  // F = Σ 1 / R²
    return net;
  }
  CyclidicStrip net;
  net.strip = strip;
  const double a[3] = {angles.lambda, angles.theta, angles.psi};
  const int n = static_cast<int>(strip.p.size()) - 1;
  Frame f;
  FrameAtStart<double>(strip.p[0], strip.p[1], a, &f.t1, &f.t2, &f.n);
  for (int k = 0; k <= n; ++k) {
    net.p_frames.push_back(f);
    const Eigen::Vector3d across = strip.q[k] - strip.p[k];
    net.q_frames.push_back({Reflect<double>(f.t1, across), Reflect<double>(f.t2, across),
                            Reflect<double>(f.n, across)});
    // C_k: through P_k and Q_k with tangent t2 at P_k.
    const Eigen::Vector3d normal = f.t2.cross(across).normalized();
    const Eigen::Vector3d inward = normal.cross(f.t2);
    const double r = across.squaredNorm() / (2.0 * across.dot(inward));
    net.circles.push_back({strip.p[k] + r * inward, normal, std::abs(r)});
    if (k < n) {
      const Eigen::Vector3d along = strip.p[k + 1] - strip.p[k];
      f = {Reflect<double>(f.t1, along), Reflect<double>(f.t2, along), Reflect<double>(f.n, along)};
    }
  }
  net.energy = StripEnergy<double>(strip.p, strip.q, a);
  return net;
}

std::vector<std::vector<Eigen::Vector3d>> CanalRows(const CyclidicStrip& net, int m) {
  if (m < 1) throw InputError("the canal mesh needs at least one segment per circle");
  // About P_0: the plane steps intersect planes and circles, which lose digits far away.
  if (const Eigen::Vector3d origin = net.strip.p[0]; origin != Eigen::Vector3d::Zero()) {
    CyclidicStrip local = net;
    for (auto* row : {&local.strip.p, &local.strip.q})
      for (Eigen::Vector3d& x : *row) x -= origin;
    for (Circle& c : local.circles) c.centre -= origin;
    std::vector<std::vector<Eigen::Vector3d>> rows = CanalRows(local, m);
    for (auto& row : rows)
      for (Eigen::Vector3d& x : row) x += origin;
    return rows;
  }
  if (const double vertices = static_cast<double>(net.strip.p.size()) * (m + 1.0); vertices > 1e7)
    throw InputError("the canal mesh would have " +
                     std::to_string(static_cast<long long>(vertices)) +
                     " vertices (at most 1e7): lower the segments");
  if (const int e = ScaleExponent(net.strip.p, net.strip.q); e != 0) {
    CyclidicStrip unit = net;
    unit.strip = Scaled(net.strip, -e);
    for (Circle& c : unit.circles) c = Scaled(c, -e);
    std::vector<std::vector<Eigen::Vector3d>> rows = CanalRows(unit, m);
    for (auto& row : rows)
      for (Eigen::Vector3d& x : row) x = Scaled(x, e);
    return rows;
  }
  const int n = static_cast<int>(net.strip.p.size()) - 1;
  std::vector<std::vector<Eigen::Vector3d>> rows(n + 1, std::vector<Eigen::Vector3d>(m + 1));
  {
    const Circle& c0 = net.circles[0];
    // The circle's normal t2 × (Q − P) makes the positive rotation start along t2 at P_0.
    const double arc = CcwAngle<double>(net.strip.p[0], net.strip.q[0], c0.centre, c0.normal);
    for (int j = 0; j <= m; ++j)
      rows[0][j] = Rotate<double>(net.strip.p[0], c0.centre, c0.normal, arc * j / m);
  }
  for (int k = 0; k < n; ++k) {
    const Circle& c = net.circles[k + 1];
    rows[k + 1][0] = net.strip.p[k + 1];
    for (int j = 0; j < m; ++j) {
      const Eigen::Vector3d& x0 = rows[k][j];
      const Eigen::Vector3d& x1 = rows[k][j + 1];
      const Eigen::Vector3d& y0 = rows[k + 1][j];
      const Eigen::Vector3d plane = (x1 - x0).cross(y0 - x0);
      const Eigen::Vector3d u = plane.cross(c.normal);
      if (!(u.norm() > 1e-12 * plane.norm()))
        throw InputError("canal mesh: the plane of quad (" + std::to_string(k) + ", " +
                         std::to_string(j) + ") is parallel to circle C_" + std::to_string(k + 1));
      const Eigen::Vector3d dir = u.normalized();
      rows[k + 1][j + 1] = y0 - 2.0 * (y0 - c.centre).dot(dir) * dir;
    }
  }
  return rows;
}

PolyMesh RowsMesh(const std::vector<std::vector<Eigen::Vector3d>>& rows, bool ring) {
  PolyMesh mesh;
  std::vector<PolyMesh::VertexHandle> v;
  for (const auto& row : rows)
    for (const auto& x : row) v.push_back(mesh.add_vertex(PolyMesh::Point(x.x(), x.y(), x.z())));
  const int count = static_cast<int>(rows.size());
  const int m = count > 0 ? static_cast<int>(rows[0].size()) - 1 : 0;
  for (int k = 0; k < (ring ? count : count - 1); ++k)
    for (int j = 0; j < m; ++j) {
      const int a = k * (m + 1) + j, b = ((k + 1) % count) * (m + 1) + j;
      mesh.add_face(std::vector<PolyMesh::VertexHandle>{v[a], v[b], v[b + 1], v[a + 1]});
    }
  return mesh;
}

PolyMesh MeshCanalSurface(const CyclidicStrip& net, int m) {
  return RowsMesh(CanalRows(net, m), false);
}

bool CanalSmoothingOptions::IsValid(std::string* why) const {
  if (max_iterations < 1) {
    *why = "max_iterations must be ≥ 1";
    return false;
  }
  if (!(length_weight >= 0.0) || !std::isfinite(length_weight)) {
    *why = "length_weight must be finite and ≥ 0";
    return false;
  }
  if (!optimize_lengths && !optimize_frame) {
    *why = "nothing to optimise: free the lengths, the frame or both";
    return false;
  }
  return !cone.enabled || cone.IsValid(why);
}

bool NormalCone::IsValid(std::string* why) const {
  if (!axis.allFinite() || !(axis.cwiseAbs().maxCoeff() > 0.0)) {
    *why = "the reference plane's normal must be finite and not zero";
    return false;
  }
  if (!(std::abs(angle_deg) <= 89.0)) {
    *why =
        "the normal's angle to the reference plane must be within [-89, 89] deg (at 90 the "
        "normal is the plane's normal: give it as the normal)";
    return false;
  }
  return true;
}

void NormalCone::Basis(Eigen::Vector3d* e1, Eigen::Vector3d* e2) const {
  const Eigen::Vector3d a = UnitAxis(axis);
  // Across the axis: from the coordinate axis least along it.
  Eigen::Index least = 0;
  a.cwiseAbs().minCoeff(&least);
  *e1 = a.cross(Eigen::Vector3d::Unit(least)).normalized();
  *e2 = a.cross(*e1);
}

Eigen::Vector3d NormalCone::NormalAt(double phi) const {
  Eigen::Vector3d e1, e2;
  Basis(&e1, &e2);
  const double alpha = angle_deg * M_PI / 180.0;
  return std::sin(alpha) * UnitAxis(axis) +
         std::cos(alpha) * (std::cos(phi) * e1 + std::sin(phi) * e2);
}

double NormalCone::Turn(const Eigen::Vector3d& n) const {
  Eigen::Vector3d e1, e2;
  Basis(&e1, &e2);
  const double x = n.dot(e1), y = n.dot(e2);
  return x == 0.0 && y == 0.0 ? 0.0 : std::atan2(y, x);
}

double NormalCone::AngleOf(const Eigen::Vector3d& n) const {
  return std::asin(std::clamp(n.normalized().dot(UnitAxis(axis)), -1.0, 1.0)) * 180.0 / M_PI;
}

FrameAngles OnCone(const FrameAngles& angles, const NormalCone& cone) {
  FrameAngles out = AnglesFromNormal(cone.NormalAt(cone.Turn(NormalOf(angles))));
  out.psi = angles.psi;
  return out;
}

CanalSmoothingSummary SmoothCanalStrip(const CircularStripInput& input,
                                       const FrameAngles& given_angles,
                                       const CanalSmoothingOptions& options,
                                       const RunCallback& callback) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError("canal smoothing: " + why);
  // On a cone the start normal is the cone's nearest to the given one.
  const FrameAngles angles =
      options.cone.enabled ? OnCone(given_angles, options.cone) : given_angles;
  const CircularStrip strip = BuildCircularStrip(input);  // validates the input
  // BFGS runs on the strip moved to P_0 and divided by its mean edge length ℓ, where lengths
  // and angles are both of order 1 whatever the input's units (on a curve of size 1e-20 the
  // line search failed at the first step); lengths and F are scaled back (F by 1 / ℓ²).
  const double scale = MeanEdgeLength(strip);
  CircularStripInput unit = input;
  for (Eigen::Vector3d& p : unit.curve) p = (p - input.curve[0]) / scale;
  unit.first_point = (input.first_point - input.curve[0]) / scale;
  for (double& l : unit.lengths) l /= scale;
  std::vector<double> x = Pack(unit, angles, options);
  // The unit strip's mean edge length is 1 by construction: no second build to measure it.
  ceres::GradientProblem problem(new CanalObjective(unit, angles, options, 1.0));  // owns it
  ceres::GradientProblemSolver::Options ceres_options;
  ceres_options.line_search_direction_type = ceres::BFGS;
  ceres_options.max_num_iterations = options.max_iterations;
  ceres_options.function_tolerance = options.function_tolerance;
  ceres_options.update_state_every_iteration = true;
  CanalSmoothingSummary out;
  // F in the input's units: the lengths scaled back (as for the result).
  const auto input_energy = [&] {
    std::vector<double> y = x;
    if (options.optimize_lengths)
      for (size_t k = 0; k < input.lengths.size(); ++k) y[k] *= scale;
    return EnergyAt(y.data(), options, input, angles);
  };
  RecordingCallback recording(input_energy, callback, &out.history);
  ceres_options.callbacks.push_back(&recording);
  // When the line search finds no step (Ceres then reports its parameter tolerance met, with a
  // zero step), BFGS restarts from there with a fresh Hessian estimate, while that lowers the
  // objective. A run whose last restart could not lower it has not converged.
  ceres::GradientProblemSolver::Summary summary;
  bool stalled = false;
  int restarts = 0;
  for (int round = 0;; ++round) {
    const double start_cost =
        round == 0 ? std::numeric_limits<double>::infinity() : out.history.back().energy;
    recording.Restart(out.iterations, round > 0);
    ceres_options.max_num_iterations = options.max_iterations - out.iterations;
    ceres::Solve(ceres_options, problem, x.data(), &summary);
    // Ceres calls no callback on the iterate where it stops by a tolerance; record it too.
    if (recording.recorded() < static_cast<int>(summary.iterations.size()))
      recording(summary.iterations.back());
    out.iterations += static_cast<int>(summary.iterations.size()) - 1;
    stalled = summary.termination_type == ceres::CONVERGENCE &&
              summary.iterations.back().step_norm == 0.0;
    const bool lowered = summary.final_cost < start_cost * (1.0 - options.function_tolerance);
    if (!stalled || out.iterations >= options.max_iterations || !lowered || recording.stopped())
      break;
    ++restarts;
  }
  out.converged =
      summary.termination_type == ceres::CONVERGENCE && !stalled && !recording.stopped();
  out.termination =
      stalled
          ? "ceres-bfgs NO_CONVERGENCE: the line search found no lower point (BFGS restarted " +
                std::to_string(restarts) + " times)"
          : std::string("ceres-bfgs ") + ceres::TerminationTypeToString(summary.termination_type) +
                ": " + (restarts > 0 ? "after " + std::to_string(restarts) + " restart(s), " : "") +
                summary.message;
  // A stop on the iterate where BFGS ended by itself (recorded after the solve) is a stop too.
  if (recording.stopped() && summary.termination_type != ceres::USER_FAILURE)
    out.termination = "USER_ABORT: stopped on request (" + out.termination + ")";
  out.message = summary.BriefReport();
  out.initial_energy = MakeCyclidicStrip(strip, angles).energy;
  CircularStripInput result = input;
  out.angles = angles;
  Unpack(x.data(), options, &result, &out.angles);
  for (double& l : result.lengths) l = options.optimize_lengths ? l * scale : l;
  out.lengths = result.lengths;
  out.final_energy = MakeCyclidicStrip(BuildCircularStrip(result), out.angles).energy;
  return out;
}

Eigen::Vector3d DefaultCanalNormal(const CircularStrip& input) {
  // A direction: computed at unit scale.
  const CircularStrip strip = Scaled(input, -ScaleExponent(input.p, input.q));
  const Eigen::Vector3d along = (strip.p[1] - strip.p[0]).normalized();
  const Eigen::Vector3d across = strip.q[0] - strip.p[0];
  return across - across.dot(along) * along;
}

bool CanalSurfaceOptions::IsValid(std::string* why) const {
  if (segments < 1 || segments > 100000) {
    *why = "segments must be in [1, 100000]";
    return false;
  }
  return !smooth || smoothing.IsValid(why);
}

CanalSurface::CanalSurface(const CircularStripInput& input, const FrameAngles& angles,
                           const CanalSurfaceOptions& options)
    : options_(options),
      input_(input),
      angles_(options.smoothing.cone.enabled ? OnCone(angles, options.smoothing.cone) : angles) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError("invalid option: " + why);
  if (options.smoothing.cone.enabled && !options.smoothing.cone.IsValid(&why))
    throw InputError("invalid option: " + why);
  strip_ = BuildCircularStrip(input);
  CheckFrameNormal(angles_, input.curve[0], input.curve[1]);
}

NamedValues CanalSurface::Measure() const {
  const CyclidicStrip net = Net();
  NamedValues m = {{"smoothness_energy", net.energy}};
  const NamedValues mesh = MeasureCircularMesh(MeshCanalSurface(net, options_.segments));
  m.insert(m.end(), mesh.begin(), mesh.end());
  return m;
}

RunReport CanalSurface::Run(const RunCallback& callback) {
  if (!options_.smooth) {
    const Construction construction(ConstructionMethod::kClosedForm, "circular strip");
    const NamedValues measures = Measure();
    return construction.Finish(measures, measures, true);
  }
  return Smooth(callback);
}

RunReport CanalSurface::Smooth(const RunCallback& callback) {
  const auto start = std::chrono::steady_clock::now();
  RunReport report;
  report.solver = SolverKind::kCeres;
  report.method = ConstructionMethodName(ConstructionMethod::kBfgs);
  try {
    report.initial = Measure();
  } catch (const InputError&) {
    report.initial = {{"smoothness_energy", Net().energy}};
  }
  const CanalSmoothingSummary s = SmoothCanalStrip(input_, angles_, options_.smoothing, callback);
  report.variables = static_cast<int>(Pack(input_, angles_, options_.smoothing).size());
  input_.lengths = s.lengths;
  angles_ = s.angles;
  strip_ = BuildCircularStrip(input_);
  report.final = Measure();
  report.converged = s.converged;
  report.termination = s.termination;
  report.iterations = s.iterations;
  report.history = s.history;
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  FailOnNonFiniteMeasures(&report);
  return report;
}

}  // namespace gproj::circular
