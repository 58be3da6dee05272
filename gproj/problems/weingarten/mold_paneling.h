#pragma once
// Paneling a B-spline surface with mold re-use (003 §4.2, Figs. 1, 11, 13).
//  1. Panels: the parameter domain is overlaid with an NU × NV grid, mapped to the surface; each
//     panel is sampled on a grid of points (its sides included) and has its (H, K), normal and
//     principal directions at the centre.
//  2. Molds: the panels are clustered in the (H, √K) plane (ClusterMolds, the grid refinement
//     of §4.2) into at most the asked number of clusters, one mold each.
//  3. Per cluster one cubic height field z = f(x, y) (through the origin of the mold's frame,
//     tangent to its xy-plane: 7 coefficients) is fitted to all its panels by least squares,
//     each panel placed by its own rigid motion: starting from the panel's principal frame, the
//     fit of f and the placements (Levenberg–Marquardt on the six parameters of each motion)
//     alternate.
//  4. The panel is the piece of its mold over the design panel: a design point x maps to the
//     mold point above (or below) it in the mold frame. Along every seam between two panels the
//     gap is the distance between the two panels' points of the same design point and the kink
//     the angle between their mold normals there.
//  5. The panels are positioned together: every placement is corrected by a rigid motion that
//     lowers the gaps and kinks at the seams, each panel held to its design panel
//     (Levenberg–Marquardt, sparse normal equations; "the panels cut from their mold and
//     positioned to minimise gaps and kinks", Fig. 13c).
// With as many molds as panels every panel is its own best cubic; with fewer, panels share a
// shape and the seams open: the paper's claim is that a Weingarten surface needs fewer molds
// for the same gaps and kinks than the freeform surface it came from.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <functional>
#include <string>
#include <vector>

#include "gproj/geometry/surface/bspline_surface.h"

namespace gproj::weingarten {

// The cubic height field of a mold: z = Σ c_k m_k(x / s, y / s) over the ten monomials
// 1, x, y, x², x y, y², x³, x² y, x y², y³ with a length scale s (the cluster's panel size).
// Fitted molds have no constant or linear term: the mold frame's origin lies on the mold and
// its xy-plane is the tangent plane there.
struct MoldShape {
  Eigen::Matrix<double, 10, 1> coefficients = Eigen::Matrix<double, 10, 1>::Zero();
  double scale = 1.0;
  double Height(double x, double y) const;
  // (f, f_x, f_y) at (x, y).
  Eigen::Vector3d HeightAndSlope(double x, double y) const;
};

struct PanelingOptions {
  int panels_u = 0, panels_v = 0;  // the panel grid over the parameter domain (≥ 1 each)
  int molds = 1;                   // clusters asked; ClusterMolds may use fewer
  int points_per_side = 7;         // fitting and seam points per panel side (≥ 3)
  int fit_rounds = 4;              // alternations of mold fit and panel placement (≥ 1)
  // Seam positioning: after the fit, all placements are corrected together to close the gaps
  // and kinks (normal differences) at the seams, each relative to its mean before positioning,
  // each panel held to its design panel by its fit residuals with weight hold_weight.
  bool seam_positioning = true;
  double hold_weight = 0.3;
  int positioning_iterations = 15;
  // Polled between molds and positioning steps (null: never): true throws RunStopped, so that
  // a run stopped during its paneling ends there.
  std::function<bool()> stop;

  // Throws InputError naming the rule broken.
  void Validate() const;
};

// Gaps (surface units) and kinks (degrees) at the seam points, and their summaries.
struct SeamMeasures {
  std::vector<double> gaps, kinks_deg;
  double mean_gap = 0.0, max_gap = 0.0, mean_kink_deg = 0.0, max_kink_deg = 0.0;
};

struct Paneling {
  int panels_u = 0, panels_v = 0;
  int num_molds = 0;
  int cells_per_axis = 0;          // of the clustering grid in the (H, √K) plane
  std::vector<int> mold_of_panel;  // panel i * panels_v + j (i along u)
  std::vector<MoldShape> molds;
  // Per panel: mold frame → world (the panel's placement).
  std::vector<Eigen::Isometry3d> placement;
  std::vector<double> h, k;   // at each panel's centre
  SeamMeasures seams;         // of the final placements
  SeamMeasures fitted_seams;  // of the placements that fit each panel to its design panel
  // How far the built panels are from the design surface: at every panel point, the distance
  // between the mold point over the design point and the design point (surface units).
  double mean_deviation = 0.0, max_deviation = 0.0;
  int num_panels() const { return panels_u * panels_v; }
};

// Panels, molds, placements and seam measures of `surface`. Throws InputError on invalid
// options or a degenerate surface (s_u × s_v = 0 at a panel centre), RunStopped when
// options.stop asks.
Paneling PanelSurface(const BSplineSurface& surface, const PanelingOptions& options);

// The fewest molds from which on every larger number meets max gap ≤ max_gap and max kink ≤
// max_kink_deg, up to one mold per panel: the counts are tried downwards from one mold per
// panel to the first that fails. (More molds do not always mean smaller seams: a clustering
// may happen to meet the tolerance at a count below others that miss it, so the fewest count
// that meets it once is not a robust answer.) The paneling reached is returned in *result;
// −1 when even one mold per panel does not meet the tolerance. Costs up to one paneling per
// distinct clustering between the answer and the panel count.
int MoldsForTolerance(const BSplineSurface& surface, PanelingOptions options, double max_gap,
                      double max_kink_deg, Paneling* result = nullptr);

// The placed panels as one mesh (each panel its own (n × n)-quad grid on its mold, vertices not
// shared) and the panel of every face, for pictures (one colour per mold).
PolyMesh PanelMesh(const BSplineSurface& surface, const Paneling& paneling, int n,
                   std::vector<int>* panel_of_face = nullptr);

}  // namespace gproj::weingarten
