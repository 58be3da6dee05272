// The multiresolution Weingarten run (003 §4.1.1): optimise, insert a knot in every span,
// optimise again, for every level.
#include "gproj/problems/weingarten/weingarten_run.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "gproj/common/input_error.h"
#include "gproj/geometry/io/mesh_io.h"
#include "gproj/geometry/render/svg_render.h"

namespace gproj::weingarten {
namespace {

// Appends a level's report to the run's.
void AppendLevel(int level, const RunReport& level_report, WeingartenRun* run) {
  RunReport& report = run->report;
  if (level == 0) {
    report.solver = level_report.solver;
    report.initial = level_report.initial;
  }
  for (const RunRecord& r : level_report.history) {
    report.history.push_back(r);
    run->history_level.push_back(level);
  }
  report.iterations += level_report.iterations;
  report.seconds += level_report.seconds;
  report.variables = level_report.variables;
  report.termination = level_report.termination;
  report.failed = level_report.failed;
  report.converged = level_report.converged;
  report.summary = level_report.summary;
}

// Control points along one direction after `levels` uniform refinements (a knot inserted in
// every non-empty span, which doubles the spans).
double RefinedCount(const std::vector<double>& knots, int count, int levels) {
  double spans = 0.0, n = count;
  for (size_t k = 0; k + 1 < knots.size(); ++k) spans += knots[k + 1] > knots[k] ? 1.0 : 0.0;
  for (int level = 0; level < levels; ++level, spans *= 2.0) n += spans;
  return n;
}

}  // namespace

WeingartenFootprint WeingartenMemoryEstimate(const BSplineSurface& input,
                                             const WeingartenOptions& options) {
  const int levels = options.refine_levels;
  const double nu = RefinedCount(input.knots_u, input.nu, levels);
  const double nv = RefinedCount(input.knots_v, input.nv, levels);
  WeingartenFootprint f;
  f.su = options.samples_u > 0 ? options.samples_u : options.samples_per_control * nu;
  f.sv = options.samples_v > 0 ? options.samples_v : options.samples_per_control * nv;
  const double stencil = (input.degree_u + 1.0) * (input.degree_v + 1.0);
  f.bytes = f.su * f.sv * (25e3 + 1.6e3 * stencil);
  return f;
}

WeingartenDenseCheck DenseCheck(const BSplineSurface& surface, const BSplineSurface& reference,
                                int su, int sv, const Eigen::Vector3d& relation,
                                bool with_relation) {
  WeingartenDenseCheck d;
  d.su = su;
  d.sv = sv;
  const WeingartenMeasures m = MeasureWeingarten(surface, reference, su, sv);
  d.misalignment = m.misalignment;
  if (!with_relation) return d;
  const SampleMaps maps = MakeSampleMaps(surface, su, sv);
  const double du = surface.u_max() - surface.u_min(), dv = surface.v_max() - surface.v_min();
  for (int a = 0; a < su; ++a)
    for (int b = 0; b < sv; ++b) {
      const int s = maps.Index(a, b);
      const double r = std::abs(relation[0] * m.h[s] + relation[1] * m.k[s] + relation[2]);
      const double tu = (maps.u[a] - surface.u_min()) / du, tv = (maps.v[b] - surface.v_min()) / dv;
      const bool near_boundary = std::min({tu, 1.0 - tu, tv, 1.0 - tv}) < 0.05;
      double& worst = near_boundary ? d.max_relation_boundary : d.max_relation_interior;
      worst = std::max(worst, r);
    }
  return d;
}

WeingartenRun RunWeingarten(const BSplineSurface& input, const WeingartenOptions& options,
                            SolverKind solver, int molds, const RunCallback& on_iteration,
                            const std::function<void(int, const WeingartenProblem&)>& on_level) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError("invalid Weingarten options: " + why);
  const WeingartenFootprint footprint = WeingartenMemoryEstimate(input, options);
  char what[200];
  std::snprintf(what, sizeof(what),
                "a Weingarten run with %d level(s), %.0f x %.0f samples at the finest, at "
                "bi-degree (%d, %d)",
                options.refine_levels + 1, footprint.su, footprint.sv, input.degree_u,
                input.degree_v);
  CheckMemory(what, footprint.bytes);
  WeingartenRun run;
  BSplineSurface current = input;
  bool stopped = false;
  const RunCallback record = [&](const RunRecord& r) {
    stopped = on_iteration && !on_iteration(r);
    return !stopped;
  };
  for (int level = 0; level <= options.refine_levels && !stopped; ++level) {
    if (level > 0)
      current = options.refine_by_refit
                    ? RefitBSpline(current,
                                   static_cast<int>(std::ceil(options.refine_factor * current.nu)),
                                   static_cast<int>(std::ceil(options.refine_factor * current.nv)))
                    : InsertKnotsUniform(current, 1);
    WeingartenProblem problem(current, options);
    run.su = problem.maps().su;
    run.sv = problem.maps().sv;
    if (on_level) on_level(level, problem);
    const RunReport level_report = problem.RunWith(solver, record);
    AppendLevel(level, level_report, &run);
    if (run.report.failed) return run;
    current = problem.Result();
    run.relation = problem.LinearRelation();
    run.tolerance = problem.tolerance();
    run.levels.push_back({level, current.nu, current.nv, run.su, run.sv, level_report.variables,
                          level_report.iterations, ValueOf(level_report.final, "misalignment")});
  }
  run.result = current;
  run.before = MeasureWeingarten(input, input, run.su, run.sv);
  run.after = MeasureWeingarten(current, input, run.su, run.sv);
  const bool with_relation = run.with_relation = options.linear_relation_weight > 0.0;
  if (with_relation)
    for (size_t s = 0; s < run.after.h.size(); ++s)
      run.after.max_relation_residual =
          std::max(run.after.max_relation_residual,
                   std::abs(run.relation[0] * run.after.h[s] + run.relation[1] * run.after.k[s] +
                            run.relation[2]));
  run.report.final = ToNamedValues(run.after, with_relation);
  run.dense = DenseCheck(current, input, 2 * run.su, 2 * run.sv, run.relation, with_relation);
  run.normals_before = MinNormalCosine(input, kFoldGridFactor * run.su, kFoldGridFactor * run.sv);
  run.normals_after = MinNormalCosine(current, kFoldGridFactor * run.su, kFoldGridFactor * run.sv);
  if (options.geodesic_parallel_weight > 0.0) {
    run.helical_before = MeasureHelicalDeviation(input, 2 * run.su, 2 * run.sv);
    run.helical_after = MeasureHelicalDeviation(current, 2 * run.su, 2 * run.sv);
  }
  if (molds > 0) {
    run.molds = ClusterMolds(run.after.h, run.after.k, molds);
    run.molds_before = ClusterMolds(run.before.h, run.before.k, molds);
  }
  return run;
}

nlohmann::json WeingartenReportFacts(const WeingartenOptions& options, const WeingartenRun& run) {
  nlohmann::json levels = nlohmann::json::array();
  for (const WeingartenLevel& l : run.levels)
    levels.push_back({{"level", l.level},
                      {"control_points", {l.nu, l.nv}},
                      {"samples", {l.su, l.sv}},
                      {"variables", l.variables},
                      {"iterations", l.iterations},
                      {"misalignment", l.misalignment}});
  nlohmann::json extra = {
      {"steps", options.project_auxiliaries ? "projected"
                : options.solver.monotone   ? "monotone"
                                            : "plain"},
      {"target", run.tolerance > 0.0 ? nlohmann::json(options.target_measure()) : nullptr},
      {"tolerance", run.tolerance},
      {"samples", {run.su, run.sv}},
      {"levels", levels},
      {"refine_method", options.refine_by_refit ? "refit" : "insert"}};
  if (run.after.worst_sample >= 0)
    extra["worst_sample"] = {run.after.worst_sample / run.sv, run.after.worst_sample % run.sv};
  if (run.with_relation)
    extra["linear_relation"] = {run.relation[0], run.relation[1], run.relation[2]};
  nlohmann::json dense = {{"samples", {run.dense.su, run.dense.sv}},
                          {"misalignment", run.dense.misalignment}};
  if (run.with_relation) {
    dense["max_relation_residual_interior"] = run.dense.max_relation_interior;
    dense["max_relation_residual_boundary"] = run.dense.max_relation_boundary;
  }
  extra["dense_check"] = dense;
  extra["min_normal_cosine"] = {{"initial", run.normals_before.min_cosine},
                                {"final", run.normals_after.min_cosine},
                                {"final_at", {run.normals_after.u, run.normals_after.v}}};
  if (run.helical_after) {
    auto helical = [](const HelicalDeviation& d) {
      return nlohmann::json{{"max_percent", d.max_percent},
                            {"mean_percent", d.mean_percent},
                            {"pitch", d.motion.pitch},
                            {"radius", d.mean_radius}};
    };
    extra["helical_deviation"] = {{"initial", helical(*run.helical_before)},
                                  {"final", helical(*run.helical_after)}};
  }
  if (run.molds)
    extra["molds"] = {{"clusters", run.molds->num_clusters},
                      {"cells_per_axis", run.molds->cells_per_axis},
                      {"cluster_sizes", run.molds->cluster_size},
                      {"before_cells_per_axis", run.molds_before->cells_per_axis}};
  return extra;
}

std::string DescribeWeingartenLevel(int level, const WeingartenProblem& problem) {
  const WeingartenMeasures m = problem.Measures();
  const BSplineSurface surface = problem.Result();  // the level's start
  char text[512];
  std::snprintf(text, sizeof(text),
                "%s%d x %d control points, bi-degree (%d, %d), %d x %d samples, %d unknowns\n"
                "start: misalignment %.4e, mean |principal curvature| %.4g (scaled by %.4g)\n",
                level > 0 ? ("level " + std::to_string(level) + ": ").c_str() : "", surface.nu,
                surface.nv, surface.degree_u, surface.degree_v, problem.maps().su,
                problem.maps().sv, problem.num_variables(), m.misalignment,
                m.mean_abs_principal_curvature, problem.scale());
  return text;
}

std::string SummarizeWeingartenRun(const WeingartenRun& run) {
  const double before = ValueOf(run.report.initial, "misalignment");
  const WeingartenMeasures& after = run.after;
  char text[2048];
  int n = std::snprintf(
      text, sizeof(text),
      "misalignment %.4e -> %.4e (%.1fx %s), deviation max %.3e (sample %d, %d) / mean "
      "%.3e of the bbox diagonal\n",
      before, after.misalignment,
      after.misalignment <= before ? before / std::max(after.misalignment, 1e-300)
                                   : after.misalignment / std::max(before, 1e-300),
      after.misalignment <= before ? "lower" : "higher", after.max_deviation,
      after.worst_sample / run.sv, after.worst_sample % run.sv, after.mean_deviation);
  if (run.with_relation)
    n += std::snprintf(text + n, sizeof(text) - n,
                       "linear relation %.6g H + %.6g K + %.6g = 0 (input units): max residual "
                       "%.3e\n",
                       run.relation[0], run.relation[1], run.relation[2],
                       after.max_relation_residual);
  n += std::snprintf(text + n, sizeof(text) - n,
                     "between the samples (%d x %d check grid): misalignment %.4e", run.dense.su,
                     run.dense.sv, run.dense.misalignment);
  if (run.with_relation)
    n += std::snprintf(text + n, sizeof(text) - n,
                       ", max relation residual %.3e inside, %.3e within 5%% of the boundary",
                       run.dense.max_relation_interior, run.dense.max_relation_boundary);
  n += std::snprintf(text + n, sizeof(text) - n, "\n");
  n += std::snprintf(text + n, sizeof(text) - n,
                     "regularity: min cosine of neighbouring normals %.4f -> %.4f%s\n",
                     run.normals_before.min_cosine, run.normals_after.min_cosine,
                     run.folds() ? " (the result folds)" : "");
  if (run.helical_after)
    n += std::snprintf(text + n, sizeof(text) - n,
                       "deviation from the nearest helical surface (%% of its radius): max %.3f "
                       "-> %.3f, mean %.3f -> %.3f (pitch %.4g per radian)\n",
                       run.helical_before->max_percent, run.helical_after->max_percent,
                       run.helical_before->mean_percent, run.helical_after->mean_percent,
                       run.helical_after->motion.pitch);
  if (run.molds)
    std::snprintf(text + n, sizeof(text) - n,
                  "molds: %d clusters in the (H, sqrt K) plane (grid %d x %d)\n",
                  run.molds->num_clusters, run.molds->cells_per_axis, run.molds->cells_per_axis);
  return text;
}

std::string WeingartenDiagramSvg(const WeingartenRun& run) {
  DiagramOptions d;
  char title[160];
  std::snprintf(title, sizeof(title), "Curvature diagram: misalignment %.3g -> %.3g",
                run.before.misalignment, run.after.misalignment);
  d.title = title;
  return RenderCurvatureDiagramSvg({{"before", "#c0392b", run.before.h, run.before.k},
                                    {"after", "#2c6fbb", run.after.h, run.after.k}},
                                   d);
}

void AddWeingartenFiles(const WeingartenRun& run, const WeingartenFiles& files, OutputFiles* out) {
  const BSplineSurface& result = run.result;
  if (!files.output.empty()) out->AddText(files.output, BSplineToJson(result));
  if (!files.curvature.empty())
    out->AddText(files.curvature,
                 WeingartenCurvatureCsv(run, run.molds ? &run.molds->cluster : nullptr));
  if (!files.diagram.empty()) out->AddText(files.diagram, WeingartenDiagramSvg(run));
  if (!files.surface_mesh.empty())
    out->AddMesh(SampleSurfaceMesh(result, 4 * result.nu, 4 * result.nv), files.surface_mesh);
  if (!files.picture.empty()) {
    SvgOptions svg;
    svg.title = "Weingarten surface (" + std::to_string(result.nu) + " x " +
                std::to_string(result.nv) + " control points)";
    out->AddText(files.picture, RenderMeshSvg(SampleSurfaceMesh(result, 60, 60), svg));
  }
}

std::string WeingartenCurvatureCsv(const WeingartenRun& run, const std::vector<int>* mold) {
  const SampleMaps maps = MakeSampleMaps(run.result, run.su, run.sv);
  std::ostringstream out;
  out.precision(10);
  out << "sample,u,v,H_before,K_before,H_after,K_after" << (mold ? ",mold" : "") << "\n";
  for (int a = 0; a < maps.su; ++a)
    for (int b = 0; b < maps.sv; ++b) {
      const int s = maps.Index(a, b);
      out << s << "," << maps.u[a] << "," << maps.v[b] << "," << run.before.h[s] << ","
          << run.before.k[s] << "," << run.after.h[s] << "," << run.after.k[s];
      if (mold) out << "," << (*mold)[s];
      out << "\n";
    }
  return out.str();
}

}  // namespace gproj::weingarten
