#include "gproj/problems/weingarten/curvature_diagram.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "gproj/geometry/render/svg_plot.h"

namespace gproj::weingarten {
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

// Points: one group per series, at most kMaxDrawnPointsPerSeries each (uniform subsample).
void AppendPoints(const PlotFrame& f, const std::vector<DiagramSeries>& series,
                  const std::vector<std::vector<int>>& finite, std::string* out) {
  std::string& svg = *out;
  char buffer[256];
  for (size_t s = 0; s < series.size(); ++s) {
    const DiagramSeries& d = series[s];
    const size_t count = finite[s].size();
    const size_t drawn = std::min<size_t>(count, kMaxDrawnPointsPerSeries);
    svg += "<g fill=\"" + EscapeXml(d.colour) + "\" fill-opacity=\"0.5\" stroke=\"none\">\n";
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

}  // namespace

std::string RenderCurvatureDiagramSvg(const std::vector<DiagramSeries>& series,
                                      const DiagramOptions& options) {
  if (options.width < 200 || options.height < 150)
    throw std::invalid_argument("curvature diagram: size " + std::to_string(options.width) + "×" +
                                std::to_string(options.height) + " is below 200×150 pixels");
  constexpr double kInf = std::numeric_limits<double>::infinity();
  double min_h = kInf, max_h = -kInf, min_k = kInf, max_k = -kInf;
  const std::vector<std::vector<int>> finite = FinitePoints(series, &min_h, &max_h, &min_k, &max_k);
  const PlotFrame f =
      MakePlotFrame(options.width, options.height, !series.empty(), min_h, max_h, min_k, max_k);
  std::string svg = SvgOpen(options.width, options.height);
  char buffer[256];
  AppendAxes(f, "H", "K", &svg);
  AppendPoints(f, series, finite, &svg);
  std::vector<LegendEntry> legend;
  for (size_t s = 0; s < series.size(); ++s) {
    std::snprintf(buffer, sizeof(buffer), " (n = %zu)", finite[s].size());
    legend.push_back({series[s].label + buffer, series[s].colour});
  }
  AppendLegendAndTitle(legend, options.title, options.width, f.left, &svg);
  svg += "</svg>\n";
  return svg;
}

}  // namespace gproj::weingarten
