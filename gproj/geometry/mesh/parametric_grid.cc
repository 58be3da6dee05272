#include "gproj/geometry/mesh/parametric_grid.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace gproj {

PolyMesh MakeParametricGrid(const std::function<Eigen::Vector3d(double, double)>& f,
                            const ParametricGridOptions& o) {
  std::vector<Eigen::Vector3d> points;
  const double ic = 0.5 * (o.nu - 1), jc = 0.5 * (o.nv - 1);
  const double steps = std::max(o.nu, o.nv) - 1;
  for (int i = 0; i < o.nu; ++i)
    for (int j = 0; j < o.nv; ++j) {
      if (o.diagonal) {
        const double a = (i - ic + j - jc) / (2.0 * steps), b = (i - ic - j + jc) / (2.0 * steps);
        points.push_back(
            f(0.5 * (o.s0 + o.s1) + (o.s1 - o.s0) * a, 0.5 * (o.t0 + o.t1) + (o.t1 - o.t0) * b));
      } else {
        points.push_back(
            f(o.s0 + (o.s1 - o.s0) * i / (o.nu - 1), o.t0 + (o.t1 - o.t0) * j / (o.nv - 1)));
      }
    }
  double edge_sum = 0.0;
  int edges = 0;
  for (int i = 0; i < o.nu; ++i)
    for (int j = 0; j < o.nv; ++j) {
      if (i + 1 < o.nu)
        edge_sum += (points[(i + 1) * o.nv + j] - points[i * o.nv + j]).norm(), ++edges;
      if (j + 1 < o.nv)
        edge_sum += (points[i * o.nv + j + 1] - points[i * o.nv + j]).norm(), ++edges;
    }
  const double h = edges > 0 ? edge_sum / edges : 0.0;
  std::mt19937 rng(o.seed);
  std::uniform_real_distribution<double> jitter(-1.0, 1.0);
  PolyMesh mesh;
  std::vector<PolyMesh::VertexHandle> v;
  for (auto p : points) {
    if (o.jitter > 0.0)
      for (int c = 0; c < 3; ++c) p[c] += o.jitter * h * jitter(rng);
    v.push_back(mesh.add_vertex(PolyMesh::Point(p[0], p[1], p[2])));
  }
  for (int i = 0; i + 1 < o.nu; ++i)
    for (int j = 0; j + 1 < o.nv; ++j)
      mesh.add_face(
          {v[i * o.nv + j], v[(i + 1) * o.nv + j], v[(i + 1) * o.nv + j + 1], v[i * o.nv + j + 1]});
  return mesh;
}

std::function<Eigen::Vector3d(double, double)> AsymptoticSurface(const std::string& name) {
  if (name == "hypar") return [](double s, double t) { return Eigen::Vector3d(s, t, s * t); };
  if (name == "hyperboloid")
    return [](double a, double b) {
      const double c = std::cos(0.5 * (a - b));
      return Eigen::Vector3d(std::cos(0.5 * (a + b)) / c, std::sin(0.5 * (a + b)) / c,
                             std::tan(0.5 * (a - b)));
    };
  if (name == "enneper")
    return [](double s, double t) {
      const double u = 0.5 * (s + t), v = 0.5 * (s - t);
      return Eigen::Vector3d(u - u * u * u / 3 + u * v * v, v - v * v * v / 3 + v * u * u,
                             u * u - v * v);
    };
  throw InputError("unknown surface '" + name + "' (hypar, hyperboloid or enneper)");
}

Eigen::Vector3d RevolutionSurface(double s, double t) {
  const double r = 1.5 + 0.5 * s * s;
  return {r * std::cos(t), r * std::sin(t), s};
}

}  // namespace gproj
