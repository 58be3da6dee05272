#pragma once
// The options of a Weingarten run (003 Table 1): the weights, the relation, the sampling, the
// soft start, the target and the multiresolution, with guided projection's defaults and the
// named presets of the paper's figures.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "gproj/solver/guided_projection.h"

namespace gproj::weingarten {

enum class CurvatureRelation { kNone, kLinear, kBSpline };

// Samples per control point and direction with a fixed relation (preset fig3, --linear). With
// Table 2's 2 the samples outnumber the surface's normal freedom by only 4:1 and the tangential
// freedom lets the surface meet the relation at the samples and miss it between them (the CMC
// bump of Fig. 3, H = −0.1: 4.4e-5 at the samples, 1.3e-3 between them); with 3 the relation
// holds between the samples as well as at them (docs/families/weingarten.md, "Relations between the
// samples").
constexpr int kRelationSamplesPerControl = 3;

// A fixed linear relation run without a tolerance asked is converged when every sample meets
// the relation to this share of its natural size |a| κ + |b| κ² (WeingartenProblem).
constexpr double kDefaultRelationShare = 0.01;

// Guided projection's defaults for Weingarten surfaces (003 eq. 11): 10 iterations, ω_f = 0.2,
// ε = 1e-3, no residual tolerance (the alignment is minimised, not driven to zero), auxiliaries
// kept in the factorisation; soft_weight_decay 0.5 is the relaxation of the soft start.
SolverOptions WeingartenSolverDefaults();

struct WeingartenOptions {
  // Guided projection: ω_f of eq. 11 is solver.fairness_weight (control-net second
  // differences), ε is solver.epsilon; solver.monotone keeps only steps that lower the energy,
  // growing ε otherwise.
  SolverOptions solver = WeingartenSolverDefaults();
  // Weights of 003 Table 1.
  double alignment_weight = 0.1;          // ω_al, isoline alignment (eq. 5)
  double bspline_relation_weight = 0.0;   // ω_bs, B-spline curvature relation (§3.2.3)
  double linear_relation_weight = 0.0;    // ω_ln, linear Weingarten relation (§3.2.2)
  double geodesic_parallel_weight = 0.0;  // ω_gp, geodesic parallel isolines (eq. 8)
  double closeness_weight = 0.1;          // ω_cl, closeness to the reference control points
  double shape_weight = 0.0;              // ω_sh, control-net edge and diagonal lengths
  double definition_weight = 1.0;         // rows defining the auxiliaries
  // Alignment rows divided by |∇H| |∇K| at x^k (sine of the gradients' angle; see
  // IsolineAlignment). false: the paper's raw residual, divided once by its RMS at the start.
  bool normalize_alignment = true;
  // Boundary control points glide along the reference boundary polygon, corners held (0: off).
  double boundary_weight = 0.0;
  // Linear relation: fitted to (H, K) at every iteration unless coefficients are given;
  // given coefficients (a, b, c) are in input units and converted to the scaled problem.
  bool fixed_linear_relation = false;
  Eigen::Vector3d linear_coefficients = Eigen::Vector3d(0.0, 1.0, 0.0);
  // A fixed relation is imposed on the surface's own H and K (SurfaceLinearWeingarten, exact
  // Jacobian in the control points) instead of on the auxiliaries: the auxiliary rows of
  // 003 §3.2.2 let the definitions absorb a far target, so the surface stalls short of it.
  bool relation_on_surface = true;
  // The 12 per-sample auxiliaries of 003 §3.1.2 and their definitions. Without them the only
  // unknowns are the control points, which only a fixed relation on the surface allows.
  bool curvature_auxiliaries = true;
  int bspline_relation_control_points = 6;
  // Samples per direction; 0: samples_per_control × control points (Table 2: 2; with a fixed
  // relation kRelationSamplesPerControl).
  int samples_u = 0, samples_v = 0;
  int samples_per_control = 2;
  // Continuation: the soft terms (closeness, shape, fairness) start soft_start times stronger
  // and relax by solver.soft_weight_decay per iteration (on the squared weights) to the values
  // above, so early steps are short while the auxiliaries adapt. 1: off (fixed weights).
  double soft_start = 1.0;
  // The run's target (0: none; the run takes solver.max_iterations steps per level, as the
  // paper's experiments do): max_relation_residual (input units, a² + b² = 1) with a fixed
  // linear relation, misalignment otherwise. A run with a target stops when it is met and
  // converges only if it is.
  double tolerance = 0.0;
  // Multiresolution (003 §4.1.1): after the first solve, each level inserts one knot in every
  // span (Boehm) and solves again. 0: off.
  int refine_levels = 0;
  // Instead of inserting knots (the same surface, exactly), refit the surface by least squares
  // on a net refine_factor times as dense in each direction (uniform knots; not nested in the
  // coarser net, so the level starts slightly off), as the paper does (§4.1.1; Fig. 6 goes
  // 10 × 8 → 14 × 10 → 18 × 14 → 25 × 18).
  bool refine_by_refit = false;
  double refine_factor = 1.4;
  double target_mean_curvature = 5.0;
  // After every step the auxiliaries are set to their exact values from the control points
  // (the definitions then hold at every x^k and each step is a Gauss–Newton step on the
  // surface itself).
  bool project_auxiliaries = false;
  // Steps that fold the surface are refused (see SolverOptions::admissible_trial): on the grid
  // the result's regularity is checked on (4 × the samples per direction), the normals of
  // neighbouring points may not turn by more than 60°, or by more than on the input where that
  // is more. Guided projection only (Ceres' steps are not checked).
  bool prevent_folds = true;

  CurvatureRelation relation() const;
  // The measure `tolerance` bounds: "max_relation_residual" or "misalignment".
  std::string target_measure() const;
  bool IsValid(std::string* why) const;
};

// Named settings of 003 Table 1: fig1 (also 7, 8, 12, 13), fig2b, fig2c, fig2d, fig3, fig4b,
// fig4c, fig9b, fig9c, fig10. Throws InputError for other names (listing the known ones).
WeingartenOptions WeingartenPreset(const std::string& name);
std::vector<std::string> WeingartenPresetNames();

}  // namespace gproj::weingarten
