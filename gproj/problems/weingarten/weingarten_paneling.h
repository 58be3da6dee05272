#pragma once
// The paneling of a Weingarten run (003 §4.2, Fig. 13): the input and the result paneled alike
// (same panel grid, same number of molds asked), their seams' gaps and kinks side by side, and
// with a tolerance the number of molds each needs to meet it.

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "gproj/geometry/surface/bspline_surface.h"
#include "gproj/problems/weingarten/mold_paneling.h"

namespace gproj::weingarten {

struct PanelSettings {
  int panels_u = 0, panels_v = 0;  // 0: no paneling
  double mold_factor = 3.0;        // k: k √N molds asked for N panels (the paper: 2, 3)
  // With both > 0: the molds needed for max gap ≤ max_gap (input units) and max kink ≤
  // max_kink_deg.
  double max_gap = 0.0, max_kink_deg = 0.0;
  bool enabled() const { return panels_u > 0 && panels_v > 0; }
  bool with_tolerance() const { return max_gap > 0.0 && max_kink_deg > 0.0; }
  // Molds asked: max(1, round(k √N)).
  int molds_asked() const;
  // Throws InputError naming the option and the rule broken.
  void Validate() const;
};

struct PanelComparison {
  PanelSettings settings;
  Paneling initial, final;  // the input and the result with the same molds asked
  // With a tolerance: molds each needs (−1: not even one per panel) and the paneling reached.
  int initial_molds_needed = 0, final_molds_needed = 0;
};

// `stop` is polled between the panelings' steps (null: never); true throws RunStopped.
PanelComparison ComparePaneling(const BSplineSurface& input, const BSplineSurface& result,
                                const PanelSettings& settings,
                                const std::function<bool()>& stop = nullptr);

// The report's "panels" object: count, grid, molds (asked), mold_factor, and initial / final
// each with molds (used), mean_gap, max_gap, mean_kink_deg, max_kink_deg, mean_deviation,
// max_deviation (the panels from the design surface; and molds_needed with a tolerance, which
// then appears as tolerance: {max_gap, max_kink_deg}).
nlohmann::json PanelsJson(const PanelComparison& c);
// A few lines for the log.
std::string SummarizePanels(const PanelComparison& c);
// Histograms of the seams' gaps and kinks, input against result (SVG, two plots side by side).
std::string SeamHistogramsSvg(const PanelComparison& c);
// The result's placed panels, one colour per mold (SVG).
std::string PanelPictureSvg(const BSplineSurface& result, const Paneling& paneling);

}  // namespace gproj::weingarten
