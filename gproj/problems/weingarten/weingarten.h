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

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "gproj/constraints/curvature_auxiliaries.h"
#include "gproj/geometry/io/mesh_io.h"
#include "gproj/geometry/surface/bspline_surface.h"
#include "gproj/problems/run/guided_problem.h"
#include "gproj/problems/run/report_json.h"
#include "gproj/problems/weingarten/curvature_diagram.h"
#include "gproj/problems/weingarten/helical_fit.h"
#include "gproj/solver/ceres_adapter.h"
#include "gproj/solver/guided_projection.h"
#include "gproj/solver/problem.h"

namespace gproj {

enum class CurvatureRelation { kNone, kLinear, kBSpline };

// Samples per control point and direction with a fixed relation (preset fig3, --linear). With
// Table 2's 2 the samples outnumber the surface's normal freedom by only 4:1 and the tangential
// freedom lets the surface meet the relation at the samples and miss it between them (the CMC
// bump of Fig. 3, H = −0.1: 4.4e-5 at the samples, 1.3e-3 between them); with 3 the relation
// holds between the samples as well as at them (docs/families/weingarten.md, "Relations between the
// samples").
constexpr int kRelationSamplesPerControl = 3;

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

// A preset with what a user overrides (unset: the preset's value); the command line and the
// Python module fill one of these.
struct WeingartenSettings {
  std::string preset = "fig1";
  // "none", "linear" (fitted every iteration) or "bspline"; empty: the preset's.
  std::string relation;
  // A fixed linear relation a H + b K + c = 0 (input units): {a, b, c}, or empty. It replaces
  // the relation.
  std::vector<double> linear;
  std::string relation_on;  // "surface" or "auxiliaries"; empty: the preset's
  std::string steps;        // "plain", "monotone" or "projected"; empty: the preset's
  bool no_auxiliaries = false;
  bool allow_folds = false;  // keep steps that fold the surface (WeingartenOptions::prevent_folds)
  std::vector<int> samples;  // {NU, NV}, or empty: the preset's density
  std::optional<int> max_iterations;
  std::optional<double> alignment, closeness, shape, geodesic_parallel, boundary, epsilon, fairness,
      definitions, soft_start, tolerance;
  int refine_levels = 0;
  std::string refine_method = "insert";  // "insert" (knot insertion) or "refit" (least squares)
  int molds = 0;  // cluster the result's samples into at most this many molds (0: none)

  // The preset with the overrides applied; throws InputError naming the rule broken.
  WeingartenOptions ToOptions() const;
};

// The most samples a problem takes (12 unknowns each: 24 million unknowns); more is refused
// before anything is allocated. WeingartenMemoryEstimate usually refuses less first.
constexpr int64_t kMaxWeingartenSamples = 2000000;

// Folds are looked for on a grid this many times as dense as the samples per direction: in
// every trial step (WeingartenOptions::prevent_folds) and in the result (WeingartenRun).
constexpr int kFoldGridFactor = 4;

// Bytes a run of `input` with `options` needs at its last (finest) level, the largest: about
// 25 KB per sample plus 1.6 KB per sample and control point of its stencil, (du + 1)(dv + 1)
// of them (the Jacobian rows, J^T J and the factor). Measured on 33 × 33 control points with
// 66 × 66 samples: 205 MB at bi-degree 3, 646 MB at 8, 2.05 GB at 16; bicubic, 310 MB at
// 40 × 40 control points and 1.4 GB at 80 × 80. RunWeingarten refuses a run whose estimate
// exceeds the machine's memory before it starts.
struct WeingartenFootprint {
  double su = 0.0, sv = 0.0;  // samples per direction at the finest level
  double bytes = 0.0;
};
WeingartenFootprint WeingartenMemoryEstimate(const BSplineSurface& input,
                                             const WeingartenOptions& options);

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
  bool HasTolerance() const override { return options_.tolerance > 0.0; }

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
  int FormsItem(int a, int b) const {
    return problem_.layout().Item(forms_block_, maps_.Index(a, b));
  }
  int CurvatureItem(int a, int b) const {
    return problem_.layout().Item(curvature_block_, maps_.Index(a, b));
  }
  int GradientItem(int a, int b) const {
    return problem_.layout().Item(gradient_block_, maps_.Index(a, b));
  }

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
  class LinearWeingarten* linear_ = nullptr;
  class SurfaceLinearWeingarten* surface_linear_ = nullptr;
};

// One level of a multiresolution run (003 §4.1.1).
struct WeingartenLevel {
  int level = 0;
  int nu = 0, nv = 0;  // control points
  int su = 0, sv = 0;  // samples
  int variables = 0;
  int iterations = 0;
  double misalignment = 0.0;  // of the level's result
};

// The result measured between the samples: on a check grid twice as dense (its points fall
// between the samples), the misalignment and, with a relation, its max residual inside and
// within 5% of the parameter domain's boundary (input units).
struct WeingartenDenseCheck {
  int su = 0, sv = 0;
  double misalignment = 0.0;
  double max_relation_interior = 0.0, max_relation_boundary = 0.0;
};
WeingartenDenseCheck DenseCheck(const BSplineSurface& surface, const BSplineSurface& reference,
                                int su, int sv, const Eigen::Vector3d& relation,
                                bool with_relation);

// A whole Weingarten run: the levels, every iterate, the result and its measures.
struct WeingartenRun {
  // The run as one report: report.history holds every level's records in order, initial the
  // input's measures, final the result's against the input (at the last level's samples);
  // converged: the last level converged (its tolerance met, or with none its steps taken).
  RunReport report;
  std::vector<int> history_level;  // the level of each record
  std::vector<WeingartenLevel> levels;
  BSplineSurface result;             // input units
  WeingartenMeasures before, after;  // the input and the result, at the last level's samples
  int su = 0, sv = 0;                // the last level's samples
  Eigen::Vector3d relation = Eigen::Vector3d::Zero();  // the linear relation, input units
  bool with_relation = false;
  // The clustering of the result's (and the input's) samples into molds, when asked.
  std::optional<MoldClustering> molds, molds_before;
  // Regularity of the input and the result on a grid 4× as dense as the samples: a fold (the
  // normal turning over between neighbouring points) makes the result unusable.
  NormalTurn normals_before, normals_after;
  WeingartenDenseCheck dense;  // the result between the samples
  // With geodesic parallel isolines (003 Fig. 4): the input's and the result's deviation from
  // the nearest helical surface (kinematic surfaces are the W-surfaces with such isolines).
  std::optional<HelicalDeviation> helical_before, helical_after;
  bool folds() const { return normals_after.min_cosine < 0.0; }
};

// Optimises `input` with `options` by `solver` (guided projection or Ceres' LM), then
// for every refinement level inserts a knot in every span and optimises again. on_level(level,
// problem) is called before each level's solve, on_iteration with every record; returning
// false from it stops the run. molds > 0: the result's samples are clustered into at most that
// many molds (003 §4.2).
WeingartenRun RunWeingarten(
    const BSplineSurface& input, const WeingartenOptions& options, SolverKind solver, int molds = 0,
    const RunCallback& on_iteration = nullptr,
    const std::function<void(int, const WeingartenProblem&)>& on_level = nullptr);

// The run's own report keys (see docs/families/weingarten.md): steps, target, tolerance,
// samples, levels, worst_sample, linear_relation, dense_check, min_normal_cosine,
// helical_deviation and, with molds, the clustering. Every history record also gets its level
// (WeingartenRun::history_level).
nlohmann::json WeingartenReportFacts(const WeingartenOptions& options, const WeingartenRun& run);
// What a level solves and where it starts (one line each), for logs.
std::string DescribeWeingartenLevel(int level, const WeingartenProblem& problem);
// The result in a few lines: misalignment before and after, deviation, relation, molds.
std::string SummarizeWeingartenRun(const WeingartenRun& run);

// The (H, K) diagram of the samples before and after (SVG).
std::string WeingartenDiagramSvg(const WeingartenRun& run);

// Where a run's results go (empty: not written).
struct WeingartenFiles {
  std::string output;        // the B-spline (JSON)
  std::string diagram;       // WeingartenDiagramSvg
  std::string curvature;     // WeingartenCurvatureCsv
  std::string surface_mesh;  // the result sampled at 4 points per control point and direction
  std::string picture;       // a shaded picture of the result (SVG)
};
// Adds each file to `out` (written all or none by OutputFiles::Commit); throws InputError naming
// the file that cannot be written.
void AddWeingartenFiles(const WeingartenRun& run, const WeingartenFiles& files, OutputFiles* out);
// H and K per sample before and after (and the mold of each sample when given) as CSV:
// "sample,u,v,H_before,K_before,H_after,K_after[,mold]".
std::string WeingartenCurvatureCsv(const WeingartenRun& run,
                                   const std::vector<int>* mold_of_sample = nullptr);

}  // namespace gproj
