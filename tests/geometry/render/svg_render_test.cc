#include "gproj/geometry/render/svg_render.h"

#include <gtest/gtest.h>

#include "gproj/geometry/mesh/quad_grid.h"

namespace gproj {
namespace {

int Count(const std::string& text, const std::string& what) {
  int n = 0;
  for (size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

TEST(SvgRenderTest, OnePolygonPerFaceAndTheTitle) {
  QuadGridOptions o;
  o.nu = 5;
  o.nv = 4;
  SvgOptions svg_options;
  svg_options.light = {0, 0, 1};
  svg_options.width = 400;
  svg_options.title = "grid";
  const std::string svg = RenderMeshSvg(MakeQuadGrid(o), svg_options);
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_EQ(Count(svg, "<polygon"), 12);
  EXPECT_NE(svg.find(">grid</text>"), std::string::npos);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
}

// Titles are XML text (a "K < 0" in a title once made the whole picture unreadable); segments
// and dots are drawn over the faces.
TEST(SvgRenderTest, EscapedTitlesSegmentsAndDots) {
  QuadGridOptions o;
  o.nu = 3;
  o.nv = 3;
  SvgOptions svg_options;
  svg_options.title = "K < 0 & H > 0";
  svg_options.legend = "<legend>";
  svg_options.segments = {{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 0)},
                          {Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(1, 0, 0)}};
  svg_options.dots = {Eigen::Vector3d(0.5, 0.5, 0)};
  const std::string svg = RenderMeshSvg(MakeQuadGrid(o), svg_options);
  EXPECT_NE(svg.find(">K &lt; 0 &amp; H &gt; 0</text>"), std::string::npos) << svg;
  EXPECT_NE(svg.find(">&lt;legend&gt;</text>"), std::string::npos);
  EXPECT_EQ(Count(svg, "<line"), 2);
  EXPECT_EQ(Count(svg, "<circle"), 1);
  EXPECT_GT(svg.find("<line"), svg.rfind("<polygon"));  // over the faces
}

TEST(SvgRenderTest, RefusesEmptyMeshes) { EXPECT_THROW(RenderMeshSvg(PolyMesh()), InputError); }

}  // namespace
}  // namespace gproj
