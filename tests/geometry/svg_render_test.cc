#include "geometry/svg_render.h"

#include <gtest/gtest.h>

#include "geometry/quad_grid.h"

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

TEST(SvgRenderTest, RefusesEmptyMeshes) { EXPECT_THROW(RenderMeshSvg(PolyMesh()), InputError); }

}  // namespace
}  // namespace gproj
