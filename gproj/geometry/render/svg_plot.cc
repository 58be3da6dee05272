#include "gproj/geometry/render/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace gproj {

std::string EscapeXml(const std::string& text) {
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

void AppendAxes(const PlotFrame& f, const std::string& x_name, const std::string& y_name,
                std::string* out) {
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
  // x = 0 and y = 0.
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
                "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">",
                (left + right) / 2, bottom + 36.0);
  svg += buffer + EscapeXml(x_name) + "</text>";
  std::snprintf(buffer, sizeof(buffer),
                "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\" "
                "transform=\"rotate(-90 %.1f %.1f)\">",
                14.0, (top + bottom) / 2, 14.0, (top + bottom) / 2);
  svg += buffer + EscapeXml(y_name) + "</text></g>\n";
}

namespace {

// Bin counts of the finite values over [lo, hi] in `bins` equal bins.
std::vector<int> Counts(const std::vector<double>& values, double lo, double hi, int bins) {
  std::vector<int> counts(bins, 0);
  for (double v : values) {
    if (!std::isfinite(v)) continue;
    const double t = hi > lo ? (v - lo) / (hi - lo) : 0.0;
    ++counts[std::clamp(static_cast<int>(std::floor(t * bins)), 0, bins - 1)];
  }
  return counts;
}

}  // namespace

std::string RenderHistogramSvg(const std::vector<HistogramSeries>& series,
                               const HistogramOptions& options) {
  if (options.width < 200 || options.height < 150 || options.bins < 1)
    throw std::invalid_argument("histogram: size " + std::to_string(options.width) + "×" +
                                std::to_string(options.height) + " below 200×150 pixels or " +
                                std::to_string(options.bins) + " bins");
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const HistogramSeries& s : series)
    for (double v : s.values)
      if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  if (!(lo <= hi)) lo = 0.0, hi = 1.0;  // no finite value
  if (options.from_zero) lo = std::min(lo, 0.0);
  if (!(hi > lo)) hi = lo + 1.0;
  const int bins = options.bins;
  std::vector<std::vector<int>> counts;
  int max_count = 1;
  for (const HistogramSeries& s : series) {
    counts.push_back(Counts(s.values, lo, hi, bins));
    max_count = std::max(max_count, *std::max_element(counts.back().begin(), counts.back().end()));
  }
  PlotFrame f =
      MakePlotFrame(options.width, options.height, !series.empty(), lo, hi, 0.0, max_count);
  f.y.lo = 0.0;  // bars stand on the axis
  std::string svg = SvgOpen(options.width, options.height);
  char buffer[256];
  AppendAxes(f, options.x_name, "count", &svg);
  // Bars of every series side by side within each bin.
  const double bin_width = (hi - lo) / bins;
  const double share = 1.0 / std::max<size_t>(series.size(), 1);
  for (size_t s = 0; s < series.size(); ++s) {
    svg += "<g fill=\"" + EscapeXml(series[s].colour) + "\" fill-opacity=\"0.8\">\n";
    for (int b = 0; b < bins; ++b) {
      if (counts[s][b] == 0) continue;
      const double x0 = f.px(lo + bin_width * (b + s * share));
      const double x1 = f.px(lo + bin_width * (b + (s + 1) * share));
      std::snprintf(buffer, sizeof(buffer),
                    "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\"/>\n", x0,
                    f.py(counts[s][b]), std::max(x1 - x0, 0.5), f.bottom - f.py(counts[s][b]));
      svg += buffer;
    }
    svg += "</g>\n";
  }
  std::vector<LegendEntry> legend;
  for (const HistogramSeries& s : series) {
    int finite = 0;
    for (double v : s.values) finite += std::isfinite(v) ? 1 : 0;
    std::snprintf(buffer, sizeof(buffer), " (n = %d)", finite);
    legend.push_back({s.label + buffer, s.colour});
  }
  AppendLegendAndTitle(legend, options.title, options.width, f.left, &svg);
  svg += "</svg>\n";
  return svg;
}

PlotFrame MakePlotFrame(int width, int height, bool legend, double x_min, double x_max,
                        double y_min, double y_max) {
  PlotFrame f;
  f.left = 72;
  f.right = width - 20.0;
  f.top = legend ? 58.0 : 40.0;
  f.bottom = height - 46.0;
  f.x = MakeAxis(x_min, x_max, static_cast<int>((f.right - f.left) / 90));
  f.y = MakeAxis(y_min, y_max, static_cast<int>((f.bottom - f.top) / 60));
  return f;
}

std::string SvgOpen(int width, int height) {
  char buffer[256];
  std::snprintf(buffer, sizeof(buffer),
                "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" "
                "font-family=\"sans-serif\">\n"
                "<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n",
                width, height);
  return buffer;
}

void AppendLegendAndTitle(const std::vector<LegendEntry>& legend, const std::string& title,
                          int width, double left, std::string* out) {
  std::string& svg = *out;
  char buffer[256];
  double legend_x = left;
  for (const LegendEntry& entry : legend) {
    std::snprintf(buffer, sizeof(buffer),
                  "<rect x=\"%.1f\" y=\"35\" width=\"10\" height=\"10\" fill=\"", legend_x);
    svg += buffer + EscapeXml(entry.colour) + "\"/>";
    std::snprintf(buffer, sizeof(buffer), "<text x=\"%.1f\" y=\"44\" font-size=\"12\">",
                  legend_x + 15);
    svg += buffer + EscapeXml(entry.text) + "</text>\n";
    legend_x += 35 + 7.0 * entry.text.size();
  }
  if (!title.empty()) {
    std::snprintf(buffer, sizeof(buffer),
                  "<text x=\"%.1f\" y=\"22\" font-size=\"15\" text-anchor=\"middle\">",
                  width / 2.0);
    svg += buffer + EscapeXml(title) + "</text>\n";
  }
}

}  // namespace gproj
