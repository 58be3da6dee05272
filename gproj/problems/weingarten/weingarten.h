#pragma once
// Weingarten surfaces on B-splines (003 §3–4): the control points of a tensor-product B-spline
// move so that the isolines of mean curvature H and Gaussian curvature K align
// (H_u K_v − H_v K_u = 0 at the samples), optionally with geodesic parallel isolines, a linear
// relation a H + b K + c = 0 or a B-spline curve relation in the (H, K) plane, while closeness,
// shape preservation, boundary gliding and control-net fairness keep the shape.
//
// Unknowns (003 Table 2): 3 per control point, 12 per sample (n, E, F, G, Δ, L, M, N, K, H),
// plus 8 per sample with geodesic parallel isolines. Before solving, the surface is centred
// and scaled so that the mean |principal curvature| at the samples is 5 (Table 1 note); results
// and measures are reported in input units.
//
// This header holds the problem (WeingartenProblem, its size limits) and the measures of a
// surface; the options are in weingarten_options.h, the multiresolution run in weingarten_run.h.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "gproj/constraints/curvature_auxiliaries.h"
#include "gproj/geometry/surface/bspline_surface.h"
#include "gproj/problems/run/guided_problem.h"
#include "gproj/problems/weingarten/weingarten_options.h"
#include "gproj/solver/ceres_adapter.h"
#include "gproj/solver/guided_projection.h"
#include "gproj/solver/problem.h"

namespace gproj {
class LinearWeingarten;
class SurfaceLinearWeingarten;
}  // namespace gproj

namespace gproj::weingarten {

// The most samples a problem takes (12 unknowns each: 24 million unknowns); more is refused
// before anything is allocated. WeingartenMemoryEstimate usually refuses less first.
constexpr int64_t kMaxWeingartenSamples = 2000000;

// Folds are looked for on a grid this many times as dense as the samples per direction: in
// every trial step (WeingartenOptions::prevent_folds) and in the result (WeingartenRun).
constexpr int kFoldGridFactor = 4;

// Number of unknowns as counted in 003 Table 2.
int WeingartenVariableCount(int nu, int nv, int su, int sv, bool geodesic_parallel);

struct WeingartenMeasures {
  // Σ |H_u K_v − H_v K_u| / Σ |∇H| |∇K| over the inner samples (central differences of the
  // surface's own H and K; 0 for a Weingarten surface).
  double misalignment = 0.0;
  double max_deviation = 0.0;   // max |s − s_ref| over the samples / bbox diagonal of s_ref
  double mean_deviation = 0.0;  // mean of the same
  int worst_sample = -1;        // where the max deviation is
  // max |a H + b K + c| over samples for the relation in use (a² + b² = 1), 0 if none.
  double max_relation_residual = 0.0;
  std::vector<double> h, k;  // per sample, input units
  double mean_abs_principal_curvature = 0.0;
};

// H and K of `surface` at the samples of `maps` (from the derivatives; exact, no auxiliaries).
// Computed at unit scale, so that any finite control net whose H and K are representable gets
// them: SampleUnitCurvatures gives H·d and K·d² of the net divided by its bounding-box diagonal
// d and returns d (1 when d is 0 or not finite).
double SampleUnitCurvatures(const BSplineSurface& surface, const SampleMaps& maps,
                            std::vector<double>* h, std::vector<double>* k);
void SampleCurvatures(const BSplineSurface& surface, const SampleMaps& maps, std::vector<double>* h,
                      std::vector<double>* k);
// Misalignment and deviation of `surface` against `reference` (same control-net size).
WeingartenMeasures MeasureWeingarten(const BSplineSurface& surface, const BSplineSurface& reference,
                                     int su, int sv);
// The measures as named values (the report's keys): misalignment, max_deviation,
// mean_deviation, max_relation_residual (with a relation) and mean_abs_principal_curvature.
NamedValues ToNamedValues(const WeingartenMeasures& m, bool with_relation);

// Run() is guided projection for solver.max_iterations steps or to the tolerance; RunCeres()
// is the cross-check: Ceres' Levenberg–Marquardt on the same rows, with the soft terms at
// their final weights (after the soft start).
class WeingartenProblem : public GuidedProblem {
 public:
  // Throws InputError if the options are invalid or the surface is degenerate at a sample.
  WeingartenProblem(const BSplineSurface& input, const WeingartenOptions& options);

  Problem& problem() override { return problem_; }
  using GuidedProblem::problem;
  // The options' solver with the soft start applied. With project_auxiliaries their
  // project_trial refers to this problem: use them with this problem only, while it lives.
  SolverOptions solver_options() const override;
  CeresOptions ceres_options(int max_iterations) const override;
  NamedValues MeasureAt(const Eigen::VectorXd& x) const override;
  bool MeetsTolerance(const NamedValues& measures) const override;
  // The tolerance asked, or with none and a fixed linear relation the relation's own: the run
  // then takes the preset's iterations and is converged when every sample meets the relation
  // to kDefaultRelationShare of its natural size |a| κ + |b| κ² (κ the input's typical
  // principal curvature). Without either the run minimises and has no tolerance.
  bool HasTolerance() const override { return tolerance_ > 0.0; }
  // Only a tolerance asked stops the run when met.
  bool StopsAtTolerance() const override { return options_.tolerance > 0.0; }
  double tolerance() const { return tolerance_; }

  // Current surface in input units.
  BSplineSurface Result() const;
  WeingartenMeasures Measures() const { return MeasuresAt(problem_.x()); }
  const SampleMaps& maps() const { return maps_; }
  int num_variables() const { return problem_.layout().num_variables(); }
  double scale() const { return scale_; }  // scaled = (input − centre) · scale
  const WeingartenOptions& options() const {
    return options_;
  }  // The linear relation's coefficients in input units (a² + b² = 1), when one is in use.
  Eigen::Vector3d LinearRelation() const;

 private:
  // The control items of a sample's stencil and the stencil.
  using SampleTerms = std::pair<std::vector<int>, SampleStencil>;
  // The build steps of the constructor, in order.
  void ScaleToTargetCurvature();
  std::vector<SampleTerms> AddCurvatureDefinitions();
  void AddAlignment();
  void AddGeodesicParallel();
  void AddRelations(const std::vector<SampleTerms>& stencils);
  void AddControlNetTerms();
  void AddBoundaryGliding(double mean_edge);

  // Items of sample (a, b): its forms (n, E, F, G, Δ, L, M, N), its curvatures (K, H), its
  // gradient auxiliaries.
  int FormsItem(int a, int b) const { return Items(forms_block_)[maps_.Index(a, b)]; }
  int CurvatureItem(int a, int b) const { return Items(curvature_block_)[maps_.Index(a, b)]; }
  int GradientItem(int a, int b) const { return Items(gradient_block_)[maps_.Index(a, b)]; }
  // The items of one of the problem's blocks (control points, forms, curvatures, gradients).
  BlockItems Items(int block) const { return BlockItems(problem_.layout(), block); }

  BSplineSurface ScaledToInput(const Eigen::VectorXd& x) const;
  WeingartenMeasures MeasuresAt(const Eigen::VectorXd& x) const;
  // Exact auxiliaries from the control points in x (curvature) or from the curvature
  // auxiliaries in x (geodesic parallel; nothing without them).
  void SetCurvatureAuxiliaries(Eigen::VectorXd* x) const;
  // Writes the twelve values of sample s (ExactAuxiliary's order) into its two items.
  void SetSampleAuxiliaries(const VariableLayout& layout, int s,
                            const Eigen::Matrix<double, 12, 1>& a, Eigen::VectorXd* x) const;
  void SetGradientAuxiliaries(Eigen::VectorXd* x) const;
  // The smallest cosine between the normals of neighbouring points of the fold-check grid.
  double MinNormalCosineAt(const Eigen::VectorXd& x) const;
  // Copies the control points of x into control_buffer_.
  void GatherControlPoints(const Eigen::VectorXd& x) const;

  WeingartenOptions options_;
  BSplineSurface reference_;  // input units
  BSplineSurface scaled_;     // scaled reference
  SampleMaps maps_;
  Eigen::Vector3d centre_ = Eigen::Vector3d::Zero();
  double scale_ = 1.0;
  double tolerance_ = 0.0;                    // HasTolerance()
  double alignment_scale_ = 1.0;              // 1 / RMS |∇H| |∇K| of the input, scaled units
  std::array<double, 5> derivative_scale_{};  // parameters rescaled to unit mean speed
  std::vector<double> inv_du_, inv_dv_;       // central-difference factors per sample row
  std::array<double, 2> gradient_scales_{1.0, 1.0};  // units of the K and H gradient auxiliaries
  // Buffers of SetCurvatureAuxiliaries (it runs after every step; sized once).
  mutable Eigen::MatrixX3d control_buffer_;
  mutable std::array<Eigen::MatrixX3d, 5> derivative_buffer_;
  // Fold prevention: the normals on the check grid and the smallest admissible cosine.
  mutable GridNormals fold_grid_;
  double fold_cosine_ = 0.5;
  Problem problem_;
  int control_block_ = -1, forms_block_ = -1, curvature_block_ = -1, gradient_block_ = -1;
  LinearWeingarten* linear_ = nullptr;
  SurfaceLinearWeingarten* surface_linear_ = nullptr;
};

}  // namespace gproj::weingarten
