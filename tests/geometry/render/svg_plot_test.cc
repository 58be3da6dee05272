#include "gproj/geometry/render/svg_plot.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace gproj {
namespace {

int Count(const std::string& text, const std::string& what) {
  int n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// Four bins over [0, 4]: "a" fills bins 0, 1, 3 (two values in bin 3), "b" bin 2 only; a NaN is
// skipped. One bar per non-empty bin and series, the legend counts the finite values.
TEST(HistogramSvgTest, OneBarPerFilledBinAndSeries) {
  HistogramOptions o;
  o.bins = 4;
  o.title = "Gaps <seams>";
  o.x_name = "gap";
  const std::string svg = RenderHistogramSvg(
      {{"a", "#ff0000", {0.5, 1.5, 3.2, 4.0}}, {"b", "#0000ff", {2.5, std::nan("")}}}, o);
  EXPECT_EQ(Count(svg, "<g fill=\"#ff0000\""), 1);
  const size_t a = svg.find("<g fill=\"#ff0000\""), b = svg.find("<g fill=\"#0000ff\"");
  ASSERT_NE(b, std::string::npos);
  EXPECT_EQ(Count(svg.substr(a, b - a), "<rect "), 3);
  EXPECT_EQ(Count(svg.substr(b, svg.find("</g>", b) - b), "<rect "), 1);
  EXPECT_NE(svg.find("a (n = 4)"), std::string::npos);
  EXPECT_NE(svg.find("b (n = 1)"), std::string::npos);
  EXPECT_NE(svg.find("Gaps &lt;seams&gt;"), std::string::npos);
  EXPECT_NE(svg.find(">gap<"), std::string::npos);
  EXPECT_NE(svg.find(">count<"), std::string::npos);
  o.bins = 0;
  EXPECT_THROW(RenderHistogramSvg({}, o), std::invalid_argument);
}

}  // namespace
}  // namespace gproj
