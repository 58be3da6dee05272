#include "gproj/problems/weingarten/weingarten_paneling.h"

#include <gtest/gtest.h>

#include <cstdio>

#include "gproj/common/input_error.h"
#include "gproj/problems/weingarten/weingarten.h"
#include "gproj/problems/weingarten/weingarten_options.h"

namespace gproj::weingarten {
namespace {

BSplineSurface Optimised(const BSplineSurface& input) {
  WeingartenProblem problem(input, WeingartenPreset("fig1"));
  const SolverSummary s = problem.Run().summary;
  EXPECT_NE(s.termination, TerminationType::kFailure) << s.FullReport();
  return problem.Result();
}

// 003 §4.2's claim on generated surfaces that were not shipped: paneled alike (10 × 10 panels,
// 3 √100 = 30 molds asked), the Weingarten result's seams are smaller than the input's on
// average (the largest gap or kink may grow where the surface moved most), and for a tolerance
// (gap ≤ 0.002, kink ≤ 2°) the results together need far fewer molds than the inputs
// (measured: 80 → 56, 49 → 28, 89 → 93, 15 → 4). The count of one surface is discrete and
// moves by a few molds with round-off: the third case needed 88 when the isoline rows' Jacobian
// was written by hand, 93 with the same rows differentiated automatically (results equal to
// 1e-13), so a single case is only held to within 10% of its input.
TEST(WeingartenPanelingTest, TheResultHasSmallerSeamsWithTheSameMolds) {
  struct Case {
    const char* name;
    BSplineSurface surface;
  };
  const Case cases[] = {{"wavy 10x10", MakeWavyBSpline(10, 10, 4)},
                        {"wavy 12x9, amplitude 0.6", MakeWavyBSpline(12, 9, 4, 0.6)},
                        {"wavy 12x10, amplitude 1.3", MakeWavyBSpline(12, 10, 4, 1.3)},
                        {"bump 12x12", MakeBumpBSpline(12)}};
  PanelSettings settings;
  settings.panels_u = settings.panels_v = 10;
  settings.max_gap = 0.002;
  settings.max_kink_deg = 2.0;
  int initial_needed = 0, final_needed = 0;
  for (const Case& c : cases) {
    const BSplineSurface result = Optimised(c.surface);
    // A usable result first: no fold anywhere (neighbouring normals on a fine grid agree).
    EXPECT_GT(MinNormalCosine(result, 80, 80).min_cosine, 0.99) << c.name;
    const PanelComparison p = ComparePaneling(c.surface, result, settings);
    std::printf(
        "%s: %d -> %d molds, gap mean %.4g -> %.4g, max %.4g -> %.4g; kink mean %.3g -> "
        "%.3g, max %.3g -> %.3g deg; molds needed %d -> %d\n",
        c.name, p.initial.num_molds, p.final.num_molds, p.initial.seams.mean_gap,
        p.final.seams.mean_gap, p.initial.seams.max_gap, p.final.seams.max_gap,
        p.initial.seams.mean_kink_deg, p.final.seams.mean_kink_deg, p.initial.seams.max_kink_deg,
        p.final.seams.max_kink_deg, p.initial_molds_needed, p.final_molds_needed);
    EXPECT_GT(p.final_molds_needed, 0) << c.name;
    EXPECT_LE(p.final_molds_needed, 1.1 * p.initial_molds_needed) << c.name;
    initial_needed += p.initial_molds_needed;
    final_needed += p.final_molds_needed;
    EXPECT_LE(p.initial.num_molds, 30) << c.name;
    EXPECT_LE(p.final.num_molds, 30) << c.name;
    EXPECT_LT(p.final.seams.mean_gap, p.initial.seams.mean_gap) << c.name;
    EXPECT_LT(p.final.seams.mean_kink_deg, p.initial.seams.mean_kink_deg) << c.name;
  }
  EXPECT_LT(final_needed, 0.8 * initial_needed);
}

TEST(WeingartenPanelingTest, ReportObjectAndSettings) {
  PanelSettings s;
  s.panels_u = 6;
  s.panels_v = 4;
  EXPECT_EQ(s.molds_asked(), 15);  // round(3 √24) = round(14.7)
  s.mold_factor = 2.0;
  EXPECT_EQ(s.molds_asked(), 10);
  s.max_gap = 0.1;
  EXPECT_THROW(s.Validate(), InputError);  // a gap without a kink
  s.max_kink_deg = 3.0;
  const BSplineSurface input = MakeWavyBSpline(8, 8, 4);
  const PanelComparison c = ComparePaneling(input, input, s);
  const nlohmann::json j = PanelsJson(c);
  EXPECT_EQ(j["count"].get<int>(), 24);
  EXPECT_EQ(j["molds"].get<int>(), 10);
  EXPECT_EQ(j["initial"], j["final"]);  // the same surface paneled twice
  EXPECT_EQ(j["initial"]["molds_needed"].get<int>(), c.initial_molds_needed);
  EXPECT_NE(SeamHistogramsSvg(c).find("Kinks at the seams"), std::string::npos);
  EXPECT_NE(SummarizePanels(c).find("24 (6 x 4), 10 molds asked"), std::string::npos);
}

}  // namespace
}  // namespace gproj::weingarten
