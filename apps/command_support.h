#pragma once
// What the generic subcommand driver shares with `gproj schema`: output paths checked before
// the work starts, the live iteration log and the exit codes.

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"
#include "gproj/problems/run/guided_problem.h"

namespace gproj {

// Exit codes shared by all subcommands.
constexpr int kExitOk = 0;
constexpr int kExitInputError = 1;     // bad file, mesh or option value: nothing written
constexpr int kExitNotConverged = 3;   // finished without meeting the tolerance: result written
constexpr int kExitSolverFailure = 4;  // numerical failure: nothing written
constexpr int kExitInterrupted = 130;  // stopped by Ctrl-C: the result at the stop written

// Throws InputError naming `option` and `path` when the path cannot be written: its directory
// is missing or not writable, or the path is a directory. An empty path (option not given)
// passes.
void CheckOutputPath(const std::string& option, const std::string& path);
// The same, and the extension must be a mesh format (.obj, .off or .ply).
void CheckMeshOutputPath(const std::string& option, const std::string& path);

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

// Prints how the run ended and what was written, and the error line for a failure, a missed
// tolerance (naming `measure` and `tolerance`; with no measure, the termination, for runs
// whose tolerance is the solver's own) or a stop by Ctrl-C (`interrupted`); returns
// ExitCodeOf(report), or kExitInterrupted for an interrupted run that did not fail.
int ConcludeRun(const std::string& command, const RunReport& report, const std::string& measure,
                double tolerance, const std::vector<std::string>& written,
                bool interrupted = false);

}  // namespace gproj
