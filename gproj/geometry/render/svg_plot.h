#pragma once
// Plots a person reads in any browser, as SVG: axes with 1-2-5 ticks, a legend, a title; and
// histograms (gaps and kinks at panel seams, 003 Fig. 13e). Shared by the curvature diagram
// (curvature_diagram.h).

#include <string>
#include <vector>

namespace gproj {

// Text and attribute values: &, <, >, " escaped.
std::string EscapeXml(const std::string& text);

// A plotted axis: [lo, hi] with ticks at multiples of a 1-2-5 step.
struct Axis {
  double lo, hi, step;
  int exponent;  // step = mantissa · 10^exponent, mantissa ∈ {1, 2, 5}
};
// [min, max] padded by 5% with about `target_ticks` ticks.
Axis MakeAxis(double min, double max, int target_ticks);
std::vector<double> Ticks(const Axis& axis);
std::string TickLabel(double value, const Axis& axis);

// The plot area and its axes: px, py map data to pixels.
struct PlotFrame {
  double left, right, top, bottom;
  Axis x, y;
  double px(double h) const { return left + (h - x.lo) / (x.hi - x.lo) * (right - left); }
  double py(double k) const { return bottom - (k - y.lo) / (y.hi - y.lo) * (bottom - top); }
};

// The frame of a width × height plot of [x_min, x_max] × [y_min, y_max]: title (and the legend,
// when there is one) above, tick labels left and below.
PlotFrame MakePlotFrame(int width, int height, bool legend, double x_min, double x_max,
                        double y_min, double y_max);
// The opening <svg> element of a width × height document on a white background.
std::string SvgOpen(int width, int height);

// Grid lines, the x = 0 and y = 0 lines, the frame, ticks and the axis names.
void AppendAxes(const PlotFrame& f, const std::string& x_name, const std::string& y_name,
                std::string* out);

struct LegendEntry {
  std::string text, colour;
};
// The legend (one row under the title) and the title, centred on `width`.
void AppendLegendAndTitle(const std::vector<LegendEntry>& legend, const std::string& title,
                          int width, double left, std::string* out);

struct HistogramSeries {
  std::string label;   // e.g. "input"
  std::string colour;  // SVG colour
  std::vector<double> values;
};

struct HistogramOptions {
  int width = 640, height = 400;  // pixels
  int bins = 20;
  bool from_zero = true;  // the value axis starts at 0 (gaps, angles)
  std::string title, x_name;
};

// One histogram of all series over a common range: each bin's bars side by side, counts on the
// vertical axis, the legend with each series' count of finite values. Non-finite values are
// skipped. Throws std::invalid_argument below 200 × 150 pixels or with no bins.
std::string RenderHistogramSvg(const std::vector<HistogramSeries>& series,
                               const HistogramOptions& options = {});

}  // namespace gproj
