#include "geometry/curvature_diagram.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>
#include <utility>

namespace gproj {
namespace {

constexpr int kMaxCellsPerAxis = 4096;
constexpr int kMaxDrawnPointsPerSeries = 20000;

// Maps v ∈ [lo, hi] to one of n cells; an axis of zero width is a single cell. Halving keeps
// hi − lo finite for finite inputs of any magnitude.
int Cell(double v, double lo, double hi, int n) {
  const double width = hi / 2 - lo / 2;
  if (!(width > 0)) return 0;
  const double t = (v / 2 - lo / 2) / width;
  return std::clamp(static_cast<int>(std::floor(t * n)), 0, n - 1);
}

struct Box {
  double min_h, max_h, min_s, max_s;
};

// Occupied cells of the n × n grid over `box`; counting stops once it exceeds `limit`.
int CountCells(const std::vector<std::pair<double, double>>& points, const Box& box, int n,
               int limit) {
  std::unordered_set<std::int64_t> cells;
  for (const auto& [h, s] : points) {
    cells.insert(std::int64_t{Cell(h, box.min_h, box.max_h, n)} * n +
                 Cell(s, box.min_s, box.max_s, n));
    if (static_cast<int>(cells.size()) > limit) break;
  }
  return static_cast<int>(cells.size());
}

}  // namespace

MoldClustering ClusterMolds(const std::vector<double>& h, const std::vector<double>& k,
                            int max_clusters) {
  if (h.empty()) throw std::invalid_argument("mold clustering: no samples");
  if (h.size() != k.size())
    throw std::invalid_argument("mold clustering: " + std::to_string(h.size()) + " H values but " +
                                std::to_string(k.size()) + " K values");
  if (max_clusters < 1)
    throw std::invalid_argument("mold clustering: max_clusters must be at least 1 (got " +
                                std::to_string(max_clusters) + ")");
  // Work in the (H, √K) plane with √K = sign(K)·√|K|.
  std::vector<std::pair<double, double>> points(h.size());
  for (size_t i = 0; i < h.size(); ++i) {
    if (!std::isfinite(h[i]) || !std::isfinite(k[i]))
      throw std::invalid_argument("mold clustering: sample " + std::to_string(i) +
                                  " has a non-finite H or K");
    points[i] = {h[i], std::copysign(std::sqrt(std::abs(k[i])), k[i])};
  }
  Box box{points[0].first, points[0].first, points[0].second, points[0].second};
  for (const auto& [ph, ps] : points) {
    box.min_h = std::min(box.min_h, ph);
    box.max_h = std::max(box.max_h, ph);
    box.min_s = std::min(box.min_s, ps);
    box.max_s = std::max(box.max_s, ps);
  }
  // Coincident samples always share a cell, so the search runs over distinct points only.
  std::vector<std::pair<double, double>> distinct = points;
  std::sort(distinct.begin(), distinct.end());
  distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
  const int num_distinct = static_cast<int>(distinct.size());

  // Refine while the grid stays admissible. Stop at the first grid with too many occupied cells,
  // or once every distinct point has a cell of its own (every finer grid is admissible too and
  // none separates more).
  int n = 1;
  int occupied = 1;
  while (occupied < num_distinct && n < kMaxCellsPerAxis) {
    const int next = CountCells(distinct, box, n + 1, max_clusters);
    if (next > max_clusters) break;
    ++n;
    occupied = next;
  }

  MoldClustering result;
  result.cells_per_axis = n;
  result.cluster.resize(points.size());
  std::unordered_map<std::int64_t, int> id;
  for (size_t i = 0; i < points.size(); ++i) {
    const std::int64_t cell = std::int64_t{Cell(points[i].first, box.min_h, box.max_h, n)} * n +
                              Cell(points[i].second, box.min_s, box.max_s, n);
    const auto [it, inserted] = id.emplace(cell, static_cast<int>(id.size()));
    if (inserted) result.cluster_size.push_back(0);
    result.cluster[i] = it->second;
    ++result.cluster_size[it->second];
  }
  result.num_clusters = static_cast<int>(id.size());
  return result;
}

namespace {

// Text and attribute values: &, <, >, " escaped.
std::string Escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// A plotted axis: [lo, hi] with ticks at multiples of a 1-2-5 step.
struct Axis {
  double lo, hi, step;
  int exponent;  // step = mantissa · 10^exponent, mantissa ∈ {1, 2, 5}
};

Axis MakeAxis(double min, double max, int target_ticks) {
  if (!(min <= max)) min = -1, max = 1;  // no finite data
  const double span = max - min;
  const double pad =
      span > 0 ? 0.05 * span : (min != 0 ? 0.1 * std::abs(min) : 1.0);  // points off the frame
  Axis axis{min - pad, max + pad, 0, 0};
  const double raw = (axis.hi - axis.lo) / std::max(target_ticks, 1);
  int e = static_cast<int>(std::floor(std::log10(raw)));
  const double f = raw / std::pow(10.0, e);
  int mantissa = f < 1.5 ? 1 : f < 3.5 ? 2 : f < 7.5 ? 5 : 10;
  if (mantissa == 10) mantissa = 1, ++e;
  axis.exponent = e;
  axis.step = mantissa * std::pow(10.0, e);
  return axis;
}

std::vector<double> Ticks(const Axis& axis) {
  std::vector<double> ticks;
  const double first = std::ceil(axis.lo / axis.step - 1e-9);
  const double last = std::floor(axis.hi / axis.step + 1e-9);
  for (double i = first; i <= last && ticks.size() < 100; ++i) ticks.push_back(i * axis.step);
  return ticks;
}

std::string TickLabel(double value, const Axis& axis) {
  char buffer[64];
  const double magnitude = std::max(std::abs(axis.lo), std::abs(axis.hi));
  if (axis.exponent >= -4 && magnitude < 1e6) {
    std::snprintf(buffer, sizeof(buffer), "%.*f", std::max(0, -axis.exponent), value);
  } else {
    const int digits = static_cast<int>(std::floor(std::log10(magnitude))) - axis.exponent + 1;
    std::snprintf(buffer, sizeof(buffer), "%.*g", std::clamp(digits, 1, 15), value);
  }
  std::string label = buffer;
  if (label.find_first_not_of("-0.") == std::string::npos) label = "0";  // no "-0"
  return label;
}

// The plot area and its axes: px, py map (H, K) to pixels.
struct PlotFrame {
  double left, right, top, bottom;
  Axis x, y;
  double px(double h) const { return left + (h - x.lo) / (x.hi - x.lo) * (right - left); }
  double py(double k) const { return bottom - (k - y.lo) / (y.hi - y.lo) * (bottom - top); }
};

// Indices of the finite points of every series; widens [min_h, max_h] × [min_k, max_k] to
// hold them. Throws std::invalid_argument when a series' H and K differ in length.
std::vector<std::vector<int>> FinitePoints(const std::vector<DiagramSeries>& series, double* min_h,
                                           double* max_h, double* min_k, double* max_k) {
  std::vector<std::vector<int>> finite(series.size());
  for (size_t s = 0; s < series.size(); ++s) {
    const DiagramSeries& d = series[s];
    if (d.h.size() != d.k.size())
      throw std::invalid_argument("curvature diagram: series \"" + d.label + "\" has " +
                                  std::to_string(d.h.size()) + " H values but " +
                                  std::to_string(d.k.size()) + " K values");
    for (size_t i = 0; i < d.h.size(); ++i) {
      if (!std::isfinite(d.h[i]) || !std::isfinite(d.k[i])) continue;
      finite[s].push_back(static_cast<int>(i));
      *min_h = std::min(*min_h, d.h[i]);
      *max_h = std::max(*max_h, d.h[i]);
      *min_k = std::min(*min_k, d.k[i]);
      *max_k = std::max(*max_k, d.k[i]);
    }
  }
  return finite;
}

// Grid lines, the H = 0 and K = 0 lines, the frame, ticks and axis names.
void AppendAxes(const PlotFrame& f, std::string* out) {
  std::string& svg = *out;
  const Axis& x = f.x;
  const Axis& y = f.y;
  const double left = f.left, right = f.right, top = f.top, bottom = f.bottom;
  const auto px = [&](double h) { return f.px(h); };
  const auto py = [&](double k) { return f.py(k); };
  char buffer[256];
  // Grid lines and tick labels.
  svg += "<g stroke=\"#e4e4e4\" stroke-width=\"1\">\n";
  for (double t : Ticks(x)) {
    std::snprintf(buffer, sizeof(buffer),
                  "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\"/>\n", px(t), top, px(t),
                  bottom);
    svg += buffer;
  }
  for (double t : Ticks(y)) {
    std::snprintf(buffer, sizeof(buffer),
                  "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\"/>\n", left, py(t), right,
                  py(t));
    svg += buffer;
  }
  svg += "</g>\n";
  // H = 0 and K = 0.
  svg += "<g stroke=\"#888888\" stroke-width=\"1\" stroke-dasharray=\"4 3\">\n";
  if (x.lo < 0 && 0 < x.hi) {
    std::snprintf(buffer, sizeof(buffer),
                  "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\"/>\n", px(0), top, px(0),
                  bottom);
    svg += buffer;
  }
  if (y.lo < 0 && 0 < y.hi) {
    std::snprintf(buffer, sizeof(buffer),
                  "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\"/>\n", left, py(0), right,
                  py(0));
    svg += buffer;
  }
  svg += "</g>\n";
  std::snprintf(buffer, sizeof(buffer),
                "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"none\" "
                "stroke=\"#333333\"/>\n",
                left, top, right - left, bottom - top);
  svg += buffer;
  svg += "<g font-size=\"11\" fill=\"#333333\">\n";
  for (double t : Ticks(x)) {
    std::snprintf(buffer, sizeof(buffer),
                  "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#333333\"/>"
                  "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">%s</text>\n",
                  px(t), bottom, px(t), bottom + 4, px(t), bottom + 16, TickLabel(t, x).c_str());
    svg += buffer;
  }
  for (double t : Ticks(y)) {
    std::snprintf(buffer, sizeof(buffer),
                  "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#333333\"/>"
                  "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\">%s</text>\n",
                  left - 4, py(t), left, py(t), left - 6, py(t) + 4, TickLabel(t, y).c_str());
    svg += buffer;
  }
  svg += "</g>\n";
  std::snprintf(buffer, sizeof(buffer),
                "<g font-size=\"14\" font-style=\"italic\" fill=\"#333333\">"
                "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">H</text>"
                "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">K</text></g>\n",
                (left + right) / 2, bottom + 36.0, 14.0, (top + bottom) / 2);
  svg += buffer;
}

// Points: one group per series, at most kMaxDrawnPointsPerSeries each (uniform subsample).
void AppendPoints(const PlotFrame& f, const std::vector<DiagramSeries>& series,
                  const std::vector<std::vector<int>>& finite, std::string* out) {
  std::string& svg = *out;
  char buffer[256];
  for (size_t s = 0; s < series.size(); ++s) {
    const DiagramSeries& d = series[s];
    const size_t count = finite[s].size();
    const size_t drawn = std::min<size_t>(count, kMaxDrawnPointsPerSeries);
    svg += "<g fill=\"" + Escape(d.colour) + "\" fill-opacity=\"0.5\" stroke=\"none\">\n";
    svg.reserve(svg.size() + drawn * 44);
    for (size_t j = 0; j < drawn; ++j) {
      const int i = finite[s][j * count / drawn];
      std::snprintf(buffer, sizeof(buffer), "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"2\"/>\n",
                    f.px(d.h[i]), f.py(d.k[i]));
      svg += buffer;
    }
    svg += "</g>\n";
  }
}

// Legend (one row under the title) and title.
void AppendLegendAndTitle(const std::vector<DiagramSeries>& series,
                          const std::vector<std::vector<int>>& finite,
                          const DiagramOptions& options, double left, std::string* out) {
  std::string& svg = *out;
  char buffer[256];
  double legend_x = left;
  for (size_t s = 0; s < series.size(); ++s) {
    const DiagramSeries& d = series[s];
    std::snprintf(buffer, sizeof(buffer), " (n = %zu)", finite[s].size());
    const std::string text = d.label + buffer;
    std::snprintf(buffer, sizeof(buffer),
                  "<rect x=\"%.1f\" y=\"35\" width=\"10\" height=\"10\" fill=\"", legend_x);
    svg += buffer + Escape(d.colour) + "\"/>";
    std::snprintf(buffer, sizeof(buffer), "<text x=\"%.1f\" y=\"44\" font-size=\"12\">",
                  legend_x + 15);
    svg += buffer + Escape(text) + "</text>\n";
    legend_x += 35 + 7.0 * text.size();
  }
  if (!options.title.empty()) {
    std::snprintf(buffer, sizeof(buffer),
                  "<text x=\"%.1f\" y=\"22\" font-size=\"15\" text-anchor=\"middle\">",
                  options.width / 2.0);
    svg += buffer + Escape(options.title) + "</text>\n";
  }
}

}  // namespace

std::string RenderCurvatureDiagramSvg(const std::vector<DiagramSeries>& series,
                                      const DiagramOptions& options) {
  if (options.width < 200 || options.height < 150)
    throw std::invalid_argument("curvature diagram: size " + std::to_string(options.width) + "×" +
                                std::to_string(options.height) + " is below 200×150 pixels");
  constexpr double kInf = std::numeric_limits<double>::infinity();
  double min_h = kInf, max_h = -kInf, min_k = kInf, max_k = -kInf;
  const std::vector<std::vector<int>> finite = FinitePoints(series, &min_h, &max_h, &min_k, &max_k);
  // Frame: title and legend above, tick labels left and below.
  PlotFrame f;
  f.left = 72;
  f.right = options.width - 20.0;
  f.top = series.empty() ? 40.0 : 58.0;
  f.bottom = options.height - 46.0;
  f.x = MakeAxis(min_h, max_h, static_cast<int>((f.right - f.left) / 90));
  f.y = MakeAxis(min_k, max_k, static_cast<int>((f.bottom - f.top) / 60));
  std::string svg;
  char buffer[256];
  std::snprintf(buffer, sizeof(buffer),
                "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" "
                "font-family=\"sans-serif\">\n"
                "<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n",
                options.width, options.height);
  svg += buffer;
  AppendAxes(f, &svg);
  AppendPoints(f, series, finite, &svg);
  AppendLegendAndTitle(series, finite, options, f.left, &svg);
  svg += "</svg>\n";
  return svg;
}

}  // namespace gproj
