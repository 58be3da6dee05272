#pragma once
// Quad grids sampled from parametric surfaces, with optional jitter: the test inputs of the
// A-net / H-net problems (grids along asymptotic lines of negatively curved surfaces).

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <string>

#include "gproj/geometry/io/mesh_io.h"

namespace gproj {

struct ParametricGridOptions {
  int nu = 11, nv = 11;                             // vertices per direction (≥ 2)
  double s0 = -1.0, s1 = 1.0, t0 = -1.0, t1 = 1.0;  // parameter rectangle
  // Each vertex moves by a uniform random vector in [−jitter·h, jitter·h]³, h the mean edge.
  double jitter = 0.0;
  uint32_t seed = 1;
  // The lattice turned by 45°: vertex (i, j) at s = s_c + (i − i_c + j − j_c) δs / 2,
  // t = t_c + (i − i_c − j + j_c) δt / 2 about the rectangle's centre (i_c = (nu − 1) / 2, δ the
  // range over max(nu, nv) − 1), so that the quads' diagonals follow the s and t lines (a
  // diamond of the rectangle, its tips at the rectangle's sides when nu = nv).
  bool diagonal = false;
};

// Vertex (i, j) = f(s_i, t_j) has index i * nv + j; faces (i, j), (i+1, j), (i+1, j+1), (i, j+1).
PolyMesh MakeParametricGrid(const std::function<Eigen::Vector3d(double, double)>& f,
                            const ParametricGridOptions& options);

// The asymptotic nets used in tests and the demo:
//   "hypar":       rulings of z = x y,  (s, t) ↦ (s, t, s t)
//   "hyperboloid": rulings of x² + y² − z² = 1, (α, β) ↦ the meeting point of the two rulings
//   "enneper":     Enneper's surface along u ± v = const in its isothermal parameters
// Throws InputError for an unknown name.
std::function<Eigen::Vector3d(double, double)> AsymptoticSurface(const std::string& name);

// A surface of revolution about the z axis, meshed along its lines of curvature (meridians and
// parallels), so every quad is circular (an isosceles trapezoid): the test input of the
// super-canal problems. (s, t) ↦ (r cos t, r sin t, s) with r = 1.5 + 0.5 s², t in radians.
Eigen::Vector3d RevolutionSurface(double s, double t);

}  // namespace gproj
