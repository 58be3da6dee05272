#include "gproj/problems/weingarten/weingarten_paneling.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>

#include "gproj/common/input_error.h"
#include "gproj/geometry/render/face_colours.h"
#include "gproj/geometry/render/svg_plot.h"
#include "gproj/geometry/render/svg_render.h"

namespace gproj::weingarten {
namespace {

// A colour per mold: hues spread by the golden angle, alternating lightness, so neighbouring
// mold numbers differ clearly.
Rgb MoldColour(int mold) {
  const double hue = std::fmod(mold * 137.507764, 360.0) / 60.0;
  const double light = mold % 2 == 0 ? 0.55 : 0.75, chroma = 0.6;
  const double x = chroma * (1.0 - std::abs(std::fmod(hue, 2.0) - 1.0));
  // (chroma, x, 0) assigned to (r, g, b) by the sector of the hue circle.
  static constexpr int kPart[6][3] = {{0, 1, 2}, {1, 0, 2}, {2, 0, 1},
                                      {2, 1, 0}, {1, 2, 0}, {0, 2, 1}};
  const double parts[3] = {chroma, x, 0.0};
  const int* part = kPart[std::clamp(static_cast<int>(hue), 0, 5)];
  const double r = parts[part[0]], g = parts[part[1]], b = parts[part[2]];
  const double m = light - chroma / 2;
  auto byte = [&](double c) {
    return static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(c + m, 0.0, 1.0)));
  };
  return {byte(r), byte(g), byte(b)};
}

nlohmann::json SeamsJson(const Paneling& p) {
  return {{"molds", p.num_molds},
          {"mean_gap", p.seams.mean_gap},
          {"max_gap", p.seams.max_gap},
          {"mean_kink_deg", p.seams.mean_kink_deg},
          {"max_kink_deg", p.seams.max_kink_deg},
          {"mean_deviation", p.mean_deviation},
          {"max_deviation", p.max_deviation}};
}

}  // namespace

int PanelSettings::molds_asked() const {
  const double n = static_cast<double>(panels_u) * panels_v;
  return std::max(1, static_cast<int>(std::lround(mold_factor * std::sqrt(n))));
}

void PanelSettings::Validate() const {
  if (!enabled()) return;
  PanelingOptions o;
  o.panels_u = panels_u;
  o.panels_v = panels_v;
  o.Validate();
  if (!(mold_factor > 0.0) || !std::isfinite(mold_factor))
    throw InputError("`mold_factor` must be > 0 (got " + std::to_string(mold_factor) + ")");
  if ((max_gap > 0.0) != (max_kink_deg > 0.0) || max_gap < 0.0 || max_kink_deg < 0.0 ||
      !std::isfinite(max_gap) || !std::isfinite(max_kink_deg))
    throw InputError("`panel_tolerance` needs GAP,KINK both > 0 and finite");
}

PanelComparison ComparePaneling(const BSplineSurface& input, const BSplineSurface& result,
                                const PanelSettings& settings, const std::function<bool()>& stop) {
  settings.Validate();
  PanelComparison c;
  c.settings = settings;
  PanelingOptions o;
  o.panels_u = settings.panels_u;
  o.panels_v = settings.panels_v;
  o.molds = settings.molds_asked();
  o.stop = stop;
  c.initial = PanelSurface(input, o);
  c.final = PanelSurface(result, o);
  if (settings.with_tolerance()) {
    c.initial_molds_needed =
        MoldsForTolerance(input, o, settings.max_gap, settings.max_kink_deg, nullptr);
    c.final_molds_needed =
        MoldsForTolerance(result, o, settings.max_gap, settings.max_kink_deg, nullptr);
  }
  return c;
}

nlohmann::json PanelsJson(const PanelComparison& c) {
  const PanelSettings& s = c.settings;
  nlohmann::json j = {{"count", s.panels_u * s.panels_v}, {"grid", {s.panels_u, s.panels_v}},
                      {"molds", s.molds_asked()},         {"mold_factor", s.mold_factor},
                      {"initial", SeamsJson(c.initial)},  {"final", SeamsJson(c.final)}};
  if (s.with_tolerance()) {
    j["tolerance"] = {{"max_gap", s.max_gap}, {"max_kink_deg", s.max_kink_deg}};
    j["initial"]["molds_needed"] = c.initial_molds_needed;
    j["final"]["molds_needed"] = c.final_molds_needed;
  }
  return j;
}

std::string SummarizePanels(const PanelComparison& c) {
  const PanelSettings& s = c.settings;
  char line[400];
  std::string out;
  std::snprintf(line, sizeof(line), "panels: %d (%d x %d), %d molds asked (%.3g sqrt N)\n",
                s.panels_u * s.panels_v, s.panels_u, s.panels_v, s.molds_asked(), s.mold_factor);
  out += line;
  for (const auto& [name, p, needed] : {std::tuple{"input ", &c.initial, c.initial_molds_needed},
                                        std::tuple{"result", &c.final, c.final_molds_needed}}) {
    std::snprintf(line, sizeof(line),
                  "  %s: %d molds, gap mean %.3g max %.3g, kink mean %.3g max %.3g deg, "
                  "panels off the design surface by mean %.3g max %.3g\n",
                  name, p->num_molds, p->seams.mean_gap, p->seams.max_gap, p->seams.mean_kink_deg,
                  p->seams.max_kink_deg, p->mean_deviation, p->max_deviation);
    out += line;
    if (s.with_tolerance()) {
      if (needed < 0)
        std::snprintf(line, sizeof(line),
                      "    gap <= %.3g and kink <= %.3g deg: not met even with one mold per "
                      "panel\n",
                      s.max_gap, s.max_kink_deg);
      else
        std::snprintf(line, sizeof(line), "    gap <= %.3g and kink <= %.3g deg: %d molds\n",
                      s.max_gap, s.max_kink_deg, needed);
      out += line;
    }
  }
  return out;
}

std::string SeamHistogramsSvg(const PanelComparison& c) {
  HistogramOptions o;
  // Gaps, then kinks: each a histogram of the input against the result.
  auto plot = [&](const char* what, const char* unit, const std::vector<double>& input,
                  const std::vector<double>& result) {
    char title[200];
    std::snprintf(title, sizeof(title), "%s at the seams, %d molds", what,
                  c.settings.molds_asked());
    o.title = title;
    o.x_name = unit;
    return RenderHistogramSvg(
        {{"input", "#c0392b", input}, {"Weingarten result", "#2c6fbb", result}}, o);
  };
  const std::string gaps =
      plot("Gaps", "gap (surface units)", c.initial.seams.gaps, c.final.seams.gaps);
  const std::string kinks =
      plot("Kinks", "kink angle (deg)", c.initial.seams.kinks_deg, c.final.seams.kinks_deg);
  // The two plots side by side, each a nested <svg> placed by x.
  char head[200];
  std::snprintf(head, sizeof(head),
                "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\">\n",
                2 * o.width, o.height);
  std::string out = head;
  auto nested = [&](const std::string& svg, int x) {
    std::string inner = svg;
    const std::string open = "<svg ";
    inner.replace(0, open.size(), "<svg x=\"" + std::to_string(x) + "\" ");
    return inner;
  };
  out += nested(gaps, 0) + nested(kinks, o.width) + "</svg>\n";
  return out;
}

std::string PanelPictureSvg(const BSplineSurface& result, const Paneling& paneling) {
  std::vector<int> panel_of_face;
  const PolyMesh mesh = PanelMesh(result, paneling, 4, &panel_of_face);
  SvgOptions svg;
  char title[200];
  std::snprintf(title, sizeof(title), "%d panels, %d molds (one colour per mold)",
                paneling.num_panels(), paneling.num_molds);
  svg.title = title;
  char legend[200];
  std::snprintf(legend, sizeof(legend), "seams: gap max %.3g, kink max %.3g deg",
                paneling.seams.max_gap, paneling.seams.max_kink_deg);
  svg.legend = legend;
  for (int panel : panel_of_face)
    svg.face_colours.push_back(MoldColour(paneling.mold_of_panel[panel]));
  return RenderMeshSvg(mesh, svg);
}

}  // namespace gproj::weingarten
