#include "gproj/problems/marionette/marionette_run.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>

#include "gproj/geometry/io/text_input.h"
#include "gproj/geometry/mesh/quad_grid.h"
#include "gproj/problems/marionette/marionette_grid_problem.h"
#include "gproj/problems/marionette/marionette_inputs.h"
#include "gproj/problems/marionette/marionette_polygons.h"
#include "gproj/problems/mesh/planarity_measures.h"
#include "gproj/problems/run/construction.h"

namespace gproj::marionette {
namespace {

using Clock = std::chrono::steady_clock;

// printf into a string.
template <typename... Args>
std::string Format(const char* format, Args... args) {
  char text[512];
  std::snprintf(text, sizeof(text), format, args...);
  return text;
}

// The plan view (quads only) and the fit target, from memory or read from their files.
PolyMesh PlanMesh(const MarionetteRunOptions& options) {
  if (!options.plan_mesh) return ReadMesh(options.plan, MeshRequirements{true});
  for (const auto f : options.plan_mesh->faces())
    if (options.plan_mesh->valence(f) != 4)
      throw InputError(options.plan + ": face " + std::to_string(f.idx()) + " has " +
                       std::to_string(options.plan_mesh->valence(f)) +
                       " vertices; the plan view needs quads");
  return *options.plan_mesh;
}
PolyMesh FitMesh(const MarionetteRunOptions& options) {
  return options.fit_mesh ? *options.fit_mesh : ReadMesh(options.fit);
}

// A grid plan lifted from guide curves or fitted to a target's heights.
class GridRun : public MarionetteRun {
 public:
  explicit GridRun(const MarionetteRunOptions& options) : options_(options) {
    const PolyMesh mesh = PlanMesh(options);
    warning_ = CheckPlanView(mesh, options.plan, options.allow_folded_plan);
    Eigen::VectorXd target, weights;
    const bool full_target = !options.fit.empty() || options.fit_mesh.has_value();
    const bool partial_target = !options.fit_heights.empty();
    if (full_target && partial_target)
      throw InputError("give either `fit` or `fit_heights`, not both");
    if ((full_target || partial_target) && (!options.row.empty() || !options.column.empty()))
      throw InputError("give either a target (`fit`, `fit_heights`) or `row`/`column`, not both");
    if (full_target) {
      const PolyMesh fit = FitMesh(options);
      if (fit.n_vertices() != mesh.n_vertices())
        throw InputError(options.fit + ": the target has " + std::to_string(fit.n_vertices()) +
                         " vertices, the plan " + std::to_string(mesh.n_vertices()));
      target.resize(fit.n_vertices());
      for (auto v : fit.vertices()) target[v.idx()] = fit.point(v)[2];
      if (!options.constraints.empty()) weights = Eigen::VectorXd::Ones(target.size());
    } else if (partial_target) {
      const int n = static_cast<int>(mesh.n_vertices());
      target = weights = Eigen::VectorXd::Zero(n);
      for (const TextLine& line :
           options.fit_heights_text ? SplitTextLines(*options.fit_heights_text, options.fit_heights)
                                    : ReadTextLines(options.fit_heights)) {
        const std::string where = TextPlace(options.fit_heights, line.number);
        if (line.words.size() != 2)
          throw InputError(where + ": a line is 'VERTEX HEIGHT' (got " +
                           std::to_string(line.words.size()) + " words)");
        const int v = ParseIndex(line.words[0], where, n, "vertex");
        if (weights[v] > 0.0)
          throw InputError(where + ": vertex " + std::to_string(v) + " is given twice");
        target[v] = ParseNumber(line.words[1], where);
        weights[v] = 1.0;
      }
    } else if (options.row.empty() || options.column.empty()) {
      throw InputError(
          "give the guide curves (`row` and `column` heights, or `guides`) or a target (`fit`, "
          "`fit_heights`)");
    }
    if (!options.constraints.empty() && !full_target && !partial_target)
      throw InputError(
          "`hold`, `volume` and `max_height` constrain a fit (`fit` or `fit_heights`)");
    if (weights.size() > 0 && options.solver != SolverKind::kDirect)
      throw InputError(
          "a partial target (`fit_heights`) and hard constraints (`hold`, `volume`, "
          "`max_height`) are solved exactly by the KKT system: use `solver` direct");
    const auto vector = [](const std::vector<double>& v) {
      return Eigen::Map<const Eigen::VectorXd>(v.data(), v.size());
    };
    problem_ = std::make_unique<MarionetteGridProblem>(
        mesh, options.plan, vector(options.row), vector(options.column), target,
        MarionetteOptions{MarionetteSolverOptions(), options.lift.tolerance});
    if (weights.size() > 0) {
      problem_->SetFitConstraints(weights, options.constraints);
      // Solved here, so that targets or constraints that do not determine the lift are an input
      // error before anything runs.
      constrained_heights_ = problem_->DirectHeights();
    }
  }

  std::string Description() const override {
    const MarionettePlan& plan = problem_->plan();
    return Format("%s: %d x %d faces, %d heights, %s\n", options_.plan.c_str(), plan.rows,
                  plan.cols, plan.num_vertices(),
                  problem_->fit() ? "least-squares fit to a target" : "lift from guide curves") +
           warning_;
  }
  RunReport Run(const RunCallback& callback) override {
    if (options_.solver == SolverKind::kGuidedProjection) return problem_->Run(callback);
    if (options_.solver == SolverKind::kCeres)
      return problem_->RunCeres(options_.lift.solver.max_iterations, callback);
    return problem_->RunDirect(
        ConstructionMethodName(problem_->fit() ? ConstructionMethod::kLinearSystem
                                               : ConstructionMethod::kPropagation),
        problem_->constrained() ? "DIRECT: KKT system of the constrained fit (002 §3.3)"
        : problem_->fit()       ? "DIRECT: normal equations of the fit (002 eq. 14)"
                                : "DIRECT: propagation (002 eq. 2)",
        [this] {
          problem_->SetHeights(constrained_heights_.size() > 0 ? constrained_heights_
                                                               : problem_->DirectHeights());
        });
  }
  PolyMesh Result() const override { return problem_->Result(); }
  nlohmann::json Facts() const override {
    const MarionettePlan& plan = problem_->plan();
    nlohmann::json facts = {
        {"input", options_.plan}, {"fit", options_.fit}, {"faces", plan.rows * plan.cols}};
    if (!options_.fit_heights.empty()) facts["fit_heights"] = options_.fit_heights;
    const MarionetteConstraints& c = options_.constraints;
    if (!c.empty()) {
      nlohmann::json held = nlohmann::json::array();
      for (const auto& [v, z] : c.heights) held.push_back({v, z});
      facts["hard_constraints"] = {
          {"heights", held},
          {"volume", c.with_volume ? nlohmann::json(c.volume) : nlohmann::json(nullptr)},
          {"max_height",
           c.with_max_height ? nlohmann::json(c.max_height) : nlohmann::json(nullptr)}};
    }
    return facts;
  }
  std::string ToleranceMeasure() const override { return "max_planarity"; }

 private:
  MarionetteRunOptions options_;
  std::unique_ptr<MarionetteGridProblem> problem_;
  std::string warning_;                  // a folded plan view lifted anyway
  Eigen::VectorXd constrained_heights_;  // the constrained or partial fit, solved up front
};

// The prescribed values of a mesh lift: from the guide file, or --row and --column on a grid.
std::vector<MarionetteTarget> MeshGuideValues(const MarionetteRunOptions& options,
                                              const PolyMesh& mesh) {
  if (!options.guides.empty() || options.guides_text) {
    if (!options.row.empty() || !options.column.empty())
      throw InputError("give either `guides` or `row`/`column`, not both");
    const int n = static_cast<int>(mesh.n_vertices());
    const MarionetteGuideFile file =
        options.guides_text ? ParseMarionetteGuides(*options.guides_text, options.guides, n)
                            : ReadMarionetteGuides(options.guides, n);
    return ResolveMarionetteGuides(mesh, file.guides, file.vertices);
  }
  if (options.row.empty() || options.column.empty())
    throw InputError("give the guides (`guides`, or `row` and `column` on a grid plan)");
  return ResolveMarionetteGuides(
      mesh, {}, GridGuideValues(DetectGridShape(mesh, options.plan), options.row, options.column));
}

// A plan of any connectivity lifted on the lines of a projection.
class MeshRun : public MarionetteRun {
 public:
  explicit MeshRun(const MarionetteRunOptions& options) : options_(options) {
    const MarionetteProjectionOptions projection =
        MarionetteProjectionFromValues(options.projection, options.axis, options.centre);
    if (!options.fit.empty() || options.fit_mesh)
      throw InputError("`fit` works with the vertical projection and `row`/`column` only");
    std::string why;
    if (!options.lift.IsValid(&why)) throw InputError("invalid option: " + why);
    const PolyMesh mesh = PlanMesh(options);
    if (options.projection == "vertical")
      warning_ = CheckPlanView(mesh, options.plan, options.allow_folded_plan);
    lines_ = MakeMarionetteLines(mesh, projection, options.plan);
    layout_ = DecomposeIntoPatches(mesh);
    prescribed_ = MeshGuideValues(options, mesh);
    lift_ = LiftMarionetteMesh(lines_, layout_, prescribed_);  // also checks the guides for gp
    problem_ = std::make_unique<MarionetteMeshProblem>(lines_, prescribed_, options.lift);
  }

  std::string Description() const override {
    std::string text = Format(
        "%s: %d vertices, %zu quads, %s projection\npatches: %zu singular "
        "vertices, %zu separatrices, %zu patches, %zu strips of patches (%d face strips, %d "
        "closed): a lift needs %d guide values, the guides give %zu\n",
        options_.plan.c_str(), lines_.num_vertices(), lines_.mesh.n_faces(),
        options_.projection.c_str(), layout_.singular_vertices.size(), layout_.separatrices.size(),
        layout_.patches.size(), layout_.patch_strips.size(), layout_.num_face_strips,
        layout_.num_closed_face_strips, layout_.design_dimension(), prescribed_.size());
    if (!lift_.redundant_faces.empty())
      text +=
          Format("note: the guides over-determine %zu faces (patches %d...) but agree with them\n",
                 lift_.redundant_faces.size(), lift_.over_determined_patches.front());
    return text + warning_;
  }
  RunReport Run(const RunCallback& callback) override {
    if (options_.solver == SolverKind::kGuidedProjection) return problem_->Run(callback);
    if (options_.solver == SolverKind::kCeres)
      return problem_->RunCeres(options_.lift.solver.max_iterations, callback);
    return problem_->RunDirect(ConstructionMethodName(ConstructionMethod::kPropagation),
                               "DIRECT: propagation (002 §2.4)",
                               [this] { problem_->SetParameters(lift_.t); });
  }
  PolyMesh Result() const override { return problem_->Result(); }
  nlohmann::json Facts() const override;
  std::string ToleranceMeasure() const override { return "max_relative_det"; }

 private:
  MarionetteRunOptions options_;
  MarionetteLines lines_;
  std::string warning_;  // a folded plan view lifted anyway
  MarionettePatchLayout layout_;
  std::vector<MarionetteTarget> prescribed_;
  MarionetteMeshLift lift_;
  std::unique_ptr<MarionetteMeshProblem> problem_;
};

nlohmann::json PatchesJson(const std::vector<MarionettePatch>& patches) {
  nlohmann::json j = nlohmann::json::array();
  for (const MarionettePatch& p : patches)
    j.push_back(
        {{"faces", p.faces.size()}, {"rows", p.rows}, {"cols", p.cols}, {"corners", p.corners}});
  return j;
}

nlohmann::json MeshRun::Facts() const {
  return {{"input", options_.plan},
          {"guides", options_.guides},
          {"projection", options_.projection},
          {"faces", static_cast<int>(lines_.mesh.n_faces())},
          {"singular_vertices", layout_.singular_vertices},
          {"patches", PatchesJson(layout_.patches)},
          {"patch_order", lift_.patch_order},
          {"strips_of_patches", static_cast<int>(layout_.patch_strips.size())},
          {"face_strips", layout_.num_face_strips},
          {"design_dimension", layout_.design_dimension()},
          {"guide_values", static_cast<int>(prescribed_.size())},
          {"redundant_faces", lift_.redundant_faces},
          {"over_determined_patches", lift_.over_determined_patches}};
}

// A plan view of any polygons (002 §4.2) lifted from prescribed heights (--hold) and the
// fairness energy of eq. 17.
class PolygonRun : public MarionetteRun {
 public:
  explicit PolygonRun(const MarionetteRunOptions& options) : options_(options) {
    if (!options.guides.empty() || options.guides_text || !options.row.empty() ||
        !options.column.empty() || !options.fit.empty() || options.fit_mesh ||
        !options.fit_heights.empty())
      throw InputError(options.plan +
                       ": a plan of polygons is lifted from prescribed heights (`hold` "
                       "VERTEX:HEIGHT) and fairness; guides, rows, columns and fits need quads");
    if (options.projection != "vertical" || options.solver != SolverKind::kDirect)
      throw InputError(options.plan + ": a plan of polygons is lifted vertically and directly");
    if (options.constraints.with_volume || options.constraints.with_max_height)
      throw InputError(options.plan + ": `volume` and `max_height` need a quad plan");
    if (options.constraints.heights.empty())
      throw InputError(options.plan +
                       ": a plan of polygons needs prescribed heights (`hold` VERTEX:HEIGHT,...)");
    plan_ = options.plan_mesh ? *options.plan_mesh : ReadMesh(options.plan);
    try {
      lift_ = LiftPolygonPlan(plan_, options.constraints.heights);
    } catch (const InputError& e) {
      throw InputError(options.plan + ": " + e.what());
    }
    space_ = lift_.space;
    construction_.Stop();
  }
  std::string Description() const override {
    std::map<int, int> sizes;
    for (auto f : plan_.faces()) ++sizes[static_cast<int>(plan_.valence(f))];
    std::string faces;
    for (const auto& [n, count] : sizes) faces += Format(" %d %d-gons,", count, n);
    return Format("%s: %d vertices,%s vertical projection\n", options_.plan.c_str(),
                  space_.vertices, faces.c_str()) +
           Format(
               "design space (002 eq. 16): %d vertices - %d planarity rows = %d; by rank %d; "
               "%zu heights prescribed, fairness (eq. 17) fixes the rest\n",
               space_.vertices, space_.planarity_rows, space_.estimate, space_.dimension,
               options_.constraints.heights.size());
  }
  RunReport Run(const RunCallback&) override {
    const NamedValues measures = {{"max_planarity", lift_.max_planarity},
                                  {"max_height_error", lift_.max_height_error},
                                  {"fairness", lift_.fairness}};
    RunReport report =
        construction_.Finish({}, measures, lift_.max_planarity <= options_.lift.tolerance);
    report.variables = space_.vertices;
    return report;
  }
  PolyMesh Result() const override { return lift_.mesh; }
  nlohmann::json Facts() const override {
    return {{"input", options_.plan},
            {"faces", static_cast<int>(plan_.n_faces())},
            {"design_space",
             {{"vertices", space_.vertices},
              {"planarity_rows", space_.planarity_rows},
              {"estimate", space_.estimate},
              {"rank", space_.rank},
              {"dimension", space_.dimension}}},
            {"prescribed_heights", static_cast<int>(options_.constraints.heights.size())},
            {"fairness_triples", lift_.fairness_triples}};
  }
  std::string ToleranceMeasure() const override { return "max_planarity"; }

 private:
  MarionetteRunOptions options_;
  PolyMesh plan_;
  MarionetteDesignSpace space_;
  MarionettePolygonLift lift_;
  Construction construction_{ConstructionMethod::kLinearSystem,
                             "planarity rows and fairness (002 §4.2, eq. 17)"};
};

// Planarity of a lifted closed strip.
NamedValues StripMeasures(const PolyMesh& mesh) {
  const PlanarityMeasures m = MeasurePlanarity(mesh, mesh);
  return {{"max_planarity", m.max_planarity}, {"mean_planarity", m.mean_planarity}};
}

// A closed strip lifted by its closing condition.
class StripRun : public MarionetteRun {
 public:
  StripRun(const MarionetteRunOptions& options, ClosedStripFile file)
      : options_(options), file_(std::move(file)) {
    if (!std::isfinite(options.outer_height)) throw InputError("`outer_height` must be finite");
    lift_ = LiftClosedStrip(file_.strip, file_.inner_heights, options.outer_height);
    warning_ = CheckPlanView(Result(), options.closed_strip, options.allow_folded_plan);
  }

  std::string Description() const override {
    std::string text =
        Format("closed strip %s: %d quads\n", options_.closed_strip.c_str(), num_quads());
    if (lift_.a_is_one)
      return text +
             Format(
                 "a = %.12g (= 1 within 1e-9): the inner curve must satisfy V.Z = 0; "
                 "projected onto it (moved by at most %.3e); the outer start height is "
                 "free: z0* = %.6g\n",
                 lift_.a, InnerCurveChange(), lift_.outer_heights[0]) +
             warning_;
    return text +
           Format(
               "a = %.12g (!= 1): one closing lift; inner curve kept; closing height "
               "z0* = zN* = V.Z / (1 - a) = %.12g\n",
               lift_.a, lift_.outer_heights[0]) +
           warning_;
  }
  RunReport Run(const RunCallback&) override;
  PolyMesh Result() const override { return ClosedStripMesh(file_.strip, lift_); }
  nlohmann::json Facts() const override {
    return {{"closed_strip", options_.closed_strip},
            {"quads", num_quads()},
            {"a", lift_.a},
            {"a_is_one", lift_.a_is_one},
            {"closing_height", lift_.outer_heights[0]},
            {"v_dot_z", lift_.v.dot(file_.inner_heights)},
            {"inner_curve_change", InnerCurveChange()}};
  }
  std::string ToleranceMeasure() const override { return "max_planarity"; }

 private:
  int num_quads() const { return static_cast<int>(file_.inner_heights.size()); }
  double InnerCurveChange() const {
    return (lift_.inner_heights - file_.inner_heights).cwiseAbs().maxCoeff();
  }

  MarionetteRunOptions options_;
  ClosedStripFile file_;
  ClosedStripLift lift_;
  std::string warning_;  // a folded plan view lifted anyway
};

// A closed mesh of several rings (002 Figs. 7–8, eq. 9), ring by ring outward.
class RingsRun : public MarionetteRun {
 public:
  RingsRun(const MarionetteRunOptions& options, ClosedStripFile file)
      : options_(options), file_(std::move(file)) {
    try {
      lift_ = LiftClosedRings(file_.curves, file_.inner_heights);
    } catch (const InputError& e) {
      throw InputError(options.closed_strip + ": " + e.what());
    }
    construction_.Stop();
    warning_ = CheckPlanView(lift_.mesh, options.closed_strip, options.allow_folded_plan);
  }
  std::string Description() const override {
    std::string text = Format("closed mesh %s: %d rings of %d quads\n",
                              options_.closed_strip.c_str(), rings(), points());
    for (int r = 0; r < rings(); ++r)
      text += Format("ring %d: a = %.12g, |V| = %.3g%s\n", r, lift_.a[r], lift_.v_norm[r],
                     std::abs(lift_.a[r] - 1.0) <= 1e-9
                         ? (lift_.v_norm[r] > 1e-9 ? " (a = 1: closes only for V.Z = 0)"
                                                   : " (a = 1, V = 0: any heights close)")
                         : " (one closing lift)");
    return text +
           Format("inner curve moved by %.3e to what the rings can close (002 eq. 9)\n",
                  lift_.inner_change) +
           warning_;
  }
  RunReport Run(const RunCallback&) override {
    const NamedValues measures = {{"max_planarity", lift_.max_planarity},
                                  {"inner_curve_change", lift_.inner_change}};
    RunReport report =
        construction_.Finish({}, measures, lift_.max_planarity <= options_.lift.tolerance);
    report.variables = (rings() + 1) * points();
    return report;
  }
  PolyMesh Result() const override { return lift_.mesh; }
  nlohmann::json Facts() const override {
    return {{"closed_strip", options_.closed_strip},
            {"rings", rings()},
            {"quads", rings() * points()},
            {"a", lift_.a},
            {"v_norm", lift_.v_norm},
            {"inner_curve_change", lift_.inner_change}};
  }
  std::string ToleranceMeasure() const override { return "max_planarity"; }

 private:
  int rings() const { return static_cast<int>(file_.curves.size()) - 1; }
  int points() const { return static_cast<int>(file_.inner_heights.size()); }
  MarionetteRunOptions options_;
  ClosedStripFile file_;
  ClosedRingsLift lift_;
  Construction construction_{ConstructionMethod::kClosedForm, "closing rings (002 eq. 8-9)"};
  std::string warning_;
};

// The measures of the strip with the given inner heights (initial) and of the lift (final).
RunReport StripRun::Run(const RunCallback&) {
  const auto start = Clock::now();
  RunReport report;
  report.solver = SolverKind::kDirect;
  report.method = ConstructionMethodName(ConstructionMethod::kClosedForm);
  report.termination = "DIRECT: closing lift (002 eq. 8)";
  report.variables = 2 * num_quads();
  ClosedStripLift given = lift_;
  given.inner_heights = file_.inner_heights;
  report.initial = StripMeasures(ClosedStripMesh(file_.strip, given));
  report.final = StripMeasures(Result());
  report.converged = ValueOf(report.final, "max_planarity") <= options_.lift.tolerance;
  report.seconds = SecondsSince(start);
  return report;
}

}  // namespace

namespace {

// Whether the plan has a face that is not a quad (read without the quads-only rule).
bool PlanHasPolygons(const MarionetteRunOptions& options) {
  const PolyMesh plan = options.plan_mesh ? *options.plan_mesh : ReadMesh(options.plan);
  for (auto f : plan.faces())
    if (plan.valence(f) != 4) return true;
  return false;
}

// Whether the quad plan is a regular grid (vertex (i, j) at i (cols + 1) + j).
bool IsGridPlan(const MarionetteRunOptions& options) {
  try {
    DetectGridShape(PlanMesh(options));
    return true;
  } catch (const InputError&) {
    return false;
  }
}

}  // namespace

std::unique_ptr<MarionetteRun> MakeMarionetteRun(const MarionetteRunOptions& options) {
  if (!options.closed_strip.empty()) {
    if (!options.plan.empty() || options.plan_mesh)
      throw InputError("give either a plan or `closed_strip`, not both");
    if (options.solver != SolverKind::kDirect)
      throw InputError("`closed_strip` is lifted directly (002 eq. 8): `solver` " +
                       std::string(SolverKindName(options.solver)) + " does not apply");
    if (!options.row.empty() || !options.column.empty() || !options.guides.empty() ||
        options.guides_text || !options.fit.empty() || options.fit_mesh ||
        !options.fit_heights.empty() || !options.constraints.empty() ||
        options.projection != "vertical")
      throw InputError(
          "`closed_strip` is lifted by its closing condition (002 eq. 8): `row`, `column`, "
          "`guides`, `fit`, `fit_heights`, `hold`, `volume`, `max_height` and `projection` "
          "belong to a plan");
    ClosedStripFile file = options.closed_strip_text
                               ? ParseClosedStrip(*options.closed_strip_text, options.closed_strip)
                               : ReadClosedStrip(options.closed_strip);
    if (file.curves.size() > 2) return std::make_unique<RingsRun>(options, std::move(file));
    return std::make_unique<StripRun>(options, std::move(file));
  }
  if (options.plan.empty() && !options.plan_mesh)
    throw InputError("give a plan view (or `closed_strip`)");
  // A plan with a face that is not a quad, or only prescribed heights on a quad plan that is
  // no grid: the polygon lift (002 §4.2).
  if (PlanHasPolygons(options) ||
      (!options.constraints.heights.empty() && options.row.empty() && options.column.empty() &&
       options.fit.empty() && !options.fit_mesh && options.fit_heights.empty() &&
       options.guides.empty() && !options.guides_text && !IsGridPlan(options)))
    return std::make_unique<PolygonRun>(options);
  if (!options.guides.empty() || options.guides_text || options.projection != "vertical")
    return std::make_unique<MeshRun>(options);
  return std::make_unique<GridRun>(options);
}

}  // namespace gproj::marionette
