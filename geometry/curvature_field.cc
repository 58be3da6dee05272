#include "geometry/curvature_field.h"

#ifndef CGAL_EIGEN3_ENABLED
#define CGAL_EIGEN3_ENABLED
#endif
#include <CGAL/Monge_via_jet_fitting.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cmath>
#include <string>

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
    for (size_t k = 0; k < p.size(); ++k) sum += 0.5 * p[k].cross(p[(k + 1) % p.size()]);
  }
  return sum;
}

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

std::vector<VertexCurvature> FitVertexCurvatures(const PolyMesh& mesh,
                                                 const CurvatureFitOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError(why);
  if (mesh.n_faces() == 0) throw InputError("the mesh has no faces");
  std::vector<VertexCurvature> out(mesh.n_vertices());
  std::vector<int> seen(mesh.n_vertices(), -1);  // the vertex whose neighbourhood saw it last
  std::vector<int> ring, next, neighbourhood;
  std::vector<Kernel::Point_3> points;
  for (auto v : mesh.vertices()) {
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
    c.fitted = std::isfinite(c.k1) && std::isfinite(c.k2) && c.normal.allFinite() &&
               c.d1.allFinite() && c.d2.allFinite();
  }
  return out;
}

double LineAngleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double c = std::abs(a.normalized().dot(b.normalized()));
  return std::acos(std::min(1.0, c)) * 180.0 / M_PI;
}

}  // namespace gproj
