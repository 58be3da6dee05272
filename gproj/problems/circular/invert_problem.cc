// `invert` in the registry: an inversion (Möbius transformation, 000 eq. 1) of a mesh,
// optionally about the centre of an M-revolution surface (000 §5.1).
#include <chrono>
#include <cstdio>

#include "gproj/geometry/mesh/mobius.h"
#include "gproj/geometry/render/svg_render.h"
#include "gproj/problems/circular/circular_mesh.h"
#include "gproj/problems/mesh/mesh_outputs.h"
#include "gproj/problems/run/builtin_problems.h"
#include "gproj/problems/run/construction.h"

namespace gproj::circular {
namespace {

struct InvertSettings {
  std::vector<double> centre;                 // empty: from m_revolution
  std::vector<Eigen::Vector3d> m_revolution;  // empty: centre given
  double ratio = 1.0, t = 1.0;
  int root = 0;
};

const OptionSchema<InvertSettings>& Schema() {
  static const OptionSchema<InvertSettings> schema = [] {
    using S = InvertSettings;
    OptionSchema<S> s;
    s.Optional<std::vector<double>>(
         "centre", OptionType::kNumbers, "Centre of inversion",
         [](S & x) -> auto& { return x.centre; })
        .Count(3, "X,Y,Z");
    s.Field<double>("ratio", OptionType::kNumber, "Ratio k of the inversion (non-zero)",
                    [](S& x) -> double& { return x.ratio; });
    s.Custom("m_revolution", OptionType::kPoints,
             "Four concyclic points whose image must be an isosceles trapezoid (the centre then "
             "solves 000 §5.1)",
             nullptr,
             [](const nlohmann::json& v, S* x) {
               for (const nlohmann::json& p : v)
                 x->m_revolution.emplace_back(p[0].get<double>(), p[1].get<double>(),
                                              p[2].get<double>());
             })
        .Count(4, "P1,P2,P3,P4");
    s.Field<double>("t", OptionType::kNumber, "Ratio of the trapezoid's parallel sides",
                    [](S& x) -> double& { return x.t; })
        .Positive();
    s.Field<int>("root", OptionType::kInt, "Which of the (up to) two centres to use: 0 or 1",
                 [](S& x) -> int& { return x.root; })
        .Range(0, 1);
    return s;
  }();
  return schema;
}

// The centre of the M-revolution asked for (000 §5.1), logged; its report in *report.
Eigen::Vector3d MRevolutionCentre(const InvertSettings& s, const RunContext& context,
                                  nlohmann::json* report) {
  MRevolutionChoice choice;
  try {
    choice = ChooseMRevolutionCentre(
        {s.m_revolution[0], s.m_revolution[1], s.m_revolution[2], s.m_revolution[3]}, s.t, s.root,
        s.ratio);
  } catch (const InputError& e) {
    throw InputError(std::string("`m_revolution`: ") + e.what());
  }
  *report = MRevolutionJson(choice, s.t, s.root);
  const Eigen::Vector3d& c = choice.centre;
  char line[512];
  std::snprintf(line, sizeof(line),
                "M-revolution (000 §5.1), t = %g: %zu centre(s); using %d: (%.6g, %.6g, %.6g); "
                "image sides P1'P2', P4'P3' at %.2e rad, diagonals %.6g and %.6g",
                s.t, choice.centres.size(), s.root, c.x(), c.y(), c.z(), choice.image.side_angle,
                choice.image.diagonals[0], choice.image.diagonals[1]);
  context.Info(line);
  return c;
}

RunResult Run(const RunInputs& inputs, const nlohmann::json& values, const RunContext& context) {
  const Construction construction(ConstructionMethod::kClosedForm, "inversion");
  const InvertSettings settings = Schema().Apply(values);
  if (settings.centre.empty() && settings.m_revolution.empty())
    throw InputError("give `centre` (x, y, z) or `m_revolution` (4 concyclic points)");
  if (!settings.centre.empty() && !settings.m_revolution.empty())
    throw InputError("give either `centre` or `m_revolution`, not both");
  const PolyMesh& mesh = inputs.Mesh("mesh");
  RunResult result;
  result.facts = {{"ratio", settings.ratio}};
  nlohmann::json m_revolution;
  const Eigen::Vector3d centre =
      settings.centre.empty()
          ? MRevolutionCentre(settings, context, &m_revolution)
          : Eigen::Vector3d(settings.centre[0], settings.centre[1], settings.centre[2]);
  if (!m_revolution.is_null()) result.facts["m_revolution"] = m_revolution;
  result.facts["centre"] = {centre.x(), centre.y(), centre.z()};
  char line[512];
  std::snprintf(line, sizeof(line),
                "%s: %zu vertices, %zu faces; centre (%.6g, %.6g, %.6g), ratio %g",
                inputs.Source("mesh").c_str(), mesh.n_vertices(), mesh.n_faces(), centre.x(),
                centre.y(), centre.z(), settings.ratio);
  context.Headline(line);
  const PolyMesh out = InvertMesh(mesh, centre, settings.ratio);
  result.report = construction.Finish(MeasureCircularMesh(mesh), MeasureCircularMesh(out), true);
  result.tolerance_measure = "max_concyclicity";
  if (result.report.failed) return result;
  result.Info(CircularMeasuresLine("input", result.report.initial));
  result.Info(CircularMeasuresLine("inverted", result.report.final));
  result.meshes["output"] = out;
  AddMeshPicture(context, "picture", out, "Inversion (Möbius transformation)", &result);
  return result;
}

}  // namespace

ProblemSpec InvertSpec() {
  ProblemSpec spec;
  spec.name = "invert";
  spec.summary =
      "Inversion (Moebius transformation, 000 eq. 1) of a mesh: CM' = k / |CM|^2 CM. Circular "
      "meshes stay circular. With m_revolution the centre solves 000 §5.1: it maps the "
      "concyclic quad P1 P2 P3 P4 to an isosceles trapezoid with P1'P2' = t P4'P3'.";
  spec.inputs = {{"mesh", InputKind::kMesh, "Mesh to invert", true}};
  spec.outputs = {{"output", OutputKind::kMesh, "the inverted mesh", true, true},
                  {"picture", OutputKind::kSvg, "a shaded picture of the result"}};
  spec.options = Schema().specs();
  spec.run = Run;
  return spec;
}

}  // namespace gproj::circular
