#include "gproj/problems/marionette/marionette_inputs.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "input_error_test_util.h"

namespace gproj::marionette {
namespace {

namespace fs = std::filesystem;

// Writes `text` to a file of the test's temporary directory and returns its path.
std::string WriteFile(const std::string& name, const std::string& text) {
  const fs::path path = fs::path(::testing::TempDir()) / ("marionette_inputs_" + name);
  std::ofstream(path) << text;
  return path.string();
}

TEST(MarionetteInputsTest, ReadsGuidesAndVerticesWithTheirLines) {
  const std::string path = WriteFile("g.txt", "# spokes\nguide 0 1 3 2.5 2\n\nvertex 7 -1.25\n");
  const MarionetteGuideFile file = ReadMarionetteGuides(path, 10);
  ASSERT_EQ(file.guides.size(), 1u);
  EXPECT_EQ(file.guides[0].start, 0);
  EXPECT_EQ(file.guides[0].next, 1);
  EXPECT_EQ(file.guides[0].values, (std::vector<double>{3, 2.5, 2}));
  EXPECT_EQ(file.guides[0].where, path + ":2");
  ASSERT_EQ(file.vertices.size(), 1u);
  EXPECT_EQ(file.vertices[0].vertex, 7);
  EXPECT_EQ(file.vertices[0].height, -1.25);
}

TEST(MarionetteInputsTest, GuideErrorsNameTheFileLineAndRule) {
  const std::string a = WriteFile("a.txt", "guide 0 1 1 2\nvertex 10 1\n");
  EXPECT_EQ(
      InputErrorOf([&] { ReadMarionetteGuides(a, 10); }).find(a + ":2: '10' is not a vertex id"),
      0u);
  const std::string b = WriteFile("b.txt", "vertex 1\n");
  EXPECT_EQ(InputErrorOf([&] { ReadMarionetteGuides(b, 10); }),
            b + ":1: expected 'guide START NEXT VALUE VALUE ...' (two values at least) or "
                "'vertex ID VALUE'");
  const std::string c = WriteFile("c.txt", "guide 0 1 1 inf\n");
  EXPECT_EQ(InputErrorOf([&] { ReadMarionetteGuides(c, 10); }), c + ":1: 'inf' is not finite");
}

TEST(MarionetteInputsTest, ReadsAClosedStripAndNamesTheLinesOfADegenerateQuad) {
  const std::string path =
      WriteFile("s.txt", "1 0 0.5 2 0\n0 1 0.25 0 2 # pair 1\n-1 0 0 -2 0\n0 -1 1 0 -2\n");
  const ClosedStripFile file = ReadClosedStrip(path);
  ASSERT_EQ(file.strip.inner.size(), 4u);
  EXPECT_EQ(file.strip.outer[1], Eigen::Vector2d(0, 2));
  EXPECT_EQ(file.inner_heights, Eigen::Vector4d(0.5, 0.25, 0, 1));
  EXPECT_EQ(DegenerateClosedStripQuad(file.strip), -1);
  // Outer 1 on the line through inner 1 and inner 2.
  const std::string bad = WriteFile("d.txt", "1 0 0 2 0\n\n0 1 0 1 2\n-1 0 0 -2 0\n");
  EXPECT_EQ(InputErrorOf([&] { ReadClosedStrip(bad); })
                .find(bad + ":3: quad 1 (vertex pairs 1 and 2, "
                            "lines 3 and 4) has a degenerate"),
            0u);
}

TEST(MarionetteInputsTest, GridGuideValuesCoverRowAndColumn) {
  const GridShape shape{2, 3};  // 2 × 3 faces: 3 × 4 vertices
  const std::vector<MarionetteTarget> values = GridGuideValues(shape, {0, 1, 2, 3}, {0, 10, 20});
  ASSERT_EQ(values.size(), 7u);
  EXPECT_EQ(values[3].vertex, 3);
  EXPECT_EQ(values[6].vertex, shape.Vertex(2, 0));
  EXPECT_EQ(values[6].height, 20);
  EXPECT_EQ(InputErrorOf([&] {
              GridGuideValues(shape, {0, 1}, {0, 10, 20});
            }),
            "guide curves need 4 row values and 3 column values, got 2 and 3");
}

TEST(MarionetteInputsTest, ProjectionFromValuesChecksTheCounts) {
  const MarionetteProjectionOptions p =
      MarionetteProjectionFromValues("cylindrical", {1, 2, 3, 0, 0, 2}, {0, 0, 0});
  EXPECT_EQ(p.type, MarionetteProjection::kCylindrical);
  EXPECT_EQ(p.axis_point, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(p.axis_direction, Eigen::Vector3d(0, 0, 2));
  EXPECT_EQ(InputErrorOf([] {
              MarionetteProjectionFromValues("conic", {0, 0, 0, 0, 0, 1}, {0, 0, 0});
            }),
            "`projection` must be vertical, cylindrical or central, not 'conic'");
  EXPECT_EQ(InputErrorOf([] {
              MarionetteProjectionFromValues("central", {0, 0, 0, 0, 0, 1}, {0, 0});
            }),
            "`centre` needs three numbers x,y,z, got 2");
}

}  // namespace
}  // namespace gproj::marionette
