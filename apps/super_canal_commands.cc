// The parts `gproj combescure`, `gproj invert` and `gproj canal` share.
#include "apps/super_canal_commands.h"

#include <cstdio>
#include <iostream>

#include "apps/commands.h"
#include "geometry/svg_render.h"
#include "problems/circular_mesh.h"

namespace gproj {

Eigen::Vector3d Vector3(const std::vector<double>& values, const std::string& option) {
  if (values.size() != 3)
    throw InputError(option + " needs three comma-separated numbers, got " +
                     std::to_string(values.size()));
  const Eigen::Vector3d p(values[0], values[1], values[2]);
  if (!p.allFinite()) throw InputError(option + " must be finite");
  return p;
}

void MeshOutputs::Check(const std::vector<std::pair<std::string, std::string>>& inputs,
                        const std::vector<OutputPath>& more) const {
  std::vector<OutputPath> outputs = {{"--output", mesh, true},
                                     {"--report", report, false, ".json"},
                                     {"--picture", picture, false, ".svg"}};
  outputs.insert(outputs.end(), more.begin(), more.end());
  CheckOutputPaths(inputs, outputs);
}

void PrintMeasures(const char* label, const NamedValues& measures) {
  std::printf("%s\n", CircularMeasuresLine(label, measures).c_str());
}

int WriteAndConclude(const std::string& command, const RunReport& report, const PolyMesh& mesh,
                     const std::string& title, const MeshOutputs& outputs, nlohmann::json extra,
                     const std::string& measure, double tolerance, const ExtraMeshes& also) {
  extra["output"] = report.failed ? "" : outputs.mesh;
  try {
    OutputFiles files;
    if (!report.failed) {
      files.AddMesh(mesh, outputs.mesh);
      for (const ExtraOutput& extra_output : also) {
        if (extra_output.path.empty()) continue;
        if (extra_output.svg_title.empty()) {
          files.AddMesh(*extra_output.mesh, extra_output.path);
        } else {
          SvgOptions svg;
          svg.title = extra_output.svg_title;
          files.AddText(extra_output.path, RenderMeshSvg(*extra_output.mesh, svg));
        }
      }
      if (!outputs.picture.empty()) {
        SvgOptions svg;
        svg.title = title;
        files.AddText(outputs.picture, RenderMeshSvg(mesh, svg));
      }
    }
    if (!report.failed && !outputs.report.empty())
      files.AddText(outputs.report, ReportJson(command, report, extra).dump(2) + "\n");
    files.Commit();
  } catch (const InputError& e) {
    std::cerr << "gproj " << command << ": " << e.what() << "\n";
    return kExitInputError;
  }
  std::vector<std::string> written = {outputs.mesh};
  for (const ExtraOutput& extra_output : also) written.push_back(extra_output.path);
  written.insert(written.end(), {outputs.picture, outputs.report});
  return ConcludeRun(command, report, measure, tolerance, written);
}

void RegisterSuperCanalCommands(CLI::App* app, int* exit_code) {
  RegisterCanalCommand(app, exit_code);
}

}  // namespace gproj
