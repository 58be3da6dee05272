#include "gproj/geometry/mesh/curvature_field.h"

#ifndef CGAL_EIGEN3_ENABLED
#define CGAL_EIGEN3_ENABLED
#endif
#include <CGAL/Monge_via_jet_fitting.h>
#include <CGAL/Simple_cartesian.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "gproj/geometry/mesh/scale_free.h"
#include "gproj/solver/sparse_cholesky.h"

namespace gproj {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using JetFitting = CGAL::Monge_via_jet_fitting<Kernel>;

Eigen::Vector3d ToEigen(const Kernel::Vector_3& v) { return Eigen::Vector3d(v.x(), v.y(), v.z()); }

// Area-weighted normal of the faces around v.
Eigen::Vector3d VertexNormal(const PolyMesh& mesh, PolyMesh::VertexHandle v) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (auto f = mesh.cvf_iter(v); f.is_valid(); ++f) {
    std::vector<Eigen::Vector3d> p;
    for (auto fv = mesh.cfv_iter(*f); fv.is_valid(); ++fv) {
      const auto& q = mesh.point(*fv);
      p.emplace_back(q[0], q[1], q[2]);
    }
    for (size_t k = 1; k + 1 < p.size(); ++k) sum += 0.5 * (p[k] - p[0]).cross(p[k + 1] - p[0]);
  }
  return sum;
}

// The mesh at unit scale (scale_free.h); *unit gets its mean edge length.
PolyMesh UnitScaled(const PolyMesh& mesh, double* unit) {
  UnitFrame frame;
  PolyMesh scaled = UnitScaleCopy(mesh, &frame);
  *unit = frame.length;
  return scaled;
}

// Principal curvatures below this, in units of the mean edge length (a radius of a million
// edges), are taken as 0: numerical noise of the fit, not curvature.
constexpr double kFlatCurvature = 1e-6;

}  // namespace

bool VertexCurvature::Asymptotic(Eigen::Vector3d* a, Eigen::Vector3d* b) const {
  if (!fitted || !(k1 > 0.0 && k2 < 0.0)) return false;
  const double theta = std::atan(std::sqrt(-k1 / k2));
  *a = (std::cos(theta) * d1 + std::sin(theta) * d2).normalized();
  *b = (std::cos(theta) * d1 - std::sin(theta) * d2).normalized();
  return true;
}

bool CurvatureFitOptions::IsValid(std::string* why) const {
  if (fit_degree < 1 || fit_degree > 4 || monge_degree < 1 || monge_degree > fit_degree) {
    *why = "the jet degree must be in [1, 4] and the Monge degree in [1, jet degree]";
    return false;
  }
  if (min_points < (fit_degree + 1) * (fit_degree + 2) / 2 || max_rings < 1) {
    *why = "a jet of degree " + std::to_string(fit_degree) + " needs at least " +
           std::to_string((fit_degree + 1) * (fit_degree + 2) / 2) + " points and one ring";
    return false;
  }
  return true;
}

namespace {

// The jet fits of a mesh at unit scale (curvatures per mean edge length).
std::vector<VertexCurvature> FitAtUnitScale(const PolyMesh& mesh,
                                            const CurvatureFitOptions& options) {
  std::vector<VertexCurvature> out(mesh.n_vertices());
  std::vector<int> seen(mesh.n_vertices(), -1);  // the vertex whose neighbourhood saw it last
  std::vector<int> ring, next, neighbourhood;
  std::vector<Kernel::Point_3> points;
  for (auto v : mesh.vertices()) {
    if (v.idx() % 1024 == 0) PollStop(options.stop, "the jet fit");
    if (mesh.is_isolated(v)) continue;
    // Rings around v until the neighbourhood is large enough.
    neighbourhood.assign(1, v.idx());
    ring.assign(1, v.idx());
    seen[v.idx()] = v.idx();
    for (int r = 0; r < options.max_rings &&
                    static_cast<int>(neighbourhood.size()) < options.min_points && !ring.empty();
         ++r) {
      next.clear();
      for (int w : ring)
        for (auto vv = mesh.cvv_iter(mesh.vertex_handle(w)); vv.is_valid(); ++vv)
          if (seen[vv->idx()] != v.idx()) {
            seen[vv->idx()] = v.idx();
            next.push_back(vv->idx());
          }
      neighbourhood.insert(neighbourhood.end(), next.begin(), next.end());
      ring.swap(next);
    }
    if (static_cast<int>(neighbourhood.size()) < options.min_points) continue;
    points.clear();
    for (int w : neighbourhood) {
      const auto& p = mesh.point(mesh.vertex_handle(w));
      points.emplace_back(p[0], p[1], p[2]);
    }
    JetFitting fitting;
    JetFitting::Monge_form form =
        fitting(points.begin(), points.end(), options.fit_degree, options.monge_degree);
    const Eigen::Vector3d given = VertexNormal(mesh, v);
    if (given.norm() > 0.0)
      form.comply_wrt_given_normal(Kernel::Vector_3(given.x(), given.y(), given.z()));
    VertexCurvature& c = out[v.idx()];
    c.normal = ToEigen(form.normal_direction()).normalized();
    c.d1 = ToEigen(form.maximal_principal_direction()).normalized();
    c.d2 = ToEigen(form.minimal_principal_direction()).normalized();
    c.k1 = form.principal_curvatures(0);
    c.k2 = form.principal_curvatures(1);
    if (std::abs(c.k1) < kFlatCurvature) c.k1 = 0.0;
    if (std::abs(c.k2) < kFlatCurvature) c.k2 = 0.0;
    c.fitted = std::isfinite(c.k1) && std::isfinite(c.k2) && c.normal.allFinite() &&
               c.d1.allFinite() && c.d2.allFinite();
  }
  return out;
}

void ToInputUnits(double unit, std::vector<VertexCurvature>* curvature) {
  for (VertexCurvature& c : *curvature) {
    c.k1 /= unit;
    c.k2 /= unit;
  }
}

}  // namespace

std::vector<VertexCurvature> FitVertexCurvatures(const PolyMesh& mesh,
                                                 const CurvatureFitOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError(why);
  if (mesh.n_faces() == 0) throw InputError("the mesh has no faces");
  double unit = 1.0;
  const PolyMesh scaled = UnitScaled(mesh, &unit);
  std::vector<VertexCurvature> out = FitAtUnitScale(scaled, options);
  ToInputUnits(unit, &out);
  return out;
}

double LineAngleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double c = std::abs(a.normalized().dot(b.normalized()));
  return std::acos(std::min(1.0, c)) * 180.0 / M_PI;
}

namespace {

Eigen::Vector3d At(const PolyMesh& mesh, PolyMesh::VertexHandle v) {
  const auto& p = mesh.point(v);
  return Eigen::Vector3d(p[0], p[1], p[2]);
}

// Signed angle from a to b about the unit axis n, in (−π, π].
double SignedAngle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& n) {
  return std::atan2(a.cross(b).dot(n), a.dot(b));
}

}  // namespace

namespace {

// symmetry N: the field's directions are equivalent under turns by 2π/N (2: lines, 4: crosses).
std::vector<double> IndicesAtUnitScale(const PolyMesh& mesh,
                                       const std::vector<Eigen::Vector3d>& lines,
                                       int symmetry = 2) {
  const double period = 2.0 * M_PI / symmetry;
  // Per face: unit normal and the matched, averaged line in its plane (zero if none).
  std::vector<Eigen::Vector3d> normal(mesh.n_faces()), line(mesh.n_faces());
  for (auto f : mesh.faces()) {
    std::vector<Eigen::Vector3d> p, d;
    for (auto fv = mesh.cfv_iter(f); fv.is_valid(); ++fv) {
      p.push_back(At(mesh, *fv));
      d.push_back(lines[fv->idx()]);
    }
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    for (size_t k = 1; k + 1 < p.size(); ++k) n += (p[k] - p[0]).cross(p[k + 1] - p[0]);
    normal[f.idx()] = n.normalized();
    // The corners' directions averaged as N-fold symmetric (angles times N) in the face plane.
    const Eigen::Vector3d e1 = (p[1] - p[0]).normalized(), e2 = normal[f.idx()].cross(e1);
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    bool complete = true;
    for (const Eigen::Vector3d& x : d) {
      if (!(x.norm() > 0.0)) complete = false;
      const double angle = symmetry * std::atan2(x.dot(e2), x.dot(e1));
      sum += Eigen::Vector2d(std::cos(angle), std::sin(angle));
    }
    const double mean = std::atan2(sum.y(), sum.x()) / symmetry;
    line[f.idx()] = complete && sum.norm() > 0.0
                        ? Eigen::Vector3d(std::cos(mean) * e1 + std::sin(mean) * e2)
                        : Eigen::Vector3d::Zero();
  }
  std::vector<double> index(mesh.n_vertices(), 0.0);
  for (auto v : mesh.vertices()) {
    if (mesh.is_boundary(v) || mesh.is_isolated(v)) continue;
    // Faces counter-clockwise about the normal; the angle defect from their corners at v.
    std::vector<PolyMesh::FaceHandle> faces;
    for (auto f = mesh.cvf_ccwiter(v); f.is_valid(); ++f) faces.push_back(*f);
    double defect = 2.0 * M_PI, turning = 0.0;
    bool complete = true;
    for (auto h = mesh.cvoh_ccwiter(v); h.is_valid(); ++h) {
      const auto next = mesh.next_halfedge_handle(*h);
      const Eigen::Vector3d a = At(mesh, mesh.to_vertex_handle(*h)) - At(mesh, v);
      const Eigen::Vector3d b = At(mesh, mesh.to_vertex_handle(next)) - At(mesh, v);
      if (!mesh.face_handle(*h).is_valid()) continue;
      defect -= std::atan2(a.cross(b).norm(), a.dot(b));
    }
    for (size_t i = 0; i < faces.size(); ++i) {
      const int f = faces[i].idx(), g = faces[(i + 1) % faces.size()].idx();
      if (!(line[f].norm() > 0.0) || !(line[g].norm() > 0.0)) complete = false;
      // Unfold g onto f's plane: the rotation taking g's normal to f's.
      const Eigen::Vector3d axis = normal[g].cross(normal[f]);
      Eigen::Vector3d moved = line[g];
      if (axis.norm() > 1e-15)
        moved = Eigen::AngleAxisd(std::atan2(axis.norm(), normal[g].dot(normal[f])),
                                  axis.normalized()) *
                line[g];
      double delta = SignedAngle(line[f], moved, normal[f]);
      delta -= period * std::round(delta / period);  // in [−π/N, π/N]
      turning += delta;
    }
    if (complete) index[v.idx()] = (turning + defect) / (2.0 * M_PI);
  }
  return index;
}

std::vector<Eigen::Vector3d> SmoothAtUnitScale(const PolyMesh& mesh,
                                               const std::vector<VertexCurvature>& curvature,
                                               double alignment_weight, int symmetry = 2,
                                               const StopPoll& stop = nullptr) {
  const double n_fold = symmetry;
  const int n = static_cast<int>(mesh.n_vertices());
  // Tangent frames: the fitted normal (or the faces') and any orthogonal e1, e2 = n × e1.
  std::vector<Eigen::Vector3d> normal(n), e1(n), e2(n);
  for (auto v : mesh.vertices()) {
    Eigen::Vector3d nv =
        curvature[v.idx()].fitted ? curvature[v.idx()].normal : VertexNormal(mesh, v).normalized();
    if (!nv.allFinite() || !(nv.norm() > 0.0)) nv = Eigen::Vector3d::UnitZ();
    normal[v.idx()] = nv;
    e1[v.idx()] = nv.unitOrthogonal();
    e2[v.idx()] = nv.cross(e1[v.idx()]);
  }
  double mean_anisotropy = 0.0;
  int fitted = 0;
  for (const VertexCurvature& c : curvature)
    if (c.fitted) mean_anisotropy += c.k1 - c.k2, ++fitted;
  mean_anisotropy = fitted > 0 && mean_anisotropy > 0.0 ? mean_anisotropy / fitted : 1.0;
  // Real form of the complex system: z_v = (x, y) at rows 2v, 2v + 1.
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(2 * n);
  auto add_block = [&](int a, int b, const Eigen::Matrix2d& m) {
    for (int r = 0; r < 2; ++r)
      for (int c = 0; c < 2; ++c) entries.emplace_back(2 * a + r, 2 * b + c, m(r, c));
  };
  for (auto e : mesh.edges()) {
    const auto h = mesh.halfedge_handle(e, 0);
    const int i = mesh.from_vertex_handle(h).idx(), j = mesh.to_vertex_handle(h).idx();
    // e1_i carried to j's plane by the minimal rotation; its angle there is the transport.
    const Eigen::Quaterniond q = Eigen::Quaterniond::FromTwoVectors(normal[i], normal[j]);
    const Eigen::Vector3d moved = q * e1[i];
    const double rho = n_fold * std::atan2(moved.dot(e2[j]), moved.dot(e1[j]));
    Eigen::Matrix2d r;
    r << std::cos(rho), -std::sin(rho), std::sin(rho), std::cos(rho);
    // |z_j − R z_i|²: (i, i) += I, (j, j) += I, (i, j) −= Rᵀ, (j, i) −= R.
    add_block(i, i, Eigen::Matrix2d::Identity());
    add_block(j, j, Eigen::Matrix2d::Identity());
    add_block(i, j, -r.transpose());
    add_block(j, i, -r);
  }
  for (int v = 0; v < n; ++v) {
    const VertexCurvature& c = curvature[v];
    double weight = 1e-8;  // keeps the system definite where nothing is fitted
    Eigen::Vector2d target = Eigen::Vector2d::Zero();
    if (c.fitted) {
      weight += alignment_weight * (c.k1 - c.k2) / mean_anisotropy;
      const double alpha = std::atan2(c.d1.dot(e2[v]), c.d1.dot(e1[v]));
      target = Eigen::Vector2d(std::cos(n_fold * alpha), std::sin(n_fold * alpha));
    }
    add_block(v, v, weight * Eigen::Matrix2d::Identity());
    rhs.segment<2>(2 * v) = weight * target;
  }
  Eigen::SparseMatrix<double> a(2 * n, 2 * n);
  a.setFromTriplets(entries.begin(), entries.end());
  PollStop(stop, "the field's smoothing");
  // CHOLMOD's supernodal factorisation on the upper triangle (several times faster than a
  // simplicial one on large meshes, which keeps the stop polls close together).
  Eigen::SparseMatrix<double> upper = a.triangularView<Eigen::Upper>();
  upper.makeCompressed();
  const CscMatrix system = ToCsc(upper);
  const std::unique_ptr<SparseCholesky> solver =
      CreateSparseCholesky(LinearSolverType::kCholmod, 0);
  std::string message;
  Eigen::VectorXd z(2 * n);
  bool solved = solver->Analyze(system, MatrixForm::kSymmetric, &message);
  PollStop(stop, "the field's smoothing");
  solved = solved && solver->Factorize(system, 0.0, &message) &&
           solver->Solve(rhs.data(), z.data(), &message) && z.allFinite();
  if (!solved) throw InputError("the field smoothing system could not be factorised: " + message);
  std::vector<Eigen::Vector3d> out(n, Eigen::Vector3d::Zero());
  for (int v = 0; v < n; ++v) {
    const Eigen::Vector2d zv = z.segment<2>(2 * v);
    if (!(zv.norm() > 0.0) || !zv.allFinite()) continue;
    const double alpha = std::atan2(zv.y(), zv.x()) / n_fold;
    out[v] = std::cos(alpha) * e1[v] + std::sin(alpha) * e2[v];
  }
  return out;
}

}  // namespace

std::vector<double> LineFieldIndices(const PolyMesh& mesh,
                                     const std::vector<Eigen::Vector3d>& lines) {
  if (lines.size() != mesh.n_vertices())
    throw InputError("a line field needs one line per vertex (" +
                     std::to_string(mesh.n_vertices()) + "), got " + std::to_string(lines.size()));
  if (mesh.n_faces() == 0) return std::vector<double>(mesh.n_vertices(), 0.0);
  double unit = 1.0;
  return IndicesAtUnitScale(UnitScaled(mesh, &unit), lines);
}

std::vector<Eigen::Vector3d> SmoothPrincipalField(const PolyMesh& mesh,
                                                  const std::vector<VertexCurvature>& curvature,
                                                  double alignment_weight, int symmetry) {
  if (symmetry != 2 && symmetry != 4)
    throw InputError("a direction field's symmetry must be 2 (lines) or 4 (crosses)");
  if (curvature.size() != mesh.n_vertices())
    throw InputError("the curvature field needs one entry per vertex");
  if (!(alignment_weight > 0.0) || !std::isfinite(alignment_weight))
    throw InputError("the field's alignment weight must be a finite number > 0");
  if (mesh.n_faces() == 0) throw InputError("the mesh has no faces");
  double unit = 1.0;
  return SmoothAtUnitScale(UnitScaled(mesh, &unit), curvature, alignment_weight, symmetry);
}

namespace {

// Per vertex, a third of the area of its triangles.
std::vector<double> VertexAreas(const PolyMesh& mesh) {
  std::vector<double> area(mesh.n_vertices(), 0.0);
  for (auto f : mesh.faces()) {
    std::vector<Eigen::Vector3d> p;
    for (auto fv = mesh.cfv_iter(f); fv.is_valid(); ++fv) p.push_back(At(mesh, *fv));
    const double third = (p[1] - p[0]).cross(p[2] - p[0]).norm() / 6.0;
    for (auto fv = mesh.cfv_iter(f); fv.is_valid(); ++fv) area[fv->idx()] += third;
  }
  return area;
}

// The field's two directions at every fitted vertex (principal, or asymptotic), the fitted
// count and the area fractions of negative and of undefined curvature. Throws InputError for
// asymptotic directions on a surface with K >= 0 everywhere.
void SetDirections(const PolyMesh& scaled, DirectionField* field) {
  const size_t n = scaled.n_vertices();
  field->first.assign(n, Eigen::Vector3d::Zero());
  field->second.assign(n, Eigen::Vector3d::Zero());
  const std::vector<double> area = VertexAreas(scaled);
  double total = 0.0, negative = 0.0, undefined = 0.0;
  for (size_t v = 0; v < n; ++v) {
    const VertexCurvature& c = field->curvature[v];
    if (!c.fitted) continue;
    ++field->fitted;
    total += area[v];
    if (c.gaussian() < 0.0) negative += area[v];
    if (c.k1 - c.k2 < kFlatCurvature) undefined += area[v];
    if (field->kind == DirectionKind::kPrincipal) {
      field->first[v] = c.d1;
      field->second[v] = c.d2;
    } else {
      c.Asymptotic(&field->first[v], &field->second[v]);
    }
  }
  field->negative_area_fraction = total > 0.0 ? negative / total : 0.0;
  field->undefined_area_fraction = total > 0.0 ? undefined / total : 0.0;
  if (field->kind == DirectionKind::kAsymptotic && !(negative > 0.0))
    throw InputError(
        "K >= 0 at every fitted vertex: asymptotic directions exist only where the "
        "Gaussian curvature is negative (use the principal directions)");
}

}  // namespace

DirectionField EstimateDirectionField(const PolyMesh& mesh, DirectionKind kind,
                                      const CurvatureFitOptions& options, double smoothing) {
  for (auto f : mesh.faces())
    if (mesh.valence(f) != 3)
      throw InputError("face " + std::to_string(f.idx()) + " has " +
                       std::to_string(mesh.valence(f)) +
                       " vertices: the curvature field needs a triangle mesh");
  std::string why;
  if (!options.IsValid(&why)) throw InputError(why);
  if (mesh.n_faces() == 0) throw InputError("the mesh has no faces");
  if (smoothing < 0.0 || !std::isfinite(smoothing))
    throw InputError("the smoothing weight must be a finite number >= 0");
  double unit = 1.0;
  const PolyMesh scaled = UnitScaled(mesh, &unit);
  DirectionField field;
  field.kind = kind;
  field.curvature = FitAtUnitScale(scaled, options);
  const size_t n = mesh.n_vertices();
  int fitted = 0;
  for (const VertexCurvature& c : field.curvature) fitted += c.fitted;
  if (fitted == 0)
    throw InputError(
        "no vertex could be fitted: none has " + std::to_string(options.min_points) +
        " vertices within " + std::to_string(options.max_rings) + " rings (the mesh has " +
        std::to_string(n) + ")" +
        (static_cast<int>(n) >= 10 ? "; lower `neighbours`" : ": too few vertices for a jet fit"));
  // Principal directions form a cross (4-fold: d1 and d2 may trade places across the field, so
  // an umbilic can split into singularities of index ±¼); the asymptotic pair is symmetric
  // about the line d1 only (2-fold: its two families never trade places).
  const int symmetry = kind == DirectionKind::kPrincipal ? 4 : 2;
  field.symmetry = symmetry;
  if (smoothing > 0.0) {
    const std::vector<Eigen::Vector3d> smooth =
        SmoothAtUnitScale(scaled, field.curvature, smoothing, symmetry, options.stop);
    PollStop(options.stop, "the field's smoothing");
    for (size_t v = 0; v < n; ++v) {
      VertexCurvature& c = field.curvature[v];
      if (!c.fitted || !(smooth[v].norm() > 0.0)) continue;
      c.d1 = smooth[v];
      c.d2 = c.normal.cross(c.d1).normalized();
    }
  }
  SetDirections(scaled, &field);
  // The principal line field carries the singularities of both nets (it bisects the
  // asymptotic pair).
  std::vector<Eigen::Vector3d> principal(n, Eigen::Vector3d::Zero());
  for (size_t v = 0; v < n; ++v)
    if (field.curvature[v].fitted) principal[v] = field.curvature[v].d1;
  // Where the principal directions mean nothing on most of the surface (flat, umbilic), their
  // indices mean nothing either.
  field.singularities_reliable = field.undefined_area_fraction <= 0.5;
  const std::vector<double> index = IndicesAtUnitScale(scaled, principal, symmetry);
  for (size_t v = 0; v < n && field.singularities_reliable; ++v)
    if (std::abs(index[v]) >= 0.5 / symmetry)
      field.singularities.push_back(
          {static_cast<int>(v), std::round(symmetry * index[v]) / symmetry});
  ToInputUnits(unit, &field.curvature);
  return field;
}

}  // namespace gproj
