#include "gproj/geometry/render/face_colours.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace gproj {

ColourScale ScaleFor(const std::string& measure, const std::vector<double>& values,
                     bool logarithmic) {
  ColourScale scale;
  scale.measure = measure;
  scale.logarithmic = logarithmic;
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (double v : values) {
    if (!std::isfinite(v) || (logarithmic && v <= 0.0)) continue;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  if (!(lo <= hi)) lo = hi = logarithmic ? 1.0 : 0.0;
  if (logarithmic) lo = std::max(lo, hi * 1e-6);
  if (hi <= lo) hi = logarithmic ? lo * 10.0 : lo + 1.0;
  scale.min = lo;
  scale.max = hi;
  return scale;
}

Rgb ColourOf(double value, const ColourScale& scale) {
  double t = 0.0;
  if (scale.logarithmic)
    t = value > 0.0 ? (std::log10(value) - std::log10(scale.min)) /
                          (std::log10(scale.max) - std::log10(scale.min))
                    : 0.0;
  else
    t = (value - scale.min) / (scale.max - scale.min);
  t = std::isfinite(t) ? std::clamp(t, 0.0, 1.0) : 1.0;
  // Blue (40, 80, 200) → yellow (240, 220, 60) → red (200, 30, 30).
  static const double stops[3][3] = {{40, 80, 200}, {240, 220, 60}, {200, 30, 30}};
  const int k = t < 0.5 ? 0 : 1;
  const double s = t < 0.5 ? 2.0 * t : 2.0 * t - 1.0;
  Rgb rgb;
  for (int c = 0; c < 3; ++c)
    rgb[c] = static_cast<std::uint8_t>(std::lround((1 - s) * stops[k][c] + s * stops[k + 1][c]));
  return rgb;
}

std::vector<Rgb> ColoursOf(const std::vector<double>& values, const ColourScale& scale) {
  std::vector<Rgb> colours;
  colours.reserve(values.size());
  for (double v : values) colours.push_back(ColourOf(v, scale));
  return colours;
}

std::string ColouredPlyText(const PolyMesh& mesh, const std::vector<Rgb>& colours) {
  if (colours.size() != mesh.n_faces())
    throw std::logic_error("ColouredPlyText: one colour per face is needed");
  std::string text = "ply\nformat ascii 1.0\ncomment written by gproj\nelement vertex " +
                     std::to_string(mesh.n_vertices()) +
                     "\nproperty double x\nproperty double y\nproperty double z\nelement face " +
                     std::to_string(mesh.n_faces()) +
                     "\nproperty list uchar int vertex_indices\nproperty uchar red\nproperty "
                     "uchar green\nproperty uchar blue\nend_header\n";
  char buffer[128];
  for (auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    std::snprintf(buffer, sizeof(buffer), "%.17g %.17g %.17g\n", p[0], p[1], p[2]);
    text += buffer;
  }
  for (auto f : mesh.faces()) {
    text += std::to_string(mesh.valence(f));
    for (auto v : mesh.fv_range(f)) text += " " + std::to_string(v.idx());
    const Rgb& c = colours[f.idx()];
    std::snprintf(buffer, sizeof(buffer), " %d %d %d\n", c[0], c[1], c[2]);
    text += buffer;
  }
  return text;
}

}  // namespace gproj
