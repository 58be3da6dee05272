#pragma once
// What `gproj combescure`, `gproj invert`, `gproj canal`, `gproj beams`, `gproj mrevolution` and
// `gproj cyclidic` (circular meshes, 000) share: their registrations (RegisterSuperCanalCommands
// calls all of them), vector options, the measures line and the writing of a mesh with its picture
// and report.

#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "apps/command_support.h"
#include "geometry/mesh_io.h"

namespace gproj {

void RegisterCanalCommand(CLI::App* app, int* exit_code);

// x, y, z from a comma-separated option; throws InputError naming `option` unless the values
// are three finite numbers.
Eigen::Vector3d Vector3(const std::vector<double>& values, const std::string& option);

// A mesh-producing command's outputs: -o/--output, --report and --picture.
struct MeshOutputs {
  std::string mesh, report, picture;
  // Throws InputError for a path that cannot be written, before any work.
  // Checks every path, and that none is an input (named in `inputs`) or another output
  // (`more` lists the command's other outputs).
  void Check(const std::vector<std::pair<std::string, std::string>>& inputs,
             const std::vector<OutputPath>& more = {}) const;
};

// "<label>: max planarity …, max concyclicity …" from MeasureCircularMesh's values.
void PrintMeasures(const char* label, const NamedValues& measures);

// Unless the run failed, writes the mesh, the `also` outputs and the picture
// (titled `title`); then the report (ReportJson with `extra` and "output"), all or none.
// Returns ConcludeRun's exit code, which names `measure` and `tolerance` for a missed tolerance
// and lists the outputs as written; kExitInputError when a file cannot be written.
// More outputs of a mesh: the mesh itself, or with `svg_title` its picture (empty paths are
// skipped).
struct ExtraOutput {
  std::string path;
  const PolyMesh* mesh = nullptr;
  std::string svg_title = {};
};
using ExtraMeshes = std::vector<ExtraOutput>;
int WriteAndConclude(const std::string& command, const RunReport& report, const PolyMesh& mesh,
                     const std::string& title, const MeshOutputs& outputs, nlohmann::json extra,
                     const std::string& measure, double tolerance, const ExtraMeshes& also = {});

}  // namespace gproj
