#pragma once
// The text inputs of Marionette meshes (002): guide files for plans of any connectivity, closed
// strip files, guide curves of grid plans and the projection given as numbers. Bad input is an
// InputError of one line that names "<file>:<line>" (or the option) and the rule broken.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "gproj/geometry/mesh/quad_grid.h"
#include "gproj/problems/marionette/marionette.h"
#include "gproj/problems/marionette/marionette_mesh.h"

namespace gproj::marionette {

// A guide file, one entry a line ('#' starts a comment):
//   guide START NEXT V0 V1 ...  values on the straight mesh polyline from vertex START through
//                               its neighbour NEXT, one per polyline vertex (two at least);
//   vertex ID VALUE             the value of one vertex.
// Vertex ids are 0-based and below `num_vertices`. Each guide's `where` is "<path>:<line>".
struct MarionetteGuideFile {
  std::vector<MarionetteGuide> guides;
  std::vector<MarionetteTarget> vertices;
};
MarionetteGuideFile ReadMarionetteGuides(const std::string& path, int num_vertices);
// The same from the file's text; `name` stands for the path in messages.
MarionetteGuideFile ParseMarionetteGuides(const std::string& text, const std::string& name,
                                          int num_vertices);

// A closed strip file (002 §2.5): one line "XI YI ZI XO YO" per vertex pair (inner vertex with
// its height, outer vertex), at least three pairs; quad i is (inner i, outer i, outer i+1,
// inner i+1), closing back to the first pair. Several rings (002 Figs. 7–8): "XI YI ZI X1 Y1
// X2 Y2 ...", the same number of outer curves on every line, ring r between curves r and r + 1.
// A quad with a degenerate plan view is refused naming its lines.
struct ClosedStripFile {
  ClosedStrip strip;                                 // the first ring
  std::vector<std::vector<Eigen::Vector2d>> curves;  // inner curve, then every outer curve
  Eigen::VectorXd inner_heights;                     // N
};
ClosedStripFile ReadClosedStrip(const std::string& path);
// The same from the file's text; `name` stands for the path in messages.
ClosedStripFile ParseClosedStrip(const std::string& text, const std::string& name);

// The guide values of a grid plan (`gproj grid` order): `row` for vertices (0, j), j = 0..cols,
// `column` for (i, 0), i = 0..rows (its first value is vertex 0's again, checked by the lift).
std::vector<MarionetteTarget> GridGuideValues(const GridShape& shape,
                                              const std::vector<double>& row,
                                              const std::vector<double>& column);

// The projection from its name ("vertical", "cylindrical" or "central"), the axis as six numbers
// (point, direction) and the centre as three, as `gproj marionette` takes them; the messages
// name its options (--projection, --axis, --centre).
MarionetteProjectionOptions MarionetteProjectionFromValues(const std::string& name,
                                                           const std::vector<double>& axis,
                                                           const std::vector<double>& centre);

}  // namespace gproj::marionette
