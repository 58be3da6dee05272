#pragma once
// A canal surface fitted to two curves (000 §4.1, eq. 6, Figs. 8–12).
//
// The first curve P_0..P_n becomes a line of curvature. A normal at P_0 (made orthogonal to the
// curve's tangent, that of the circle through P_0, P_1, P_2) is carried along it by reflection
// in the bisector plane of every segment, so that
// consecutive normal lines meet: they span the developable of normals that holds the sphere
// centres (000 Fig. 9). On the normal line of P_k the centre C_k = P_k + s_k n_k of the sphere
// through P_k is found by Newton's method on |C_k P_k| − |C_k C'_k| = 0 (C'_k the closest point
// of the second curve; eq. 6 term by term), starting at C_k = P_k. The spheres S_k (radius
// R_k = |s_k|) meet their successors in the circles 𝒞_k = S_k ∩ S_{k+1}; consecutive circles lie
// on a common sphere, so the mesh between them by plane intersections (000 Fig. 13,
// MeshCanalSurface) has circular quads. Each circle's first vertex is its point nearest to
// P_k (the line of curvature); the first circle's arc runs to its point nearest to the second
// curve, so the mesh spans the strip between the two curves.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"
#include "gproj/geometry/mesh/circle.h"
#include "gproj/problems/run/guided_problem.h"

namespace gproj::circular {

struct CanalFromCurvesOptions {
  int segments = 12;             // quads across the strip, in [1, 100000]
  int max_newton_steps = 50;     // per sphere
  double fit_tolerance = 1e-10;  // |R_k − dist(C_k, curve 2)| / curve-1 length, per sphere
  bool IsValid(std::string* why) const;
};

struct CanalFromCurves {
  std::vector<Eigen::Vector3d> normals;  // n_k, unit, at every P_k
  std::vector<Eigen::Vector3d> centres;  // C_k
  std::vector<double> radii;             // R_k
  std::vector<double> fit_residuals;     // |R_k − dist(C_k, curve 2)| per sphere
  std::vector<Circle> circles;           // 𝒞_k = S_k ∩ S_{k+1}, k = 0..n−1
  PolyMesh mesh;                         // n × (segments + 1) vertices, grid order
  // Measures (the report's keys): max_sphere_fit (max |R_k − dist(C_k, curve 2)|, curve
  // units), max_curve1_distance (the circles' first vertices from curve 1),
  // max_curve2_distance (each sphere's contact point with curve 2 from the nearer of its two
  // circles: how closely the surface passes the second curve), and MeasureCircularMesh's of
  // the mesh. The mesh's far column is a line of curvature from the first circle's point
  // nearest to curve 2; it follows curve 2 only where that is a line of curvature too.
  NamedValues measures;
};

// curve1: P_0..P_n (n ≥ 2); curve2: a polyline (≥ 2 points); normal at P_0 (not along the
// first segment). Computed at unit scale (curve 1 translated to its first point and divided by
// its length), so far or huge coordinates lose nothing. Throws InputError naming the sphere or
// circle that cannot be built: a normal along the curve, a second curve through a point of the
// first (a sphere of radius 0), a Newton iteration that finds no equidistant centre, two
// consecutive spheres that do not meet.
CanalFromCurves FitCanalToCurves(const std::vector<Eigen::Vector3d>& curve1,
                                 const std::vector<Eigen::Vector3d>& curve2,
                                 const Eigen::Vector3d& normal,
                                 const CanalFromCurvesOptions& options);

}  // namespace gproj::circular
