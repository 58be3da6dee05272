#include "gproj/geometry/render/face_colours.h"

#include <gtest/gtest.h>

namespace gproj {
namespace {

TEST(FaceColoursTest, LogScaleRunsFromBlueToRed) {
  const ColourScale scale = ScaleFor("planarity", {1e-9, 1e-6, 1e-3, 0.0}, true);
  EXPECT_DOUBLE_EQ(scale.max, 1e-3);
  EXPECT_DOUBLE_EQ(scale.min, 1e-9);  // above max · 1e-6 = 1e-9: kept
  EXPECT_EQ(ColourOf(1e-9, scale), (Rgb{40, 80, 200}));
  EXPECT_EQ(ColourOf(1e-3, scale), (Rgb{200, 30, 30}));
  EXPECT_EQ(ColourOf(1e-6, scale), (Rgb{240, 220, 60}));  // the middle decade
  EXPECT_EQ(ColourOf(0.0, scale), (Rgb{40, 80, 200}));    // non-positive: the bottom
  EXPECT_EQ(ColourOf(1.0, scale), (Rgb{200, 30, 30}));    // clamped
}

TEST(FaceColoursTest, LinearScaleAndFlatValues) {
  const ColourScale flat = ScaleFor("angle", {3.0, 3.0}, false);
  EXPECT_LT(flat.min, flat.max);
  const ColourScale scale = ScaleFor("angle", {0.0, 10.0}, false);
  EXPECT_EQ(ColourOf(5.0, scale), (Rgb{240, 220, 60}));
}

}  // namespace
}  // namespace gproj
