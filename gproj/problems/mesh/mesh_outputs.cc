#include "gproj/problems/mesh/mesh_outputs.h"

#include <cstdio>

#include "gproj/geometry/render/svg_render.h"

namespace gproj {

void AddFaceOutputTexts(const PolyMesh& mesh, const std::vector<double>& values,
                        const ColourScale& scale, const std::string& csv, const std::string& title,
                        const RunContext& context, RunResult* result) {
  if (context.Wants("face_values")) result->texts["face_values"] = csv;
  if (!context.Wants("heatmap") && !context.Wants("picture")) return;
  const std::vector<Rgb> colours = ColoursOf(values, scale);
  if (context.Wants("heatmap")) result->texts["heatmap"] = ColouredPlyText(mesh, colours);
  if (context.Wants("picture")) {
    char legend[256];
    std::snprintf(legend, sizeof(legend),
                  "colour: %s per face (/ mean edge), %s scale, blue %.1e to red %.1e",
                  scale.measure.c_str(), scale.logarithmic ? "log" : "linear", scale.min,
                  scale.max);
    SvgOptions svg;
    svg.title = title;
    svg.legend = legend;
    svg.face_colours = colours;
    result->texts["picture"] = RenderMeshSvg(mesh, svg);
  }
}

std::vector<std::string> PanelSummaryLines(const NamedValues& initial, const NamedValues& final) {
  std::vector<std::string> lines;
  char text[512];
  const double glide = ValueOf(final, "max_glide_distance");  // NaN without gliding
  if (glide >= 0.0) {
    std::snprintf(text, sizeof(text),
                  "       boundary vertices glided; max distance from the input boundary %.2e of "
                  "the bbox diagonal",
                  glide);
    lines.push_back(text);
  }
  std::snprintf(
      text, sizeof(text),
      "panels: non-convex quads %.0f -> %.0f, smallest corner angle %.1f -> %.1f deg, max kink "
      "%.2e -> %.2e deg, max planarity %.2e -> %.2e (diagonal distance, input units)",
      ValueOf(initial, "non_convex_quads"), ValueOf(final, "non_convex_quads"),
      ValueOf(initial, "min_corner_angle_deg"), ValueOf(final, "min_corner_angle_deg"),
      ValueOf(initial, "max_kink_deg"), ValueOf(final, "max_kink_deg"),
      ValueOf(initial, "max_planarity_abs"), ValueOf(final, "max_planarity_abs"));
  lines.push_back(text);
  return lines;
}

std::optional<std::string> FarFromInputWarning(const std::string& target, const ShapeChange& change,
                                               double max_displacement) {
  if (!(change.share_changed > 0.05 || max_displacement > 0.02)) return std::nullopt;
  char text[512];
  std::snprintf(text, sizeof(text),
                "the input is far from %s: %.1f%% of the %s changed a corner angle by more "
                "than %g deg (at most %.1f deg), max displacement %.2f%% of the bbox diagonal",
                target.c_str(), 100.0 * change.share_changed,
                change.polygons > 0 ? "faces" : "quads", change.threshold_deg,
                change.max_corner_change_deg, 100.0 * max_displacement);
  return std::string(text);
}

void AddPanelMessages(const std::string& target, const PolyMesh& input, const PolyMesh& mesh,
                      double threshold_deg, double max_displacement, RunResult* result) {
  for (std::string& line : PanelSummaryLines(result->report.initial, result->report.final))
    result->Info(std::move(line));
  if (auto warning = FarFromInputWarning(target, CompareCornerAngles(input, mesh, threshold_deg),
                                         max_displacement))
    result->Warn(std::move(*warning));
}

void AddMeshPicture(const RunContext& context, const std::string& output, const PolyMesh& mesh,
                    const std::string& title, RunResult* result) {
  if (!context.Wants(output)) return;
  SvgOptions svg;
  svg.title = title;
  result->texts[output] = RenderMeshSvg(mesh, svg);
}

}  // namespace gproj
