#include "apps/command_support.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "gproj/geometry/io/mesh_io.h"
#include "gproj/geometry/render/face_colours.h"
#include "gproj/geometry/render/svg_render.h"
#include "gproj/problems/mesh/mesh_outputs.h"

namespace gproj {

namespace fs = std::filesystem;

void CheckOutputPath(const std::string& option, const std::string& path) {
  if (path.empty()) return;
  const std::string where = option + " " + path + ": ";
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw InputError(where + "is a directory, not a file");
  fs::path directory = fs::path(path).parent_path();
  if (directory.empty()) directory = ".";
  if (!fs::is_directory(directory, ec))
    throw InputError(where + "the directory " + directory.string() + " does not exist");
  if (::access(directory.c_str(), W_OK) != 0)
    throw InputError(where + "the directory " + directory.string() + " is not writable");
}

void CheckDistinctPaths(const std::vector<std::pair<std::string, std::string>>& inputs,
                        const std::vector<std::pair<std::string, std::string>>& outputs) {
  const auto same = [](const std::string& a, const std::string& b) {
    // Absolute first: weakly_canonical leaves a relative path whose first element does not exist
    // relative ("o.obj" and "./o.obj" would differ).
    std::error_code ec;
    return fs::weakly_canonical(fs::absolute(a, ec), ec) ==
           fs::weakly_canonical(fs::absolute(b, ec), ec);
  };
  for (size_t i = 0; i < outputs.size(); ++i) {
    const auto& [option, path] = outputs[i];
    if (path.empty()) continue;
    for (const auto& [input_option, input] : inputs)
      if (!input.empty() && same(path, input))
        throw InputError(option + " " + path + " is the " + input_option + " file");
    for (size_t j = 0; j < i; ++j)
      if (!outputs[j].second.empty() && same(path, outputs[j].second))
        throw InputError(outputs[j].first + " and " + option + " are the same file " + path);
  }
}

void CheckOutputPaths(const std::vector<std::pair<std::string, std::string>>& inputs,
                      const std::vector<OutputPath>& outputs) {
  std::vector<std::pair<std::string, std::string>> paths;
  for (const OutputPath& o : outputs) {
    (o.mesh ? CheckMeshOutputPath : CheckOutputPath)(o.option, o.path);
    if (!o.path.empty() && !o.extension.empty()) {
      std::string ext = fs::path(o.path).extension().string();
      std::transform(ext.begin(), ext.end(), ext.begin(),
                     [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
      if (ext != o.extension)
        throw InputError(o.option + " " + o.path + ": the file is written as " + o.extension +
                         "; give it that extension");
    }
    paths.emplace_back(o.option, o.path);
  }
  CheckDistinctPaths(inputs, paths);
}

void CheckMeshOutputPath(const std::string& option, const std::string& path) {
  if (path.empty()) return;
  CheckOutputPath(option, path);
  try {
    CheckMeshExtension(path);
  } catch (const InputError& e) {
    throw InputError(option + " " + e.what());
  }
}

namespace {

// A validator of finite numbers for which `ok` holds; `rule` completes "<value> is not ...".
CLI::Validator FiniteWhere(const std::function<bool(double)>& ok, const std::string& rule,
                           const std::string& description) {
  return CLI::Validator(
      [ok, rule](std::string& text) -> std::string {
        double value = 0.0;
        size_t used = 0;
        try {
          value = std::stod(text, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (text.empty()) return std::string("an empty value is not allowed");
        if (used != text.size() || !std::isfinite(value) ||
            text.find_first_of("xX") != std::string::npos)  // decimal notation only
          return text + " is not a finite number";
        return ok(value) ? "" : text + " is not " + rule;
      },
      description);
}

std::string Compact(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", value);
  return text;
}

}  // namespace

CLI::Validator Finite() {
  return FiniteWhere([](double) { return true; }, "finite", "FINITE");
}

CLI::Validator Positive() {
  return FiniteWhere([](double v) { return v > 0.0; }, "> 0", "POSITIVE");
}

CLI::Validator NonNegative() {
  return FiniteWhere([](double v) { return v >= 0.0; }, ">= 0", "NONNEGATIVE");
}

CLI::Validator Within(double min, double max) {
  const std::string range = "[" + Compact(min) + ", " + Compact(max) + "]";
  return FiniteWhere([min, max](double v) { return v >= min && v <= max; }, "in " + range,
                     "in " + range);
}

void RefuseEmptyValues(CLI::App* app) {
  const CLI::Validator non_empty(
      [](std::string& text) { return text.empty() ? "an empty value is not allowed" : ""; }, "");
  for (CLI::Option* option : app->get_options())
    if (option->get_type_size() != 0) option->check(non_empty);
  for (CLI::App* command : app->get_subcommands([](CLI::App*) { return true; }))
    RefuseEmptyValues(command);
}

void AddSolverOptions(CLI::App* command, SolverOptions* solver, std::string* linear_solver) {
  command->add_option("--max-iterations", solver->max_iterations, "Iterations at most")
      ->check(Within(0, 100000))
      ->capture_default_str();
  command
      ->add_option("--fairness", solver->fairness_weight,
                   "omega_f: weight of the fairness (second differences along polylines)")
      ->check(NonNegative())
      ->capture_default_str();
  command
      ->add_option("--soft-decay", solver->soft_weight_decay,
                   "Closeness and fairness weights are multiplied by this each iteration ...")
      ->check(Within(1e-12, 1.0))
      ->capture_default_str();
  command
      ->add_option("--soft-floor", solver->soft_weight_floor,
                   "... down to this fraction of their initial value")
      ->check(Within(0.0, 1.0))
      ->capture_default_str();
  command
      ->add_option("--soft-residual", solver->soft_weight_residual_factor,
                   "... and, when > 0, also by this times the max constraint residual of the "
                   "iteration (the soft weights vanish as the constraints converge)")
      ->check(NonNegative())
      ->capture_default_str();
  command
      ->add_option("--epsilon", solver->epsilon,
                   "epsilon: weight of the proximal term eps^2 |x - x^k|^2")
      ->check(Positive())
      ->capture_default_str();
  command
      ->add_option("--epsilon-min", solver->epsilon_min,
                   "When > 0, epsilon follows the constraint residual down to this (quadratic "
                   "convergence near the solution)")
      ->check(NonNegative())
      ->capture_default_str();
  command
      ->add_option("--linear-solver", *linear_solver,
                   "Sparse Cholesky backend for gp: cholmod (supernodal) or eigen")
      ->check(CLI::IsMember({"cholmod", "eigen"}))
      ->capture_default_str();
  command->add_option("--threads", solver->num_threads, "Threads for BLAS / Ceres (0: default)")
      ->check(Within(0, 256))
      ->capture_default_str();
  command->add_flag("--monotone,!--plain-steps", solver->monotone,
                    "Monotone steps: keep a step only if it lowers the energy, else damp it "
                    "(--plain-steps: take every Gauss-Newton step)");
}

void AddPanelBoundsOptions(CLI::App* command, PanelBoundsOptions* panels) {
  command
      ->add_option("--min-angle", panels->min_angle_deg,
                   "Every quad corner angle stays within [DEG, 180 - DEG] (a corner already "
                   "outside in the input is kept from getting worse); 0 only keeps quads convex")
      ->check(Within(0.0, 59.9))
      ->capture_default_str();
  command
      ->add_option_function<std::vector<double>>(
          "--edge-length",
          [panels](const std::vector<double>& v) {
            panels->min_edge_length = v[0];
            panels->max_edge_length = v[1];
          },
          "MIN,MAX: every edge length stays within these, in the input's units (an edge outside "
          "in the input is kept from getting worse); without it no edge shrinks below 10% of its "
          "input length")
      ->delimiter(',')
      ->expected(2)
      ->check(NonNegative());
  command->add_flag_callback(
      "--allow-folds", [panels]() { panels->AllowFolds(); },
      "No corner-angle or default edge bounds: quads may turn non-convex or fold");
}

void AddVertexControlOptions(CLI::App* command, std::string* fixed_path,
                             VertexControlOptions* options) {
  command->add_option("--fixed", *fixed_path,
                      "Vertices that do not move at all: a text file of 0-based vertex ids "
                      "separated by spaces or newlines, '#' comments");
  auto* fix = command->add_flag("--fix-boundary", options->fix_boundary,
                                "Every boundary vertex stays where it is");
  command
      ->add_flag("--glide-boundary", options->glide_boundary,
                 "Boundary vertices slide along the input's boundary (they stay on it to "
                 "rounding)")
      ->excludes(fix);
}

void AddFaceOutputOptions(CLI::App* command, std::string* face_values, std::string* heatmap,
                          std::string* picture, const std::string& columns,
                          const std::string& measure) {
  command->add_option("--face-values", *face_values, "Write per-face values as CSV: " + columns);
  command->add_option("--heatmap", *heatmap,
                      "Write the result as a .ply with a colour per face (" + measure +
                          ", log scale; MeshLab and Blender show it; the scale is in the report)");
  command->add_option("--picture", *picture,
                      "Also write a shaded picture of the result (.svg, opens in any browser), "
                      "each face coloured by its " +
                          measure);
}

void CheckHeatmapPath(const std::string& path) {
  if (!path.empty() && (path.size() < 4 || path.compare(path.size() - 4, 4, ".ply") != 0))
    throw InputError("--heatmap " + path + ": the heatmap is written as .ply");
}

void AddFaceOutputs(const PolyMesh& result, const std::vector<double>& values,
                    const ColourScale& scale, const std::string& csv,
                    const std::string& face_values, const std::string& heatmap,
                    const std::string& picture, const std::string& title, OutputFiles* out) {
  RunContext context;
  for (const auto& [name, path] : {std::pair{"face_values", &face_values},
                                   std::pair{"heatmap", &heatmap}, std::pair{"picture", &picture}})
    if (!path->empty()) context.outputs.insert(name);
  RunResult texts;
  AddFaceOutputTexts(result, values, scale, csv, title, context, &texts);
  if (!face_values.empty()) out->AddText(face_values, texts.texts["face_values"]);
  if (!heatmap.empty()) out->AddText(heatmap, texts.texts["heatmap"]);
  if (!picture.empty()) out->AddText(picture, texts.texts["picture"]);
}

void PrintPanelSummary(const NamedValues& initial, const NamedValues& final) {
  for (const std::string& line : PanelSummaryLines(initial, final))
    std::printf("%s\n", line.c_str());
}

ShapeChange WarnIfFarFromInput(const std::string& command, const std::string& target,
                               const PolyMesh& input, const PolyMesh& result,
                               double max_displacement, double threshold_deg) {
  const ShapeChange change = CompareCornerAngles(input, result, threshold_deg);
  std::fflush(stdout);
  if (const auto warning = FarFromInputWarning(target, change, max_displacement))
    std::fprintf(stderr, "gproj %s: warning: %s\n", command.c_str(), warning->c_str());
  return change;
}

void ApplyLinearSolver(const std::string& name, SolverOptions* solver) {
  if (!ParseLinearSolverType(name, &solver->linear_solver))
    throw InputError("--linear-solver must be cholmod or eigen, not '" + name + "'");
}

namespace {
bool EndsWith(const std::string& text, const std::string& tail) {
  return text.size() >= tail.size() &&
         text.compare(text.size() - tail.size(), tail.size(), tail) == 0;
}
}  // namespace

void IterationLog::PrintHeader() const {
  std::printf("%5s %13s", "iter", "energy");
  for (const std::string& m : measures_)
    std::printf(" %*s", std::max(15, static_cast<int>(m.size())), m.c_str());
  std::printf(" %11s %10s\n", "step", "time_s");
  std::fflush(stdout);
}

void IterationLog::Print(const RunRecord& r) const {
  std::printf("%5d %13.6e", r.iteration, r.energy);
  for (const std::string& m : measures_) {
    const int width = std::max(15, static_cast<int>(m.size()));
    const double value = m == "max_constraint" ? r.max_constraint : ValueOf(r.measures, m);
    if (EndsWith(m, "_quads"))
      std::printf(" %*.0f", width, value);
    else if (EndsWith(m, "_deg"))
      std::printf(" %*.2f", width, value);
    else
      std::printf(" %*.3e", width, value);
  }
  std::printf(" %11.3e %10.4f\n", r.step, r.seconds);
  std::fflush(stdout);
}

int ExitCodeOf(const RunReport& report) {
  if (report.failed) return kExitSolverFailure;
  return report.converged ? kExitOk : kExitNotConverged;
}

int ConcludeRun(const std::string& command, const RunReport& report, const std::string& measure,
                double tolerance, const std::vector<std::string>& written) {
  std::printf("%s after %d iterations, %.3f s\n", report.termination.c_str(), report.iterations,
              report.seconds);
  const int code = ExitCodeOf(report);
  if (code == kExitSolverFailure) {
    std::fprintf(stderr, "gproj %s: solver failed (%s); nothing written\n", command.c_str(),
                 report.termination.c_str());
    return code;
  }
  std::string files;
  for (const std::string& path : written)
    if (!path.empty()) files += (files.empty() ? "" : ", ") + path;
  std::printf("wrote %s\n", files.c_str());
  if (code == kExitNotConverged && measure.empty())
    std::fprintf(stderr, "gproj %s: not converged (%s); the result was written, exit code %d\n",
                 command.c_str(), report.termination.c_str(), kExitNotConverged);
  else if (code == kExitNotConverged)
    std::fprintf(stderr,
                 "gproj %s: tolerance %.1e not reached (%s %.3e); the result was written, exit "
                 "code %d\n",
                 command.c_str(), tolerance, measure.c_str(), ValueOf(report.final, measure),
                 kExitNotConverged);
  return code;
}

}  // namespace gproj
