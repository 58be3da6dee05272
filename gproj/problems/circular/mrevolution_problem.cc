// `mrevolution` in the registry: an M-revolution surface in one step (000 §5.1), from a planar
// curve and two points on the circle through its ends.
#include <chrono>
#include <cstdio>

#include "gproj/geometry/render/svg_render.h"
#include "gproj/problems/circular/circular_mesh.h"
#include "gproj/problems/circular/m_revolution.h"
#include "gproj/problems/mesh/mesh_outputs.h"
#include "gproj/problems/run/builtin_problems.h"
#include "gproj/problems/run/construction.h"

namespace gproj::circular {
namespace {

struct MRevolutionSettings {
  MRevolutionOptions options;
  std::vector<double> p2, p3, up;
};

const OptionSchema<MRevolutionSettings>& Schema() {
  static const OptionSchema<MRevolutionSettings> schema = [] {
    using S = MRevolutionSettings;
    OptionSchema<S> s;
    s.Optional<std::vector<double>>(
         "p2", OptionType::kNumbers, "P2: on the circle through P1 and P4 (drawing plane)",
         [](S & x) -> auto& { return x.p2; })
        .Count(3, "X,Y,Z")
        .Required();
    s.Optional<std::vector<double>>(
         "p3", OptionType::kNumbers, "P3: on the same circle", [](S & x) -> auto& { return x.p3; })
        .Count(3, "X,Y,Z")
        .Required();
    s.Field<double>("t", OptionType::kNumber, "Ratio P1'P2' / P4'P3' of the trapezoid",
                    [](S& x) -> double& { return x.options.t; })
        .Positive();
    s.Field<int>("root", OptionType::kInt, "Which of the (up to) two centres: 0 or 1",
                 [](S& x) -> int& { return x.options.root; })
        .Range(0, 1);
    s.Field<int>("arch_segments", OptionType::kInt, "Quads along each arch", [](S& x) -> int& {
       return x.options.arch_segments;
     }).Range(2, 100000);
    s.Optional<std::vector<double>>(
         "up", OptionType::kNumbers,
         "The arches rise to this side of the drawing plane, which it must not lie in (not "
         "given: +z, or the side of (P2 - P1) x (P4 - P1) when +z lies in the plane)",
         [](S & x) -> auto& { return x.up; })
        .Count(3, "X,Y,Z");
    return s;
  }();
  return schema;
}

Eigen::Vector3d Point(const std::vector<double>& p) { return {p[0], p[1], p[2]}; }

// The log's lines and the report's facts.
void Describe(const MRevolutionSurface& surface, const MRevolutionOptions& options,
              RunResult* result) {
  const Eigen::Vector3d& c = surface.choice.centre;
  char line[512];
  std::snprintf(line, sizeof(line),
                "inversion centre (%.6g, %.6g, %.6g), ratio %.6g: P1P2P3P4 maps to an isosceles "
                "trapezoid (sides at %.1e rad, diagonals %.6g and %.6g)",
                c.x(), c.y(), c.z(), surface.ratio, surface.choice.image.side_angle,
                surface.choice.image.diagonals[0], surface.choice.image.diagonals[1]);
  result->Info(line);
  result->Info(CircularMeasuresLine("surface of revolution", result->report.initial));
  result->Info(CircularMeasuresLine("M-revolution surface", result->report.final));
  std::snprintf(line, sizeof(line),
                "f^-1(f(curve)) against the curve %.1e, far meridian against P2, P3 %.1e, arches "
                "off their planes %.1e (curve extents)",
                surface.curve_roundtrip, surface.far_meridian_miss, surface.arch_planarity);
  result->Info(line);
  result->facts = {{"t", options.t}, {"root", options.root}};
  result->facts["centre"] = {c.x(), c.y(), c.z()};
  result->facts["ratio"] = surface.ratio;
  const Eigen::Vector3d &p = surface.axis_point, &d = surface.axis_direction;
  result->facts["axis"] = {{"point", {p.x(), p.y(), p.z()}}, {"direction", {d.x(), d.y(), d.z()}}};
}

RunResult Run(const RunInputs& inputs, const nlohmann::json& values, const RunContext& context) {
  const MRevolutionSettings settings = Schema().Apply(values);
  MRevolutionOptions options = settings.options;
  if (!settings.up.empty()) {
    options.up = Point(settings.up);
    if (options.up.norm() == 0.0) throw InputError("`up` must not be zero");
  }
  const std::vector<Eigen::Vector3d>& curve = inputs.Curve("curve");
  const Construction construction(ConstructionMethod::kClosedForm,
                                  "inversion of a surface of revolution");
  const MRevolutionSurface surface =
      BuildMRevolutionSurface(curve, Point(settings.p2), Point(settings.p3), options);
  char line[512];
  std::snprintf(line, sizeof(line),
                "%s: %zu points from P1 to P4, P2 and P3 on their circle; t = %g, root %d, %d "
                "segments per arch",
                inputs.Source("curve").c_str(), curve.size(), options.t, options.root,
                options.arch_segments);
  context.Headline(line);
  NamedValues measures = MeasureCircularMesh(surface.mesh);
  measures.push_back({"curve_roundtrip", surface.curve_roundtrip});
  measures.push_back({"far_meridian_miss", surface.far_meridian_miss});
  measures.push_back({"arch_planarity", surface.arch_planarity});
  RunResult result;
  result.report = construction.Finish(MeasureCircularMesh(surface.revolution), measures, true);
  if (result.report.failed) return result;
  Describe(surface, options, &result);
  result.meshes["output"] = surface.mesh;
  if (context.Wants("revolution")) result.meshes["revolution"] = surface.revolution;
  std::snprintf(line, sizeof(line), "M-revolution surface (000 §5.1), %zu circular quads",
                surface.mesh.n_faces());
  AddMeshPicture(context, "picture", surface.mesh, line, &result);
  return result;
}

}  // namespace

ProblemSpec MRevolutionSpec() {
  ProblemSpec spec;
  spec.name = "mrevolution";
  spec.summary =
      "M-revolution surface in one step (000 §5.1): the inversion centre that maps P1 P2 P3 P4 "
      "(P1, P4 the curve's ends) to an isosceles trapezoid, the surface of revolution whose "
      "meridian is the curve's image, meshed by meridians and parallels, inverted back: a "
      "circular mesh through the curve's points and P2, P3, with planar arches.";
  spec.inputs = {{"curve", InputKind::kCurve, "Planar curve P1 .. P4", true}};
  spec.outputs = {
      {"output", OutputKind::kMesh, "the M-revolution mesh", true},
      {"revolution", OutputKind::kMesh, "the surface of revolution it is the inversion of"},
      {"picture", OutputKind::kSvg, "a shaded picture of the M-revolution mesh"}};
  spec.options = Schema().specs();
  spec.run = Run;
  return spec;
}

}  // namespace gproj::circular
