#pragma once
// The multiresolution Weingarten run (003 §4.1.1): the memory estimate checked before it starts,
// RunWeingarten and its WeingartenRun (the levels, every iterate, the result and its measures,
// between the samples too), and what front ends make of a run: the report's own keys, log lines,
// the curvature diagram, the CSV and the output files.

#include <Eigen/Core>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"
#include "gproj/geometry/surface/bspline_surface.h"
#include "gproj/problems/run/guided_problem.h"
#include "gproj/problems/weingarten/curvature_diagram.h"
#include "gproj/problems/weingarten/helical_fit.h"
#include "gproj/problems/weingarten/weingarten.h"
#include "gproj/problems/weingarten/weingarten_options.h"

namespace gproj::weingarten {

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
  double tolerance = 0.0;  // the last level's (WeingartenProblem::tolerance; 0: none)
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

}  // namespace gproj::weingarten
