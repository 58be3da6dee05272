#pragma once
// What every subcommand shares, so that each one only parses, calls, logs and writes: output
// paths checked before the work starts, guided projection's options on the command line, the
// live iteration log, the JSON report (one schema for every command) and the exit codes.

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"
#include "gproj/geometry/mesh/quad_shape.h"
#include "gproj/problems/mesh/panel_bounds.h"
#include "gproj/problems/mesh/vertex_control.h"
#include "gproj/problems/run/guided_problem.h"
#include "gproj/problems/run/report_json.h"

namespace gproj {

// Exit codes shared by all subcommands.
constexpr int kExitOk = 0;
constexpr int kExitInputError = 1;     // bad file, mesh or option value: nothing written
constexpr int kExitNotConverged = 3;   // finished without meeting the tolerance: result written
constexpr int kExitSolverFailure = 4;  // numerical failure: nothing written

// Throws InputError naming `option` and `path` when the path cannot be written: its directory
// is missing or not writable, or the path is a directory. An empty path (option not given)
// passes.
void CheckOutputPath(const std::string& option, const std::string& path);
// The same, and the extension must be a mesh format (.obj, .off or .ply).
void CheckMeshOutputPath(const std::string& option, const std::string& path);

// Checks of numeric options. CLI11's own let NaN and infinity through and print bounds like
// 1.797e308 in full; these refuse non-finite values and name the rule compactly, e.g.
// "--epsilon: nan is not a finite number", "--soft-decay: 2 is not in [1e-12, 1]". They apply
// to each value of a list option.
CLI::Validator Finite();
CLI::Validator Positive();                      // finite and > 0
CLI::Validator NonNegative();                   // finite and ≥ 0
CLI::Validator Within(double min, double max);  // finite and in [min, max]

// Makes every option of `app` and of its subcommands that takes a value refuse an empty one
// ("--closeness: an empty value is not allowed"): CLI11 reads '' as 0 for a number, and an
// empty path would silently mean "not written".
void RefuseEmptyValues(CLI::App* app);

// Throws InputError when two of the named paths are one file: an output over an input ("--output
// in.obj is the input file"), or two outputs ("--report and --output are the same file
// out.obj"). Each entry is (option, path); inputs are named "input" (or their option); empty
// paths are skipped.
void CheckDistinctPaths(const std::vector<std::pair<std::string, std::string>>& inputs,
                        const std::vector<std::pair<std::string, std::string>>& outputs);

// An output of a command: its option, its path (empty: not asked) and whether it is a mesh.
struct OutputPath {
  std::string option, path;
  bool mesh = false;
  std::string extension = {};  // when not empty, the path must end in it (any case), e.g. ".svg"
};
// Every output checked (CheckOutputPath, CheckMeshOutputPath for meshes), then all of them and
// the inputs checked to be distinct files (CheckDistinctPaths).
void CheckOutputPaths(const std::vector<std::pair<std::string, std::string>>& inputs,
                      const std::vector<OutputPath>& outputs);

// Guided projection's options as command-line options (--max-iterations, --epsilon,
// --soft-decay, --soft-floor, --fairness, --linear-solver, --threads), with the problem's
// defaults shown in --help. `linear_solver` receives the backend's name; ApplyLinearSolver
// turns it into the option.
void AddSolverOptions(CLI::App* command, SolverOptions* solver, std::string* linear_solver);
void ApplyLinearSolver(const std::string& name, SolverOptions* solver);

// --min-angle DEG, --edge-length MIN,MAX and --allow-folds for a problem's panel bounds.
void AddPanelBoundsOptions(CLI::App* command, PanelBoundsOptions* panels);
// --fixed FILE, --fix-boundary and --glide-boundary; the file's path goes to *fixed_path (read
// with ReadVertexIds once the mesh is known).
void AddVertexControlOptions(CLI::App* command, std::string* fixed_path,
                             VertexControlOptions* options);

// --face-values, --heatmap and --picture of a quad-mesh command; `columns` names the CSV's
// columns, `measure` what the colours show.
void AddFaceOutputOptions(CLI::App* command, std::string* face_values, std::string* heatmap,
                          std::string* picture, const std::string& columns,
                          const std::string& measure);

// Throws InputError unless `path` is empty or ends in .ply (the --heatmap format).
void CheckHeatmapPath(const std::string& path);

// Adds the per-face outputs of a mesh result to `out`: `face_values` (the CSV text `csv`),
// `heatmap` (PLY with a colour per face) and `picture` (SVG), each only when its path is not
// empty. The colours show `values` (one per face) on `scale`.
void AddFaceOutputs(const PolyMesh& result, const std::vector<double>& values,
                    const ColourScale& scale, const std::string& csv,
                    const std::string& face_values, const std::string& heatmap,
                    const std::string& picture, const std::string& title, OutputFiles* out);

// "panels: non-convex quads 0 -> 0, smallest corner angle …" from the ShapeValues of the initial
// and final measures, after the gliding line when the final measures have max_glide_distance.
void PrintPanelSummary(const NamedValues& initial, const NamedValues& final);
// Warns on stderr when the result is far from the input (a corner angle changed by more than
// `threshold_deg` in over 5% of the quads, or a vertex moved more than 2% of the bbox diagonal):
// the input was far from the asked net type. Returns the change for the report.
ShapeChange WarnIfFarFromInput(const std::string& command, const std::string& target,
                               const PolyMesh& input, const PolyMesh& result,
                               double max_displacement, double threshold_deg);

// The live log: a header line, then one line per record with the iteration, the energy, the
// given measures ("max_constraint": the record's max |φ| over constraint rows), the step and
// the time; flushed after every line.
class IterationLog {
 public:
  explicit IterationLog(std::vector<std::string> measures) : measures_(std::move(measures)) {}
  void PrintHeader() const;
  void Print(const RunRecord& record) const;

 private:
  std::vector<std::string> measures_;
};

// 0 converged, 3 tolerance not met (result written), 4 numerical failure (nothing written).
int ExitCodeOf(const RunReport& report);

// Prints how the run ended and what was written, and the error line for a failure or a missed
// tolerance (naming `measure` and `tolerance`; with no measure, the termination, for runs
// whose tolerance is the solver's own); returns ExitCodeOf(report).
int ConcludeRun(const std::string& command, const RunReport& report, const std::string& measure,
                double tolerance, const std::vector<std::string>& written);

}  // namespace gproj
