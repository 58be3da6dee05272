#pragma once
// Principal curvatures and directions at the vertices of a triangle mesh by a jet fit, and the
// asymptotic directions where the Gaussian curvature is negative (004 §3.1: "the curvature
// tensor … estimated by a 3rd-order jet fit"). CGAL's Monge_via_jet_fitting (Cazals & Pouget,
// "Estimating differential quantities using polynomial fitting of osculating jets", CAGD 22,
// 2005) fits a bivariate polynomial height function to the vertex and its neighbours within a
// few rings, in a frame from their principal axes, and returns its Monge form.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "gproj/common/run_stopped.h"
#include "gproj/geometry/io/mesh_io.h"

namespace gproj {

struct VertexCurvature {
  bool fitted = false;  // false: too few neighbours or a degenerate fit
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // unit, on the side of the mesh's normal
  Eigen::Vector3d d1 = Eigen::Vector3d::Zero();      // unit principal direction of k1
  Eigen::Vector3d d2 = Eigen::Vector3d::Zero();      // unit principal direction of k2
  double k1 = 0.0, k2 = 0.0;                         // k1 ≥ k2, with respect to `normal`
  double gaussian() const { return k1 * k2; }
  double mean() const { return 0.5 * (k1 + k2); }
  // The two asymptotic directions (unit tangents, where the normal curvature vanishes)
  // cos θ d1 ± sin θ d2 with tan² θ = −k1 / k2; false where K ≥ 0 (none, or a flat point).
  bool Asymptotic(Eigen::Vector3d* a, Eigen::Vector3d* b) const;
};

struct CurvatureFitOptions {
  int fit_degree = 3;    // degree of the fitted jet (004: 3)
  int monge_degree = 2;  // degree of the Monge form returned (≤ fit_degree)
  int min_points = 20;   // rings are added until the neighbourhood has this many vertices
  int max_rings = 64;
  // Asked between vertices and between the field's steps (null: never): true throws
  // RunStopped (gproj/common/run_stopped.h).
  StopPoll stop;
  bool IsValid(std::string* why) const;
};

// One VertexCurvature per vertex. Throws InputError for invalid options or a mesh without
// faces.
std::vector<VertexCurvature> FitVertexCurvatures(const PolyMesh& mesh,
                                                 const CurvatureFitOptions& options = {});

// Angle in degrees between two lines (directions up to sign), in [0, 90].
double LineAngleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b);

// Index of a line field (one tangent line per vertex: a direction up to sign; zero where there
// is none) at every inner vertex, a multiple of ½ (Ray, Vallet, Li, Lévy, "N-symmetry direction
// field design", ACM TOG 27, 2008, with N = 2). Per face the field is its corners' lines
// matched to the first and averaged; around the vertex it turns by Σ Δθ, each Δθ the angle
// (in (−π/2, π/2]) between consecutive faces' lines after unfolding the next face about their
// common edge; with the angle defect K_v, index = (Σ Δθ + K_v) / 2π. The asymptotic net's
// singularities are those of the principal line field, which bisects it (004 Theorem 6: an
// ordinary flat point has index −½). Boundary vertices, and vertices with a face without a
// line, get 0.
std::vector<double> LineFieldIndices(const PolyMesh& mesh,
                                     const std::vector<Eigen::Vector3d>& lines);

// A smoothed line field (N = 2; Knöppel, Crane, Pinkall, Schröder, "Globally optimal direction
// fields", ACM TOG 32, 2013): per vertex the line as a unit complex number z = e^{2iα} in a
// tangent frame; z minimises Σ_edges |z_j − r_ij z_i|² + w Σ_v a_v |z_v − g_v|², r_ij the
// doubled-angle transport from vertex i's frame to j's (the minimal rotation of the tangent
// planes), g_v the fitted principal line d1, a_v its anisotropy |κ1 − κ2| / mean |κ1 − κ2| (so
// umbilics and flat points, where d1 means nothing, follow their neighbours). One sparse
// symmetric solve. Returns unit tangents (zero where a vertex has no fit and no neighbour).
// symmetry 4 smooths the principal cross {±d1, ±d2} instead (z = e^{4iα}), where d1 and d2 may
// trade places.
std::vector<Eigen::Vector3d> SmoothPrincipalField(const PolyMesh& mesh,
                                                  const std::vector<VertexCurvature>& curvature,
                                                  double alignment_weight, int symmetry = 2);

// The direction field a quad remeshing follows (004 §3.1): the principal directions (a 4-fold
// symmetric cross field), or the asymptotic pair where K < 0 (a frame symmetric about the
// principal line d1, 2-fold), per vertex from the jet fit, with the singularities of d1 as a
// field of that symmetry (indices in quarters for the cross, halves for the pair). Unless
// smoothed, near flat points and umbilics the directions are those of the fit.
enum class DirectionKind { kPrincipal, kAsymptotic };
struct Singularity {
  int vertex = -1;
  double index = 0.0;  // a multiple of 1 / symmetry
};
struct DirectionField {
  DirectionKind kind = DirectionKind::kAsymptotic;
  std::vector<VertexCurvature> curvature;
  // Per vertex the field's lines: d1, d2 (principal) or the asymptotic pair; zero vectors where
  // there is none (not fitted, or K ≥ 0 for the asymptotic pair).
  std::vector<Eigen::Vector3d> first, second;
  // 2: the field is a line field (the asymptotic pair about d1); 4: a cross (principal
  // directions, d1 and d2 interchangeable).
  int symmetry = 2;
  std::vector<Singularity> singularities;  // inner vertices with |index| ≥ 1 / (2 symmetry)
  int fitted = 0;                          // vertices with a fitted jet
  double negative_area_fraction = 0.0;     // area (vertex shares) where K < 0
  // Area where the principal directions are undefined (flat or umbilic: κ1 − κ2 below 1e-6 per
  // mean edge length); above half of it no singularities are reported.
  double undefined_area_fraction = 0.0;
  bool singularities_reliable = true;
};
// Computed at unit scale (centroid, mean edge length), so far, huge or tiny meshes lose nothing;
// principal curvatures below 1e-6 per mean edge length count as 0 (a plane or a cylinder has no
// asymptotic pair). Throws InputError for a face that is not a triangle (naming it), when no
// vertex has enough neighbours for a fit, or, for the asymptotic pair, when K ≥ 0 at every
// fitted vertex.
// smoothing > 0: the principal lines are first smoothed by SmoothPrincipalField with that
// alignment weight and the field's symmetry (the asymptotic pair follows: it is symmetric about
// d1 at the fitted angle); for the cross, first and second are then its two arms, not
// necessarily the directions of κ1 and κ2.
DirectionField EstimateDirectionField(const PolyMesh& mesh, DirectionKind kind,
                                      const CurvatureFitOptions& options = {},
                                      double smoothing = 0.0);

}  // namespace gproj
