// `cyclidic` in the registry: the smooth cyclidic surface of a circular mesh (000 §2.1–2.2): a
// frame at one vertex makes it a cyclidic net, every quad carries a Dupin cyclide patch, and the
// patches join with common tangent planes.
#include <chrono>
#include <cstdio>

#include "gproj/geometry/render/svg_render.h"
#include "gproj/problems/circular/cyclidic_surface.h"
#include "gproj/problems/mesh/mesh_outputs.h"
#include "gproj/problems/run/builtin_problems.h"
#include "gproj/problems/run/construction.h"

namespace gproj::circular {
namespace {

struct CyclidicSettings {
  CyclidicMeshOptions options;
  std::vector<double> normal;       // empty: the frame minimising 000 eq. 5
  double tangent_tolerance = 1e-4;  // degrees
};

const OptionSchema<CyclidicSettings>& Schema() {
  static const OptionSchema<CyclidicSettings> schema = [] {
    using S = CyclidicSettings;
    OptionSchema<S> s;
    s.Optional<std::vector<double>>(
         "normal", OptionType::kNumbers,
         "Normal of the frame at vertex 0 (not given: the frame minimising 000 eq. 5)",
         [](S & x) -> auto& { return x.normal; })
        .Count(3, "X,Y,Z");
    s.Field<double>("psi", OptionType::kNumber,
                    "Turn of the frame's first tangent about the normal (the start of the "
                    "minimisation without normal)",
                    [](S& x) -> double& { return x.options.angles.psi; })
        .Unit("rad");
    s.Field<int>("segments", OptionType::kInt, "Fine quads along every arc", [](S& x) -> int& {
       return x.options.surface.segments;
     }).Range(1, 1000);
    s.Field<int>("max_iterations", OptionType::kInt, "BFGS iterations for the frame",
                 [](S& x) -> int& { return x.options.max_iterations; })
        .Range(1, 100000);
    s.Field<double>("closure_tolerance", OptionType::kNumber,
                    "Largest angle by which frames carried around a face may miss themselves (0 "
                    "for circular faces)",
                    [](S& x) -> double& { return x.options.closure_tolerance; })
        .Positive()
        .Unit("deg");
    s.Field<double>("tangent_tolerance", OptionType::kNumber,
                    "Largest angle between the tangent planes of two patches along their common "
                    "arc for convergence",
                    [](S& x) -> double& { return x.tangent_tolerance; })
        .Positive()
        .Unit("deg");
    return s;
  }();
  return schema;
}

RunResult Run(const RunInputs& inputs, const nlohmann::json& values, const RunContext& context) {
  CyclidicSettings settings = Schema().Apply(values);
  CyclidicMeshOptions& options = settings.options;
  if (!settings.normal.empty()) {
    const Eigen::Vector3d normal(settings.normal[0], settings.normal[1], settings.normal[2]);
    if (normal.norm() == 0.0) throw InputError("`normal` must not be zero");
    const double psi = options.angles.psi;
    options.given_frame = true;
    options.angles = AnglesFromNormal(normal);
    options.angles.psi = psi;
  }
  const PolyMesh& mesh = inputs.Mesh("mesh");
  const std::string source = inputs.Source("mesh");
  char line[512];
  std::snprintf(line, sizeof(line), "%s: %zu faces; %d fine quads per arc; frame at vertex 0 %s",
                source.c_str(), mesh.n_faces(), options.surface.segments,
                options.given_frame ? "from `normal`"
                                    : "by 000 eq. 5 (sum of 1/R^2 over the arcs, Ceres BFGS)");
  context.Headline(line);
  const Construction construction(
      options.given_frame ? ConstructionMethod::kClosedForm : ConstructionMethod::kBfgs,
      options.given_frame ? "frame given" : "frame by eq. 5");
  options.callback = [&context](const RunRecord& record) { return context.Record(record); };
  const CyclidicMeshResult r = CyclidicSurfaceOfMesh(mesh, options, source);
  RunResult result;
  result.report = CyclidicRunReport(r, settings.tangent_tolerance, construction);
  result.facts = CyclidicJson(r);
  if (result.report.failed) return result;
  const NamedValues& m = result.report.final;
  std::snprintf(line, sizeof(line), "eq. 5 of the net: %.6g -> %.6g",
                ValueOf(result.report.initial, "smoothness_energy"),
                ValueOf(m, "smoothness_energy"));
  result.Info(line);
  std::snprintf(line, sizeof(line),
                "%g Dupin cyclide patches, %zu fine quads (circular to %.1e: curvature-line "
                "quads); tangent planes across shared arcs agree to %.1e deg; frames close around "
                "every face to %.1e deg",
                ValueOf(m, "patches"), r.surface.mesh.n_faces(),
                ValueOf(m, "fine_max_concyclicity"), ValueOf(m, "max_tangent_angle_deg"),
                ValueOf(m, "max_face_frame_closure_deg"));
  result.Info(line);
  result.meshes["output"] = r.surface.mesh;
  std::snprintf(line, sizeof(line), "Smooth cyclidic surface (000 §2.2), %g Dupin cyclide patches",
                ValueOf(m, "patches"));
  AddMeshPicture(context, "picture", r.surface.mesh, line, &result);
  return result;
}

}  // namespace

ProblemSpec CyclidicSpec() {
  ProblemSpec spec;
  spec.name = "cyclidic";
  spec.summary =
      "Smooth cyclidic surface of a circular quad mesh in grid order (000 §2.1-2.2): a frame at "
      "vertex 0, carried to every vertex by mirror images across the edges, makes the mesh a "
      "cyclidic net; every quad carries a Dupin cyclide patch (both families of curvature lines "
      "circles), the patches join with common tangent planes, and the surface is returned as a "
      "fine mesh along its curvature lines. The frame minimises 000 eq. 5 unless normal is given. "
      "Not converged when the surface folds or pinches, or the tangent planes disagree beyond "
      "tangent_tolerance (the result is returned).";
  spec.inputs = {{"mesh", InputKind::kQuadMesh, "Circular quad mesh in grid order", true}};
  spec.outputs = {{"output", OutputKind::kMesh, "the fine mesh of the smooth surface", true},
                  {"picture", OutputKind::kSvg, "a shaded picture of the smooth surface"}};
  spec.options = Schema().specs();
  spec.run = Run;
  return spec;
}

}  // namespace gproj::circular
