// `darboux` in the registry: the image of an H-net under an inversion, a smooth skin of Darboux
// cyclide patches (gproj/problems/nets/darboux.h).
#include <cstdio>

#include "gproj/problems/nets/darboux.h"
#include "gproj/problems/run/builtin_problems.h"
#include "gproj/problems/run/construction.h"

namespace gproj::nets {
namespace {

// Rounding the exact construction may leave: distances / the skin's diagonal, and seam angles.
constexpr double kSkinTolerance = 1e-8, kSkinAngleTolerance = 1e-6;
// H-net patches meeting at more than this (degrees) are not smooth: warned about.
constexpr double kSmoothHNetDeg = 1e-4;
// A centre nearer the surface (× the H-net's diagonal) is warned about.
constexpr double kNearCentre = 1e-2;
// Samples of the measures and the surface at most (patches × (samples + 1)²).
constexpr double kMaxSkinSamples = 2e7;

struct DarbouxSettings {
  std::vector<double> centre;  // empty: DefaultInversion
  double radius = 0.0;         // 0: DefaultInversion's (or, with a centre, the distance from it
                               // to the H-net's box centre)
  int samples = 8;
};

const OptionSchema<DarbouxSettings>& Schema() {
  static const OptionSchema<DarbouxSettings> schema = [] {
    using S = DarbouxSettings;
    OptionSchema<S> s;
    s.Optional<std::vector<double>>(
         "centre", OptionType::kNumbers,
         "Centre of the inversion, off the H-net (default: half the H-net's bounding-box "
         "diagonal off its box's centre along the mean normal). Nearer the surface, the skin's "
         "curvature changes more (regions of K > 0 appear)",
         [](S & x) -> auto& { return x.centre; })
        .Count(3, "X,Y,Z");
    s.Optional<double>("radius", OptionType::kNumber,
                       "Radius of the inversion (default: the distance from the centre to the "
                       "H-net's box centre, which then maps to itself)",
                       [](S& x) -> double& { return x.radius; })
        .Positive();
    s.Field<int>("samples", OptionType::kInt,
                 "Samples per patch edge of the surface output, the measures and the picture (at "
                 "most 6 there)",
                 [](S& x) -> int& { return x.samples; })
        .Range(2, 200);
    return s;
  }();
  return schema;
}

NamedValues Values(const DarbouxMeasures& m) {
  return {{"max_tangent_angle_deg", m.max_tangent_angle_deg},
          {"hnet_max_tangent_angle_deg", m.hnet_max_tangent_angle_deg},
          {"max_circle_deviation", m.max_circle_deviation},
          {"max_centre_off_circle", m.max_centre_off_circle},
          {"k_positive_samples", static_cast<double>(m.skin_k_positive)},
          {"k_negative_samples", static_cast<double>(m.skin_k_negative)},
          {"skin_diagonal", m.skin_diagonal}};
}

nlohmann::json MeasuresJson(const DarbouxMeasures& m) {
  return {{"max_tangent_angle_deg", m.max_tangent_angle_deg},
          {"hnet_max_tangent_angle_deg", m.hnet_max_tangent_angle_deg},
          {"max_tangent_angle_change_deg", m.max_tangent_angle_change_deg},
          {"rulings", m.rulings},
          {"max_circle_deviation", m.max_circle_deviation},
          {"max_centre_off_circle", m.max_centre_off_circle},
          {"curvature_samples", m.curvature_samples},
          {"k_positive_samples", m.skin_k_positive},
          {"k_negative_samples", m.skin_k_negative},
          {"hnet_k_positive_samples", m.hnet_k_positive},
          {"hnet_k_negative_samples", m.hnet_k_negative},
          {"min_k_times_diagonal2", m.skin_min_k},
          {"max_k_times_diagonal2", m.skin_max_k},
          {"max_curvature_formula_error", m.max_curvature_formula_error},
          {"patches_with_nonpositive_weights", m.patches_with_nonpositive_weights},
          {"hnet_diagonal", m.hnet_diagonal},
          {"skin_diagonal", m.skin_diagonal},
          {"centre_distance", m.centre_distance}};
}

RunResult Run(const RunInputs& inputs, const nlohmann::json& values, const RunContext& context) {
  const Construction construction(ConstructionMethod::kClosedForm, "inversion of an H-net");
  const DarbouxSettings settings = Schema().Apply(values);
  const std::string source = inputs.Source("hnet");
  const HNetPatchwork hnet = ParseHNetJson(*inputs.Text("hnet"), source);
  // The samples of the measures and the surface, checked before anything is allocated.
  const double samples = static_cast<double>(hnet.mesh.n_faces()) * (settings.samples + 1.0) *
                         (settings.samples + 1.0);
  if (samples > kMaxSkinSamples) {
    char text[256];
    std::snprintf(text, sizeof(text),
                  "`samples` %d on %zu patches asks for %.3g samples; at most %g (fewer samples "
                  "per patch edge)",
                  settings.samples, hnet.mesh.n_faces(), samples, kMaxSkinSamples);
    throw InputError(text);
  }
  const bool default_centre = settings.centre.empty();
  Inversion inversion =
      default_centre
          ? DefaultInversion(hnet.mesh)
          : InversionAbout(hnet.mesh, Eigen::Vector3d(settings.centre[0], settings.centre[1],
                                                      settings.centre[2]));
  if (settings.radius > 0.0) inversion.radius = settings.radius;
  const Eigen::Vector3d& c = inversion.centre;
  char line[512];
  std::snprintf(line, sizeof(line),
                "%s: %zu patches; inversion about (%.6g, %.6g, %.6g)%s, radius %.6g",
                source.c_str(), hnet.mesh.n_faces(), c.x(), c.y(), c.z(),
                default_centre ? " (default)" : "", inversion.radius);
  context.Headline(line);
  const DarbouxSkin skin = MakeDarbouxSkin(hnet, inversion);
  const DarbouxMeasures m = MeasureDarbouxSkin(hnet, skin, settings.samples);
  // The construction is exact: its measures show what rounding left (circles, seams).
  const bool exact = m.max_circle_deviation <= kSkinTolerance &&
                     m.max_centre_off_circle <= kSkinTolerance &&
                     m.max_tangent_angle_change_deg <= kSkinAngleTolerance;
  RunResult result;
  result.report = construction.Finish({}, Values(m), exact);
  result.tolerance_measure = "max_circle_deviation";
  result.tolerance = kSkinTolerance;
  if (!exact) {
    char text[320];
    std::snprintf(text, sizeof(text),
                  "the skin lost precision to rounding: rulings %.2g off their circles (%.2g "
                  "for the centre), seam angles changed by %.2g deg (at most %g, %g and %g deg): "
                  "choose a centre nearer the H-net",
                  m.max_circle_deviation, m.max_centre_off_circle, m.max_tangent_angle_change_deg,
                  kSkinTolerance, kSkinTolerance, kSkinAngleTolerance);
    result.shortfalls.push_back(text);
  }
  if (result.report.failed) return result;
  result.facts = {{"inversion",
                   {{"centre", {c.x(), c.y(), c.z()}},
                    {"radius", inversion.radius},
                    {"default", default_centre}}},
                  {"patches", skin.patches.size()},
                  {"measures", MeasuresJson(m)}};
  std::snprintf(line, sizeof(line),
                "skin: %zu rational biquadratic patches, diagonal %.4g (H-net %.4g); centre "
                "%.3g of the H-net's diagonal off it",
                skin.patches.size(), m.skin_diagonal, m.hnet_diagonal, m.centre_distance);
  result.Info(line);
  std::snprintf(line, sizeof(line),
                "tangent planes along the patch seams: max %.3e deg (H-net %.3e deg, largest "
                "change %.1e deg)",
                m.max_tangent_angle_deg, m.hnet_max_tangent_angle_deg,
                m.max_tangent_angle_change_deg);
  result.Info(line);
  std::snprintf(line, sizeof(line),
                "rulings: %d mapped to circles through the centre (max deviation %.1e, centre "
                "off them %.1e, / skin diagonal)",
                m.rulings, m.max_circle_deviation, m.max_centre_off_circle);
  result.Info(line);
  std::snprintf(line, sizeof(line),
                "Gaussian curvature at %d samples: K > 0 at %d, K < 0 at %d (H-net: %d and %d); "
                "K x diagonal^2 in [%.3g, %.3g]",
                m.curvature_samples, m.skin_k_positive, m.skin_k_negative, m.hnet_k_positive,
                m.hnet_k_negative, m.skin_min_k, m.skin_max_k);
  result.Info(line);
  if (m.skin_k_positive == 0 && m.skin_k_negative > 0)
    result.Info("no region of K > 0: a centre nearer the surface shifts the curvature further");
  if (m.hnet_max_tangent_angle_deg > kSmoothHNetDeg) {
    std::snprintf(line, sizeof(line),
                  "the input's patches meet at up to %.3g deg along their common edges: it is "
                  "not a smooth H-net (gproj hnet makes one), and the skin keeps those kinks",
                  m.hnet_max_tangent_angle_deg);
    result.Warn(line);
  }
  if (m.patches_with_nonpositive_weights > 0)
    result.Warn(std::to_string(m.patches_with_nonpositive_weights) +
                " patches have non-positive weights (the centre is near them): the output "
                "gives them as homogeneous control points only, not as NURBS weights");
  if (m.centre_distance < kNearCentre) {
    std::snprintf(line, sizeof(line),
                  "the centre is %.3g of the H-net's diagonal off its surface: the skin is "
                  "stretched near it (%.3g times its diagonal)",
                  m.centre_distance, m.skin_diagonal / m.hnet_diagonal);
    result.Warn(line);
  }
  result.texts["output"] = DarbouxSkinJson(hnet, skin).dump(1) + "\n";
  if (context.Wants("surface"))
    result.meshes["surface"] = SampleDarbouxSkin(hnet, skin, settings.samples);
  if (context.Wants("picture")) {
    std::snprintf(line, sizeof(line),
                  "Darboux cyclide skin: %zu patches, K > 0 at %d of %d samples",
                  skin.patches.size(), m.skin_k_positive, m.curvature_samples);
    result.texts["picture"] = DarbouxSkinSvg(skin, line, settings.samples);
  }
  return result;
}

}  // namespace

ProblemSpec DarbouxSpec() {
  ProblemSpec spec;
  spec.name = "darboux";
  spec.summary =
      "A smooth skin of Darboux cyclide patches (004 §4): the image of an H-net under an "
      "inversion, each rational bilinear patch mapped exactly to a rational biquadratic one, "
      "its rulings to circles through the centre, the tangent-plane continuity kept; the "
      "Gaussian curvature may change sign (K > 0 regions from a K < 0 H-net).";
  spec.inputs = {{"hnet", InputKind::kJson, "H-net (the JSON gproj hnet writes)", true}};
  spec.outputs = {{"output", OutputKind::kJson,
                   "the skin: the inversion, the H-net, and per patch its rational biquadratic "
                   "control points",
                   true},
                  {"surface", OutputKind::kMesh, "a welded triangle mesh sampling the skin"},
                  {"picture", OutputKind::kSvg,
                   "a shaded picture coloured by the sign of the Gaussian curvature"}};
  spec.options = Schema().specs();
  spec.run = Run;
  return spec;
}

}  // namespace gproj::nets
